//! The material of every element: the body's, or that of the [`Region`] claiming it.

use crate::error::SolverError;
use crate::problem::material::Material;
use crate::problem::Region;
use isochor_energies::Hyperelastic;
use isochor_mesh::ElementMesh;
use std::sync::Arc;

/// The materials of a body and which element is made of which. Region `0` is the body's
/// own material (elements no [`Region`] claims); region `i >= 1` is `Problem::regions[i - 1]`.
#[derive(Debug, Clone)]
pub struct Regions {
    names: Vec<String>,
    materials: Vec<Material>,
    energies: Vec<Arc<dyn Hyperelastic>>,
    element_regions: Vec<usize>,
}

impl Regions {
    /// The regions of `mesh`, with `energy` the elastic density the method puts on a material.
    ///
    /// Errors: a material with a bad parameter (named with its region), a region without
    /// elements, an element index outside the mesh, an element in two regions.
    pub(super) fn new(
        mesh: &ElementMesh,
        body: Material,
        regions: Vec<Region>,
        energy: impl Fn(&Material) -> Result<Arc<dyn Hyperelastic>, SolverError>,
    ) -> Result<Self, SolverError> {
        body.validate()?;
        let n = mesh.num_elements();
        let mut element_regions = vec![0; n];
        let mut names = vec!["body".to_string()];
        let mut materials = vec![body];
        for (index, region) in regions.into_iter().enumerate() {
            let id = index + 1;
            let bad = |what: String| {
                SolverError::InvalidProblem(format!("region '{}': {what}", region.name))
            };
            region.material.validate().map_err(|e| bad(e.to_string()))?;
            if region.elements.is_empty() {
                return Err(bad("it holds no element".into()));
            }
            for &e in &region.elements {
                match element_regions.get(e).copied() {
                    None => {
                        return Err(bad(format!(
                            "element {e} is not in the mesh ({n} elements)"
                        )))
                    }
                    Some(0) => element_regions[e] = id,
                    Some(other) if other == id => {}
                    Some(other) => {
                        return Err(bad(format!(
                            "element {e} is also in region '{}'; a region claims each element at most once",
                            names[other]
                        )))
                    }
                }
            }
            names.push(region.name);
            materials.push(region.material);
        }
        let energies = materials
            .iter()
            .zip(&names)
            .map(|(m, name)| {
                energy(m).map_err(|e| match e {
                    SolverError::InvalidProblem(what) if name != "body" => {
                        SolverError::InvalidProblem(format!("region '{name}': {what}"))
                    }
                    other => other,
                })
            })
            .collect::<Result<_, _>>()?;
        Ok(Regions {
            names,
            materials,
            energies,
            element_regions,
        })
    }

    /// The region of every element (`0`: the body's material).
    pub fn element_regions(&self) -> &[usize] {
        &self.element_regions
    }

    /// The name of every region (`"body"` first).
    pub fn names(&self) -> &[String] {
        &self.names
    }

    /// The material of every region.
    pub fn materials(&self) -> &[Material] {
        &self.materials
    }

    /// The elastic energy density of every region.
    pub fn energies(&self) -> &[Arc<dyn Hyperelastic>] {
        &self.energies
    }

    /// The elastic energy density of element `e`.
    pub fn energy(&self, e: usize) -> &dyn Hyperelastic {
        self.energies[self.element_regions[e]].as_ref()
    }

    /// `f` of each element's material.
    pub fn per_element<T: Clone>(&self, f: impl Fn(&Material) -> T) -> Vec<T> {
        let values: Vec<T> = self.materials.iter().map(f).collect();
        self.element_regions
            .iter()
            .map(|&r| values[r].clone())
            .collect()
    }

    /// `f` of each element's material, for a fallible `f`.
    pub fn try_per_element<T: Clone, E: Into<SolverError>>(
        &self,
        f: impl Fn(&Material) -> Result<T, E>,
    ) -> Result<Vec<T>, SolverError> {
        let values = self
            .materials
            .iter()
            .map(|m| f(m).map_err(Into::into))
            .collect::<Result<Vec<T>, SolverError>>()?;
        Ok(self
            .element_regions
            .iter()
            .map(|&r| values[r].clone())
            .collect())
    }

    /// The volume-weighted mean shear modulus over `mesh` (the scale of forces and contact
    /// stiffnesses).
    pub fn mean_shear_modulus(&self, mesh: &ElementMesh) -> f64 {
        let volumes = mesh.corners().rest_volumes();
        let total: f64 = volumes.iter().sum();
        let weighted: f64 = volumes
            .iter()
            .zip(&self.element_regions)
            .map(|(v, &r)| v * self.materials[r].mu)
            .sum();
        if total > 0.0 {
            weighted / total
        } else {
            self.materials[0].mu
        }
    }

    /// The material with the largest Poisson's ratio among the regions that hold elements.
    pub fn most_incompressible(&self) -> &Material {
        let mut used = vec![false; self.materials.len()];
        for &r in &self.element_regions {
            used[r] = true;
        }
        self.materials
            .iter()
            .zip(used)
            .filter(|(_, u)| *u)
            .map(|(m, _)| m)
            .max_by(|a, b| a.nu.total_cmp(&b.nu))
            .unwrap_or(&self.materials[0])
    }
}
