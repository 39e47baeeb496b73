//! Edge-edge squared distance with the closest-feature classification of IPC (Li et al.
//! 2020, supplement A): the lines where both closest parameters fall inside the edges (and
//! the edges are not parallel), else the nearest of the four end-point-to-edge cases.

use super::affine::Derivatives;
use super::kind::DistanceKind;
use super::point_edge::point_edge_kind_of;
use super::point_triangle::DEGENERATE;
use crate::Vec3;

/// The closest features of edges `(a0, a1)` (local 0, 1) and `(b0, b1)` (local 2, 3).
pub fn edge_edge_distance_kind(a0: &Vec3, a1: &Vec3, b0: &Vec3, b1: &Vec3) -> DistanceKind {
    let (u, v, w) = (a1 - a0, b1 - b0, a0 - b0);
    let (a, b, c) = (u.norm_squared(), u.dot(&v), v.norm_squared());
    let (d, e) = (u.dot(&w), v.dot(&w));
    // a c - b^2, without its cancellation (exactly parallel edges give a rounding-level
    // determinant, far below the threshold).
    let det = u.cross(&v).norm_squared();
    if det > DEGENERATE * a * c {
        let s = (b * e - c * d) / det;
        let t = (a * e - b * d) / det;
        if s > 0.0 && s < 1.0 && t > 0.0 && t < 1.0 {
            return DistanceKind::LineLine;
        }
    }
    let x = [*a0, *a1, *b0, *b1];
    [[0, 2, 3], [1, 2, 3], [2, 0, 1], [3, 0, 1]]
        .map(|[p, i, j]| point_edge_kind_of([p, i, j], &x[p], &x[i], &x[j]))
        .into_iter()
        .map(|kind| (kind.squared_distance(&x), kind))
        .min_by(|a, b| a.0.total_cmp(&b.0))
        .map(|(_, kind)| kind)
        .unwrap_or(DistanceKind::PointPoint(0, 2))
}

/// Squared distance between the segments `(a0, a1)` and `(b0, b1)`.
pub fn edge_edge_squared_distance(a0: &Vec3, a1: &Vec3, b0: &Vec3, b1: &Vec3) -> f64 {
    edge_edge_distance_kind(a0, a1, b0, b1).squared_distance(&[*a0, *a1, *b0, *b1])
}

/// Squared distance between the segments with its gradient and Hessian in
/// `(a0, a1, b0, b1)`.
pub fn edge_edge_squared_distance_derivatives(
    a0: &Vec3,
    a1: &Vec3,
    b0: &Vec3,
    b1: &Vec3,
) -> Derivatives<12> {
    edge_edge_distance_kind(a0, a1, b0, b1).derivatives(&[*a0, *a1, *b0, *b1])
}
