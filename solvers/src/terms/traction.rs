//! Dead traction: a constant force per unit rest area on boundary faces, lumped equally to
//! the three vertices of each face; potential `-load sum_i f_i . x_i`.

use super::EnergyTerm;
use crate::SolverError;
use isochor_mesh::Vec3;

/// Dead traction on a set of faces, stored as the equivalent nodal forces.
#[derive(Debug, Clone)]
pub struct DeadTraction {
    forces: Vec<(usize, Vec3)>,
}

impl DeadTraction {
    /// Traction `traction` (force per rest area) on `faces` at rest positions `rest`.
    pub fn new(rest: &[Vec3], faces: &[[usize; 3]], traction: Vec3) -> Self {
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
        DeadTraction { forces }
    }

    /// Total force at full load.
    pub fn total_force(&self) -> Vec3 {
        self.forces.iter().map(|f| f.1).sum()
    }
}

impl EnergyTerm for DeadTraction {
    fn name(&self) -> &'static str {
        "traction"
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
