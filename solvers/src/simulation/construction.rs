//! Building a simulation from a problem, and restoring one from a checkpoint.

use super::state::{Checkpoint, State};
use super::Simulation;
use crate::error::SolverError;
use crate::model::{Model, NonlinearScheme};
use crate::problem::friction::FrictionSpec;
use crate::problem::mesh_obstacle::MeshObstacle;
use crate::problem::schedule::LoadLevel;
use crate::problem::Problem;
use crate::settings::{LinearSolver, Settings};
use crate::terms::SurfaceContactSpec;
use isochor_mesh::Vec3;

impl Simulation {
    /// Builds the model of `problem` (only the terms it names) at its rest state.
    pub fn new(problem: Problem, settings: Settings) -> Result<Self, SolverError> {
        check_settings(&settings)?;
        problem.validate()?;
        let model = Model::new(problem, settings.project_hessians)?;
        if model.scheme == NonlinearScheme::Dual && settings.accept_unconverged {
            return Err(SolverError::InvalidProblem(
                "accept_unconverged does not apply to dual: its max_iterations counts primal iterations per dual iteration".into(),
            ));
        }
        if model.scheme == NonlinearScheme::Dual
            && matches!(settings.linear, LinearSolver::Iterative(_))
        {
            return Err(SolverError::InvalidProblem(
                "the dual solver reuses the primal factorization (eq. 41): use the direct linear solver".into(),
            ));
        }
        let n = model.mesh.num_nodes();
        let m = model.row_volumes.len();
        let state = State {
            positions: model.mesh.nodes().to_vec(),
            velocities: vec![Vec3::zeros(); n],
            multipliers: vec![
                0.0;
                if model.scheme == NonlinearScheme::Minimize {
                    0
                } else {
                    m
                }
            ],
            t: 0.0,
        };
        let rest = model.mesh.nodes();
        let rest_external = model
            .terms
            .iter()
            .filter(|t| t.is_external())
            .map(|t| t.evaluate(rest, &LoadLevel::FULL, None, None))
            .sum::<Result<f64, _>>()?;
        Ok(Simulation {
            model,
            settings,
            state,
            resume: None,
            rest_external,
        })
    }

    /// Turns barrier contact between the mesh's boundary surfaces on (between bodies, and of
    /// a surface with itself if `spec.self_contact`): every line-search step of every method
    /// is then limited so that no pair of surface triangles crosses. Errors: a bad `dhat` or
    /// a body list of another length than the nodes.
    pub fn set_surface_contact(&mut self, spec: SurfaceContactSpec) -> Result<(), SolverError> {
        self.model.set_surface_contact(spec)
    }

    /// Turns lagged smoothed Coulomb friction on (Li et al. 2020, sec. 5): against the
    /// obstacles (one coefficient each, in the problem's order; none for none) and, with
    /// `spec.surfaces`, between surfaces, which needs [`Self::set_surface_contact`] first.
    /// Errors: a negative or non-finite coefficient, a non-positive `epsv`, a count of
    /// coefficients or node bodies that is not the problem's.
    pub fn set_friction(&mut self, spec: FrictionSpec) -> Result<(), SolverError> {
        self.model.set_friction(spec)
    }

    /// Adds meshed rigid obstacles to the barrier contact of [`Self::set_surface_contact`]
    /// (which must be on): the bodies' surfaces meet their triangles, placed at each
    /// attempt's load level; an obstacle motion that would cross a body in one step fails
    /// the attempt, so adaptive stepping cuts the increment. Errors: surface contact off, a
    /// bad obstacle, or one intersecting a body at the start.
    pub fn set_mesh_obstacles(&mut self, obstacles: Vec<MeshObstacle>) -> Result<(), SolverError> {
        self.model.set_mesh_obstacles(obstacles)
    }

    /// Sets the velocity of every node (the initial velocity of a dynamic run; quasi-static
    /// stepping ignores it). Errors: a length other than the number of nodes, or a value that
    /// is not finite.
    pub fn set_velocities(&mut self, velocities: Vec<Vec3>) -> Result<(), SolverError> {
        let n = self.state.positions.len();
        if velocities.len() != n {
            return Err(SolverError::InvalidProblem(format!(
                "{} velocities for {n} nodes",
                velocities.len()
            )));
        }
        if let Some(node) = velocities
            .iter()
            .position(|v| !v.iter().all(|c| c.is_finite()))
        {
            return Err(SolverError::InvalidProblem(format!(
                "the velocity of node {node} is not finite"
            )));
        }
        self.state.velocities = velocities;
        Ok(())
    }

    /// Continues from `checkpoint` (taken from a [`Frame`](crate::Frame) of a run of this problem with the
    /// same stepping): the next [`Self::run`] starts where that run stood, and gives the
    /// results the uninterrupted run gives, bit for bit.
    pub fn restore(&mut self, checkpoint: Checkpoint) -> Result<(), SolverError> {
        let Checkpoint {
            state,
            progress,
            contact_multipliers,
        } = checkpoint;
        let n = self.model.mesh.num_nodes();
        if state.positions.len() != n
            || state.velocities.len() != n
            || state.multipliers.len() != self.state.multipliers.len()
        {
            return Err(SolverError::InvalidProblem(format!(
                "the checkpoint holds {} positions, {} velocities and {} multipliers; this problem has {n} nodes and {} multipliers",
                state.positions.len(),
                state.velocities.len(),
                state.multipliers.len(),
                self.state.multipliers.len()
            )));
        }
        if !(progress.increment > 0.0
            && progress.increment.is_finite()
            && progress.t.is_finite()
            && progress.t >= 0.0)
        {
            return Err(SolverError::InvalidProblem(format!(
                "the checkpoint's progress is not a run's: t = {}, increment = {}",
                progress.t, progress.increment
            )));
        }
        if let Some(surface) = &self.model.surface_contact {
            surface.forget_placement();
        }
        if let Some(contact) = &self.model.contact {
            contact.set_multipliers(contact_multipliers)?;
        } else if !contact_multipliers.is_empty() {
            return Err(SolverError::InvalidProblem(
                "the checkpoint holds contact multipliers, but the problem has no obstacles".into(),
            ));
        }
        self.state = state;
        self.resume = Some(progress);
        Ok(())
    }
}

/// Checks the solver settings before a simulation is built.
fn check_settings(s: &Settings) -> Result<(), SolverError> {
    let bad = |what: &str| {
        Err(SolverError::InvalidProblem(format!(
            "invalid solver setting: {what}"
        )))
    };
    if s.max_iterations == 0 {
        return bad("max_iterations must be at least 1");
    }
    if !(s.force_tolerance > 0.0 && s.force_tolerance.is_finite()) {
        return bad("force_tolerance must be positive");
    }
    if !(s.constraint_tolerance > 0.0 && s.constraint_tolerance.is_finite()) {
        return bad("constraint_tolerance must be positive");
    }
    if !(s.contact_tolerance > 0.0 && s.contact_tolerance.is_finite()) {
        return bad("contact_tolerance must be positive");
    }
    if s.max_contact_iterations == 0 {
        return bad("max_contact_iterations must be at least 1");
    }
    s.volume_projection.validate()
}
