//! The epidermis surface energy, eq. 16 of Sheen et al. 2021.

use crate::parameters::require;
use crate::penalties::SheenPenalty;
use crate::triangle::{area_ratio, area_ratio_derivatives, RestTriangle};
use crate::{Lame, Matrix9, ParameterError, Vector9};
use nalgebra::Vector3;

/// Energy, gradient and Hessian of one surface triangle.
#[derive(Debug, Clone, PartialEq)]
pub struct TriangleTerms {
    /// `A_0 Psi_e(J~)`.
    pub energy: f64,
    /// Gradient with respect to the 9 vertex coordinates.
    pub gradient: Vector9,
    /// Hessian (symmetric, 9x9).
    pub hessian: Matrix9,
}

/// `Psi_e = lambda_e/12 (J~ - 1)^2 [gamma (J~ - 1)^2 + 6] = lambda_e U(J~; gamma)` (eq. 16) per
/// unit rest area, with `J~` the area ratio of a surface triangle; the element energy is
/// `A_0 Psi_e`. The paper uses `gamma = 1` and `lambda_e` from `(E_e, nu_e)` by eq. 3 with
/// `nu_e` in `[0.4, 0.49]`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Epidermis {
    lambda_e: f64,
    penalty: SheenPenalty,
}

impl Epidermis {
    /// `lambda_e > 0` and `gamma >= 0`, both finite.
    pub fn new(lambda_e: f64, gamma: f64) -> Result<Self, ParameterError> {
        let lambda_e = require(
            "lambda_e",
            lambda_e,
            lambda_e.is_finite() && lambda_e > 0.0,
            "the epidermis stiffness must be finite and positive",
        )?;
        let penalty =
            SheenPenalty::new(gamma).map_err(|e| ParameterError { name: "gamma", ..e })?;
        Ok(Epidermis { lambda_e, penalty })
    }

    /// `lambda_e = E_e nu_e / ((1 + nu_e)(1 - 2 nu_e))` (eq. 3), `nu_e` in `(0, 0.5)`.
    pub fn from_young_poisson(e_e: f64, nu_e: f64, gamma: f64) -> Result<Self, ParameterError> {
        let lame = Lame::from_young_poisson(e_e, nu_e)?;
        Self::new(lame.lambda, gamma).map_err(|e| match e.name {
            "lambda_e" => ParameterError {
                name: "nu",
                value: nu_e,
                reason: "the epidermis needs nu > 0 (lambda_e > 0)",
            },
            _ => e,
        })
    }

    /// `lambda_e`.
    pub fn lambda(&self) -> f64 {
        self.lambda_e
    }

    /// `gamma`.
    pub fn gamma(&self) -> f64 {
        self.penalty.beta()
    }

    /// `Psi_e(J~)` per unit rest area.
    pub fn energy_density(&self, area_ratio: f64) -> f64 {
        self.lambda_e * self.penalty.u(area_ratio)
    }

    /// `A_0 Psi_e(J~)`.
    pub fn energy(&self, x: &[Vector3<f64>; 3], rest: &RestTriangle) -> f64 {
        rest.area() * self.energy_density(area_ratio(x, rest))
    }

    /// `A_0 lambda_e U'(J~) dJ~/dx`.
    pub fn gradient(&self, x: &[Vector3<f64>; 3], rest: &RestTriangle) -> Vector9 {
        self.energy_gradient_hessian(x, rest).gradient
    }

    /// `A_0 lambda_e (U''(J~) dJ~/dx dJ~/dx^T + U'(J~) d2J~/dx2)`.
    pub fn hessian(&self, x: &[Vector3<f64>; 3], rest: &RestTriangle) -> Matrix9 {
        self.energy_gradient_hessian(x, rest).hessian
    }

    /// Energy, gradient and Hessian together.
    pub fn energy_gradient_hessian(
        &self,
        x: &[Vector3<f64>; 3],
        rest: &RestTriangle,
    ) -> TriangleTerms {
        let d = area_ratio_derivatives(x, rest);
        let s = rest.area() * self.lambda_e;
        let (u1, u2) = (self.penalty.du(d.value), self.penalty.ddu(d.value));
        let mut hessian = d.hessian * (s * u1);
        hessian.ger(s * u2, &d.gradient, &d.gradient, 1.0);
        TriangleTerms {
            energy: s * self.penalty.u(d.value),
            gradient: d.gradient * (s * u1),
            hessian,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn validates_parameters() {
        assert_eq!(Epidermis::new(0.0, 1.0).unwrap_err().name, "lambda_e");
        assert_eq!(Epidermis::new(1.0, -1.0).unwrap_err().name, "gamma");
        assert_eq!(
            Epidermis::from_young_poisson(1.0, 0.5, 1.0)
                .unwrap_err()
                .name,
            "nu"
        );
        assert_eq!(
            Epidermis::from_young_poisson(1.0, 0.0, 1.0)
                .unwrap_err()
                .name,
            "nu"
        );
        assert_eq!(
            Epidermis::from_young_poisson(-1.0, 0.4, 1.0)
                .unwrap_err()
                .name,
            "E"
        );
        let e = Epidermis::from_young_poisson(3.0, 0.4, 1.0).unwrap();
        approx::assert_relative_eq!(e.lambda(), 3.0 * 0.4 / (1.4 * 0.2), max_relative = 1e-14);
    }
}
