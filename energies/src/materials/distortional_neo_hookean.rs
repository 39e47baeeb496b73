//! The distortional neo-Hookean energy, eq. 32 of Francu et al. 2021.

use crate::kinematics::{add_volumetric_tangent, cofactor, positive_determinant};
use crate::parameters::require_mu;
use crate::{Hyperelastic, Matrix9, OutOfDomain, ParameterError};
use nalgebra::Matrix3;

/// `Psi = mu/2 (I_C - 3) - mu log J` (eq. 32): `P = mu (F - F^-T)`, with shear modulus `mu`
/// (the initial shear modulus). Rest stable; undefined
/// ([`OutOfDomain`]) for `J <= 0`. With `lambda (log J)^2 / 2` it is the standard
/// neo-Hookean energy (see [`standard_neo_hookean`](crate::standard_neo_hookean)).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DistortionalNeoHookean {
    mu: f64,
}

impl DistortionalNeoHookean {
    /// `mu` finite and positive.
    pub fn new(mu: f64) -> Result<Self, ParameterError> {
        Ok(DistortionalNeoHookean {
            mu: require_mu(mu)?,
        })
    }

    /// Shear modulus.
    pub fn mu(&self) -> f64 {
        self.mu
    }

    fn j(&self, f: &Matrix3<f64>) -> Result<f64, OutOfDomain> {
        positive_determinant(self.name(), f)
    }
}

impl Hyperelastic for DistortionalNeoHookean {
    fn name(&self) -> &'static str {
        "distortional neo-Hookean"
    }

    fn energy_density(&self, f: &Matrix3<f64>) -> Result<f64, OutOfDomain> {
        let j = self.j(f)?;
        Ok(0.5 * self.mu * (f.norm_squared() - 3.0) - self.mu * j.ln())
    }

    fn pk1(&self, f: &Matrix3<f64>) -> Result<Matrix3<f64>, OutOfDomain> {
        let j = self.j(f)?;
        Ok((f - cofactor(f) / j) * self.mu)
    }

    fn pk1_derivative(&self, f: &Matrix3<f64>) -> Result<Matrix9, OutOfDomain> {
        let j = self.j(f)?;
        let mut h = Matrix9::from_diagonal_element(self.mu);
        add_volumetric_tangent(&mut h, f, -self.mu / j, self.mu / (j * j));
        Ok(h)
    }
}
