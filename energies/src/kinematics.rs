//! Kinematic quantities shared by every density: flattening, the first and second
//! derivatives of `J = det F`, which every `J`-based term (log barriers, penalties, `J^-2/3`
//! factors) goes through, and the invariants of `C = F^T F`, plain and isochoric, with their
//! gradients and Hessians.
//!
//! `dJ/dF = cof(F) = J F^-T` and `d2J/dF2` are both written with cross products of the columns
//! of `F` (Smith et al. 2018, 2019), so they are defined for singular and inverted `F` too.
//!
//! The invariant densities `W(Ib1, Ib2)` (Bonet-Wood, Mooney-Rivlin, Yeoh) get their stress
//! and tangent from [`IsochoricInvariants`] and the chain rule of
//! [`IsochoricInvariants::stress`] and [`IsochoricInvariants::tangent`].

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

/// Second invariant `I_2 = ((tr C)^2 - tr(C^2)) / 2 = |cof F|_F^2` (the sum of the principal
/// minors of `C`, i.e. `tr cof C`, and `cof C = cof(F)^T cof(F)`).
#[inline]
pub fn second_invariant(f: &Matrix3<f64>) -> f64 {
    cofactor(f).norm_squared()
}

/// A function `a(J)` of the volume ratio with its first two derivatives: the factor of a
/// scaled invariant `a(J) I(F)` such as `J^-2/3 I_1`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct VolumeFactor {
    /// `a(J)`.
    pub a: f64,
    /// `a'(J)`.
    pub da: f64,
    /// `a''(J)`.
    pub dda: f64,
}

impl VolumeFactor {
    /// `a = J^-2/3`, `a' = -2/3 a / J`, `a'' = 10/9 a / J^2`, for `J > 0`.
    pub fn isochoric_first(j: f64) -> Self {
        let c = j.cbrt();
        let a = 1.0 / (c * c);
        VolumeFactor {
            a,
            da: -2.0 / 3.0 * a / j,
            dda: 10.0 / 9.0 * a / (j * j),
        }
    }

    /// `a = J^-4/3`, `a' = -4/3 a / J`, `a'' = 28/9 a / J^2`, for `J > 0`.
    pub fn isochoric_second(j: f64) -> Self {
        let c = j.cbrt();
        let a = 1.0 / (c * c * c * c);
        VolumeFactor {
            a,
            da: -4.0 / 3.0 * a / j,
            dda: 28.0 / 9.0 * a / (j * j),
        }
    }

    /// `a = J^p`, `a' = p a / J`, `a'' = p (p - 1) a / J^2`, for `J > 0` (Ogden's
    /// `J^(-alpha/3)`).
    pub fn power(j: f64, p: f64) -> Self {
        let a = j.powf(p);
        VolumeFactor {
            a,
            da: p * a / j,
            dda: p * (p - 1.0) * a / (j * j),
        }
    }

    /// Gradient of `a(J) I(F)`: `a dI/dF + a' I g`, with `g = vec(cof F) = dJ/dF`.
    pub fn scaled_gradient(&self, i: f64, di: &Vector9, g: &Vector9) -> Vector9 {
        di * self.a + g * (self.da * i)
    }

    /// Hessian of `a(J) I(F)`:
    /// `a d2I + a' (dI g^T + g dI^T) + a'' I g g^T + a' I d2J/dF2`, with `g = vec(cof F)`.
    pub fn scaled_hessian(
        &self,
        f: &Matrix3<f64>,
        i: f64,
        di: &Vector9,
        d2i: &Matrix9,
        g: &Vector9,
    ) -> Matrix9 {
        let mut h = d2i * self.a;
        h.ger(self.dda * i, g, g, 1.0);
        h.ger(self.da, di, g, 1.0);
        h.ger(self.da, g, di, 1.0);
        add_det_hessian(&mut h, f, self.da * i);
        h
    }
}

/// First and second partial derivatives of an invariant density `W(Ib1, Ib2)`, the input of
/// the chain rule [`IsochoricInvariants::stress`] and [`IsochoricInvariants::tangent`].
/// A density of `Ib1` alone leaves the `Ib2` terms zero (the default).
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct InvariantPartials {
    /// `dW/dIb1`.
    pub w1: f64,
    /// `dW/dIb2`.
    pub w2: f64,
    /// `d2W/dIb1^2`.
    pub w11: f64,
    /// `d2W/dIb1 dIb2`.
    pub w12: f64,
    /// `d2W/dIb2^2`.
    pub w22: f64,
}

impl InvariantPartials {
    fn uses_second_invariant(&self) -> bool {
        self.w2 != 0.0 || self.w12 != 0.0 || self.w22 != 0.0
    }
}

/// The isochoric invariants `Ib1 = J^-2/3 I_1` and `Ib2 = J^-4/3 I_2` of `C = F^T F`
/// (`I_1 = tr C`, `I_2 = ((tr C)^2 - tr(C^2)) / 2`), for `J > 0`, with their gradients and
/// Hessians with respect to `F` (column-major flattening).
///
/// With `g = vec(cof F)` and `H_J = d2J/dF2`: `dI_1/dF = 2 vec(F)`, `d2I_1/dF2 = 2 I`;
/// `I_2 = |cof F|^2`, so `dI_2/dF = 2 H_J g` and `d2I_2/dF2 = 2 H_J H_J + 2 H_J(cof F)`, the
/// last term being [`det_hessian`] evaluated at `cof F` (`H_J(F) v` is bilinear and symmetric
/// in `F` and `v`). The factors `J^-2/3`, `J^-4/3` enter through [`VolumeFactor`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct IsochoricInvariants {
    f: Matrix3<f64>,
    cof: Matrix3<f64>,
    i1: f64,
    i2: f64,
    a1: VolumeFactor,
    a2: VolumeFactor,
}

impl IsochoricInvariants {
    /// The invariants of `f`; [`OutOfDomain`] for `energy` unless `det F > 0`.
    pub fn new(energy: &'static str, f: &Matrix3<f64>) -> Result<Self, OutOfDomain> {
        let j = positive_determinant(energy, f)?;
        let cof = cofactor(f);
        Ok(IsochoricInvariants {
            f: *f,
            cof,
            i1: first_invariant(f),
            i2: cof.norm_squared(),
            a1: VolumeFactor::isochoric_first(j),
            a2: VolumeFactor::isochoric_second(j),
        })
    }

    /// `Ib1 = J^-2/3 I_1`.
    pub fn ib1(&self) -> f64 {
        self.a1.a * self.i1
    }

    /// `Ib2 = J^-4/3 I_2`.
    pub fn ib2(&self) -> f64 {
        self.a2.a * self.i2
    }

    /// `dIb1/dF`.
    pub fn ib1_gradient(&self) -> Vector9 {
        self.a1
            .scaled_gradient(self.i1, &(flatten(&self.f) * 2.0), &flatten(&self.cof))
    }

    /// `dIb2/dF`.
    pub fn ib2_gradient(&self) -> Vector9 {
        let g = flatten(&self.cof);
        self.a2
            .scaled_gradient(self.i2, &(det_hessian(&self.f) * g * 2.0), &g)
    }

    /// `d2Ib1/dF2`.
    pub fn ib1_hessian(&self) -> Matrix9 {
        self.a1.scaled_hessian(
            &self.f,
            self.i1,
            &(flatten(&self.f) * 2.0),
            &Matrix9::from_diagonal_element(2.0),
            &flatten(&self.cof),
        )
    }

    /// `d2Ib2/dF2`.
    pub fn ib2_hessian(&self) -> Matrix9 {
        let g = flatten(&self.cof);
        let hj = det_hessian(&self.f);
        let mut d2i = hj * hj * 2.0;
        add_det_hessian(&mut d2i, &self.cof, 2.0);
        self.a2
            .scaled_hessian(&self.f, self.i2, &(hj * g * 2.0), &d2i, &g)
    }

    /// Chain rule for `P = dW/dF = w1 dIb1/dF + w2 dIb2/dF`.
    pub fn stress(&self, w: &InvariantPartials) -> Matrix3<f64> {
        let mut p = self.ib1_gradient() * w.w1;
        if w.uses_second_invariant() {
            p += self.ib2_gradient() * w.w2;
        }
        unflatten(&p)
    }

    /// Chain rule for `dP/dF = w1 d2Ib1 + w2 d2Ib2 + w11 d1 d1^T + w12 (d1 d2^T + d2 d1^T)
    /// + w22 d2 d2^T`, with `dk = dIbk/dF`. The `Ib2` terms are skipped when `w2`, `w12` and
    /// `w22` are all zero.
    pub fn tangent(&self, w: &InvariantPartials) -> Matrix9 {
        let d1 = self.ib1_gradient();
        let mut h = self.ib1_hessian() * w.w1;
        h.ger(w.w11, &d1, &d1, 1.0);
        if w.uses_second_invariant() {
            let d2 = self.ib2_gradient();
            h += self.ib2_hessian() * w.w2;
            h.ger(w.w12, &d1, &d2, 1.0);
            h.ger(w.w12, &d2, &d1, 1.0);
            h.ger(w.w22, &d2, &d2, 1.0);
        }
        h
    }
}

/// `J = det F` if it is positive, else [`OutOfDomain`] for `energy` (also for NaN).
pub(crate) fn positive_determinant(
    energy: &'static str,
    f: &Matrix3<f64>,
) -> Result<f64, OutOfDomain> {
    OutOfDomain::positive(energy, f.determinant())
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

    #[test]
    fn second_invariant_is_the_classical_formula() {
        let f = sample();
        let c = f.transpose() * f;
        let classical = 0.5 * (c.trace().powi(2) - (c * c).trace());
        assert_relative_eq!(second_invariant(&f), classical, max_relative = 1e-14);
    }

    /// Gradients and Hessians of `Ib1`, `Ib2` against central differences, and the values
    /// against their definitions.
    #[test]
    fn isochoric_invariants_match_differences() {
        let f = sample();
        let inv = IsochoricInvariants::new("test", &f).unwrap();
        let j = f.determinant();
        let c = f.transpose() * f;
        let i2 = 0.5 * (c.trace().powi(2) - (c * c).trace());
        assert_relative_eq!(
            inv.ib1(),
            j.powf(-2.0 / 3.0) * c.trace(),
            max_relative = 1e-14
        );
        assert_relative_eq!(inv.ib2(), j.powf(-4.0 / 3.0) * i2, max_relative = 1e-14);
        let eps = 1e-6;
        let at = |v: &Vector9| IsochoricInvariants::new("test", &unflatten(v)).unwrap();
        let (g1, g2) = (inv.ib1_gradient(), inv.ib2_gradient());
        let (h1, h2) = (inv.ib1_hessian(), inv.ib2_hessian());
        for k in 0..9 {
            let mut fp = flatten(&f);
            let mut fm = fp;
            fp[k] += eps;
            fm[k] -= eps;
            let (p, m) = (at(&fp), at(&fm));
            assert_relative_eq!(g1[k], (p.ib1() - m.ib1()) / (2.0 * eps), epsilon = 1e-8);
            assert_relative_eq!(g2[k], (p.ib2() - m.ib2()) / (2.0 * eps), epsilon = 1e-8);
            let d1 = (p.ib1_gradient() - m.ib1_gradient()) / (2.0 * eps);
            let d2 = (p.ib2_gradient() - m.ib2_gradient()) / (2.0 * eps);
            assert_relative_eq!(h1.column(k).into_owned(), d1, epsilon = 1e-8);
            assert_relative_eq!(h2.column(k).into_owned(), d2, epsilon = 1e-8);
        }
        assert_relative_eq!(h1, h1.transpose(), epsilon = 1e-14);
        assert_relative_eq!(h2, h2.transpose(), epsilon = 1e-13);
    }

    #[test]
    fn isochoric_invariants_refuse_non_positive_j() {
        let flat = Matrix3::from_diagonal(&Vector3::new(1.0, 1.0, 0.0));
        let err = IsochoricInvariants::new("test", &flat).unwrap_err();
        assert_eq!((err.energy, err.j), ("test", 0.0));
    }
}
