//! The uncoupled distortional energy of Bonet and Wood, eq. 30 of Francu et al. 2021.

use super::scaled_invariant::{self, Factor};
use crate::kinematics::positive_determinant;
use crate::parameters::require_mu;
use crate::{Hyperelastic, Matrix9, OutOfDomain, ParameterError};
use nalgebra::Matrix3;

/// `Psi = mu/2 (J^-2/3 I_C - 3)` (eq. 30) with its exact stress and tangent (not the
/// approximation `P ~ mu J^-2/3 F` of eq. 31). Rest stable and purely distortional
/// (homogeneous of order 0 in `J`); undefined ([`OutOfDomain`]) for `J <= 0`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BonetWood {
    mu: f64,
}

impl BonetWood {
    /// `mu` finite and positive.
    pub fn new(mu: f64) -> Result<Self, ParameterError> {
        Ok(BonetWood {
            mu: require_mu(mu)?,
        })
    }

    /// Shear modulus.
    pub fn mu(&self) -> f64 {
        self.mu
    }

    /// `a = J^-2/3`, `a' = -2/3 a / J`, `a'' = 10/9 a / J^2`.
    fn factor(&self, f: &Matrix3<f64>) -> Result<Factor, OutOfDomain> {
        let j = positive_determinant(self.name(), f)?;
        let c = j.cbrt();
        let a = 1.0 / (c * c);
        Ok(Factor {
            a,
            da: -2.0 / 3.0 * a / j,
            dda: 10.0 / 9.0 * a / (j * j),
        })
    }
}

impl Hyperelastic for BonetWood {
    fn name(&self) -> &'static str {
        "Bonet-Wood"
    }

    fn energy_density(&self, f: &Matrix3<f64>) -> Result<f64, OutOfDomain> {
        Ok(scaled_invariant::energy(self.mu, f, self.factor(f)?))
    }

    fn pk1(&self, f: &Matrix3<f64>) -> Result<Matrix3<f64>, OutOfDomain> {
        Ok(scaled_invariant::pk1(self.mu, f, self.factor(f)?))
    }

    fn pk1_derivative(&self, f: &Matrix3<f64>) -> Result<Matrix9, OutOfDomain> {
        Ok(scaled_invariant::tangent(self.mu, f, self.factor(f)?))
    }
}
