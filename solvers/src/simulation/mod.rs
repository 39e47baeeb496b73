//! The stepping drivers (quasi-static load stepping and implicit Euler) and their results.

mod construction;
mod limit_point;
mod linearize;
mod matrices;
mod postprocess;
mod run;
mod state;
mod stepper;
mod stepping;
mod volume_projection;

pub use linearize::{Linearizer, NewtonSystem};
pub use matrices::Matrices;
pub use state::{Checkpoint, Energies, Frame, RunSummary, SimulationFailure, State};
pub use stepper::{Adaptive, Progress, StepControl, MIN_INCREMENT_FLOOR};
pub use stepping::Stepping;

use crate::error::SolverError;
use crate::model::regions::Regions;
use crate::model::Model;
use crate::nonlinear::target::norm;
use crate::problem::method::Method;
use crate::problem::schedule::LoadLevel;
use crate::settings::Settings;
use isochor_mesh::ElementMesh;

/// A problem turned into a model, with its current state.
#[derive(Debug)]
pub struct Simulation {
    model: Model,
    settings: Settings,
    state: State,
    /// Where a restored run continues (see [`Simulation::restore`]).
    resume: Option<Progress>,
    /// The external loads' potential at rest, the zero of [`Energies::external`].
    rest_external: f64,
}

impl Simulation {
    /// The mesh in its rest configuration.
    pub fn mesh(&self) -> &ElementMesh {
        &self.model.mesh
    }

    /// The method.
    pub fn method(&self) -> Method {
        self.model.method
    }

    /// The current state.
    pub fn state(&self) -> &State {
        &self.state
    }

    /// Unknowns of the linear systems: free displacement DOFs plus multipliers.
    pub fn num_dofs(&self) -> usize {
        self.model.dofs.num_free() + self.state.multipliers.len()
    }

    /// Rest volume measured by each constraint (empty for `standard` and `condensed`).
    pub fn constraint_volumes(&self) -> &[f64] {
        &self.model.row_volumes
    }

    /// The force scale tolerances are relative to: the larger of the external load's norm
    /// at full load and `mu h^2 sqrt(n)` (a unit strain's nodal force over the mesh).
    pub fn force_scale(&self) -> Result<f64, SolverError> {
        let x = self.model.mesh.nodes();
        let mut external = vec![0.0; 3 * x.len()];
        for term in self.model.terms.iter().filter(|t| t.is_external()) {
            term.evaluate(x, &LoadLevel::FULL, Some(&mut external), None)?;
        }
        let mesh = self.model.mesh.corners();
        let h2 = (mesh.rest_volume() / mesh.num_tets() as f64).powf(2.0 / 3.0);
        let elastic = self.model.mu() * h2 * (self.model.mesh.num_nodes() as f64).sqrt();
        Ok(norm(&self.model.dofs.gather(&external)).max(elastic))
    }

    /// The materials of the body and the region of every element.
    pub fn regions(&self) -> &Regions {
        &self.model.regions
    }
}
