//! The unknowns of a simulation and what a run reports of them: the state, its energies, the
//! frame an observer sees, the checkpoint that continues a run, and how a run ends.

use super::stepper::Progress;
use crate::error::SolverError;
use crate::model::pressure_gauges::PressureReading;
use crate::nonlinear::report::StepReport;
use crate::terms::SurfaceContactSummary;
use isochor_mesh::Vec3;
use nalgebra::Matrix3;
use std::time::Duration;

/// What continues an interrupted run exactly: the state, where the stepping stood, and the
/// contact multipliers (see [`Simulation::restore`](crate::Simulation::restore)).
#[derive(Debug, Clone, PartialEq)]
pub struct Checkpoint {
    /// The last accepted state.
    pub state: State,
    /// Where the stepping stood after it.
    pub progress: Progress,
    /// The contact multipliers (empty without obstacles).
    pub contact_multipliers: Vec<f64>,
}

/// The unknowns of a simulation.
#[derive(Debug, Clone, PartialEq)]
pub struct State {
    /// Positions.
    pub positions: Vec<Vec3>,
    /// Velocities (zero in quasi-static stepping).
    pub velocities: Vec<Vec3>,
    /// Pressures or multipliers, one per constraint (empty for `standard`).
    pub multipliers: Vec<f64>,
    /// Load parameter or time of this state.
    pub t: f64,
}

/// Energies of a state, for plots of energy against time.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Energies {
    /// Kinetic energy `v^T M v / 2`.
    pub kinetic: f64,
    /// Stored elastic energy (including epidermis): for the mixed, dual and condensed methods
    /// only the distortional part, their volumetric energy is [`Energies::constraint`].
    pub elastic: f64,
    /// Energy of the compliant volume constraints: `p^T C p / 2` at the state's pressures
    /// (equal to the penalty `phi^T C^-1 phi / 2` once `phi = C p`; for `dual`, without the
    /// base Poisson ratio's augmentation), `phi^T C^-1 phi / 2` for `condensed`, 0 for
    /// `standard` and for hard constraints (`C = 0`).
    pub constraint: f64,
    /// Potential of the external loads (gravity, tractions, pressure) relative to the rest
    /// state: minus their work on the displacements.
    pub external: f64,
}

/// What the observer sees after each accepted step.
#[derive(Debug)]
pub struct Frame<'a> {
    /// Accepted step, from 1.
    pub index: usize,
    /// The frame this step ends on (from 1), if it ends on one.
    pub frame: Option<usize>,
    /// Where the stepping stands after this step.
    pub progress: Progress,
    /// The accepted state.
    pub state: &'a State,
    /// Pressure per tet (see [`crate::Simulation::tet_pressures`]).
    pub tet_pressures: Vec<f64>,
    /// Von Mises stress per tet (see [`crate::Simulation::von_mises`]).
    pub von_mises: Vec<f64>,
    /// Cauchy stress per tet (see [`crate::Simulation::cauchy_stress`]).
    pub stress: Vec<Matrix3<f64>>,
    /// The nodal pressure field of the P1 methods (see [`crate::Simulation::nodal_pressures`]).
    pub nodal_pressures: Option<Vec<f64>>,
    /// Energies of the state.
    pub energies: Energies,
    /// Tets with non-positive volume in this state.
    pub inverted_tets: usize,
    /// Contact force on every vertex (empty without obstacles).
    pub contact_forces: Vec<Vec3>,
    /// The barrier contact of the bodies' surfaces at the state (`None` when it is off).
    pub surface_contact: Option<SurfaceContactSummary>,
    /// Where each meshed obstacle's vertices stand at the state (empty without).
    pub mesh_obstacles: Vec<Vec<Vec3>>,
    /// The step's iteration log.
    pub report: &'a StepReport,
    /// The failed attempts (cut steps) since the previous accepted step.
    pub cuts: &'a [StepReport],
    /// The contact multipliers of the state (empty without obstacles).
    pub contact_multipliers: Vec<f64>,
    /// Every pressure load's pressure and enclosed volume ratio, in the order of the
    /// problem's pressure loads (see [`crate::Simulation::pressure_readings`]).
    pub pressure_loads: Vec<PressureReading>,
}

impl Frame<'_> {
    /// What continues the run from this step.
    pub fn checkpoint(&self) -> Checkpoint {
        Checkpoint {
            state: self.state.clone(),
            progress: self.progress,
            contact_multipliers: self.contact_multipliers.clone(),
        }
    }
}

/// A run that ended early: why, the last accepted state, and every step's log.
#[derive(Debug, Clone, thiserror::Error)]
#[error("step {failed_step} failed: {error}")]
pub struct SimulationFailure {
    /// What went wrong.
    #[source]
    pub error: SolverError,
    /// The step that failed (1-based, counting accepted steps).
    pub failed_step: usize,
    /// The last converged state (the rest state if the first step failed).
    pub last_state: State,
    /// Reports of every step, the failed one last.
    pub reports: Vec<StepReport>,
}

/// A completed run.
#[derive(Debug, Clone, PartialEq)]
pub struct RunSummary {
    /// Reports of every attempted step, cut ones included.
    pub reports: Vec<StepReport>,
    /// The final state.
    pub final_state: State,
    /// The most inverted tets in any accepted state.
    pub max_inverted_tets: usize,
    /// Wall time of the whole run.
    pub wall_time: Duration,
}

impl RunSummary {
    /// Newton (or dual) iterations over all steps, cut ones included.
    pub fn newton_iterations(&self) -> usize {
        self.reports.iter().map(StepReport::newton_iterations).sum()
    }

    /// Failed attempts that were retried with a smaller increment.
    pub fn cuts(&self) -> usize {
        self.reports.iter().filter(|r| r.failure.is_some()).count()
    }
}
