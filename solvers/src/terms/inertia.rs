//! The inertial energy of implicit Euler: `|x - x^n - h v^n|_M^2 / (2 h^2)` (eq. 20 and 33
//! of Francu et al. 2021) with a lumped mass matrix.

use super::EnergyTerm;
use crate::error::SolverError;
use crate::problem::schedule::LoadLevel;
use isochor_mesh::Vec3;

/// Inertia of one implicit Euler step.
#[derive(Debug, Clone)]
pub struct Inertia {
    masses: Vec<f64>,
    dt: f64,
    predicted: Vec<Vec3>,
}

impl Inertia {
    /// Inertia with lumped vertex `masses` and time step `dt`; call [`Inertia::begin_step`]
    /// before each step (which may change the step).
    pub fn new(masses: Vec<f64>, dt: f64) -> Self {
        let n = masses.len();
        Inertia {
            masses,
            dt,
            predicted: vec![Vec3::zeros(); n],
        }
    }

    /// Sets the time step `h` and the inertial prediction `x^n + h v^n`.
    pub fn begin_step(&mut self, x: &[Vec3], v: &[Vec3], dt: f64) {
        self.dt = dt;
        for ((p, xi), vi) in self.predicted.iter_mut().zip(x).zip(v) {
            *p = xi + self.dt * vi;
        }
    }
}

impl EnergyTerm for Inertia {
    fn name(&self) -> &'static str {
        "inertia"
    }

    fn hessian_pattern(&self) -> Vec<(usize, usize)> {
        (0..3 * self.masses.len()).map(|d| (d, d)).collect()
    }

    fn evaluate(
        &self,
        x: &[Vec3],
        _level: &LoadLevel,
        gradient: Option<&mut [f64]>,
        hessian: Option<&mut [f64]>,
    ) -> Result<f64, SolverError> {
        let w = 1.0 / (self.dt * self.dt);
        if let Some(g) = gradient {
            for (i, m) in self.masses.iter().enumerate() {
                let d = x[i] - self.predicted[i];
                for k in 0..3 {
                    g[3 * i + k] += w * m * d[k];
                }
            }
        }
        if let Some(h) = hessian {
            for (i, m) in self.masses.iter().enumerate() {
                h[3 * i..3 * i + 3].fill(w * m);
            }
        }
        Ok(0.5
            * w
            * self
                .masses
                .iter()
                .zip(x.iter().zip(&self.predicted))
                .map(|(m, (xi, pi))| m * (xi - pi).norm_squared())
                .sum::<f64>())
    }
}
