//! Lagged smoothed friction of IPC (Li et al. 2020, sec. 5): the tangent basis of a pair and
//! the relative tangential motion of its closest points, both frozen at the lagged state,
//! and the friction potential `D(u) = mu lambda f0(|T^T Gamma u|)` of the vertex motions `u`
//! over the step, with the smoothed static-to-kinetic transition
//!
//! `f1(y) = -y^2 / epsv^2 + 2 y / epsv` for `y < epsv`, else 1 (eq. 14), and `f0' = f1`,
//! `f0(epsv) = epsv`: `f0(y) = -y^3 / (3 epsv^2) + y^2 / epsv + epsv / 3` below `epsv`.
//!
//! Here `u` is a displacement over the step and `epsv` a slip length (IPC's velocity
//! `epsv` times the time step); in quasi-static runs the slip is the step's increment.

use isochor_mesh::contact::{Derivatives, DistanceKind};
use isochor_mesh::Vec3;
use nalgebra::{Matrix2, Matrix3x2, SMatrix, SVector, Vector2};

/// `f0(y)`: the smoothed `|y|`, the friction potential per unit force.
pub fn friction_f0(y: f64, epsv: f64) -> f64 {
    if y < epsv {
        -y * y * y / (3.0 * epsv * epsv) + y * y / epsv + epsv / 3.0
    } else {
        y
    }
}

/// `f1(y) = f0'(y)`: the friction force per unit normal force, from 0 at rest to 1 at slip
/// `epsv`.
pub fn friction_f1(y: f64, epsv: f64) -> f64 {
    if y < epsv {
        -y * y / (epsv * epsv) + 2.0 * y / epsv
    } else {
        1.0
    }
}

/// `f1(y) / y` (finite at 0: `2 / epsv`).
fn f1_over_y(y: f64, epsv: f64) -> f64 {
    if y < epsv {
        -y / (epsv * epsv) + 2.0 / epsv
    } else {
        1.0 / y
    }
}

/// `(f1'(y) y - f1(y)) / y^3`, the coefficient of `tau tau^T` in the Hessian.
fn f1_curvature(y: f64, epsv: f64) -> f64 {
    if y < epsv {
        -1.0 / (epsv * epsv * y)
    } else {
        -1.0 / (y * y * y)
    }
}

/// A unit vector orthogonal to `n` (the axis least aligned with it, made orthogonal).
fn orthogonal(n: &Vec3) -> Vec3 {
    let axis = Vec3::ith(n.iamin(), 1.0);
    (axis - n * (n.dot(&axis) / n.norm_squared())).normalize()
}

/// Two orthonormal tangent directions of a pair's closest features (columns), orthogonal to
/// its normal direction: the triangle's plane for [`DistanceKind::PointPlane`]; the plane of
/// both edge directions for [`DistanceKind::LineLine`]; the edge and the normal of the plane
/// through point and edge for [`DistanceKind::PointEdge`]; any two directions orthogonal to
/// the line of the points for [`DistanceKind::PointPoint`]. `x` is the pair's four vertices
/// (as for the distances).
pub fn tangent_basis(kind: DistanceKind, x: &[Vec3; 4]) -> Matrix3x2<f64> {
    let (first, normal) = match kind {
        DistanceKind::PointPlane => {
            let e = x[2] - x[1];
            (e, e.cross(&(x[3] - x[1])))
        }
        DistanceKind::LineLine => {
            let e = x[1] - x[0];
            (e, e.cross(&(x[3] - x[2])))
        }
        DistanceKind::PointEdge(p, a, b) => {
            let e = x[b] - x[a];
            (e, e.cross(&(x[p] - x[a])).cross(&e))
        }
        DistanceKind::PointPoint(i, j) => return plane_basis(&(x[i] - x[j])),
    };
    let t0 = first.normalize();
    let t1 = normal.cross(&t0).normalize();
    Matrix3x2::from_columns(&[t0, t1])
}

/// Two orthonormal directions (columns) of the plane normal to `normal` (any length but
/// zero): the tangent plane of an obstacle at a vertex, or of a point-point pair.
pub fn plane_basis(normal: &Vec3) -> Matrix3x2<f64> {
    let t0 = orthogonal(normal);
    let t1 = normal.cross(&t0).normalize();
    Matrix3x2::from_columns(&[t0, t1])
}

/// The friction of one pair, frozen at the lagged state.
#[derive(Debug, Clone, PartialEq)]
pub struct FrictionPair {
    /// The pair's tangent basis `T` (from [`tangent_basis`]).
    pub basis: Matrix3x2<f64>,
    /// The closest-point weights `w` (from [`DistanceKind::weights`]): `Gamma u = sum_i w_i
    /// u_i`, the relative motion of the closest points.
    pub weights: [f64; 4],
    /// `mu lambda`: the friction coefficient times the lagged normal force
    /// (see [`super::normal_force`]).
    pub mu_lambda: f64,
    /// The slip below which friction is static (smoothed).
    pub epsv: f64,
}

impl FrictionPair {
    /// The pair of closest features `kind` at the lagged vertex positions `x`.
    pub fn new(kind: DistanceKind, x: &[Vec3; 4], mu_lambda: f64, epsv: f64) -> Self {
        FrictionPair {
            basis: tangent_basis(kind, x),
            weights: kind.weights(x),
            mu_lambda,
            epsv,
        }
    }

    /// The tangential relative motion `tau = T^T Gamma u` of the vertex motions `u`.
    pub fn tangential_motion(&self, u: &[Vec3; 4]) -> Vector2<f64> {
        let relative: Vec3 = (0..4).map(|i| u[i] * self.weights[i]).sum();
        self.basis.transpose() * relative
    }

    /// `D(u) = mu lambda f0(|tau|)`.
    pub fn potential(&self, u: &[Vec3; 4]) -> f64 {
        self.mu_lambda * friction_f0(self.tangential_motion(u).norm(), self.epsv)
    }

    /// `D(u)` with its gradient `mu lambda f1(y)/y Gamma^T T tau` and Hessian `mu lambda
    /// Gamma^T T M T^T Gamma`, `M = f1/y I + (f1' y - f1)/y^3 tau tau^T`, in the twelve
    /// motion coordinates; `M` is positive semidefinite for this `f1`, so the Hessian is too.
    pub fn derivatives(&self, u: &[Vec3; 4]) -> Derivatives<12> {
        let tau = self.tangential_motion(u);
        let y = tau.norm();
        let mut m = Matrix2::identity() * f1_over_y(y, self.epsv);
        if y > 0.0 {
            m += tau * tau.transpose() * f1_curvature(y, self.epsv);
        }
        // Gamma^T T: block i is w_i T (3 x 2).
        let mut gt = SMatrix::<f64, 12, 2>::zeros();
        for i in 0..4 {
            gt.fixed_view_mut::<3, 2>(3 * i, 0)
                .copy_from(&(self.basis * self.weights[i]));
        }
        let gradient: SVector<f64, 12> = gt * tau * (self.mu_lambda * f1_over_y(y, self.epsv));
        Derivatives {
            value: self.mu_lambda * friction_f0(y, self.epsv),
            gradient,
            hessian: gt * m * gt.transpose() * self.mu_lambda,
        }
    }
}
