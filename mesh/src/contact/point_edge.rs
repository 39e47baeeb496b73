//! Point-point and point-edge squared distances (Li et al. 2020, supplement A): the building
//! blocks of the point-triangle and edge-edge classifications, and distances of their own.

use super::affine::Derivatives;
use super::kind::DistanceKind;
use crate::Vec3;
use nalgebra::{SMatrix, SVector};

/// `|p - q|^2`.
pub fn point_point_squared_distance(p: &Vec3, q: &Vec3) -> f64 {
    (p - q).norm_squared()
}

/// `|p - q|^2` with its gradient and Hessian in `(p, q)`.
pub fn point_point_squared_distance_derivatives(p: &Vec3, q: &Vec3) -> Derivatives<6> {
    restrict(DistanceKind::PointPoint(0, 1).derivatives(&[*p, *q, Vec3::zeros(), Vec3::zeros()]))
}

/// The closest features of point `p` (local 0) and segment `(a, b)` (local 1, 2): an end
/// point when the projection of `p` falls outside the segment (or the segment has no
/// length), else the line.
pub fn point_edge_distance_kind(p: &Vec3, a: &Vec3, b: &Vec3) -> DistanceKind {
    point_edge_kind_of([0, 1, 2], p, a, b)
}

/// The classification with the local indices `[p, a, b]` of the three vertices in a larger
/// pair.
pub(crate) fn point_edge_kind_of(local: [usize; 3], p: &Vec3, a: &Vec3, b: &Vec3) -> DistanceKind {
    let e = b - a;
    let t = (p - a).dot(&e) / e.norm_squared();
    // A zero-length segment gives t = NaN (or +-inf): the end point `a`.
    if t.is_nan() || t <= 0.0 {
        DistanceKind::PointPoint(local[0], local[1])
    } else if t >= 1.0 {
        DistanceKind::PointPoint(local[0], local[2])
    } else {
        DistanceKind::PointEdge(local[0], local[1], local[2])
    }
}

/// Squared distance from `p` to the segment `(a, b)`.
pub fn point_edge_squared_distance(p: &Vec3, a: &Vec3, b: &Vec3) -> f64 {
    point_edge_distance_kind(p, a, b).squared_distance(&[*p, *a, *b, Vec3::zeros()])
}

/// Squared distance from `p` to the segment `(a, b)` with its gradient and Hessian in
/// `(p, a, b)` (those of the closest-feature case: exact away from the case boundaries).
pub fn point_edge_squared_distance_derivatives(p: &Vec3, a: &Vec3, b: &Vec3) -> Derivatives<9> {
    restrict(point_edge_distance_kind(p, a, b).derivatives(&[*p, *a, *b, Vec3::zeros()]))
}

/// The first `D` coordinates of derivatives on four vertices whose last ones carry no weight.
fn restrict<const D: usize>(full: Derivatives<12>) -> Derivatives<D> {
    Derivatives {
        value: full.value,
        gradient: SVector::from(full.gradient.fixed_rows::<D>(0)),
        hessian: SMatrix::from(full.hessian.fixed_view::<D, D>(0, 0)),
    }
}
