//! The stepping loop of [`Simulation::run`]: a plan fixed before the first step, then per
//! step an attempt (the method's solve inside the contact updates), a cut on failure, or the
//! accepted state (velocities, volume projection) and its frame.

use super::limit_point::PressureHistory;
use super::state::{Frame, RunSummary, SimulationFailure, State};
use super::stepper::{Attempt, Progress, Stepper};
use super::stepping::{check_stepping, Stepping};
use super::volume_projection::VolumeProjector;
use super::Simulation;
use crate::assembly::System;
use crate::error::SolverError;
use crate::model::{Model, NonlinearScheme};
use crate::nonlinear::dual;
use crate::nonlinear::newton::Newton;
use crate::nonlinear::report::StepReport;
use crate::nonlinear::saddle::SaddleNewton;
use crate::nonlinear::target::StepTarget;
use crate::problem::schedule::LoadLevel;
use crate::settings::{Settings, VolumeProjection};
use crate::terms::Inertia;
use isochor_mesh::Vec3;
use std::ops::ControlFlow;
use std::time::Instant;

impl Simulation {
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
        self.run_until(stepping, |frame| {
            observer(frame);
            ControlFlow::Continue(())
        })
    }

    /// [`Simulation::run`] with an `observer` that may stop the stepping: when it returns
    /// [`ControlFlow::Break`] after an accepted step, the run ends there with
    /// [`SolverError::Interrupted`], the state left at that step (which the error carries).
    pub fn run_until(
        &mut self,
        stepping: Stepping,
        mut observer: impl FnMut(&Frame<'_>) -> ControlFlow<()>,
    ) -> Result<RunSummary, Box<SimulationFailure>> {
        let start = Instant::now();
        let plan = self
            .plan(stepping)
            .map_err(|e| failure(e, 0, &self.state, &[]))?;
        let setup = Instant::now();
        let mut run = Run::new(&self.model, plan).map_err(|e| failure(e, 0, &self.state, &[]))?;
        run.setup = setup.elapsed();
        let stepper = Stepper::new(&stepping, &self.model.curve_corners);
        let mut progress = match self.resume.take() {
            Some(resumed) => {
                stepper.check_progress(&resumed).map_err(|m| {
                    let e = SolverError::InvalidProblem(format!("the checkpoint's {m}"));
                    failure(e, 0, &self.state, &[])
                })?;
                resumed
            }
            None => Progress::start(&stepping),
        };
        if !run.system.is_valid(&self.state.positions) {
            let e = SolverError::InvalidInitialState(format!(
                "{} tets are inverted or degenerate where the energy is undefined",
                self.model.mesh.count_inverted(&self.state.positions)
            ));
            return Err(failure(e, progress.steps + 1, &self.state, &[]));
        }
        let mut reports = Vec::new();
        let mut max_inverted = self.model.mesh.count_inverted(&self.state.positions);
        let mut cuts: Vec<StepReport> = Vec::new();
        let mut pressures = PressureHistory::new(
            self.model
                .pressure_gauges
                .iter()
                .map(|g| g.is_given())
                .collect(),
            self.pressure_readings(&self.state, stepper.level_at(&progress)),
        );
        while !stepper.finished(&progress) {
            let attempt = stepper.next(&progress);
            let step = progress.steps + 1;
            let start_level = stepper.level(self.state.t);
            let (x, p, mut report, result) = run.attempt(&self.state, &attempt, start_level, step);
            if let Err(e) = result {
                report.converged = false;
                report.failure = Some(e.to_string());
                reports.push(report.clone());
                if let (false, Some(e)) = (cuts.is_empty(), pressures.limit_point()) {
                    return Err(failure(e, step, &self.state, &reports));
                }
                match stepper.cut(&progress, &attempt, e) {
                    Ok(cut) => {
                        cuts.push(report);
                        progress = cut;
                        continue;
                    }
                    Err(e) => return Err(failure(e, step, &self.state, &reports)),
                }
            }
            reports.push(report);
            self.state = run
                .accept(&self.state, x, p, &attempt)
                .map_err(|e| failure(e, step, &self.state, &reports))?;
            if let Some(contact) = &self.model.surface_contact {
                contact.accept_step();
            }
            let report = reports.last().expect("pushed above");
            progress = stepper.accept(&progress, &attempt, report.newton_iterations());
            let inverted = self.model.mesh.count_inverted(&self.state.positions);
            max_inverted = max_inverted.max(inverted);
            let frame = self.frame(
                attempt.frame,
                progress,
                attempt.level,
                inverted,
                report,
                &cuts,
            );
            pressures.push(frame.pressure_loads.clone());
            if observer(&frame).is_break() {
                let e = SolverError::Interrupted { after_step: step };
                return Err(failure(e, step + 1, &self.state, &reports));
            }
            cuts.clear();
        }
        Ok(RunSummary {
            reports,
            final_state: self.state.clone(),
            max_inverted_tets: max_inverted,
            wall_time: start.elapsed(),
        })
    }

    /// Checks that `progress`, read from a checkpoint, is a point a run of `stepping` on this
    /// problem can reach (levels, steps, load parameter or time and increment consistent with the
    /// stepping and the load curves); the message names the field at fault.
    pub fn check_progress(&self, stepping: Stepping, progress: &Progress) -> Result<(), String> {
        Stepper::new(&stepping, &self.model.curve_corners).check_progress(progress)
    }

    /// Checks `stepping` against the settings and fixes what a run of it needs before its
    /// first step (the contact stiffness of its time step included).
    fn plan(&mut self, stepping: Stepping) -> Result<RunPlan, SolverError> {
        let dt = match stepping {
            Stepping::QuasiStatic { .. } => None,
            Stepping::ImplicitEuler { dt, .. } => Some(dt),
        };
        check_stepping(stepping)?;
        if self.settings.accept_unconverged && dt.is_none() {
            return Err(SolverError::InvalidProblem(
                "accept_unconverged applies to implicit Euler only: a quasi-static step must be an equilibrium".into(),
            ));
        }
        if self.settings.volume_projection != VolumeProjection::None && dt.is_none() {
            return Err(SolverError::InvalidProblem(
                "a volume projection applies to implicit Euler only: it corrects the state after each time step".into(),
            ));
        }
        let projector = VolumeProjector::new(
            self.settings.volume_projection,
            &self.model.mesh,
            &self.model.masses,
            &self.model.dofs,
            self.settings.ordering,
        )?;
        let force_tolerance = self.settings.force_tolerance * self.force_scale()?;
        self.model.set_contact_stiffness(dt);
        let (lo, hi) = self.model.mesh.corners().bounding_box();
        let contact_tolerance = self.settings.contact_tolerance * (hi - lo).norm();
        Ok(RunPlan {
            settings: self.settings,
            dt,
            projector,
            force_tolerance,
            contact_tolerance,
        })
    }
}

/// What a run fixes before its first step.
struct RunPlan {
    settings: Settings,
    /// The time step (`None`: quasi-static).
    dt: Option<f64>,
    /// The volume projection after each step.
    projector: VolumeProjector,
    /// The absolute force tolerance of the nonlinear solves.
    force_tolerance: f64,
    /// The absolute penetration tolerance of the contact updates.
    contact_tolerance: f64,
}

/// The nonlinear solver of a run.
enum Solver {
    Newton(Newton),
    Saddle(SaddleNewton),
    Dual(Newton),
}

/// A run under way: its assembled system, nonlinear solver and plan.
struct Run<'s> {
    system: System<'s>,
    solver: Solver,
    plan: RunPlan,
    /// Whether a state with inverted elements may be accepted ([`System::admits_inversion`]).
    admits_inversion: bool,
    /// The time building the system and the solver took, not yet reported (the first
    /// attempt's report carries it).
    setup: std::time::Duration,
}

impl<'s> Run<'s> {
    /// The assembled system of `model` (inertia in implicit Euler, none in quasi-static
    /// stepping) and the nonlinear solver of the model's scheme.
    fn new(model: &'s Model, plan: RunPlan) -> Result<Self, SolverError> {
        let inertia = plan.dt.map(|dt| Inertia::new(model.masses.clone(), dt));
        let system = System::new(model, inertia, plan.settings)?;
        let solver = match model.scheme {
            NonlinearScheme::Minimize => Solver::Newton(Newton::new(&system)?),
            NonlinearScheme::Dual => Solver::Dual(Newton::new(&system)?),
            NonlinearScheme::SaddleDirect | NonlinearScheme::SaddleSchur => {
                Solver::Saddle(SaddleNewton::new(&system)?)
            }
        };
        Ok(Run {
            admits_inversion: system.admits_inversion(),
            system,
            solver,
            plan,
            setup: std::time::Duration::ZERO,
        })
    }

    /// Attempts step `step` from `state` (where the loads stood at `start_level`): the
    /// positions and multipliers it ended on, its log, and whether it converged. A failed
    /// attempt puts the contact multipliers back to where they stood at `state`.
    fn attempt(
        &mut self,
        state: &State,
        attempt: &Attempt,
        start_level: LoadLevel,
        step: usize,
    ) -> (Vec<Vec3>, Vec<f64>, StepReport, Result<(), SolverError>) {
        let step_start = Instant::now();
        let target = step_target(self.system.model, attempt.level, self.plan.force_tolerance);
        if let Some(inertia) = &mut self.system.inertia {
            inertia.begin_step(&state.positions, &state.velocities, attempt.increment);
        }
        let contact_start = self.system.model.contact.as_ref().map(|c| c.snapshot());
        if let Some(contact) = &self.system.model.contact {
            contact.begin_step(attempt.level);
        }
        let mut x = state.positions.clone();
        let mut p = state.multipliers.clone();
        let mut report = StepReport {
            step,
            t: attempt.level.t,
            increment: attempt.increment,
            ..StepReport::default()
        };
        let run_setup = std::mem::take(&mut self.setup);
        report.timings.setup = run_setup;
        // The meshed obstacles move to the attempt's level; a crossing fails the attempt.
        let placed = self
            .system
            .model
            .surface_contact
            .as_ref()
            .map_or(Ok(()), |c| {
                c.begin_attempt(&state.positions, &attempt.level)
            });
        let friction = Friction {
            start: &state.positions,
            start_level,
        };
        let rebuilds = self.system.pattern_rebuilds;
        let result = placed.and_then(|()| {
            friction.lag(&self.system, &x);
            self.solve(&mut x, &mut p, &target, &friction, &mut report)
                .and_then(|()| self.check_domain(&x))
        });
        report.pattern_rebuilds = self.system.pattern_rebuilds - rebuilds;
        if let Some(contact) = &self.system.model.contact {
            report.contact = contact.summary(&x);
        }
        // The first attempt's wall time holds the run's setup too.
        report.wall_time = step_start.elapsed() + run_setup;
        if result.is_err() {
            // Back to the last accepted step, contact multipliers included.
            if let (Some(contact), Some(start)) = (&self.system.model.contact, contact_start) {
                contact.restore(start);
            }
        }
        (x, p, report, result)
    }

    /// A converged state with inverted elements (`J <= 0` at a corner or at a point of any
    /// quadrature rule, [`ElementMesh::count_inverted`]) is a failed attempt unless every
    /// term and constraint admits inversion: the line search keeps the energy's own
    /// quadrature points in its domain, but a 10-node element may still fold at a corner.
    ///
    /// [`ElementMesh::count_inverted`]: isochor_mesh::ElementMesh::count_inverted
    fn check_domain(&self, x: &[Vec3]) -> Result<(), SolverError> {
        if self.admits_inversion {
            return Ok(());
        }
        match self.system.model.mesh.count_inverted(x) {
            0 => Ok(()),
            inverted => Err(SolverError::InvertedState { inverted }),
        }
    }

    /// The method's own solve of one step, inside the contact's projected multiplier
    /// updates (its module docs) and the friction's lags of the normal forces.
    fn solve(
        &mut self,
        x: &mut [Vec3],
        p: &mut [f64],
        target: &StepTarget,
        friction: &Friction<'_>,
        report: &mut StepReport,
    ) -> Result<(), SolverError> {
        let system = &mut self.system;
        let settings = &self.plan.settings;
        loop {
            let solved = match &mut self.solver {
                Solver::Newton(newton) => newton.minimize(system, x, target, report),
                Solver::Saddle(saddle) => saddle.solve(system, x, p, target, report),
                Solver::Dual(newton) => dual::solve(newton, system, x, p, target, report),
            };
            // A fixed iteration count: the last iterate is the step (`report.converged`
            // stays false).
            let solved = match solved {
                Err(SolverError::NotConverged { .. }) if settings.accept_unconverged => Ok(()),
                other => other,
            };
            let model = system.model;
            let has_friction = model.surface_friction.is_some()
                || model.contact.as_ref().is_some_and(|c| c.has_friction());
            if model.contact.is_none() && !has_friction {
                return solved;
            }
            solved?;
            let converged = match &model.contact {
                Some(contact) => {
                    report.contact_iterations += 1;
                    contact.update(x, self.plan.contact_tolerance)
                }
                None => true,
            };
            // Friction lagged again at the solution (the obstacles' at the multipliers just
            // updated), solved again until its forces settle, a bounded number of times.
            let settled =
                !has_friction || friction.lag(system, x) || report.friction_lags >= MAX_LAGS;
            if !settled {
                report.friction_lags += 1;
            }
            if converged && settled {
                return Ok(());
            }
            let Some(contact) = &model.contact else {
                continue;
            };
            if report.contact_iterations >= settings.max_contact_iterations {
                report.converged = false;
                return Err(SolverError::ContactNotConverged {
                    iterations: report.contact_iterations,
                    max_penetration: contact.summary(x).max_penetration,
                });
            }
        }
    }

    /// The state an accepted step from `previous` ends on: positions `x`, multipliers `p`,
    /// the velocities of the time step (unchanged in quasi-static stepping), then the volume
    /// projection.
    fn accept(
        &self,
        previous: &State,
        mut x: Vec<Vec3>,
        p: Vec<f64>,
        attempt: &Attempt,
    ) -> Result<State, SolverError> {
        let mut velocities = match self.plan.dt {
            Some(_) => x
                .iter()
                .zip(&previous.positions)
                .map(|(a, b)| (a - b) / attempt.increment)
                .collect(),
            None => previous.velocities.clone(),
        };
        self.plan.projector.apply(
            &self.system.model.mesh,
            &mut x,
            &mut velocities,
            attempt.increment,
        )?;
        Ok(State {
            positions: x,
            velocities,
            multipliers: p,
            t: attempt.level.t,
        })
    }
}

/// Lags of the friction's normal forces beyond the first, per step.
const MAX_LAGS: usize = 4;

/// Where a step's friction measures its slip from.
struct Friction<'a> {
    /// The positions at the step's start.
    start: &'a [Vec3],
    /// Where the loads (and obstacles) stood then.
    start_level: LoadLevel,
}

impl Friction<'_> {
    /// Lags every friction term of `system` at `x`: the obstacles' at their multipliers, the
    /// surfaces' at the barrier's forces; returns whether their forces settled (true
    /// without friction).
    fn lag(&self, system: &System<'_>, x: &[Vec3]) -> bool {
        let model = system.model;
        let obstacles = model
            .contact
            .as_ref()
            .is_none_or(|c| c.lag_friction(self.start, x, self.start_level));
        let surfaces = match (&model.surface_friction, &model.surface_contact) {
            (Some(friction), Some(contact)) => {
                friction.lag(self.start, &contact.friction_lag(x, &self.start_level))
            }
            _ => true,
        };
        obstacles && surfaces
    }
}

/// A failed run: `error` at `step`, the state left at `state`, and the reports so far.
fn failure(
    error: SolverError,
    step: usize,
    state: &State,
    reports: &[StepReport],
) -> Box<SimulationFailure> {
    Box::new(SimulationFailure {
        error,
        failed_step: step,
        last_state: state.clone(),
        reports: reports.to_vec(),
    })
}

/// The target of a solve at `level`: the loads' level and the prescribed DOFs' values.
pub(super) fn step_target(model: &Model, level: LoadLevel, force_tolerance: f64) -> StepTarget {
    StepTarget {
        level,
        prescribed: model.dofs.targets(model.mesh.nodes(), level).collect(),
        force_tolerance,
    }
}
