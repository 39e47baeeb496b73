//! Dead loads: constant nodal forces `f_i`, ramped by the load parameter, with potential
//! `-load sum_i f_i . x_i`. Gravity lumps `m_i g` to the vertices; a dead traction lumps
//! `t A_f / 3` to the three vertices of each loaded face.

use super::EnergyTerm;
use crate::SolverError;
use isochor_mesh::Vec3;

/// Constant nodal forces.
#[derive(Debug, Clone)]
pub struct DeadLoad {
    name: &'static str,
    forces: Vec<(usize, Vec3)>,
}

impl DeadLoad {
    /// Gravity `acceleration` acting on vertices of the given lumped `masses`.
    pub fn gravity(masses: &[f64], acceleration: Vec3) -> Self {
        DeadLoad {
            name: "gravity",
            forces: masses
                .iter()
                .enumerate()
                .map(|(i, m)| (i, acceleration * *m))
                .collect(),
        }
    }

    /// Traction `traction` (force per unit rest area) on `faces` at rest positions `rest`.
    pub fn traction(rest: &[Vec3], faces: &[[usize; 3]], traction: Vec3) -> Self {
        let forces = faces
            .iter()
            .flat_map(|f| {
                let area = 0.5
                    * (rest[f[1]] - rest[f[0]])
                        .cross(&(rest[f[2]] - rest[f[0]]))
                        .norm();
                f.map(|v| (v, traction * (area / 3.0)))
            })
            .collect();
        DeadLoad {
            name: "traction",
            forces,
        }
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
        load: f64,
        gradient: Option<&mut [f64]>,
        _hessian: Option<&mut [f64]>,
    ) -> Result<f64, SolverError> {
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
