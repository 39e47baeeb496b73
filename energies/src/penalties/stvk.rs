//! `U(J) = 9 (J^(2/3) - 1)^2 / 8`: the Saint Venant-Kirchhoff energy's `lambda (tr E)^2 / 2`
//! under a pure dilation `F = J^(1/3) I`, our reading of the Kikuuwe et al. 2009 curve of Fig. 3
//! of Sheen et al. 2021.
//!
//! Sheen et al. plot a penalty for Kikuuwe et al. 2009 (an edge-based formulation of the Saint
//! Venant-Kirchhoff material) but print no equation for it, and we have not seen one in that
//! paper. Our reading: that material's volumetric term as a function of `J`. Under
//! `F = s I` with `s = J^(1/3)`, `E = (s^2 - 1) I / 2` and `tr E = 3 (s^2 - 1) / 2`, so
//! `lambda (tr E)^2 / 2 = lambda 9 (J^(2/3) - 1)^2 / 8`.

use crate::{OutOfDomain, VolumetricPenalty};

/// `U = 9 (s^2 - 1)^2 / 8` with `s = J^(1/3)`; `U' = 3 (s - 1/s) / 2`,
/// `U'' = (s^-2 + s^-4) / 2`. Convex where defined, `U(0+) = 9/8` finite but
/// `U' -> -infinity` as `J -> 0+` (like `-J^(-1/3)`): undefined (returns [`OutOfDomain`]) for
/// `J <= 0`.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct StvkPenalty;

impl StvkPenalty {
    /// `s = J^(1/3)` where defined.
    fn stretch(&self, j: f64) -> Result<f64, OutOfDomain> {
        Ok(OutOfDomain::positive(self.name(), j)?.cbrt())
    }
}

impl VolumetricPenalty for StvkPenalty {
    fn name(&self) -> &'static str {
        "StVK dilation penalty"
    }

    fn value(&self, j: f64) -> Result<f64, OutOfDomain> {
        let s = self.stretch(j)?;
        let d = s * s - 1.0;
        Ok(1.125 * d * d)
    }

    fn first_derivative(&self, j: f64) -> Result<f64, OutOfDomain> {
        let s = self.stretch(j)?;
        Ok(1.5 * (s - 1.0 / s))
    }

    fn second_derivative(&self, j: f64) -> Result<f64, OutOfDomain> {
        let s = self.stretch(j)?;
        let inv2 = 1.0 / (s * s);
        Ok(0.5 * (inv2 + inv2 * inv2))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn refuses_non_positive_j() {
        for j in [0.0, -0.5, f64::NAN] {
            let err = StvkPenalty.value(j).unwrap_err();
            assert_eq!(err.energy, StvkPenalty.name());
            assert!(StvkPenalty.first_derivative(j).is_err());
            assert!(StvkPenalty.second_derivative(j).is_err());
        }
    }
}
