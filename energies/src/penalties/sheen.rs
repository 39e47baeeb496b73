//! The compression penalty `U(J; beta)` of Sheen et al. 2021, eq. 13-15.

use crate::parameters::require;
use crate::{OutOfDomain, ParameterError, VolumetricPenalty};

/// `U(J; beta) = (J - 1)^2 [beta (J - 1)^2 + 6] / 12` (eq. 13), with
/// `U' = (J - 1) [beta (J - 1)^2 + 3] / 3` (eq. 14) and `U'' = beta (J - 1)^2 + 1` (eq. 15).
///
/// It meets the five conditions of sec. 5 of the paper:
/// a) `U(1) = 0`; b) `U'(1) = 0`; c) `U''(1) = 1`, so that `lambda` is the Lame parameter of
/// linear elasticity; d) `U` is defined for every real `J` (inversion included);
/// e) `U''(J) >= 0` for every `J`, so it penalizes both compression and stretch.
///
/// `beta = 0` gives the Stable neo-Hookean penalty `(J - 1)^2 / 2`; larger `beta` resists
/// strong compression (and inversion) more steeply.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SheenPenalty {
    beta: f64,
}

impl SheenPenalty {
    /// `beta` finite and `>= 0`.
    pub fn new(beta: f64) -> Result<Self, ParameterError> {
        let beta = require(
            "beta",
            beta,
            beta.is_finite() && beta >= 0.0,
            "the penalty steepness must be finite and non-negative",
        )?;
        Ok(SheenPenalty { beta })
    }

    /// The steepness `beta`.
    pub fn beta(&self) -> f64 {
        self.beta
    }

    /// `U(J; beta)` (eq. 13); infallible, as `U` is defined everywhere.
    pub fn u(&self, j: f64) -> f64 {
        let d2 = (j - 1.0) * (j - 1.0);
        d2 * (self.beta * d2 + 6.0) / 12.0
    }

    /// `U'(J; beta)` (eq. 14).
    pub fn du(&self, j: f64) -> f64 {
        let d = j - 1.0;
        d * (self.beta * d * d + 3.0) / 3.0
    }

    /// `U''(J; beta)` (eq. 15).
    pub fn ddu(&self, j: f64) -> f64 {
        let d = j - 1.0;
        self.beta * d * d + 1.0
    }
}

impl VolumetricPenalty for SheenPenalty {
    fn name(&self) -> &'static str {
        "U(J; beta) penalty"
    }

    fn value(&self, j: f64) -> Result<f64, OutOfDomain> {
        Ok(self.u(j))
    }

    fn first_derivative(&self, j: f64) -> Result<f64, OutOfDomain> {
        Ok(self.du(j))
    }

    fn second_derivative(&self, j: f64) -> Result<f64, OutOfDomain> {
        Ok(self.ddu(j))
    }

    fn is_defined_at(&self, _j: f64) -> bool {
        true
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn validates_beta() {
        for beta in [-1.0, f64::NAN, f64::INFINITY] {
            assert_eq!(SheenPenalty::new(beta).unwrap_err().name, "beta");
        }
        assert!(SheenPenalty::new(0.0).is_ok());
    }

    #[test]
    fn beta_zero_is_quadratic() {
        let u = SheenPenalty::new(0.0).unwrap();
        for j in [-2.0, 0.0, 0.3, 1.0, 4.0] {
            approx::assert_relative_eq!(u.value(j).unwrap(), 0.5 * (j - 1.0) * (j - 1.0));
        }
    }
}
