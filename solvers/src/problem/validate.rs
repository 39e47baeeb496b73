//! The checks a [`Problem`] passes before a model is built from it: every index it holds is in
//! range and every number is usable, so that a bad input is an error naming the index rather
//! than a panic deep in assembly.

use super::loads::Load;
use super::Problem;
use crate::error::SolverError;

impl Problem {
    /// Checks what can be checked without building the model: the material's parameters,
    /// the node of every Dirichlet condition, the corners of every loaded face and the tets
    /// of every zone (each against the mesh's counts), finite load vectors and pressures, and
    /// every obstacle's shape. The error names the first bad condition, load, zone or index.
    /// [`crate::Simulation::new`] runs these checks.
    pub fn validate(&self) -> Result<(), SolverError> {
        let bad = |message: String| Err(SolverError::InvalidProblem(message));
        self.material.validate()?;
        let nodes = self.mesh.num_nodes();
        for (c, condition) in self.dirichlet.iter().enumerate() {
            if let Some(&v) = condition.nodes.iter().find(|&&v| v >= nodes) {
                return bad(format!(
                    "Dirichlet condition {c}: node {v} is out of range (the mesh has {nodes} nodes)"
                ));
            }
        }
        let vertices = self.mesh.num_vertices();
        let finite = |v: &isochor_mesh::Vec3| v.iter().all(|c| c.is_finite());
        for (l, scheduled) in self.loads.iter().enumerate() {
            let (faces, usable) = match &scheduled.load {
                Load::Gravity(g) => (&[][..], finite(g)),
                Load::Traction { faces, traction } => (&faces[..], finite(traction)),
                Load::Pressure {
                    faces,
                    pressure,
                    origin,
                    ..
                } => (&faces[..], pressure.is_finite() && finite(origin)),
                Load::Cavity {
                    faces,
                    volume_ratio,
                    origin,
                    ..
                } => {
                    if !(*volume_ratio > 0.0 && volume_ratio.is_finite()) {
                        return bad(format!(
                            "load {l}: volume_ratio = {volume_ratio} must be positive and finite"
                        ));
                    }
                    (&faces[..], finite(origin))
                }
            };
            if !usable {
                return bad(format!("load {l}: its vector or pressure is not finite"));
            }
            for (f, face) in faces.iter().enumerate() {
                if let Some(&v) = face.iter().find(|&&v| v >= vertices) {
                    return bad(format!(
                        "load {l}: face {f} {face:?} names vertex {v}, but the mesh has {vertices} corner vertices"
                    ));
                }
            }
        }
        if let Some(zones) = &self.zones {
            let tets = self.mesh.num_elements();
            for (z, zone) in zones.iter().enumerate() {
                if let Some(&e) = zone.iter().find(|&&e| e >= tets) {
                    return bad(format!(
                        "zone {z}: tet {e} is out of range (the mesh has {tets} tets)"
                    ));
                }
            }
        }
        for (i, obstacle) in self.obstacles.iter().enumerate() {
            obstacle.validate().map_err(|e| match e {
                SolverError::InvalidProblem(m) => SolverError::InvalidProblem(m.replacen(
                    "obstacle:",
                    &format!("obstacle {i} (numbered from 0):"),
                    1,
                )),
                other => other,
            })?;
        }
        let mut in_tets = vec![false; vertices];
        self.mesh
            .corners()
            .tets()
            .iter()
            .flatten()
            .for_each(|&v| in_tets[v] = true);
        for sheet in &self.cloths {
            sheet.validate(&in_tets)?;
        }
        Ok(())
    }
}
