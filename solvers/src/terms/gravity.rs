//! Gravity: the body force `rho g` lumped to the vertices, potential `-load sum_i m_i g . x_i`.

use super::EnergyTerm;
use crate::SolverError;
use isochor_mesh::Vec3;

/// Gravity acting on lumped vertex masses.
#[derive(Debug, Clone)]
pub struct Gravity {
    masses: Vec<f64>,
    acceleration: Vec3,
}

impl Gravity {
    /// Gravity `acceleration` on vertices of the given lumped `masses`.
    pub fn new(masses: Vec<f64>, acceleration: Vec3) -> Self {
        Gravity {
            masses,
            acceleration,
        }
    }
}

impl EnergyTerm for Gravity {
    fn name(&self) -> &'static str {
        "gravity"
    }

    fn hessian_pattern(&self) -> Vec<(usize, usize)> {
        Vec::new()
    }

    fn evaluate(
        &self,
        x: &[Vec3],
        load: f64,
        gradient: Option<&mut [f64]>,
        _hessian: Option<&mut [f64]>,
    ) -> Result<f64, SolverError> {
        let g = load * self.acceleration;
        if let Some(grad) = gradient {
            for (i, m) in self.masses.iter().enumerate() {
                for k in 0..3 {
                    grad[3 * i + k] -= m * g[k];
                }
            }
        }
        Ok(-self
            .masses
            .iter()
            .zip(x)
            .map(|(m, xi)| m * g.dot(xi))
            .sum::<f64>())
    }

    fn is_external(&self) -> bool {
        true
    }
}
