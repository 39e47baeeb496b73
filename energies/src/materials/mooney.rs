//! The Mooney distortional energy, eq. 29 of Francu et al. 2021.

use crate::parameters::require_mu;
use crate::{Hyperelastic, Matrix9, OutOfDomain, ParameterError};
use nalgebra::Matrix3;

/// `Psi = mu/2 (I_C - 3)` (eq. 29): `P = mu F`, `dP/dF = mu I`, with shear modulus `mu` (the
/// initial shear modulus under a volume constraint). Defined for every `F`.
///
/// Not rest stable on its own (`P(I) = mu I`): it relies on a volumetric term or constraint
/// to balance the stress at rest.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Mooney {
    mu: f64,
}

impl Mooney {
    /// `mu` finite and positive.
    pub fn new(mu: f64) -> Result<Self, ParameterError> {
        Ok(Mooney {
            mu: require_mu(mu)?,
        })
    }

    /// Shear modulus.
    pub fn mu(&self) -> f64 {
        self.mu
    }
}

impl Hyperelastic for Mooney {
    fn name(&self) -> &'static str {
        "Mooney"
    }

    fn energy_density(&self, f: &Matrix3<f64>) -> Result<f64, OutOfDomain> {
        Ok(0.5 * self.mu * (f.norm_squared() - 3.0))
    }

    fn pk1(&self, f: &Matrix3<f64>) -> Result<Matrix3<f64>, OutOfDomain> {
        Ok(f * self.mu)
    }

    fn pk1_derivative(&self, _f: &Matrix3<f64>) -> Result<Matrix9, OutOfDomain> {
        Ok(Matrix9::from_diagonal_element(self.mu))
    }

    fn is_defined_at(&self, _j: f64) -> bool {
        true
    }
}
