//! `U(J) = (log J)^2 / 2`, the volumetric term of the standard neo-Hookean energy (eq. 6 of
//! Francu et al. 2021, eq. 4 of Sheen et al. 2021).

use crate::{OutOfDomain, VolumetricPenalty};

/// `U(J) = (log J)^2 / 2`, `U' = log J / J`, `U'' = (1 - log J) / J^2`: an infinite barrier at
/// `J = 0`, undefined (returns [`OutOfDomain`]) for `J <= 0`.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct LogPenalty;

impl LogPenalty {
    fn log_j(&self, j: f64) -> Result<f64, OutOfDomain> {
        Ok(OutOfDomain::positive(self.name(), j)?.ln())
    }
}

impl VolumetricPenalty for LogPenalty {
    fn name(&self) -> &'static str {
        "(log J)^2/2 penalty"
    }

    fn value(&self, j: f64) -> Result<f64, OutOfDomain> {
        let l = self.log_j(j)?;
        Ok(0.5 * l * l)
    }

    fn first_derivative(&self, j: f64) -> Result<f64, OutOfDomain> {
        Ok(self.log_j(j)? / j)
    }

    fn second_derivative(&self, j: f64) -> Result<f64, OutOfDomain> {
        Ok((1.0 - self.log_j(j)?) / (j * j))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn refuses_non_positive_j() {
        for j in [0.0, -0.5, f64::NAN] {
            let err = LogPenalty.value(j).unwrap_err();
            assert_eq!(err.energy, LogPenalty.name());
            assert!(LogPenalty.first_derivative(j).is_err());
            assert!(LogPenalty.second_derivative(j).is_err());
        }
        assert_eq!(LogPenalty.second_derivative(1.0).unwrap(), 1.0);
    }
}
