//! The epidermis surface energy, eq. 16 of Sheen et al. 2021, on 3- and 6-node faces by
//! quadrature; a 3-node face with the one-point rule is the case `n = 3` of the same code.

use crate::kernel::mirror_lower;
use crate::parameters::require;
use crate::penalties::SheenPenalty;
use crate::triangle::{add_area_terms, RestFacePoints, RestTriangle};
use crate::{Lame, Matrix9, ParameterError, Vector9};
use isochor_mesh::element::TriQuadrature;
use isochor_mesh::Vec3;
use nalgebra::{Vector2, Vector3};

/// Energy, gradient and Hessian of one 3-node surface triangle.
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

    /// `A_0 Psi_e(J~)` of a 3-node triangle.
    pub fn energy(&self, x: &[Vector3<f64>; 3], rest: &RestTriangle) -> f64 {
        let (areas, gradients) = rest.one_point();
        self.evaluate(x, &[0, 1, 2], one_point(&areas, &gradients), None, None)
    }

    /// `A_0 lambda_e U'(J~) dJ~/dx` of a 3-node triangle.
    pub fn gradient(&self, x: &[Vector3<f64>; 3], rest: &RestTriangle) -> Vector9 {
        let (areas, gradients) = rest.one_point();
        let mut gradient = Vector9::zeros();
        self.evaluate(
            x,
            &[0, 1, 2],
            one_point(&areas, &gradients),
            Some(gradient.as_mut_slice()),
            None,
        );
        gradient
    }

    /// `A_0 lambda_e (U''(J~) dJ~/dx dJ~/dx^T + U'(J~) d2J~/dx2)` of a 3-node triangle.
    pub fn hessian(&self, x: &[Vector3<f64>; 3], rest: &RestTriangle) -> Matrix9 {
        self.energy_gradient_hessian(x, rest).hessian
    }

    /// Energy, gradient and Hessian of a 3-node triangle together.
    pub fn energy_gradient_hessian(
        &self,
        x: &[Vector3<f64>; 3],
        rest: &RestTriangle,
    ) -> TriangleTerms {
        let (areas, gradients) = rest.one_point();
        let mut gradient = Vector9::zeros();
        let mut hessian = Matrix9::zeros();
        let energy = self.evaluate(
            x,
            &[0, 1, 2],
            one_point(&areas, &gradients),
            Some(gradient.as_mut_slice()),
            Some(hessian.as_mut_slice()),
        );
        TriangleTerms {
            energy,
            gradient,
            hessian,
        }
    }

    /// The epidermis energy of a face of `n` nodes (3 or 6; indices `nodes` into `x`) by
    /// quadrature, `sum_q w_q S_q Psi_e(s_q / S_q)` with `s_q` the deformed area element
    /// ([`crate::triangle::area_element`]), and, when asked for, its gradient (`3n`) and
    /// Hessian (`3n x 3n`, column-major, exactly symmetric) written over `gradient` and
    /// `hessian`:
    /// `sum_q w_q lambda_e (U'(J~_q) ds_q/dx)` and
    /// `sum_q w_q lambda_e (U''(J~_q) ds_q/dx ds_q/dx^T / S_q + U'(J~_q) d2s_q/dx2)`.
    ///
    /// # Panics
    ///
    /// If `rest` does not hold one area and `n` gradients per weight, or an output does not
    /// have `3n` or `9n^2` entries.
    pub fn evaluate(
        &self,
        x: &[Vec3],
        nodes: &[usize],
        rest: RestFacePoints<'_>,
        mut gradient: Option<&mut [f64]>,
        mut hessian: Option<&mut [f64]>,
    ) -> f64 {
        let n = nodes.len();
        assert!(
            n > 0
                && rest.areas.len() == rest.weights.len()
                && rest.gradients.len() == n * rest.weights.len(),
            "{} areas and {} shape gradients for {} points of a {n}-node face",
            rest.areas.len(),
            rest.gradients.len(),
            rest.weights.len()
        );
        if let Some(g) = gradient.as_deref_mut() {
            assert_eq!(g.len(), 3 * n, "gradient length");
            g.fill(0.0);
        }
        if let Some(h) = hessian.as_deref_mut() {
            assert_eq!(h.len(), 9 * n * n, "Hessian length");
            h.fill(0.0);
        }
        let mut energy = 0.0;
        let points = rest.weights.iter().zip(rest.areas);
        for ((&w, &area), grads) in points.zip(rest.gradients.chunks_exact(n)) {
            let coefficients = |s: f64| {
                let j = s / area;
                let c = w * self.lambda_e;
                (c * self.penalty.du(j), c * self.penalty.ddu(j) / area)
            };
            let s = add_area_terms(
                x,
                nodes,
                grads,
                coefficients,
                gradient.as_deref_mut(),
                hessian.as_deref_mut(),
            );
            energy += w * area * self.energy_density(s / area);
        }
        if let Some(h) = hessian {
            mirror_lower(h, 3 * n);
        }
        energy
    }
}

/// The one-point rule data of a 3-node triangle as [`RestFacePoints`].
fn one_point<'a>(areas: &'a [f64; 1], gradients: &'a [Vector2<f64>; 3]) -> RestFacePoints<'a> {
    RestFacePoints {
        weights: TriQuadrature::Degree1.weights(),
        areas,
        gradients,
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
