//! The distortional part of Stable neo-Hookean (Smith, de Goes and Kim 2018, eq. 14).

use crate::kinematics::{add_det_hessian, cofactor, first_invariant, flatten};
use crate::parameters::require_mu;
use crate::{Hyperelastic, Matrix9, OutOfDomain, ParameterError};
use nalgebra::Matrix3;

/// `Psi_d = mu/2 (I_C - 3) - mu/2 log((I_C + 1) / 4) - 3 mu/4 (J - 1)`, with shear modulus
/// `mu` (the `mu` of the energy; see
/// [`StableNeoHookean::from_linear_lame`](crate::StableNeoHookean::from_linear_lame) for the
/// reparametrization that matches linear elasticity).
///
/// The rest-stable Stable neo-Hookean energy of Smith et al. 2018 (eq. 14),
/// `mu/2 (I_C - 3) + lambda/2 (J - alpha)^2 - mu/2 log(I_C + 1)` with
/// `alpha = 1 + 3 mu / (4 lambda)`, expands, since
/// `lambda/2 (J - alpha)^2 = lambda/2 (J - 1)^2 - 3 mu/4 (J - 1) + 9 mu^2 / (32 lambda)`, to
/// `Psi_d + lambda/2 (J - 1)^2 + 9 mu^2 / (32 lambda) - mu/2 log 4`: this density carries
/// everything but the volumetric `lambda/2 (J - 1)^2` and a constant, chosen so that
/// `Psi_d(I) = 0`.
///
/// `P = mu (1 - 1/(I_C + 1)) F - 3 mu/4 cof F`, so `P(I) = mu (3/4) I - 3 mu/4 I = 0`: rest
/// stable on its own (for every `lambda`, including a volume constraint in its place).
/// Defined for every `F`, singular and inverted included (`I_C + 1 >= 1`). The initial shear
/// modulus is `3/4 mu` (the log term softens the small-strain response; hence the `4/3` of
/// the reparametrization).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DistortionalStableNeoHookean {
    mu: f64,
}

impl DistortionalStableNeoHookean {
    /// `mu` finite and positive.
    pub fn new(mu: f64) -> Result<Self, ParameterError> {
        Ok(DistortionalStableNeoHookean {
            mu: require_mu(mu)?,
        })
    }

    /// Shear modulus `mu` as used in the energy.
    pub fn mu(&self) -> f64 {
        self.mu
    }
}

impl Hyperelastic for DistortionalStableNeoHookean {
    fn name(&self) -> &'static str {
        "distortional Stable neo-Hookean"
    }

    fn energy_density(&self, f: &Matrix3<f64>) -> Result<f64, OutOfDomain> {
        let ic = first_invariant(f);
        let j = f.determinant();
        Ok(0.5 * self.mu * (ic - 3.0 - (0.25 * (ic + 1.0)).ln() - 1.5 * (j - 1.0)))
    }

    /// `P = mu (1 - 1/(I_C + 1)) F - 3 mu/4 cof F`.
    fn pk1(&self, f: &Matrix3<f64>) -> Result<Matrix3<f64>, OutOfDomain> {
        let ic = first_invariant(f);
        Ok(f * (self.mu * (1.0 - 1.0 / (ic + 1.0))) - cofactor(f) * (0.75 * self.mu))
    }

    /// `dP/dF = mu (1 - 1/(I_C+1)) I + 2 mu/(I_C+1)^2 f f^T - 3 mu/4 d2J/dF2`.
    fn pk1_derivative(&self, f: &Matrix3<f64>) -> Result<Matrix9, OutOfDomain> {
        let ic1 = first_invariant(f) + 1.0;
        let mut h = Matrix9::from_diagonal_element(self.mu * (1.0 - 1.0 / ic1));
        let fv = flatten(f);
        h.ger(2.0 * self.mu / (ic1 * ic1), &fv, &fv, 1.0);
        add_det_hessian(&mut h, f, -0.75 * self.mu);
        Ok(h)
    }

    fn is_defined_at(&self, _j: f64) -> bool {
        true
    }
}
