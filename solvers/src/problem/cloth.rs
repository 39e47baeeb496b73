//! A cloth sheet of a problem: triangles over vertices of the mesh that no tet uses, its
//! fabric, its areal density and its rest shape (the placed one scaled by `rest_scale`).

use crate::error::SolverError;
use isochor_energies::cloth::Fabric;

/// One sheet of fabric among the problem's nodes (its nodes are unknowns like the bodies').
#[derive(Debug, Clone, PartialEq)]
pub struct ClothSheet {
    /// Name for errors and reports.
    pub name: String,
    /// Consistently oriented triangles, indices into the mesh's vertices.
    pub triangles: Vec<[usize; 3]>,
    /// The fabric's membrane and bending constants.
    pub fabric: Fabric,
    /// Density of the fabric's material (kg/m^3): its mass per rest area is
    /// `density * thickness`.
    pub density: f64,
    /// The rest lengths are the placed lengths times this factor (below 1: tighter than
    /// placed).
    pub rest_scale: f64,
}

impl ClothSheet {
    /// Checks the sheet against a mesh of `vertices` corner vertices of which `in_tets`
    /// marks those a tet uses: triangles present and in range, on no tet's vertex, a
    /// positive finite density and `rest_scale`. The error names the sheet.
    pub fn validate(&self, in_tets: &[bool]) -> Result<(), SolverError> {
        let bad = |m: String| {
            Err(SolverError::InvalidProblem(format!(
                "cloth '{}': {m}",
                self.name
            )))
        };
        if self.triangles.is_empty() {
            return bad("has no triangles".into());
        }
        let vertices = in_tets.len();
        for (t, triangle) in self.triangles.iter().enumerate() {
            if let Some(&v) = triangle.iter().find(|&&v| v >= vertices) {
                return bad(format!(
                    "triangle {t} {triangle:?} names vertex {v}, but the mesh has {vertices} vertices"
                ));
            }
            if let Some(&v) = triangle.iter().find(|&&v| in_tets[v]) {
                return bad(format!(
                    "triangle {t} {triangle:?} names vertex {v}, which belongs to a tet"
                ));
            }
        }
        if !(self.density.is_finite() && self.density > 0.0) {
            return bad(format!(
                "density = {} must be finite and positive",
                self.density
            ));
        }
        if !(self.rest_scale.is_finite() && self.rest_scale > 0.0) {
            return bad(format!(
                "rest_scale = {} must be finite and positive",
                self.rest_scale
            ));
        }
        Ok(())
    }
}
