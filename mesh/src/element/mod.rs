//! The element layer: reference elements, quadrature, isoparametric rest geometry and meshes
//! of 4- or 10-node tetrahedra. Geometry only, no physics: energies, constraints and loads
//! evaluate their integrands at the quadrature points this layer provides.
//!
//! - [`TetElement`] (`Tet4`, `Tet10`) and [`TriElement`] (`Tri3`, `Tri6`): shape functions
//!   and their reference gradients, node coordinates, faces and edges.
//! - [`TetQuadrature`] and [`TriQuadrature`]: rules of stated degree, all with positive
//!   weights.
//! - [`deformation_gradient`]: `F = sum_a x_a (dN_a/dX)^T`, the one kernel for every
//!   gradient of an interpolated map.
//! - [`ElementMesh`]: a [`crate::TetMesh`] of corners plus mid-edge nodes; [`RestGeometry`]:
//!   `w_q det(dX/dxi)` and `dN_a/dX` per element and quadrature point; [`ElementSurface`]:
//!   the boundary as 3- or 6-node triangles; [`ElementMesh::disjoint_union`]: several
//!   bodies as one mesh, each a [`Part`] of it.
//!
//! # Node order
//!
//! Corners first, then mid-edge nodes, in Gmsh's order (the reference manual's section "Node
//! ordering"; element types 4, 11, 2 and 9):
//!
//! | local node | 4, 5, 6 | 7, 8, 9 |
//! |---|---|---|
//! | 10-node tet (Gmsh type 11, ours) | edges (0,1), (1,2), (0,2) | edges (0,3), (2,3), (1,3) |
//! | VTK quadratic tetra (cell type 24) | edges (0,1), (1,2), (0,2) | edges (0,3), (1,3), (2,3) |
//!
//! | local node | 3, 4, 5 |
//! |---|---|
//! | 6-node triangle (Gmsh type 9, VTK cell type 22, ours) | edges (0,1), (1,2), (2,0) |
//!
//! So VTK's nodes 8 and 9 are our 9 and 8; [`TetElement::vtk_order`] is that permutation
//! (its own inverse), applied by the VTU writer and reader.

mod deformed;
mod gradient;
mod lagrange;
mod lumping;
mod mesh;
mod quadrature;
mod rest;
mod surface;
mod tet;
mod triangle;
mod union;

pub use gradient::deformation_gradient;
pub use mesh::ElementMesh;
pub(crate) use mesh::Labels;
pub use quadrature::{TetQuadrature, TriQuadrature};
pub use rest::RestGeometry;
pub(crate) use surface::faces_enclosed_volume;
pub use surface::ElementSurface;
pub use tet::{TetElement, TET_EDGES};
pub use triangle::{TriElement, TRI_EDGES};
pub use union::Part;
