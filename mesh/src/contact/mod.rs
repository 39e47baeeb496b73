//! Contact geometry of IPC (Li et al. 2020, "Incremental Potential Contact"): the contact
//! surface of a mesh, the squared distances between its primitives with their
//! closest-feature classification, gradients and Hessians, the edge-edge mollifier,
//! continuous collision detection (Wang et al. 2021) with a minimum separation, a broad
//! phase linear in the surface size, and a check that a surface does not intersect itself.
//!
//! Distances are squared (as in IPC, which puts its barrier on squared distances) and every
//! derivative is with respect to the pair's vertex coordinates, vertex-major: a
//! point-triangle pair is `(p, a, b, c)`, an edge-edge pair `(a0, a1, b0, b1)`.

mod aabb;
mod affine;
mod broad_phase;
mod ccd;
mod edge_edge;
mod hash_grid;
mod intersection;
mod interval;
mod kind;
mod mollifier;
mod point_edge;
mod point_triangle;
mod queries;
mod surface;

pub use aabb::Aabb;
pub use affine::Derivatives;
pub use broad_phase::{contact_candidates, Candidates, PairFilter};
pub use ccd::{edge_edge_ccd, point_triangle_ccd, CcdSettings};
pub use edge_edge::{
    edge_edge_distance_kind, edge_edge_squared_distance, edge_edge_squared_distance_derivatives,
};
pub use intersection::{intersecting_triangles, triangles_intersect};
pub use kind::DistanceKind;
pub use mollifier::{
    edge_edge_cross_squared_derivatives, edge_edge_mollifier, edge_edge_mollifier_derivatives,
    edge_edge_mollifier_threshold,
};
pub use point_edge::{
    point_edge_distance_kind, point_edge_squared_distance, point_edge_squared_distance_derivatives,
    point_point_squared_distance, point_point_squared_distance_derivatives,
};
pub use point_triangle::{
    point_triangle_distance_kind, point_triangle_squared_distance,
    point_triangle_squared_distance_derivatives,
};
pub use queries::{
    parse_ccd_queries, rational_to_f64, read_ccd_queries, CcdQuery, CcdTally, QueryKind,
};
pub use surface::ContactSurface;
