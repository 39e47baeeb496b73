//! The stored elastic energy `W(x) = sum_e sum_q w_q Psi(F_q(x))` (eq. 2 of Sheen et al. 2021
//! integrated by quadrature), evaluated in parallel over elements.

use super::{scatter, BlockOrder, ElementBlocks, EnergyTerm};
use crate::error::SolverError;
use crate::problem::schedule::LoadLevel;
use isochor_energies::kernel::{self, RestPoints};
use isochor_energies::{project_to_psd, Hyperelastic};
use isochor_mesh::element::{deformation_gradient, RestGeometry, TetElement, TetQuadrature};
use isochor_mesh::{ElementMesh, Vec3};
use nalgebra::{DMatrix, Matrix3};
use rayon::prelude::*;
use std::sync::Arc;

/// The quadrature rule of the elastic energy on `mesh`: the one-point rule on 4-node tets
/// (exact, `F` is constant); on 10-node tets the 4-point degree-2 rule when every element is
/// straight-sided (the usual full integration of the quadratic tet: `F` is linear, and the
/// patch test passes exactly), the 15-point degree-5 rule when the mesh has curved elements
/// (there `integral dN_a/dX dV` is a cubic that the degree-2 rule misses, so a homogeneous
/// stretch would not be an equilibrium).
pub fn elastic_rule(mesh: &ElementMesh) -> TetQuadrature {
    match mesh.kind() {
        TetElement::Tet4 => TetQuadrature::Degree1,
        TetElement::Tet10 if mesh.is_affine() => TetQuadrature::Degree2,
        TetElement::Tet10 => TetQuadrature::Degree5,
    }
}

/// Elastic energy of every element, each with its material.
#[derive(Debug)]
pub struct Elastic {
    nodes_per_element: usize,
    connectivity: Vec<usize>,
    rest: RestGeometry,
    materials: Vec<Arc<dyn Hyperelastic>>,
    /// Index into `materials` of each element.
    material_of: Vec<usize>,
    project: bool,
    /// `sum_e V_e max |dP/dF (I)|`, see [`EnergyTerm::rounding_scale`].
    rounding_scale: f64,
}

impl Elastic {
    /// The elastic energy of `mesh` with `material`, integrated by [`elastic_rule`]; with
    /// `project`, element Hessians are projected to positive semi-definite (for Newton on
    /// displacement-only problems).
    pub fn new(
        mesh: &ElementMesh,
        material: Arc<dyn Hyperelastic>,
        project: bool,
    ) -> Result<Self, SolverError> {
        Self::with_materials(mesh, vec![material], vec![0; mesh.num_elements()], project)
    }

    /// As [`Elastic::new`] with element `e` made of `materials[material_of[e]]`.
    pub fn with_materials(
        mesh: &ElementMesh,
        materials: Vec<Arc<dyn Hyperelastic>>,
        material_of: Vec<usize>,
        project: bool,
    ) -> Result<Self, SolverError> {
        if material_of.len() != mesh.num_elements()
            || material_of.iter().any(|&m| m >= materials.len())
        {
            return Err(SolverError::InvalidProblem(format!(
                "elastic energy: {} material indices for {} elements and {} materials",
                material_of.len(),
                mesh.num_elements(),
                materials.len()
            )));
        }
        let stiffness: Vec<f64> = materials
            .iter()
            .map(|m| {
                m.pk1_derivative(&Matrix3::identity())
                    .map_or(0.0, |d| d.amax())
            })
            .collect();
        let rest = mesh.rest_geometry(elastic_rule(mesh))?;
        let rounding_scale = material_of
            .iter()
            .enumerate()
            .map(|(e, &m)| stiffness[m] * rest.element_volume(e))
            .sum();
        Ok(Elastic {
            nodes_per_element: mesh.kind().num_nodes(),
            connectivity: mesh.connectivity().to_vec(),
            rounding_scale,
            rest,
            materials,
            material_of,
            project,
        })
    }

    /// The material of element `e`.
    pub fn material(&self, e: usize) -> &dyn Hyperelastic {
        self.materials[self.material_of[e]].as_ref()
    }

    /// The element blocks of the Hessian, column-major as the element matrices.
    fn blocks(&self) -> ElementBlocks {
        ElementBlocks {
            nodes: self.connectivity.clone(),
            per_element: self.nodes_per_element,
            order: BlockOrder::ColumnMajor,
        }
    }

    fn num_elements(&self) -> usize {
        self.connectivity.len() / self.nodes_per_element
    }

    fn nodes(&self, e: usize) -> &[usize] {
        let n = self.nodes_per_element;
        &self.connectivity[e * n..(e + 1) * n]
    }

    fn points(&self, e: usize) -> RestPoints<'_> {
        RestPoints {
            weights: self.rest.element_weights(e),
            gradients: self.rest.element_gradients(e),
        }
    }

    fn element(
        &self,
        e: usize,
        x: &[Vec3],
        gradient: Option<&mut [f64]>,
        hessian: Option<&mut [f64]>,
    ) -> Result<f64, SolverError> {
        let material = self.material(e);
        let energy = kernel::evaluate(
            material,
            x,
            self.nodes(e),
            self.points(e),
            gradient,
            hessian,
        )?;
        Ok(energy)
    }
}

impl EnergyTerm for Elastic {
    fn name(&self) -> &'static str {
        match self.materials.as_slice() {
            [one] => one.name(),
            _ => "elastic (several materials)",
        }
    }

    fn hessian_pattern(&self) -> Vec<(usize, usize)> {
        self.blocks().pairs()
    }

    fn hessian_blocks(&self) -> Option<ElementBlocks> {
        Some(self.blocks())
    }

    fn evaluate(
        &self,
        x: &[Vec3],
        _level: &LoadLevel,
        gradient: Option<&mut [f64]>,
        hessian: Option<&mut [f64]>,
    ) -> Result<f64, SolverError> {
        let dim = 3 * self.nodes_per_element;
        let derivatives = gradient.is_some() || hessian.is_some();
        let mut local = vec![
            0.0;
            if derivatives {
                dim * self.num_elements()
            } else {
                0
            }
        ];
        // Per-element energies summed in element order: a parallel reduction would sum in an
        // order that depends on scheduling, and resumed runs must equal uninterrupted ones bit
        // for bit.
        let energies: Vec<f64> = match hessian {
            Some(out) => out
                .par_chunks_mut(dim * dim)
                .zip(local.par_chunks_mut(dim))
                .enumerate()
                .map(|(e, (h, g))| {
                    let energy = self.element(e, x, Some(g), Some(h))?;
                    if self.project {
                        let projected = project_to_psd(&DMatrix::from_column_slice(dim, dim, h));
                        h.copy_from_slice(projected.as_slice());
                    }
                    Ok(energy)
                })
                .collect::<Result<_, SolverError>>()?,
            None if derivatives => local
                .par_chunks_mut(dim)
                .enumerate()
                .map(|(e, g)| self.element(e, x, Some(g), None))
                .collect::<Result<_, SolverError>>()?,
            None => (0..self.num_elements())
                .into_par_iter()
                .map(|e| self.element(e, x, None, None))
                .collect::<Result<_, SolverError>>()?,
        };
        let energy = energies.iter().sum();
        if let Some(g) = gradient {
            for (e, l) in local.chunks_exact(dim).enumerate() {
                scatter(self.nodes(e), l, g);
            }
        }
        Ok(energy)
    }

    /// Whether `det F` is in the material's domain at every quadrature point.
    fn is_valid(&self, x: &[Vec3]) -> bool {
        let points = self.rest.num_points();
        (0..self.num_elements()).into_par_iter().all(|e| {
            let n = self.nodes_per_element;
            let gradients = self.rest.element_gradients(e);
            (0..points).all(|q| {
                let f = deformation_gradient(x, self.nodes(e), &gradients[q * n..(q + 1) * n]);
                self.material(e).is_defined_at(f.determinant())
            })
        })
    }

    fn admits_inversion(&self) -> bool {
        self.materials
            .iter()
            .all(|m| m.is_defined_at(0.0) && m.is_defined_at(-1.0))
    }

    fn rounding_scale(&self) -> f64 {
        self.rounding_scale
    }
}
