//! # isochor-mesh
//!
//! Geometry and topology of tetrahedral meshes, with no physics: the linear [`TetMesh`] and
//! its rest data, the boundary surface, adjacency and k-rings, named selections and groups, volume
//! zones (Sheen et al. 2021, sec. 4 and 6), the element layer of 4- and 10-node tets
//! ([`element`]: reference elements, quadrature, isoparametric rest geometry, [`ElementMesh`]),
//! mesh generators, [`probes`] of a deformed state, file I/O (VTU/PVD for ParaView, Gmsh `.msh`, TetGen `.node`/`.ele`),
//! and the [`contact`] geometry of IPC (Li et al. 2020): contact surfaces, squared distances with
//! their derivatives, the edge-edge mollifier, continuous collision detection, a broad phase and
//! an intersection check.

#![deny(missing_docs)]

mod adjacency;
mod closest;
pub mod contact;
pub mod element;
mod error;
pub mod generate;
mod groups;
pub mod io;
mod locate;
pub mod probes;
mod selection;
mod surface;
mod tet_mesh;
mod zones;

pub use adjacency::Adjacency;
pub use closest::{closest_point_on_triangle, TriangleBvh};
pub use element::{ElementMesh, ElementSurface};
pub use error::MeshError;
pub use groups::{corner_numbering, PhysicalGroup, PhysicalGroups};
pub use locate::TetLocator;
pub use selection::{FaceSelection, Region, VertexSelection};
pub use surface::{check_closed_manifold, hinges, BoundarySurface, TET_FACES};
pub use tet_mesh::{shape_matrix, signed_volume, Orientation, TetMesh, DEGENERACY};
pub use zones::Zones;

/// A 3-vector of `f64`: positions, displacements, forces.
pub type Vec3 = nalgebra::Vector3<f64>;
