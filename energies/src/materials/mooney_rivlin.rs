//! The uncoupled Mooney-Rivlin energy (Mooney 1940, Rivlin 1948), as FEBio's "Mooney-Rivlin"
//! material (FEBio User's Manual, uncoupled materials), without its volumetric term.

use crate::kinematics::{InvariantPartials, IsochoricInvariants};
use crate::parameters::require;
use crate::{Hyperelastic, Matrix9, OutOfDomain, ParameterError};
use nalgebra::Matrix3;

/// `Psi = c10 (Ib1 - 3) + c01 (Ib2 - 3)`, with the isochoric invariants `Ib1 = J^-2/3 I_1`,
/// `Ib2 = J^-4/3 I_2` of `C = F^T F` (see [`IsochoricInvariants`]).
///
/// Parameters: `c10` and `c01` (FEBio calls them `c1` and `c2`), in units of stress; the
/// initial shear modulus is `mu = 2 (c10 + c01)`. Purely distortional (homogeneous of order 0
/// in `J`) and rest stable (`P(I) = 0`); undefined ([`OutOfDomain`]) for `J <= 0`. With
/// `c01 = 0` it is [`BonetWood`](crate::BonetWood) with `mu = 2 c10`. For incompressible
/// uniaxial stretch `l` the nominal stress is `2 (l - l^-2) (c10 + c01 / l)`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MooneyRivlin {
    c10: f64,
    c01: f64,
}

impl MooneyRivlin {
    /// `c10` and `c01` finite with `c10 + c01 > 0` (a positive initial shear modulus); either
    /// may be negative. A non-positive sum is reported on `c01` if it is negative, else on
    /// `c10`.
    pub fn new(c10: f64, c01: f64) -> Result<Self, ParameterError> {
        let c10 = require("c10", c10, c10.is_finite(), "c10 must be finite")?;
        let c01 = require("c01", c01, c01.is_finite(), "c01 must be finite")?;
        if c10 + c01 > 0.0 {
            Ok(MooneyRivlin { c10, c01 })
        } else {
            let (name, value) = if c01 < 0.0 {
                ("c01", c01)
            } else {
                ("c10", c10)
            };
            Err(ParameterError {
                name,
                value,
                reason: "c10 + c01 (half the initial shear modulus) must be positive",
            })
        }
    }

    /// The coefficient `c10` of `Ib1 - 3`.
    pub fn c10(&self) -> f64 {
        self.c10
    }

    /// The coefficient `c01` of `Ib2 - 3`.
    pub fn c01(&self) -> f64 {
        self.c01
    }

    /// Initial shear modulus `mu = 2 (c10 + c01)`.
    pub fn mu(&self) -> f64 {
        2.0 * (self.c10 + self.c01)
    }

    fn invariants(&self, f: &Matrix3<f64>) -> Result<IsochoricInvariants, OutOfDomain> {
        IsochoricInvariants::new(self.name(), f)
    }

    /// `dW/dIb1 = c10`, `dW/dIb2 = c01`; the second derivatives vanish.
    fn partials(&self) -> InvariantPartials {
        InvariantPartials {
            w1: self.c10,
            w2: self.c01,
            ..InvariantPartials::default()
        }
    }
}

impl Hyperelastic for MooneyRivlin {
    fn name(&self) -> &'static str {
        "Mooney-Rivlin"
    }

    fn energy_density(&self, f: &Matrix3<f64>) -> Result<f64, OutOfDomain> {
        let inv = self.invariants(f)?;
        Ok(self.c10 * (inv.ib1() - 3.0) + self.c01 * (inv.ib2() - 3.0))
    }

    fn pk1(&self, f: &Matrix3<f64>) -> Result<Matrix3<f64>, OutOfDomain> {
        Ok(self.invariants(f)?.stress(&self.partials()))
    }

    fn pk1_derivative(&self, f: &Matrix3<f64>) -> Result<Matrix9, OutOfDomain> {
        Ok(self.invariants(f)?.tangent(&self.partials()))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_bad_parameters() {
        let name = |c10, c01| MooneyRivlin::new(c10, c01).unwrap_err().name;
        assert_eq!(name(f64::NAN, 1.0), "c10");
        assert_eq!(name(1.0, f64::INFINITY), "c01");
        assert_eq!(name(1.0, -1.5), "c01");
        assert_eq!(name(0.0, 0.0), "c10");
        assert_eq!(name(-1.0, 0.5), "c10");
        let m = MooneyRivlin::new(-0.2, 1.0).unwrap();
        assert_eq!(m.mu(), 1.6);
    }
}
