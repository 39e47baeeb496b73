//! The linear systems of one Newton step, for tests against finite differences and for the
//! matrices handed to users ([`Simulation::linearizer`]).

use super::run::step_target;
use super::state::State;
use super::stepping::{check_stepping, Stepping};
use super::Simulation;
use crate::assembly::System;
use crate::error::SolverError;
use crate::model::{Model, NonlinearScheme};
use crate::nonlinear::newton;
use crate::nonlinear::saddle::SaddleNewton;
use crate::nonlinear::target::StepTarget;
use crate::problem::schedule::LoadLevel;
use crate::terms::Inertia;
use faer::sparse::SparseColMat;
use nalgebra::DMatrix;

/// The sparse matrices of a linearization.
pub(super) type Sparse = SparseColMat<usize, f64>;

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
pub(super) struct Linear {
    pub(super) residual: Vec<f64>,
    pub(super) rhs: Vec<f64>,
    pub(super) gap: Vec<f64>,
    pub(super) k: Sparse,
    pub(super) kkt: Option<(Sparse, Option<Sparse>)>,
}

/// The linear systems of one step (see [`Simulation::linearizer`]).
pub struct Linearizer<'s> {
    pub(super) system: System<'s>,
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
    pub(super) fn linearize(&mut self, trial: &State) -> Result<Linear, SolverError> {
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

impl Simulation {
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
    pub(super) fn linearizer_at(
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
}
