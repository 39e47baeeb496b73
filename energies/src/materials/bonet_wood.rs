//! The uncoupled distortional energy of Bonet and Wood, eq. 30 of Francu et al. 2021.

use crate::kinematics::{InvariantPartials, IsochoricInvariants};
use crate::parameters::require_mu;
use crate::{Hyperelastic, Matrix9, OutOfDomain, ParameterError};
use nalgebra::Matrix3;

/// `Psi = mu/2 (Ib1 - 3)`, `Ib1 = J^-2/3 I_C` (eq. 30), with its exact stress and tangent (not
/// the approximation `P ~ mu J^-2/3 F` of eq. 31). Shear modulus `mu`. Rest stable and purely
/// distortional (homogeneous of order 0 in `J`); undefined ([`OutOfDomain`]) for `J <= 0`.
/// The uncoupled neo-Hookean model: [`MooneyRivlin`](crate::MooneyRivlin) with
/// `c10 = mu/2`, `c01 = 0` and [`Yeoh`](crate::Yeoh) with `c10 = mu/2`, `c20 = c30 = 0`.
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

    /// `dW/dIb1 = mu/2`: the chain rule of [`IsochoricInvariants`].
    fn partials(&self) -> InvariantPartials {
        InvariantPartials {
            w1: 0.5 * self.mu,
            ..InvariantPartials::default()
        }
    }

    fn invariants(&self, f: &Matrix3<f64>) -> Result<IsochoricInvariants, OutOfDomain> {
        IsochoricInvariants::new(self.name(), f)
    }
}

impl Hyperelastic for BonetWood {
    fn name(&self) -> &'static str {
        "Bonet-Wood"
    }

    fn energy_density(&self, f: &Matrix3<f64>) -> Result<f64, OutOfDomain> {
        Ok(0.5 * self.mu * (self.invariants(f)?.ib1() - 3.0))
    }

    fn pk1(&self, f: &Matrix3<f64>) -> Result<Matrix3<f64>, OutOfDomain> {
        Ok(self.invariants(f)?.stress(&self.partials()))
    }

    fn pk1_derivative(&self, f: &Matrix3<f64>) -> Result<Matrix9, OutOfDomain> {
        Ok(self.invariants(f)?.tangent(&self.partials()))
    }
}
