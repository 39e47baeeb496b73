//! The epidermis energy on the boundary surface: `sum_f A_f lambda_e U(J~_f; gamma)`
//! (eq. 16 of Sheen et al. 2021), an area-preserving skin over the volume.

use super::{block_pattern, scatter, EnergyTerm};
use crate::SolverError;
use isochor_energies::triangle::RestTriangle;
use isochor_energies::Epidermis;
use isochor_mesh::{TetMesh, Vec3};
use rayon::prelude::*;

/// Epidermis energy on every boundary triangle of a mesh.
#[derive(Debug)]
pub struct EpidermisTerm {
    faces: Vec<[usize; 3]>,
    rest: Vec<RestTriangle>,
    skin: Epidermis,
}

impl EpidermisTerm {
    /// The skin `skin` on the boundary of `mesh`.
    pub fn new(mesh: &TetMesh, skin: Epidermis) -> Result<Self, SolverError> {
        let surface = mesh.boundary()?;
        let faces = surface.triangles().to_vec();
        let x = mesh.positions();
        let rest = faces
            .iter()
            .enumerate()
            .map(|(f, t)| {
                RestTriangle::new(&t.map(|i| x[i])).ok_or_else(|| {
                    SolverError::InvalidProblem(format!("boundary face {f} is degenerate"))
                })
            })
            .collect::<Result<_, _>>()?;
        Ok(EpidermisTerm { faces, rest, skin })
    }
}

impl EnergyTerm for EpidermisTerm {
    fn name(&self) -> &'static str {
        "epidermis"
    }

    fn hessian_pattern(&self) -> Vec<(usize, usize)> {
        self.faces.iter().flat_map(block_pattern).collect()
    }

    fn evaluate(
        &self,
        x: &[Vec3],
        _load: f64,
        gradient: Option<&mut [f64]>,
        hessian: Option<&mut [f64]>,
    ) -> Result<f64, SolverError> {
        let corners = |f: usize| self.faces[f].map(|i| x[i]);
        let energy = match hessian {
            Some(out) => {
                let terms: Vec<_> = (0..self.faces.len())
                    .into_par_iter()
                    .map(|f| {
                        self.skin
                            .energy_gradient_hessian(&corners(f), &self.rest[f])
                    })
                    .collect();
                for (block, t) in out.chunks_mut(81).zip(&terms) {
                    block.copy_from_slice(t.hessian.as_slice());
                }
                if let Some(g) = gradient {
                    for (face, t) in self.faces.iter().zip(&terms) {
                        scatter(face, t.gradient.as_slice(), g);
                    }
                }
                terms.iter().map(|t| t.energy).sum()
            }
            None => {
                if let Some(g) = gradient {
                    for (f, face) in self.faces.iter().enumerate() {
                        scatter(
                            face,
                            self.skin.gradient(&corners(f), &self.rest[f]).as_slice(),
                            g,
                        );
                    }
                }
                (0..self.faces.len())
                    .into_par_iter()
                    .map(|f| self.skin.energy(&corners(f), &self.rest[f]))
                    .sum()
            }
        };
        Ok(energy)
    }
}
