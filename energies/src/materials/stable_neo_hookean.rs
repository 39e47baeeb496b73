//! Stable neo-Hookean (Smith, de Goes and Kim 2018), the invertible energy compared against in
//! sec. 5 of Sheen et al. 2021.

use crate::kinematics::{add_volumetric_tangent, cofactor, first_invariant, flatten};
use crate::parameters::{require, require_mu};
use crate::{Hyperelastic, Lame, Matrix9, OutOfDomain, ParameterError};
use nalgebra::Matrix3;

/// The rest-stable form of Smith et al. 2018 (their eq. 14):
/// `Psi = mu/2 (I_C - 3) + lambda/2 (J - alpha)^2 - mu/2 log(I_C + 1)`,
/// `alpha = 1 + 3 mu / (4 lambda)`, so that `P(I) = 0`. Defined for every `F` (`I_C + 1 >= 1`).
///
/// `Psi(I) = lambda/2 (1 - alpha)^2 - mu/2 log 4` is a nonzero constant; stresses and tangents
/// are unaffected. [`StableNeoHookean::new`] uses the Lame parameters as given;
/// [`StableNeoHookean::from_linear_lame`] applies the paper's reparametrization
/// `mu' = 4/3 mu`, `lambda' = lambda + 5/6 mu`, which makes the small-strain response match
/// linear elasticity with `(mu, lambda)`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StableNeoHookean {
    mu: f64,
    lambda: f64,
    alpha: f64,
}

impl StableNeoHookean {
    /// With `(mu, lambda)` used directly in the energy; `lambda` must be positive (`alpha`
    /// involves `1 / lambda`).
    pub fn new(lame: Lame) -> Result<Self, ParameterError> {
        let mu = require_mu(lame.mu)?;
        let lambda = require(
            "lambda",
            lame.lambda,
            lame.lambda.is_finite() && lame.lambda > 0.0,
            "Stable neo-Hookean needs a finite, positive lambda",
        )?;
        Ok(StableNeoHookean {
            mu,
            lambda,
            alpha: 1.0 + 0.75 * mu / lambda,
        })
    }

    /// From the Lame parameters of the linear material to match: `mu' = 4/3 mu`,
    /// `lambda' = lambda + 5/6 mu` (Smith et al. 2018, sec. 3.4).
    pub fn from_linear_lame(lame: Lame) -> Result<Self, ParameterError> {
        let mu = require_mu(lame.mu)?;
        Self::new(Lame {
            mu: 4.0 / 3.0 * mu,
            lambda: lame.lambda + 5.0 / 6.0 * mu,
        })
    }

    /// `(mu, lambda)` as used in the energy.
    pub fn lame(&self) -> Lame {
        Lame {
            mu: self.mu,
            lambda: self.lambda,
        }
    }

    /// Rest-stability offset `alpha = 1 + 3 mu / (4 lambda)`.
    pub fn alpha(&self) -> f64 {
        self.alpha
    }
}

impl Hyperelastic for StableNeoHookean {
    fn name(&self) -> &'static str {
        "Stable neo-Hookean"
    }

    fn energy_density(&self, f: &Matrix3<f64>) -> Result<f64, OutOfDomain> {
        let ic = first_invariant(f);
        let d = f.determinant() - self.alpha;
        Ok(0.5 * (self.mu * (ic - 3.0) + self.lambda * d * d - self.mu * (ic + 1.0).ln()))
    }

    /// `P = mu (1 - 1/(I_C + 1)) F + lambda (J - alpha) cof F`.
    fn pk1(&self, f: &Matrix3<f64>) -> Result<Matrix3<f64>, OutOfDomain> {
        let ic = first_invariant(f);
        let d1 = self.lambda * (f.determinant() - self.alpha);
        Ok(f * (self.mu * (1.0 - 1.0 / (ic + 1.0))) + cofactor(f) * d1)
    }

    /// `dP/dF = mu (1 - 1/(I_C+1)) I + 2 mu/(I_C+1)^2 f f^T + lambda g g^T
    /// + lambda (J - alpha) d2J/dF2`.
    fn pk1_derivative(&self, f: &Matrix3<f64>) -> Result<Matrix9, OutOfDomain> {
        let ic1 = first_invariant(f) + 1.0;
        let mut h = Matrix9::from_diagonal_element(self.mu * (1.0 - 1.0 / ic1));
        let fv = flatten(f);
        h.ger(2.0 * self.mu / (ic1 * ic1), &fv, &fv, 1.0);
        let d1 = self.lambda * (f.determinant() - self.alpha);
        add_volumetric_tangent(&mut h, f, d1, self.lambda);
        Ok(h)
    }

    fn is_defined_at(&self, _j: f64) -> bool {
        true
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn needs_positive_lambda() {
        let err = StableNeoHookean::new(Lame {
            mu: 1.0,
            lambda: 0.0,
        })
        .unwrap_err();
        assert_eq!(err.name, "lambda");
        let m = StableNeoHookean::from_linear_lame(Lame {
            mu: 3.0,
            lambda: 0.0,
        })
        .unwrap();
        assert_eq!(
            m.lame(),
            Lame {
                mu: 4.0,
                lambda: 2.5
            }
        );
    }
}
