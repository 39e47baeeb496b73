//! The edge-edge mollifier of IPC (Li et al. 2020, sec. 4.3, eq. 12): near-parallel edges
//! have a barrier multiplied by `e_k(c) = (2 - c / eps_x) c / eps_x` for `c < eps_x` (else 1)
//! on `c = |(a1 - a0) x (b1 - b0)|^2`, which makes the edge-edge barrier smooth where the
//! closest-feature case switches at parallel edges.

use super::affine::Derivatives;
use crate::Vec3;
use nalgebra::{Matrix3, SMatrix, SVector};

/// The threshold `eps_x = 1e-3 |a1 - a0|^2 |b1 - b0|^2` of two edges at rest.
pub fn edge_edge_mollifier_threshold(a0: &Vec3, a1: &Vec3, b0: &Vec3, b1: &Vec3) -> f64 {
    1e-3 * (a1 - a0).norm_squared() * (b1 - b0).norm_squared()
}

/// `c = |(a1 - a0) x (b1 - b0)|^2 = |u|^2 |v|^2 - (u . v)^2` with its gradient and Hessian in
/// `(a0, a1, b0, b1)`.
pub fn edge_edge_cross_squared_derivatives(x: &[Vec3; 4]) -> Derivatives<12> {
    let (u, v) = (x[1] - x[0], x[3] - x[2]);
    let (uu, uv, vv) = (u.norm_squared(), u.dot(&v), v.norm_squared());
    let du = u * (2.0 * vv) - v * (2.0 * uv);
    let dv = v * (2.0 * uu) - u * (2.0 * uv);
    let id = Matrix3::identity();
    let duu = id * (2.0 * vv) - v * v.transpose() * 2.0;
    let dvv = id * (2.0 * uu) - u * u.transpose() * 2.0;
    let duv = u * v.transpose() * 4.0 - v * u.transpose() * 2.0 - id * (2.0 * uv);
    // u = x1 - x0, v = x3 - x2: the sign of each vertex in its edge vector.
    let sign = [-1.0, 1.0, -1.0, 1.0];
    let mut gradient = SVector::<f64, 12>::zeros();
    let mut hessian = SMatrix::<f64, 12, 12>::zeros();
    for i in 0..4 {
        let d = if i < 2 { du } else { dv };
        gradient
            .fixed_rows_mut::<3>(3 * i)
            .copy_from(&(d * sign[i]));
        for j in 0..4 {
            let block = match (i < 2, j < 2) {
                (true, true) => duu,
                (false, false) => dvv,
                (true, false) => duv,
                (false, true) => duv.transpose(),
            };
            hessian
                .fixed_view_mut::<3, 3>(3 * i, 3 * j)
                .copy_from(&(block * (sign[i] * sign[j])));
        }
    }
    Derivatives {
        value: u.cross(&v).norm_squared(),
        gradient,
        hessian,
    }
}

/// `e_k(c)` and its first and second derivatives in `c`.
fn mollifier_of_cross(c: f64, eps_x: f64) -> (f64, f64, f64) {
    if c < eps_x {
        let s = c / eps_x;
        (
            (2.0 - s) * s,
            (2.0 - 2.0 * s) / eps_x,
            -2.0 / (eps_x * eps_x),
        )
    } else {
        (1.0, 0.0, 0.0)
    }
}

/// The mollifier `e_k` of edges `x = [a0, a1, b0, b1]` with threshold `eps_x`.
pub fn edge_edge_mollifier(x: &[Vec3; 4], eps_x: f64) -> f64 {
    let (u, v) = (x[1] - x[0], x[3] - x[2]);
    mollifier_of_cross(u.cross(&v).norm_squared(), eps_x).0
}

/// The mollifier with its gradient and Hessian in `(a0, a1, b0, b1)`.
pub fn edge_edge_mollifier_derivatives(x: &[Vec3; 4], eps_x: f64) -> Derivatives<12> {
    let c = edge_edge_cross_squared_derivatives(x);
    let (e, de, dde) = mollifier_of_cross(c.value, eps_x);
    Derivatives {
        value: e,
        gradient: c.gradient * de,
        hessian: c.hessian * de + c.gradient * c.gradient.transpose() * dde,
    }
}
