//! The uncoupled Yeoh energy (Yeoh 1993), a cubic in `Ib1 - 3`.

use crate::kinematics::{InvariantPartials, IsochoricInvariants};
use crate::parameters::require;
use crate::{Hyperelastic, Matrix9, OutOfDomain, ParameterError};
use nalgebra::Matrix3;

/// `Psi = c10 (Ib1 - 3) + c20 (Ib1 - 3)^2 + c30 (Ib1 - 3)^3`, with the isochoric invariant
/// `Ib1 = J^-2/3 I_1` (see [`IsochoricInvariants`]).
///
/// Parameters: `c10 > 0`, and `c20`, `c30` of either sign (typically `c20 < 0` for the
/// softening at moderate strain and `c30 > 0` for the stiffening at large strain of filled
/// rubbers), in units of stress; the initial shear modulus is `mu = 2 c10`. Purely
/// distortional and rest stable (`P(I) = 0`); undefined ([`OutOfDomain`]) for `J <= 0`. With
/// `c20 = c30 = 0` it is [`BonetWood`](crate::BonetWood) with `mu = 2 c10`. For incompressible
/// uniaxial stretch `l` the nominal stress is
/// `2 (l - l^-2) (c10 + 2 c20 (I_1 - 3) + 3 c30 (I_1 - 3)^2)`, `I_1 = l^2 + 2/l`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Yeoh {
    c10: f64,
    c20: f64,
    c30: f64,
}

impl Yeoh {
    /// `c10` finite and positive, `c20` and `c30` finite.
    pub fn new(c10: f64, c20: f64, c30: f64) -> Result<Self, ParameterError> {
        Ok(Yeoh {
            c10: require(
                "c10",
                c10,
                c10.is_finite() && c10 > 0.0,
                "c10 (half the initial shear modulus) must be finite and positive",
            )?,
            c20: require("c20", c20, c20.is_finite(), "c20 must be finite")?,
            c30: require("c30", c30, c30.is_finite(), "c30 must be finite")?,
        })
    }

    /// The coefficients `(c10, c20, c30)`.
    pub fn coefficients(&self) -> (f64, f64, f64) {
        (self.c10, self.c20, self.c30)
    }

    /// Initial shear modulus `mu = 2 c10`.
    pub fn mu(&self) -> f64 {
        2.0 * self.c10
    }

    fn invariants(&self, f: &Matrix3<f64>) -> Result<IsochoricInvariants, OutOfDomain> {
        IsochoricInvariants::new(self.name(), f)
    }

    /// `dW/dIb1 = c10 + 2 c20 x + 3 c30 x^2` and `d2W/dIb1^2 = 2 c20 + 6 c30 x`, `x = Ib1 - 3`.
    fn partials(&self, inv: &IsochoricInvariants) -> InvariantPartials {
        let x = inv.ib1() - 3.0;
        InvariantPartials {
            w1: self.c10 + x * (2.0 * self.c20 + 3.0 * self.c30 * x),
            w11: 2.0 * self.c20 + 6.0 * self.c30 * x,
            ..InvariantPartials::default()
        }
    }
}

impl Hyperelastic for Yeoh {
    fn name(&self) -> &'static str {
        "Yeoh"
    }

    fn energy_density(&self, f: &Matrix3<f64>) -> Result<f64, OutOfDomain> {
        let x = self.invariants(f)?.ib1() - 3.0;
        Ok(x * (self.c10 + x * (self.c20 + x * self.c30)))
    }

    fn pk1(&self, f: &Matrix3<f64>) -> Result<Matrix3<f64>, OutOfDomain> {
        let inv = self.invariants(f)?;
        Ok(inv.stress(&self.partials(&inv)))
    }

    fn pk1_derivative(&self, f: &Matrix3<f64>) -> Result<Matrix9, OutOfDomain> {
        let inv = self.invariants(f)?;
        Ok(inv.tangent(&self.partials(&inv)))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_bad_parameters() {
        let name = |c10, c20, c30| Yeoh::new(c10, c20, c30).unwrap_err().name;
        assert_eq!(name(0.0, 0.0, 0.0), "c10");
        assert_eq!(name(f64::NAN, 0.0, 0.0), "c10");
        assert_eq!(name(1.0, f64::NAN, 0.0), "c20");
        assert_eq!(name(1.0, 0.0, f64::NEG_INFINITY), "c30");
        assert_eq!(Yeoh::new(0.5, -0.1, 0.01).unwrap().mu(), 1.0);
    }
}
