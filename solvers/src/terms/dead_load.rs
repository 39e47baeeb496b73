//! Dead loads: constant nodal forces `f_a` scaled by `s` (the load ramp or the load's curve),
//! with potential `-s sum_a f_a . x_a`. Both are consistent loads, `f_a = integral N_a b`: gravity
//! `b = rho g` over the volume, a dead traction `t` over the rest area of the loaded faces
//! (on 3-node faces `t A_f / 3` per vertex, on 6-node flat faces `t A_f / 3` per mid-edge
//! node and nothing at the corners).

use super::{EnergyTerm, Faces};
use crate::error::SolverError;
use crate::problem::schedule::{Curve, LoadLevel};
use isochor_mesh::Vec3;

/// Constant nodal forces.
#[derive(Debug, Clone)]
pub struct DeadLoad {
    name: &'static str,
    forces: Vec<(usize, Vec3)>,
    curve: Option<Curve>,
}

impl DeadLoad {
    /// Gravity `acceleration` on nodes of weights `masses`: `rho integral N_a dV` per node
    /// (the mesh's [`isochor_mesh::ElementMesh::node_volumes`] times the density).
    pub fn gravity(masses: &[f64], acceleration: Vec3) -> Self {
        DeadLoad {
            name: "gravity",
            forces: masses
                .iter()
                .enumerate()
                .map(|(i, m)| (i, acceleration * *m))
                .collect(),
            curve: None,
        }
    }

    /// Traction `traction` (force per unit rest area) on `faces` at rest positions `rest`.
    pub fn traction(rest: &[Vec3], faces: &Faces, traction: Vec3) -> Self {
        let forces = faces
            .node_areas(rest)
            .into_iter()
            .map(|(a, area)| (a, traction * area))
            .collect();
        DeadLoad {
            name: "traction",
            forces,
            curve: None,
        }
    }

    /// The same load scaled by `curve` (`None`: the default ramp).
    pub fn following(self, curve: Option<Curve>) -> Self {
        DeadLoad { curve, ..self }
    }

    /// Total force at full load.
    pub fn total_force(&self) -> Vec3 {
        self.forces.iter().map(|f| f.1).sum()
    }
}

impl EnergyTerm for DeadLoad {
    fn name(&self) -> &'static str {
        self.name
    }

    fn hessian_pattern(&self) -> Vec<(usize, usize)> {
        Vec::new()
    }

    fn evaluate(
        &self,
        x: &[Vec3],
        level: &LoadLevel,
        gradient: Option<&mut [f64]>,
        _hessian: Option<&mut [f64]>,
    ) -> Result<f64, SolverError> {
        let load = level.load_scale(self.curve.as_ref());
        if let Some(g) = gradient {
            for (v, f) in &self.forces {
                for k in 0..3 {
                    g[3 * v + k] -= load * f[k];
                }
            }
        }
        Ok(-load * self.forces.iter().map(|(v, f)| f.dot(&x[*v])).sum::<f64>())
    }

    fn is_external(&self) -> bool {
        true
    }
}
