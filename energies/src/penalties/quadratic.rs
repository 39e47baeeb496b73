//! `U(J) = (J - 1)^2 / 2`, the volumetric term of the `(J-1)^2` neo-Hookean variant (Ogden 1997,
//! remark after eq. 6 of Francu et al. 2021) and of Stable neo-Hookean; `U(J; 0)` of eq. 13
//! of Sheen et al. 2021.

use crate::{OutOfDomain, VolumetricPenalty};

/// `U(J) = (J - 1)^2 / 2`, defined for every `J`.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct QuadraticPenalty;

impl VolumetricPenalty for QuadraticPenalty {
    fn name(&self) -> &'static str {
        "(J-1)^2/2 penalty"
    }

    fn value(&self, j: f64) -> Result<f64, OutOfDomain> {
        Ok(0.5 * (j - 1.0) * (j - 1.0))
    }

    fn first_derivative(&self, j: f64) -> Result<f64, OutOfDomain> {
        Ok(j - 1.0)
    }

    fn second_derivative(&self, _j: f64) -> Result<f64, OutOfDomain> {
        Ok(1.0)
    }

    fn is_defined_at(&self, _j: f64) -> bool {
        true
    }
}
