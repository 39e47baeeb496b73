//! `U(J) = ((J - 1) - (J - 1)^2 / 2)^2 / 2`: the second-order expanded Stable neo-Hookean
//! penalty ("SNH2") of Fig. 3 of Sheen et al. 2021.
//!
//! Sheen et al. name this penalty but print no equation for it. Our reading: the Stable
//! neo-Hookean penalty `(J - 1)^2 / 2` (after eq. 15) is the neo-Hookean `(log J)^2 / 2` (eq. 4)
//! with `log J` replaced by its first-order Taylor polynomial about `J = 1`; SNH2 replaces it
//! by the second-order one, `log J ~ (J - 1) - (J - 1)^2 / 2`.

use crate::{OutOfDomain, VolumetricPenalty};

/// `U = g^2 / 2` with `g = d - d^2 / 2` and `d = J - 1`; `U' = g (1 - d)`,
/// `U'' = (1 - d)^2 - g`. Defined for every `J`, but `U'' < 0` for
/// `J` in `(2 - 1/sqrt 3, 2 + 1/sqrt 3)` (condition e of sec. 5 fails there), and `U` returns to
/// 0 at `J = 3`, where the truncated logarithm vanishes again.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Snh2Penalty;

impl Snh2Penalty {
    /// The truncated logarithm `g = d - d^2 / 2` and `d = J - 1`.
    fn g(j: f64) -> (f64, f64) {
        let d = j - 1.0;
        (d - 0.5 * d * d, d)
    }
}

impl VolumetricPenalty for Snh2Penalty {
    fn name(&self) -> &'static str {
        "SNH2 penalty"
    }

    fn value(&self, j: f64) -> Result<f64, OutOfDomain> {
        let (g, _) = Self::g(j);
        Ok(0.5 * g * g)
    }

    fn first_derivative(&self, j: f64) -> Result<f64, OutOfDomain> {
        let (g, d) = Self::g(j);
        Ok(g * (1.0 - d))
    }

    fn second_derivative(&self, j: f64) -> Result<f64, OutOfDomain> {
        let (g, d) = Self::g(j);
        Ok((1.0 - d) * (1.0 - d) - g)
    }

    fn is_defined_at(&self, _j: f64) -> bool {
        true
    }
}
