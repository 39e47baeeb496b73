//! The epidermis energy on the boundary surface: `sum_f integral_f lambda_e U(J~; gamma) dA`
//! (eq. 16 of Sheen et al. 2021), an area-preserving skin over the volume, on the 3- or
//! 6-node boundary faces of the mesh.

use super::{block_pattern, scatter, EnergyTerm, Faces};
use crate::error::SolverError;
use crate::problem::schedule::LoadLevel;
use isochor_energies::triangle::{area_element, RestFacePoints};
use isochor_energies::Epidermis;
use isochor_mesh::{ElementMesh, Vec3};
use rayon::prelude::*;

/// Epidermis energy on every boundary face of a mesh.
#[derive(Debug)]
pub struct EpidermisTerm {
    faces: Faces,
    /// Rest area element `S_q` of every face at every point, face-major.
    rest_areas: Vec<f64>,
    skin: Epidermis,
}

impl EpidermisTerm {
    /// The skin `skin` on the boundary of `mesh`.
    pub fn new(mesh: &ElementMesh, skin: Epidermis) -> Result<Self, SolverError> {
        let surface = mesh.boundary()?;
        let faces = Faces::from_nodes(surface.kind(), surface.faces().to_vec());
        let x = mesh.nodes();
        let mut rest_areas = Vec::with_capacity(faces.len() * faces.weights().len());
        for (f, face) in faces.iter().enumerate() {
            for q in 0..faces.weights().len() {
                let area = area_element(x, face, faces.gradients(q));
                if area.is_nan() || area <= 0.0 {
                    return Err(SolverError::InvalidProblem(format!(
                        "boundary face {f} is degenerate"
                    )));
                }
                rest_areas.push(area);
            }
        }
        Ok(EpidermisTerm {
            faces,
            rest_areas,
            skin,
        })
    }

    fn rest(&self, f: usize) -> RestFacePoints<'_> {
        let points = self.faces.weights().len();
        RestFacePoints {
            weights: self.faces.weights(),
            areas: &self.rest_areas[f * points..(f + 1) * points],
            gradients: self.faces.all_gradients(),
        }
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
        _level: &LoadLevel,
        gradient: Option<&mut [f64]>,
        hessian: Option<&mut [f64]>,
    ) -> Result<f64, SolverError> {
        let n = self.faces.nodes_per_face();
        let count = self.faces.len();
        let face = |f: usize| self.faces.face(f);
        let derivatives = gradient.is_some() || hessian.is_some();
        let mut local = vec![0.0; if derivatives { 3 * n * count } else { 0 }];
        // Per-face energies summed in face order: a parallel reduction would sum in an order
        // that depends on scheduling, and resumed runs must equal uninterrupted ones bit for bit.
        let energies: Vec<f64> = match hessian {
            Some(out) => out
                .par_chunks_mut(9 * n * n)
                .zip(local.par_chunks_mut(3 * n))
                .enumerate()
                .map(|(f, (h, g))| {
                    self.skin
                        .evaluate(x, face(f), self.rest(f), Some(g), Some(h))
                })
                .collect(),
            None if derivatives => local
                .par_chunks_mut(3 * n)
                .enumerate()
                .map(|(f, g)| self.skin.evaluate(x, face(f), self.rest(f), Some(g), None))
                .collect(),
            None => (0..count)
                .into_par_iter()
                .map(|f| self.skin.evaluate(x, face(f), self.rest(f), None, None))
                .collect(),
        };
        let energy = energies.iter().sum();
        if let Some(g) = gradient {
            for (f, l) in local.chunks_exact(3 * n).enumerate() {
                scatter(face(f), l, g);
            }
        }
        Ok(energy)
    }
}
