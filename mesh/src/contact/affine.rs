//! The one kernel behind every squared distance and its derivatives: the squared norm of an
//! affine combination of the vertices, minimized over its free parameters.
//!
//! Every closest-feature case of IPC (Li et al. 2020, sec. 4 and supplement A) is of the form
//! `d(x) = min_lambda phi(x, lambda)`, `phi = |r|^2`, `r(x, lambda) = sum_i w_i(lambda) x_i`,
//! with weights affine in `lambda` (none for point-point, one for point-edge, two for
//! point-triangle and edge-edge). At the interior minimizer `lambda*` the envelope theorem
//! gives the closed forms
//!
//! `grad d = phi_x`, `hess d = phi_xx - phi_xl phi_ll^-1 phi_lx`,
//!
//! with `phi_x = 2 w_i r`, `phi_xx = 2 w_i w_j I`, `phi_ll = 2 E^T E` (`E` the columns
//! `e_k = dr/dlambda_k`) and `phi_xl = 2 (dw_ik r + w_i e_k)`: exact, and symmetric by
//! construction.

use crate::Vec3;
use nalgebra::{SMatrix, SVector};

/// `r = sum_i (w0_i + sum_k lambda_k dw_ki) x_i` over `N` vertices with `K <= 2` parameters.
pub(crate) struct AffineResidual<const N: usize, const K: usize> {
    /// Weights at `lambda = 0`.
    pub(crate) w0: [f64; N],
    /// `dw[k][i] = d w_i / d lambda_k`.
    pub(crate) dw: [[f64; N]; K],
}

/// A scalar function of vertex positions (a squared distance, a mollifier) with its gradient
/// and Hessian with respect to the `D = 3 N` vertex
/// coordinates (vertex-major: `x_0, y_0, z_0, x_1, ...`).
#[derive(Debug, Clone, PartialEq)]
pub struct Derivatives<const D: usize> {
    /// The value.
    pub value: f64,
    /// Its gradient.
    pub gradient: SVector<f64, D>,
    /// Its Hessian (symmetric, not projected: it is indefinite in general).
    pub hessian: SMatrix<f64, D, D>,
}

impl<const N: usize, const K: usize> AffineResidual<N, K> {
    /// The minimizing parameters `lambda*` (unconstrained) and the weights there. The caller
    /// only uses this case where `E^T E` is well conditioned and `lambda*` is interior.
    fn solve(&self, x: &[Vec3; N]) -> [f64; N] {
        let combine = |w: &[f64; N]| -> Vec3 { (0..N).map(|i| x[i] * w[i]).sum() };
        let r0 = combine(&self.w0);
        let e: [Vec3; K] = std::array::from_fn(|k| combine(&self.dw[k]));
        // Normal equations E^T E lambda = -E^T r0.
        let rhs: [f64; K] = std::array::from_fn(|k| -e[k].dot(&r0));
        let lambda: [f64; K] = match K {
            0 => std::array::from_fn(|_| 0.0),
            1 => std::array::from_fn(|_| rhs[0] / e[0].norm_squared()),
            _ => {
                let (a, b, c) = (e[0].norm_squared(), e[0].dot(&e[1]), e[1].norm_squared());
                // a c - b^2, without its cancellation.
                let det = e[0].cross(&e[1]).norm_squared();
                let l = [
                    (c * rhs[0] - b * rhs[1]) / det,
                    (a * rhs[1] - b * rhs[0]) / det,
                ];
                std::array::from_fn(|k| l[k])
            }
        };
        let mut w = self.w0;
        for (l, dw) in lambda.iter().zip(&self.dw) {
            for (wi, dwi) in w.iter_mut().zip(dw) {
                *wi += l * dwi;
            }
        }
        w
    }

    /// The minimum of `|r|^2` over `lambda`.
    pub(crate) fn value(&self, x: &[Vec3; N]) -> f64 {
        let w = self.solve(x);
        (0..N).map(|i| x[i] * w[i]).sum::<Vec3>().norm_squared()
    }

    /// The minimum with its gradient and Hessian; `D` must be `3 N`.
    pub(crate) fn derivatives<const D: usize>(&self, x: &[Vec3; N]) -> Derivatives<D> {
        debug_assert_eq!(D, 3 * N);
        let w = self.solve(x);
        let r: Vec3 = (0..N).map(|i| x[i] * w[i]).sum();
        let e: [Vec3; K] = std::array::from_fn(|k| (0..N).map(|i| x[i] * self.dw[k][i]).sum());
        let mut gradient = SVector::<f64, D>::zeros();
        let mut hessian = SMatrix::<f64, D, D>::zeros();
        for i in 0..N {
            gradient
                .fixed_rows_mut::<3>(3 * i)
                .copy_from(&(r * (2.0 * w[i])));
            for j in 0..N {
                for a in 0..3 {
                    hessian[(3 * i + a, 3 * j + a)] = 2.0 * w[i] * w[j];
                }
            }
        }
        if K > 0 {
            // phi_ll^-1 = (2 E^T E)^-1, written out for K = 1, 2.
            let gram = |k: usize, l: usize| 2.0 * e[k].dot(&e[l]);
            let inverse: [[f64; 2]; 2] = if K == 1 {
                [[1.0 / gram(0, 0), 0.0], [0.0, 0.0]]
            } else {
                let (a, b, c) = (gram(0, 0), gram(0, 1), gram(1, 1));
                let det = 4.0 * e[0].cross(&e[1]).norm_squared();
                [[c / det, -b / det], [-b / det, a / det]]
            };
            // B = phi_xl, D x K.
            let mut mixed = [SVector::<f64, D>::zeros(); 2];
            for (k, column) in mixed.iter_mut().enumerate().take(K) {
                for (i, wi) in w.iter().enumerate() {
                    let block = r * (2.0 * self.dw[k][i]) + e[k] * (2.0 * wi);
                    column.fixed_rows_mut::<3>(3 * i).copy_from(&block);
                }
            }
            for k in 0..K {
                for l in 0..K {
                    hessian -= mixed[k] * mixed[l].transpose() * inverse[k][l];
                }
            }
        }
        Derivatives {
            value: r.norm_squared(),
            gradient,
            hessian,
        }
    }

    /// The weights at the minimizer: the affine combination whose norm is the distance.
    pub(crate) fn weights(&self, x: &[Vec3; N]) -> [f64; N] {
        self.solve(x)
    }
}
