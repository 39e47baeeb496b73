//! The stepping drivers (quasi-static load stepping and implicit Euler) and their results.

use crate::assembly::System;
use crate::model::{Model, NonlinearScheme};
use crate::nonlinear::dual;
use crate::nonlinear::newton::{self, Newton};
use crate::nonlinear::saddle::SaddleNewton;
use crate::nonlinear::target::{norm, StepTarget};

mod matrices;
mod projection;
mod report;
mod stepper;

use crate::terms::{EnergyTerm, Inertia};
use crate::{LoadLevel, Method, Problem, Regions, Settings, SolverError};
use faer::sparse::SparseColMat;
pub use matrices::Matrices;
use projection::Projector;
pub use projection::VolumeProjection;
pub use report::{IterationReport, StepReport, Timings};
use stepper::Stepper;
pub use stepper::{Adaptive, Progress, StepControl};

use isochor_mesh::element::{deformation_gradient, TET_EDGES};
use isochor_mesh::{ElementMesh, Vec3};
use nalgebra::{DMatrix, Matrix3};
use std::time::{Duration, Instant};

/// How time or load advances.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Stepping {
    /// Loads and prescribed motions follow the load parameter from 0 to 1; the levels
    /// `k / steps` are the frames, and `control` chooses the increments between them.
    QuasiStatic {
        /// Number of frames: the levels `k / steps`, `k = 1..=steps`.
        steps: usize,
        /// How the increments between frames are chosen.
        control: StepControl,
    },
    /// Implicit Euler (eq. 20-21) with time step `dt` for `frames` steps; prescribed motions
    /// follow `time / (dt * frames)`, loads are constant (unless they follow curves). A failed
    /// step is retried in substeps (`dt/2`, `dt/4`, ... down to `dt/1024`) that end on the
    /// frame's time.
    ImplicitEuler {
        /// Time step, in seconds.
        dt: f64,
        /// Number of steps (each a frame).
        frames: usize,
    },
}

impl Stepping {
    /// Quasi-static stepping with one solve per level `k / steps`.
    pub fn quasi_static(steps: usize) -> Self {
        Stepping::QuasiStatic {
            steps,
            control: StepControl::Fixed,
        }
    }

    /// Quasi-static stepping with adaptive increments (the defaults of [`Adaptive`]) and
    /// frames at the levels `k / steps`.
    pub fn adaptive(steps: usize) -> Self {
        Stepping::QuasiStatic {
            steps,
            control: StepControl::Adaptive(Adaptive::default()),
        }
    }

    /// The number of frames (levels written as results).
    pub fn frames(&self) -> usize {
        match *self {
            Stepping::QuasiStatic { steps, .. } => steps,
            Stepping::ImplicitEuler { frames, .. } => frames,
        }
    }
}

/// What continues an interrupted run exactly: the state, where the stepping stood, and the
/// contact multipliers (see [`Simulation::restore`]).
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
    /// The step's iteration log.
    pub report: &'a StepReport,
    /// The failed attempts (cut steps) since the previous accepted step.
    pub cuts: &'a [StepReport],
    /// The contact multipliers of the state (empty without obstacles).
    pub contact_multipliers: Vec<f64>,
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

type Sparse = SparseColMat<usize, f64>;

/// The linear system of one Newton iteration over the free DOFs and the multipliers (see
/// [`Linearizer::newton_system`]), dense: meant for tests and small meshes.
#[derive(Debug, Clone, PartialEq)]
pub struct NewtonSystem {
    /// The free DOFs (indices `3 v + axis` into the positions), in row order.
    pub free: Vec<usize>,
    /// The residual: the force residual on the free DOFs, then the constraint residual
    /// `phi - C p` (saddle-point methods only).
    pub residual: Vec<f64>,
    /// The right-hand side solved for: `-residual` minus the coupling to the prescribed
    /// DOFs (`K_fc` and `G_c`) applied to `gap`.
    pub rhs: Vec<f64>,
    /// The prescribed increments `target - x` (full space, zero on free DOFs).
    pub gap: Vec<f64>,
    /// The symmetric matrix: `K` over the free DOFs, or `[[K, G^T], [G, -C]]`.
    pub matrix: DMatrix<f64>,
}

impl NewtonSystem {
    /// Densifies `K` (lower triangle) and, for a KKT system, `G` and `C`.
    fn new(model: &Model, linear: Linear) -> Self {
        let Linear {
            residual,
            rhs,
            gap,
            k,
            kkt,
        } = linear;
        let n = k.ncols();
        let mut matrix = DMatrix::zeros(residual.len(), residual.len());
        let entries = |a: &Sparse| {
            let a = a.as_ref();
            (0..a.ncols())
                .flat_map(move |c| {
                    a.row_idx_of_col(c)
                        .zip(a.val_of_col(c))
                        .map(move |(r, v)| (r, c, *v))
                })
                .collect::<Vec<_>>()
        };
        for (r, c, v) in entries(&k) {
            matrix[(r, c)] += v;
            if r != c {
                matrix[(c, r)] += v;
            }
        }
        if let Some((g, compliance)) = &kkt {
            for (r, c, v) in entries(g) {
                matrix[(n + r, c)] += v;
                matrix[(c, n + r)] += v;
            }
            for (r, c, v) in compliance.as_ref().map(entries).unwrap_or_default() {
                matrix[(n + r, n + c)] -= v;
            }
        }
        NewtonSystem {
            free: model.dofs.free().to_vec(),
            residual,
            rhs,
            gap,
            matrix,
        }
    }
}

/// One Newton linearization as the solvers assemble it: the residual, right-hand side and
/// prescribed increments of [`NewtonSystem`], `K` over the free DOFs (lower triangle) and,
/// for a saddle-point method, `G` and the compliance `C` (`None` when `C = 0`).
struct Linear {
    residual: Vec<f64>,
    rhs: Vec<f64>,
    gap: Vec<f64>,
    k: Sparse,
    kkt: Option<(Sparse, Option<Sparse>)>,
}

/// The linear systems of one step (see [`Simulation::linearizer`]).
pub struct Linearizer<'s> {
    system: System<'s>,
    saddle: Option<SaddleNewton>,
    target: StepTarget,
    multipliers: usize,
}

impl Linearizer<'_> {
    /// The linear system the method's nonlinear solver builds at `trial`, after Dirichlet
    /// elimination. Quasi-static: `[[K, G^T], [G, -C]]` of eq. 24 of Francu et al. 2021;
    /// implicit Euler: with `M / dt^2` added to `K` (eq. 21). `K` includes the constraints'
    /// geometric stiffness (eq. 23). `standard` and `condensed` have `K` alone, and `dual`
    /// the Hessian of its primal problem (eq. 39) at the multipliers of `trial`.
    pub fn newton_system(&mut self, trial: &State) -> Result<NewtonSystem, SolverError> {
        let linear = self.linearize(trial)?;
        Ok(NewtonSystem::new(self.system.model, linear))
    }

    /// The linearization behind [`Self::newton_system`] and [`Self::matrices`].
    fn linearize(&mut self, trial: &State) -> Result<Linear, SolverError> {
        let model = self.system.model;
        if trial.positions.len() != model.mesh.num_nodes()
            || trial.multipliers.len() != self.multipliers
        {
            return Err(SolverError::InvalidProblem(format!(
                "a trial state needs {} positions and {} multipliers",
                model.mesh.num_nodes(),
                self.multipliers
            )));
        }
        let x = &trial.positions;
        match &self.saddle {
            None => {
                if let (Some(augmented), false) = (&model.augmented, trial.multipliers.is_empty()) {
                    augmented.set_multipliers(&trial.multipliers);
                }
                let l = newton::linearize(&mut self.system, x, &self.target)?;
                Ok(Linear {
                    residual: l.residual,
                    rhs: l.rhs,
                    gap: l.d_fixed,
                    k: l.k,
                    kkt: None,
                })
            }
            Some(saddle) => {
                let l = saddle.linearize(&mut self.system, x, &trial.multipliers, &self.target)?;
                let mut residual = l.sigma_f;
                residual.extend(l.theta);
                let mut rhs = l.rhs_x;
                rhs.extend(l.rhs_p);
                Ok(Linear {
                    residual,
                    rhs,
                    gap: l.d_fixed,
                    k: l.k,
                    kkt: Some((l.g, saddle.compliance().cloned())),
                })
            }
        }
    }
}

/// The nonlinear solver of a run.
enum Solver {
    Newton(Newton),
    Saddle(SaddleNewton),
    Dual(Newton),
}

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
            && matches!(settings.linear, crate::LinearSolver::Iterative(_))
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

    /// Continues from `checkpoint` (taken from a [`Frame`] of a run of this problem with the
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

    /// Pressure per tet at `state`: for `standard`, the mean Cauchy stress `tr(sigma)/3`;
    /// for the mixed and dual methods, the constraint pressures (P0 value, P1 average, `p/J`
    /// for the logarithmic measure); for `zonal`, the zone multipliers plus the mean stress
    /// of the energy (its penalty's `lambda U'(J)`, sec. 8.2 of Sheen et al. 2021).
    pub fn tet_pressures(&self, state: &State) -> Vec<f64> {
        let x = &state.positions;
        let constrained = match &self.model.constraints {
            Some(c) if state.multipliers.len() == c.num_constraints() => {
                Some(c.tet_pressures(x, &state.multipliers))
            }
            _ => None,
        };
        let material_pressure = |e: usize| mean_stress(&self.model, e, x);
        (0..self.model.mesh.num_elements())
            .map(|e| match (&constrained, self.model.method) {
                (None, _) => material_pressure(e),
                (Some(p), Method::Zonal) => p[e] + material_pressure(e),
                (Some(p), _) => p[e],
            })
            .collect()
    }

    /// Cauchy stress per element at its centroid: the material's `P F^T / J` plus, for the
    /// methods with constraints, their hydrostatic part (the multiplier pressure of the
    /// element, see [`Simulation::tet_pressures`]). NaN where the energy is undefined.
    pub fn cauchy_stress(&self, state: &State) -> Vec<Matrix3<f64>> {
        let x = &state.positions;
        let constrained = match &self.model.constraints {
            Some(c) if state.multipliers.len() == c.num_constraints() => {
                c.tet_pressures(x, &state.multipliers)
            }
            _ => Vec::new(),
        };
        (0..self.model.mesh.num_elements())
            .map(|e| {
                let material =
                    material_stress(&self.model, e, x).unwrap_or_else(|| Matrix3::repeat(f64::NAN));
                material + Matrix3::identity() * constrained.get(e).copied().unwrap_or(0.0)
            })
            .collect()
    }

    /// Von Mises stress `sqrt(3/2 s:s)` per element at its centroid, `s` the deviatoric
    /// Cauchy stress (NaN where the energy is undefined). The hydrostatic constraint
    /// pressures do not enter it, so it is the same for every method's stress.
    pub fn von_mises(&self, state: &State) -> Vec<f64> {
        self.cauchy_stress(state).iter().map(von_mises).collect()
    }

    /// The nodal (P1) pressure field of the methods with one multiplier per vertex
    /// (`mixed-p1`, `mixed-p1-log`, `dual`), tension positive like the multipliers, at every
    /// node: a vertex's multiplier, and on a 10-node mesh the mean of the two ends at a
    /// mid-edge node (the field is linear in each element). `None` for the other methods.
    pub fn nodal_pressures(&self, state: &State) -> Option<Vec<f64>> {
        let nodal = matches!(
            self.model.method,
            Method::MixedP1 | Method::MixedP1Log | Method::Dual
        );
        let mesh = &self.model.mesh;
        let vertices = mesh.corners().num_vertices();
        if !nodal || state.multipliers.len() != vertices {
            return None;
        }
        let mut p = state.multipliers.clone();
        p.resize(mesh.num_nodes(), 0.0);
        for e in 0..mesh.num_elements() {
            let nodes = mesh.element(e);
            for (k, [a, b]) in TET_EDGES
                .iter()
                .enumerate()
                .take(nodes.len().saturating_sub(4))
            {
                p[nodes[4 + k]] =
                    0.5 * (state.multipliers[nodes[*a]] + state.multipliers[nodes[*b]]);
            }
        }
        Some(p)
    }

    /// The contact multipliers (normal force per vertex and obstacle, never negative),
    /// boundary-vertex-major over the obstacles; empty without obstacles.
    pub fn contact_multipliers(&self) -> Vec<f64> {
        self.model
            .contact
            .as_ref()
            .map(|c| c.multipliers())
            .unwrap_or_default()
    }

    /// Energies of `state`.
    pub fn energies(&self, state: &State) -> Energies {
        let mut energies = Energies {
            kinetic: 0.5
                * self
                    .model
                    .masses
                    .iter()
                    .zip(&state.velocities)
                    .map(|(m, v)| m * v.norm_squared())
                    .sum::<f64>(),
            ..Energies::default()
        };
        for term in &self.model.terms {
            let e = term
                .evaluate(&state.positions, &LoadLevel::FULL, None, None)
                .unwrap_or(f64::NAN);
            if term.is_external() {
                energies.external += e;
            } else {
                energies.elastic += e;
            }
        }
        // Relative to rest: minus the work of the loads on the displacements.
        energies.external -= self.rest_external;
        energies.constraint = self.constraint_energy(state);
        energies
    }

    /// [`Energies::constraint`] of `state`.
    fn constraint_energy(&self, state: &State) -> f64 {
        let p = &state.multipliers;
        match (&self.model.constraints, &self.model.augmented) {
            (Some(c), _) if p.len() == c.num_constraints() => {
                0.5 * c
                    .compliance()
                    .nonzero_entries()
                    .into_iter()
                    .map(|(r, k, v)| p[r] * v * p[k])
                    .sum::<f64>()
            }
            (None, Some(augmented)) => augmented
                .evaluate(&state.positions, &LoadLevel::FULL, None, None)
                .unwrap_or(f64::NAN),
            _ => 0.0,
        }
    }

    /// The linearization of step `step` (from 1) of `stepping` from the current state (the
    /// previous step), taken with one solve per frame: [`Linearizer::newton_system`] gives
    /// the linear system the method's nonlinear solver builds at any trial state, for tests
    /// against finite differences of its residual. Obstacles, if any, are moved to the
    /// step's position (as [`Self::run`] does at each step) and keep their multipliers.
    pub fn linearizer(
        &mut self,
        stepping: Stepping,
        step: usize,
    ) -> Result<Linearizer<'_>, SolverError> {
        check_stepping(stepping)?;
        let (level, dt) = match stepping {
            Stepping::QuasiStatic { steps, .. } => {
                (LoadLevel::quasi_static(step as f64 / steps as f64), None)
            }
            Stepping::ImplicitEuler { dt, frames } => (
                LoadLevel {
                    t: step as f64 * dt,
                    ramp: 1.0,
                    fraction: step as f64 / frames as f64,
                },
                Some(dt),
            ),
        };
        self.linearizer_at(level, dt)
    }

    /// The linearizer of a step to `level` with time step `dt` (`None`: quasi-static).
    fn linearizer_at(
        &mut self,
        level: LoadLevel,
        dt: Option<f64>,
    ) -> Result<Linearizer<'_>, SolverError> {
        let force_tolerance = self.settings.force_tolerance * self.force_scale()?;
        self.model.set_contact_stiffness(dt);
        let inertia = dt.map(|dt| {
            let mut inertia = Inertia::new(self.model.masses.clone(), dt);
            inertia.begin_step(&self.state.positions, &self.state.velocities, dt);
            inertia
        });
        let system = System::new(&self.model, inertia, self.settings)?;
        let saddle = match self.model.scheme {
            NonlinearScheme::Minimize | NonlinearScheme::Dual => None,
            NonlinearScheme::SaddleDirect | NonlinearScheme::SaddleSchur => {
                Some(SaddleNewton::new(&system)?)
            }
        };
        let target = step_target(&self.model, level, force_tolerance);
        if let Some(contact) = &self.model.contact {
            contact.begin_step(level);
        }
        Ok(Linearizer {
            system,
            saddle,
            target,
            multipliers: self.state.multipliers.len(),
        })
    }

    /// Runs `stepping` from the current state (or from where a restored checkpoint stood),
    /// calling `observer` after every accepted step. A failed step is retried with half the
    /// increment (adaptive quasi-static stepping, dynamics) from the last accepted state,
    /// contact multipliers included; when no retry is left the run ends, the state left at
    /// the last accepted step, which the error carries too.
    ///
    /// ```
    /// use isochor_mesh::generate::box_grid;
    /// use isochor_solvers::{Problem, Settings, Simulation, Stepping, Vec3};
    ///
    /// // A 1 cm silicone cube on its base, squashed by its own weight in two load steps.
    /// let mesh = box_grid(Vec3::zeros(), Vec3::repeat(0.01), [1, 1, 1])?;
    /// let base: Vec<usize> = (0..4).collect(); // the vertices at z = 0
    /// let problem = Problem::builder(mesh)
    ///     .clamp(base)
    ///     .gravity(Vec3::new(0.0, 0.0, -9.81))
    ///     .build()?;
    /// let mut simulation = Simulation::new(problem, Settings::default())?;
    /// let mut frames = 0;
    /// let summary = simulation.run(Stepping::quasi_static(2), |_frame| frames += 1)?;
    /// assert_eq!(frames, 2);
    /// let top = summary.final_state.positions[7]; // the corner (1, 1, 1) cm
    /// assert!(top.z < 0.01);
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn run(
        &mut self,
        stepping: Stepping,
        mut observer: impl FnMut(&Frame<'_>),
    ) -> Result<RunSummary, Box<SimulationFailure>> {
        let start = Instant::now();
        let mut reports = Vec::new();
        let fail = |error: SolverError, step: usize, state: &State, reports: &Vec<StepReport>| {
            Box::new(SimulationFailure {
                error,
                failed_step: step,
                last_state: state.clone(),
                reports: reports.clone(),
            })
        };
        let dt = match stepping {
            Stepping::QuasiStatic { .. } => None,
            Stepping::ImplicitEuler { dt, .. } => Some(dt),
        };
        if let Err(e) = check_stepping(stepping) {
            return Err(fail(e, 0, &self.state, &reports));
        }
        if self.settings.accept_unconverged && dt.is_none() {
            let e = SolverError::InvalidProblem(
                "accept_unconverged applies to implicit Euler only: a quasi-static step must be an equilibrium".into(),
            );
            return Err(fail(e, 0, &self.state, &reports));
        }
        if self.settings.volume_projection != VolumeProjection::None && dt.is_none() {
            let e = SolverError::InvalidProblem(
                "a volume projection applies to implicit Euler only: it corrects the state after each time step".into(),
            );
            return Err(fail(e, 0, &self.state, &reports));
        }
        let projector = match Projector::new(
            self.settings.volume_projection,
            &self.model.mesh,
            &self.model.masses,
            &self.model.dofs,
            self.settings.ordering,
        ) {
            Ok(p) => p,
            Err(e) => return Err(fail(e, 0, &self.state, &reports)),
        };
        let force_tolerance = match self.force_scale() {
            Ok(scale) => self.settings.force_tolerance * scale,
            Err(e) => return Err(fail(e, 0, &self.state, &reports)),
        };
        self.model.set_contact_stiffness(dt);
        let (lo, hi) = self.model.mesh.corners().bounding_box();
        let contact_tolerance = self.settings.contact_tolerance * (hi - lo).norm();
        let (mut system, mut solver) = match setup(&self.model, self.settings, dt) {
            Ok(s) => s,
            Err(e) => return Err(fail(e, 0, &self.state, &reports)),
        };
        let stepper = Stepper::new(&stepping, &self.model.curve_corners);
        let mut progress = self
            .resume
            .take()
            .unwrap_or_else(|| Progress::start(&stepping));
        if !system.is_valid(&self.state.positions) {
            let e = SolverError::InvalidInitialState(format!(
                "{} tets are inverted or degenerate where the energy is undefined",
                self.model.mesh.count_inverted(&self.state.positions)
            ));
            return Err(fail(e, progress.steps + 1, &self.state, &reports));
        }
        let mut max_inverted = self.model.mesh.count_inverted(&self.state.positions);
        let mut cuts: Vec<StepReport> = Vec::new();
        while !stepper.finished(&progress) {
            let step_start = Instant::now();
            let attempt = stepper.next(&progress);
            let step = progress.steps + 1;
            let target = step_target(&self.model, attempt.level, force_tolerance);
            if let Some(inertia) = &mut system.inertia {
                inertia.begin_step(
                    &self.state.positions,
                    &self.state.velocities,
                    attempt.increment,
                );
            }
            let contact_start = system.model.contact.as_ref().map(|c| c.snapshot());
            if let Some(contact) = &system.model.contact {
                contact.begin_step(attempt.level);
            }
            let mut x = self.state.positions.clone();
            let mut p = self.state.multipliers.clone();
            let mut report = StepReport {
                step,
                t: attempt.level.t,
                increment: attempt.increment,
                ..StepReport::default()
            };
            // The contact's projected multiplier updates (its module docs) around the
            // method's own solve.
            let result = loop {
                let solved = match &mut solver {
                    Solver::Newton(newton) => {
                        newton.minimize(&mut system, &mut x, &target, &mut report)
                    }
                    Solver::Saddle(saddle) => {
                        saddle.solve(&mut system, &mut x, &mut p, &target, &mut report)
                    }
                    Solver::Dual(newton) => {
                        dual::solve(newton, &mut system, &mut x, &mut p, &target, &mut report)
                    }
                };
                // A fixed iteration count: the last iterate is the step (`report.converged`
                // stays false).
                let solved = match solved {
                    Err(SolverError::NotConverged { .. }) if self.settings.accept_unconverged => {
                        Ok(())
                    }
                    other => other,
                };
                let Some(contact) = &system.model.contact else {
                    break solved;
                };
                if solved.is_err() {
                    break solved;
                }
                report.contact_iterations += 1;
                if contact.update(&x, contact_tolerance) {
                    break solved;
                }
                if report.contact_iterations >= self.settings.max_contact_iterations {
                    report.converged = false;
                    break Err(SolverError::ContactNotConverged {
                        iterations: report.contact_iterations,
                        max_penetration: contact.summary(&x).max_penetration,
                    });
                }
            };
            if let Some(contact) = &system.model.contact {
                report.contact = contact.summary(&x);
            }
            report.wall_time = step_start.elapsed();
            if let Err(e) = result {
                // Back to the last accepted step, contact multipliers included.
                if let (Some(contact), Some(start)) = (&system.model.contact, contact_start) {
                    contact.restore(start);
                }
                report.converged = false;
                report.failure = Some(e.to_string());
                reports.push(report.clone());
                match stepper.cut(&progress, &attempt, e) {
                    Ok(cut) => {
                        cuts.push(report);
                        progress = cut;
                        continue;
                    }
                    Err(e) => return Err(fail(e, step, &self.state, &reports)),
                }
            }
            reports.push(report);
            let mut velocities = match dt {
                Some(_) => x
                    .iter()
                    .zip(&self.state.positions)
                    .map(|(a, b)| (a - b) / attempt.increment)
                    .collect(),
                None => self.state.velocities.clone(),
            };
            if let Err(e) =
                projector.apply(&self.model.mesh, &mut x, &mut velocities, attempt.increment)
            {
                return Err(fail(e, step, &self.state, &reports));
            }
            self.state = State {
                positions: x,
                velocities,
                multipliers: p,
                t: attempt.level.t,
            };
            let report = reports.last().expect("pushed above");
            progress = stepper.accept(&progress, &attempt, report.newton_iterations());
            let inverted = self.model.mesh.count_inverted(&self.state.positions);
            max_inverted = max_inverted.max(inverted);
            let contact = self.model.contact.as_ref();
            let stress = self.cauchy_stress(&self.state);
            observer(&Frame {
                index: step,
                frame: attempt.frame,
                progress,
                state: &self.state,
                tet_pressures: self.tet_pressures(&self.state),
                von_mises: stress.iter().map(von_mises).collect(),
                stress,
                nodal_pressures: self.nodal_pressures(&self.state),
                energies: self.energies(&self.state),
                inverted_tets: inverted,
                contact_forces: contact
                    .map(|c| c.vertex_forces(&self.state.positions))
                    .unwrap_or_default(),
                report,
                cuts: &cuts,
                contact_multipliers: contact.map(|c| c.multipliers()).unwrap_or_default(),
            });
            cuts.clear();
        }
        Ok(RunSummary {
            reports,
            final_state: self.state.clone(),
            max_inverted_tets: max_inverted,
            wall_time: start.elapsed(),
        })
    }
}

/// The assembled system of a run with time step `dt` (inertia in implicit Euler, none in
/// quasi-static stepping) and the nonlinear solver of the model's scheme.
fn setup(
    model: &Model,
    settings: Settings,
    dt: Option<f64>,
) -> Result<(System<'_>, Solver), SolverError> {
    let inertia = dt.map(|dt| Inertia::new(model.masses.clone(), dt));
    let system = System::new(model, inertia, settings)?;
    let solver = match model.scheme {
        NonlinearScheme::Minimize => Solver::Newton(Newton::new(&system)?),
        NonlinearScheme::Dual => Solver::Dual(Newton::new(&system)?),
        NonlinearScheme::SaddleDirect | NonlinearScheme::SaddleSchur => {
            Solver::Saddle(SaddleNewton::new(&system)?)
        }
    };
    Ok((system, solver))
}

/// The target of a solve at `level`: the loads' level and the prescribed DOFs' values.
fn step_target(model: &Model, level: LoadLevel, force_tolerance: f64) -> StepTarget {
    StepTarget {
        level,
        prescribed: model.dofs.targets(model.mesh.nodes(), level).collect(),
        force_tolerance,
    }
}

/// Cauchy stress `P F^T / J` of the model's material energy at the centroid of element `e`
/// (`None` where the energy is undefined). The constraint pressures of the mixed and zonal
/// methods add only a hydrostatic part.
fn material_stress(model: &Model, e: usize, x: &[Vec3]) -> Option<Matrix3<f64>> {
    let f = deformation_gradient(x, model.mesh.element(e), model.centroids.gradients(e, 0));
    let j = f.determinant();
    let p = model.regions.energy(e).pk1(&f).ok()?;
    Some(p * f.transpose() / j)
}

/// Von Mises stress `sqrt(3/2 s:s)` of a Cauchy stress, `s` its deviatoric part.
fn von_mises(sigma: &Matrix3<f64>) -> f64 {
    let dev = sigma - Matrix3::identity() * (sigma.trace() / 3.0);
    (1.5 * dev.norm_squared()).sqrt()
}

/// Mean Cauchy stress `tr(sigma) / 3` of the model's material at the centroid of element `e`
/// (NaN where the energy is undefined).
fn mean_stress(model: &Model, e: usize, x: &[Vec3]) -> f64 {
    material_stress(model, e, x).map_or(f64::NAN, |s| s.trace() / 3.0)
}

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

fn check_stepping(stepping: Stepping) -> Result<(), SolverError> {
    match stepping {
        Stepping::QuasiStatic { steps: 0, .. } => Err(SolverError::InvalidProblem(
            "steps must be at least 1".into(),
        )),
        Stepping::QuasiStatic {
            control: StepControl::Adaptive(a),
            ..
        } if !(a.first > 0.0 && a.first <= 1.0 && a.min > 0.0 && a.min <= a.first) => {
            Err(SolverError::InvalidProblem(format!(
                "adaptive stepping needs 0 < min increment ({}) <= first increment ({}) <= 1",
                a.min, a.first
            )))
        }
        Stepping::ImplicitEuler { frames: 0, .. } => Err(SolverError::InvalidProblem(
            "frames must be at least 1".into(),
        )),
        Stepping::ImplicitEuler { dt, .. } if !(dt > 0.0 && dt.is_finite()) => Err(
            SolverError::InvalidProblem(format!("dt = {dt} must be positive")),
        ),
        _ => Ok(()),
    }
}
