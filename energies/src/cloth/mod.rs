//! Cloth: a thin sheet of fabric on a triangle surface, with a membrane energy per triangle
//! ([`membrane`]: Saint Venant-Kirchhoff under plane stress) and a bending energy per interior
//! edge ([`bending`]: the dihedral-angle hinge of discrete shells, Grinspun et al. 2003).
//! [`Fabric`] holds the constants both read.

pub mod bending;
pub mod membrane;

use crate::parameters::require;
use crate::{Lame, ParameterError};

/// The constants of an isotropic fabric sheet of thickness `h`, from Young's modulus `E` and
/// Poisson's ratio `nu` of its material:
/// - the plane-stress Lame pair of the membrane, per unit volume,
///   `mu = E / (2 (1 + nu))`, `lambda_s = E nu / (1 - nu^2)` (the 2D `lambda` after the
///   through-thickness stress is eliminated: `lambda_s = 2 mu lambda / (lambda + 2 mu)`);
/// - the plate bending stiffness `D = E h^3 / (12 (1 - nu^2))`.
///
/// Energies per unit rest area are these times `h` (membrane) or `D` (bending).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Fabric {
    mu: f64,
    lambda_s: f64,
    thickness: f64,
    bending_stiffness: f64,
}

impl Fabric {
    /// `E > 0`, `nu` in `(-1, 0.5]` and a finite thickness `h > 0`.
    pub fn new(young: f64, poisson: f64, thickness: f64) -> Result<Self, ParameterError> {
        let mu = Lame::shear_modulus(young, poisson)?;
        let thickness = require(
            "thickness",
            thickness,
            thickness.is_finite() && thickness > 0.0,
            "the fabric's thickness must be finite and positive",
        )?;
        let plate = 1.0 - poisson * poisson;
        Ok(Fabric {
            mu,
            lambda_s: young * poisson / plate,
            thickness,
            bending_stiffness: young * thickness.powi(3) / (12.0 * plate),
        })
    }

    /// The membrane's shear modulus `mu` (per unit volume).
    pub fn mu(&self) -> f64 {
        self.mu
    }

    /// The membrane's plane-stress `lambda_s = E nu / (1 - nu^2)` (per unit volume).
    pub fn lambda_s(&self) -> f64 {
        self.lambda_s
    }

    /// The thickness `h`.
    pub fn thickness(&self) -> f64 {
        self.thickness
    }

    /// The plate bending stiffness `D = E h^3 / (12 (1 - nu^2))`.
    pub fn bending_stiffness(&self) -> f64 {
        self.bending_stiffness
    }
}
