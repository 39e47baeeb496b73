//! The stored elastic energy `W(x) = sum_e V_e Psi(F_e(x))` (eq. 2 of Sheen et al. 2021),
//! evaluated in parallel over tets.

use super::{block_pattern, scatter, EnergyTerm};
use crate::SolverError;
use isochor_energies::{project_to_psd, tet, Hyperelastic, Vector12};
use isochor_mesh::{TetMesh, Vec3};
use nalgebra::Matrix3;
use rayon::prelude::*;
use std::sync::Arc;

/// Elastic energy of every tet with one material.
#[derive(Debug)]
pub struct Elastic {
    tets: Vec<[usize; 4]>,
    inverse_rest_shapes: Vec<Matrix3<f64>>,
    rest_volumes: Vec<f64>,
    material: Arc<dyn Hyperelastic>,
    project: bool,
    /// `sum_e V_e max |dP/dF (I)|`, see [`EnergyTerm::rounding_scale`].
    rounding_scale: f64,
}

impl Elastic {
    /// The elastic energy of `mesh` with `material`; with `project`, element Hessians are
    /// projected to positive semi-definite (for Newton on displacement-only problems).
    pub fn new(mesh: &TetMesh, material: Arc<dyn Hyperelastic>, project: bool) -> Self {
        let stiffness = material
            .pk1_derivative(&Matrix3::identity())
            .map_or(0.0, |d| d.amax());
        Elastic {
            tets: mesh.tets().to_vec(),
            inverse_rest_shapes: mesh.inverse_rest_shapes().to_vec(),
            rest_volumes: mesh.rest_volumes().to_vec(),
            material,
            project,
            rounding_scale: stiffness * mesh.rest_volume(),
        }
    }

    /// The material.
    pub fn material(&self) -> &dyn Hyperelastic {
        self.material.as_ref()
    }

    fn corners(&self, e: usize, x: &[Vec3]) -> [Vec3; 4] {
        self.tets[e].map(|i| x[i])
    }

    fn energy_and_gradient(&self, e: usize, x: &[Vec3]) -> Result<(f64, Vector12), SolverError> {
        let xe = self.corners(e, x);
        let (dm, v) = (&self.inverse_rest_shapes[e], self.rest_volumes[e]);
        let energy = tet::energy(self.material.as_ref(), &xe, dm, v)?;
        let gradient = tet::gradient(self.material.as_ref(), &xe, dm, v)?;
        Ok((energy, gradient))
    }
}

impl EnergyTerm for Elastic {
    fn name(&self) -> &'static str {
        self.material.name()
    }

    fn hessian_pattern(&self) -> Vec<(usize, usize)> {
        self.tets.iter().flat_map(block_pattern).collect()
    }

    fn evaluate(
        &self,
        x: &[Vec3],
        _load: f64,
        gradient: Option<&mut [f64]>,
        hessian: Option<&mut [f64]>,
    ) -> Result<f64, SolverError> {
        let n = self.tets.len();
        let (energy, local_gradients) = match hessian {
            Some(out) => {
                let mut local = vec![Vector12::zeros(); n];
                let energy = out
                    .par_chunks_mut(144)
                    .zip(local.par_iter_mut())
                    .enumerate()
                    .map(|(e, (block, g))| {
                        let xe = self.corners(e, x);
                        let terms = tet::energy_gradient_hessian(
                            self.material.as_ref(),
                            &xe,
                            &self.inverse_rest_shapes[e],
                            self.rest_volumes[e],
                        )?;
                        let h = if self.project {
                            project_to_psd(&terms.hessian)
                        } else {
                            terms.hessian
                        };
                        block.copy_from_slice(h.as_slice());
                        *g = terms.gradient;
                        Ok(terms.energy)
                    })
                    .sum::<Result<f64, SolverError>>()?;
                (energy, Some(local))
            }
            None if gradient.is_some() => {
                let pairs = (0..n)
                    .into_par_iter()
                    .map(|e| self.energy_and_gradient(e, x))
                    .collect::<Result<Vec<_>, _>>()?;
                let energy = pairs.iter().map(|p| p.0).sum();
                (energy, Some(pairs.into_iter().map(|p| p.1).collect()))
            }
            None => {
                let energy = (0..n)
                    .into_par_iter()
                    .map(|e| {
                        let xe = self.corners(e, x);
                        tet::energy(
                            self.material.as_ref(),
                            &xe,
                            &self.inverse_rest_shapes[e],
                            self.rest_volumes[e],
                        )
                        .map_err(SolverError::from)
                    })
                    .sum::<Result<f64, SolverError>>()?;
                (energy, None)
            }
        };
        if let (Some(g), Some(local)) = (gradient, local_gradients) {
            for (t, le) in self.tets.iter().zip(&local) {
                scatter(t, le.as_slice(), g);
            }
        }
        Ok(energy)
    }

    fn is_valid(&self, x: &[Vec3]) -> bool {
        (0..self.tets.len()).into_par_iter().all(|e| {
            let xe = self.corners(e, x);
            let f = tet::deformation_gradient(&xe, &self.inverse_rest_shapes[e]);
            self.material.is_defined_at(f.determinant())
        })
    }

    fn rounding_scale(&self) -> f64 {
        self.rounding_scale
    }
}
