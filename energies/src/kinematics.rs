//! Kinematic quantities shared by every density: flattening, and the first and second
//! derivatives of `J = det F`, which every `J`-based term (log barriers, penalties, `J^-2/3`
//! factors) goes through.
//!
//! `dJ/dF = cof(F) = J F^-T` and `d2J/dF2` are both written with cross products of the columns
//! of `F` (Smith et al. 2018, 2019), so they are defined for singular and inverted `F` too.

use crate::{Matrix9, OutOfDomain, Vector9};
use nalgebra::{Matrix3, Vector3};

/// Column-major flattening `vec(M)[3*j + i] = M[(i, j)]`.
#[inline]
pub fn flatten(m: &Matrix3<f64>) -> Vector9 {
    Vector9::from_column_slice(m.as_slice())
}

/// Inverse of [`flatten`].
#[inline]
pub fn unflatten(v: &Vector9) -> Matrix3<f64> {
    Matrix3::from_column_slice(v.as_slice())
}

/// Cofactor matrix `cof(F) = dJ/dF = J F^-T`, column by column `[f1 x f2, f2 x f0, f0 x f1]`.
#[inline]
pub fn cofactor(f: &Matrix3<f64>) -> Matrix3<f64> {
    let (f0, f1, f2) = columns(f);
    Matrix3::from_columns(&[f1.cross(&f2), f2.cross(&f0), f0.cross(&f1)])
}

/// `d2J/dF2`: the 9x9 Hessian of the determinant in column-major flattening.
pub fn det_hessian(f: &Matrix3<f64>) -> Matrix9 {
    let mut h = Matrix9::zeros();
    add_det_hessian(&mut h, f, 1.0);
    h
}

/// `h += s * d2J/dF2`. Block `(a, b)` of the Hessian (columns `a`, `b` of `F`) is
/// `-eps_abc [f_c]x`, with `[v]x` the cross-product matrix and `eps` the Levi-Civita symbol.
pub fn add_det_hessian(h: &mut Matrix9, f: &Matrix3<f64>, s: f64) {
    // (a, b, c) with eps_abc = +1; the transposed block (b, a) has the opposite sign.
    for (a, b, c) in [(0, 1, 2), (1, 2, 0), (2, 0, 1)] {
        let v = f.column(c) * s;
        let (r, q) = (3 * a, 3 * b);
        // -[v]x at block (a, b) and +[v]x at block (b, a) (the transpose of -[v]x).
        h[(r + 1, q)] -= v[2];
        h[(r + 2, q)] += v[1];
        h[(r, q + 1)] += v[2];
        h[(r + 2, q + 1)] -= v[0];
        h[(r, q + 2)] -= v[1];
        h[(r + 1, q + 2)] += v[0];
        h[(q + 1, r)] += v[2];
        h[(q + 2, r)] -= v[1];
        h[(q, r + 1)] -= v[2];
        h[(q + 2, r + 1)] += v[0];
        h[(q, r + 2)] += v[1];
        h[(q + 1, r + 2)] -= v[0];
    }
}

/// Adds the tangent of a term `g(J)` with `g'(J) = d1`, `g''(J) = d2`:
/// `h += d2 vec(cof F) vec(cof F)^T + d1 d2J/dF2` (its stress is `d1 cof F`).
pub fn add_volumetric_tangent(h: &mut Matrix9, f: &Matrix3<f64>, d1: f64, d2: f64) {
    let g = flatten(&cofactor(f));
    h.ger(d2, &g, &g, 1.0);
    add_det_hessian(h, f, d1);
}

/// First invariant `I_C = tr(F^T F) = |F|_F^2`.
#[inline]
pub fn first_invariant(f: &Matrix3<f64>) -> f64 {
    f.norm_squared()
}

/// `J = det F` if it is positive, else [`OutOfDomain`] for `energy` (also for NaN).
pub(crate) fn positive_determinant(
    energy: &'static str,
    f: &Matrix3<f64>,
) -> Result<f64, OutOfDomain> {
    let j = f.determinant();
    if j > 0.0 {
        Ok(j)
    } else {
        Err(OutOfDomain { energy, j })
    }
}

fn columns(f: &Matrix3<f64>) -> (Vector3<f64>, Vector3<f64>, Vector3<f64>) {
    (f.column(0).into(), f.column(1).into(), f.column(2).into())
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;

    fn sample() -> Matrix3<f64> {
        Matrix3::new(1.1, 0.2, -0.3, 0.05, 0.9, 0.4, -0.2, 0.1, 1.3)
    }

    #[test]
    fn cofactor_is_j_f_inverse_transpose() {
        let f = sample();
        let expected = f.determinant() * f.try_inverse().unwrap().transpose();
        assert_relative_eq!(cofactor(&f), expected, max_relative = 1e-14);
    }

    #[test]
    fn det_hessian_is_derivative_of_cofactor() {
        let f = sample();
        let h = det_hessian(&f);
        let eps = 1e-6;
        for k in 0..9 {
            let mut fp = flatten(&f);
            let mut fm = fp;
            fp[k] += eps;
            fm[k] -= eps;
            let col = (flatten(&cofactor(&unflatten(&fp))) - flatten(&cofactor(&unflatten(&fm))))
                / (2.0 * eps);
            assert_relative_eq!(h.column(k).into_owned(), col, epsilon = 1e-9);
        }
        assert_eq!(h, h.transpose());
    }
}
