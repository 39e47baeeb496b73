//! The closest-feature classification of IPC (Li et al. 2020, supplement A): which pair of
//! features (vertex, edge, face) realizes a point-triangle or edge-edge distance.

use super::affine::{AffineResidual, Derivatives};
use crate::Vec3;

/// The closest features of a pair, by local vertex: for point-triangle pairs `0` is the point
/// and `1, 2, 3` the triangle; for edge-edge pairs `0, 1` are edge `a` and `2, 3` edge `b`
/// (point-edge pairs use `0` for the point and `1, 2` for the edge).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum DistanceKind {
    /// Between vertices `i` and `j`: `|x_i - x_j|^2`.
    PointPoint(usize, usize),
    /// Between vertex `p` and the line through vertices `a`, `b`.
    PointEdge(usize, usize, usize),
    /// Between the point (vertex 0) and the plane of the triangle (vertices 1, 2, 3).
    PointPlane,
    /// Between the lines of the two edges (vertices 0, 1 and 2, 3).
    LineLine,
}

/// Runs `$body` with `$r` the residual whose minimal squared norm is the distance of `$kind`
/// over four vertices (the residual's type depends on the number of parameters).
macro_rules! with_residual {
    ($kind:expr, |$r:ident| $body:expr) => {{
        let pair = |i: usize, j: usize| -> [f64; 4] {
            let mut w = [0.0; 4];
            w[i] = 1.0;
            w[j] = -1.0;
            w
        };
        match $kind {
            DistanceKind::PointPoint(i, j) => {
                let $r = AffineResidual::<4, 0> {
                    w0: pair(i, j),
                    dw: [],
                };
                $body
            }
            DistanceKind::PointEdge(p, a, b) => {
                // r = x_p - x_a - l (x_b - x_a)
                let $r = AffineResidual::<4, 1> {
                    w0: pair(p, a),
                    dw: [pair(a, b)],
                };
                $body
            }
            DistanceKind::PointPlane => {
                // r = p - a - l1 (b - a) - l2 (c - a)
                let $r = AffineResidual::<4, 2> {
                    w0: pair(0, 1),
                    dw: [pair(1, 2), pair(1, 3)],
                };
                $body
            }
            DistanceKind::LineLine => {
                // r = a0 + l1 (a1 - a0) - b0 - l2 (b1 - b0)
                let $r = AffineResidual::<4, 2> {
                    w0: pair(0, 2),
                    dw: [pair(1, 0), pair(2, 3)],
                };
                $body
            }
        }
    }};
}

impl DistanceKind {
    /// The squared distance of this kind between the features of `x` (the pair's four
    /// vertices), e.g. of a kind fixed for a Newton iteration.
    pub fn squared_distance(self, x: &[Vec3; 4]) -> f64 {
        with_residual!(self, |r| r.value(x))
    }

    /// The squared distance of this kind with its gradient and Hessian (12 coordinates).
    pub fn derivatives(self, x: &[Vec3; 4]) -> Derivatives<12> {
        with_residual!(self, |r| r.derivatives::<12>(x))
    }

    /// The weights `w` with `sum_i w_i x_i` the vector between the closest points (from the
    /// second feature to the first); they sum to zero. The relative motion of the closest
    /// points is `sum_i w_i u_i` for vertex motions `u` (the operator of IPC's friction).
    pub fn weights(self, x: &[Vec3; 4]) -> [f64; 4] {
        with_residual!(self, |r| r.weights(x))
    }
}
