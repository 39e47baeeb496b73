//! The shared kernel of `Psi = mu/2 (a(J) I_C - 3)`: Bonet-Wood (`a = J^-2/3`, eq. 30 of
//! Francu et al. 2021) and the F-bar deviatoric neo-Hookean (`a = alpha~(J)^2`, eq. 12 of
//! Sheen et al. 2021).

use crate::kinematics::{add_det_hessian, cofactor, first_invariant, flatten};
use crate::Matrix9;
use nalgebra::Matrix3;

/// A scalar factor `a(J)` with its first two derivatives.
#[derive(Debug, Clone, Copy)]
pub(super) struct Factor {
    pub a: f64,
    pub da: f64,
    pub dda: f64,
}

/// `mu/2 (a I_C - 3)`.
pub(super) fn energy(mu: f64, f: &Matrix3<f64>, k: Factor) -> f64 {
    0.5 * mu * (k.a * first_invariant(f) - 3.0)
}

/// `P = mu/2 (a' I_C cof F + 2 a F)`.
pub(super) fn pk1(mu: f64, f: &Matrix3<f64>, k: Factor) -> Matrix3<f64> {
    f * (mu * k.a) + cofactor(f) * (0.5 * mu * k.da * first_invariant(f))
}

/// `dP/dF = mu/2 [a'' I_C g g^T + 2 a' (g f^T + f g^T) + a' I_C d2J/dF2 + 2 a I]`,
/// with `g = vec(cof F)`, `f = vec(F)`.
pub(super) fn tangent(mu: f64, f: &Matrix3<f64>, k: Factor) -> Matrix9 {
    let ic = first_invariant(f);
    let (g, fv) = (flatten(&cofactor(f)), flatten(f));
    let mut h = Matrix9::from_diagonal_element(mu * k.a);
    h.ger(0.5 * mu * k.dda * ic, &g, &g, 1.0);
    h.ger(mu * k.da, &g, &fv, 1.0);
    h.ger(mu * k.da, &fv, &g, 1.0);
    add_det_hessian(&mut h, f, 0.5 * mu * k.da * ic);
    h
}
