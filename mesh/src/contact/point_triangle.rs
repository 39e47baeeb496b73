//! Point-triangle squared distance with the closest-feature classification of IPC (Li et al.
//! 2020, supplement A): the plane where the projection falls inside the triangle, else the
//! nearest of its three edges (each an edge or one of its end points).

use super::affine::Derivatives;
use super::kind::DistanceKind;
use super::point_edge::point_edge_kind_of;
use crate::Vec3;

/// Below `DEGENERATE * |e0|^2 |e1|^2` the Gram determinant counts as zero: the triangle (or
/// the pair of edges) is treated as degenerate (parallel) and its boundary cases are used.
pub(crate) const DEGENERATE: f64 = 1e-20;

/// The closest features of point `p` (local 0) and triangle `(a, b, c)` (local 1, 2, 3).
pub fn point_triangle_distance_kind(p: &Vec3, a: &Vec3, b: &Vec3, c: &Vec3) -> DistanceKind {
    let (e0, e1, ap) = (b - a, c - a, p - a);
    let (g00, g01, g11) = (e0.norm_squared(), e0.dot(&e1), e1.norm_squared());
    // g00 g11 - g01^2, without its cancellation.
    let det = e0.cross(&e1).norm_squared();
    if det > DEGENERATE * g00 * g11 {
        let (r0, r1) = (e0.dot(&ap), e1.dot(&ap));
        let l1 = (g11 * r0 - g01 * r1) / det;
        let l2 = (g00 * r1 - g01 * r0) / det;
        if l1 >= 0.0 && l2 >= 0.0 && l1 + l2 <= 1.0 {
            return DistanceKind::PointPlane;
        }
    }
    let x = [*p, *a, *b, *c];
    [[1, 2], [2, 3], [3, 1]]
        .map(|[i, j]| point_edge_kind_of([0, i, j], p, &x[i], &x[j]))
        .into_iter()
        .map(|kind| (kind.squared_distance(&x), kind))
        .min_by(|a, b| a.0.total_cmp(&b.0))
        .map(|(_, kind)| kind)
        .unwrap_or(DistanceKind::PointPoint(0, 1))
}

/// Squared distance from `p` to the triangle `(a, b, c)`.
pub fn point_triangle_squared_distance(p: &Vec3, a: &Vec3, b: &Vec3, c: &Vec3) -> f64 {
    point_triangle_distance_kind(p, a, b, c).squared_distance(&[*p, *a, *b, *c])
}

/// Squared distance from `p` to the triangle `(a, b, c)` with its gradient and Hessian in
/// `(p, a, b, c)`.
pub fn point_triangle_squared_distance_derivatives(
    p: &Vec3,
    a: &Vec3,
    b: &Vec3,
    c: &Vec3,
) -> Derivatives<12> {
    point_triangle_distance_kind(p, a, b, c).derivatives(&[*p, *a, *b, *c])
}
