//! Saddle-point Newton for constrained problems (eq. 21 dynamic, eq. 24 static of Francu
//! et al. 2021; the KKT system of the zonal constraints of Sheen et al. 2021, eq. 7-8):
//!
//! `[[K + K_g, G^T], [G, -C]] (dx, dp) = -(grad E + G^T p, phi - C p)`.
//!
//! Two linear strategies: the whole KKT matrix factorized by `LDL^T` with an inertia check
//! (mixed methods, one constraint per node or element), or a Schur complement on the few
//! dense zone rows, `S = G K^-1 G^T`, with `K` factorized by Cholesky and never densified
//! (zonal). Steps are globalized by a backtracking line search on the merit
//! `|sigma / tol_f|^2 + |theta / (V tol_c)|^2` (squared residuals scaled by their
//! tolerances; the Newton direction is a descent direction for it) that also rejects states
//! outside the domain of the energy or the constraints.

use crate::assembly::System;
use crate::error::SolverError;
use crate::linear::{
    CholeskySolver, KktOptions, KktSolver, LinearError, NearNullSpace, ShiftSchedule,
};
use crate::model::NonlinearScheme;
use crate::nonlinear::forcing::Forcing;
use crate::nonlinear::krylov::{solve_saddle, SaddleSystem, StiffnessPreconditioner};
use crate::nonlinear::newton::newton_matrix;
use crate::nonlinear::report::{IterationReport, StepReport};
use crate::nonlinear::target::{
    add_scaled, gap, max_abs, norm, remaining_gap, snap, volume_error, StepTarget,
};
use crate::problem::schedule::LoadLevel;
use crate::settings::{IterativeSettings, Jacobian};
use faer::sparse::{SparseColMat, Triplet};
use isochor_mesh::Vec3;
use nalgebra::{DMatrix, DVector};
use std::time::Instant;

/// Armijo constant of the merit decrease.
const ARMIJO: f64 = 1e-4;

/// Full steps per solve that may increase the merit (watchdog).
const WATCHDOG_STEPS: usize = 3;

/// The linear solver of the saddle-point step.
#[derive(Debug)]
enum Linear {
    Direct(Box<KktSolver>),
    Schur(Box<Schur>),
    /// MINRES on the whole saddle-point operator (sec. 8 of Francu et al. 2021) with a
    /// block-diagonal preconditioner, keeping the latest matrices for the solves.
    Iterative(Box<Iterative>),
}

/// The iterative path's settings, forcing terms and latest `K` and `G`.
#[derive(Debug)]
struct Iterative {
    settings: IterativeSettings,
    forcing: Forcing,
    /// The relative tolerance of this Newton iteration's solves.
    eta: f64,
    /// Krylov iterations since the last Newton iteration was reported.
    iterations: usize,
    k: SparseColMat<usize, f64>,
    g: SparseColMat<usize, f64>,
    /// The preconditioner of `K`.
    p_k: StiffnessPreconditioner,
    /// The rest volume of each constraint row and the shear modulus, for the pressure block
    /// of the preconditioner.
    row_volumes: Vec<f64>,
    mu: f64,
}

/// The Schur complement solve of the zonal KKT system: `K` factorized by Cholesky, the few
/// dense rows of `G`, `Z = K^-1 G^T` and `S = G Z + C` (dense, m x m).
#[derive(Debug)]
struct Schur {
    cholesky: CholeskySolver,
    rows: DMatrix<f64>,
    z: DMatrix<f64>,
    schur: DMatrix<f64>,
}

/// The KKT system of one saddle-point Newton step (see [`SaddleNewton::linearize`]).
pub struct Linearized {
    /// Prescribed increments `target - x` (full space, zero on free DOFs).
    pub d_fixed: Vec<f64>,
    /// Force residual `grad E + G^T p` on the free DOFs.
    pub sigma_f: Vec<f64>,
    /// Constraint residual `phi - C p`.
    pub theta: Vec<f64>,
    /// `-sigma_f - K_fc d_fixed`.
    pub rhs_x: Vec<f64>,
    /// `-theta - G_c d_fixed`.
    pub rhs_p: Vec<f64>,
    /// `K_ff` (with the geometric stiffness of the constraints), lower triangle.
    pub k: SparseColMat<usize, f64>,
    /// `G_f`, the constraint Jacobian on the free DOFs.
    pub g: SparseColMat<usize, f64>,
}

/// Saddle-point Newton with its factorizations, kept across steps.
#[derive(Debug)]
pub struct SaddleNewton {
    linear: Linear,
    /// `C` over the constraint rows, `None` if identically zero.
    compliance: Option<SparseColMat<usize, f64>>,
    /// Diagonal and off-diagonal action of `C` on multipliers.
    compliance_entries: Vec<(usize, usize, f64)>,
    /// `(row, dof)` of the constraint Jacobian entries, fetched once.
    jacobian_pattern: Vec<(usize, usize)>,
    /// Whether the next iteration may reuse the factorization ([`Jacobian::Modified`]).
    reusable: bool,
}

/// The full-space force residual `grad E + G^T p` and the constraint residual `phi - C p`.
type Residuals = (Vec<f64>, Vec<f64>);

/// How an iteration with the last factorization went.
enum Reuse {
    /// The iterate met the tolerances.
    Converged,
    /// The full step halved the residual and was taken.
    Accepted,
    /// It did not: the iteration is redone with a fresh matrix.
    Refused,
}

fn linear_error(e: crate::linear::LinearError) -> SolverError {
    SolverError::Linear(e.to_string())
}

impl SaddleNewton {
    /// Symbolic analysis for the system's patterns (once per run).
    pub fn new(system: &System<'_>) -> Result<Self, SolverError> {
        let constraints = system.model.constraints.as_ref().ok_or_else(|| {
            SolverError::InvalidProblem("saddle-point Newton without constraints".into())
        })?;
        let m = constraints.num_constraints();
        let compliance_entries: Vec<(usize, usize, f64)> =
            constraints.compliance().nonzero_entries();
        let compliance = if compliance_entries.is_empty() {
            None
        } else {
            let triplets: Vec<_> = compliance_entries
                .iter()
                .map(|&(r, c, v)| Triplet::new(r, c, v))
                .collect();
            Some(
                SparseColMat::try_new_from_triplets(m, m, &triplets)
                    .map_err(|e| SolverError::Linear(format!("{e:?}")))?,
            )
        };
        let jacobian = system
            .jacobian
            .as_ref()
            .ok_or_else(|| SolverError::InvalidProblem("no Jacobian layout".into()))?;
        let unknowns = system.hessian.pattern().symbolic().nrows() + m;
        let iterative = system.settings.linear.iterative_for(unknowns);
        let linear = match (iterative, system.model.scheme) {
            (Some(settings), _) => {
                let empty =
                    |r, c| SparseColMat::try_new_from_triplets(r, c, &[]).expect("empty matrix");
                Linear::Iterative(Box::new(Iterative {
                    settings,
                    forcing: Forcing::new(settings.tolerance),
                    eta: settings.tolerance,
                    iterations: 0,
                    k: empty(0, 0),
                    g: empty(0, 0),
                    p_k: StiffnessPreconditioner::default(),
                    row_volumes: system.model.row_volumes.clone(),
                    mu: system.model.mu(),
                }))
            }
            (_, NonlinearScheme::SaddleSchur) => Linear::Schur(Box::new(Schur {
                cholesky: CholeskySolver::with_ordering(
                    system.hessian.pattern().symbolic(),
                    system.settings.ordering,
                )
                .map_err(linear_error)?,
                rows: DMatrix::zeros(0, 0),
                z: DMatrix::zeros(0, 0),
                schur: DMatrix::zeros(0, 0),
            })),
            (_, _) => {
                let dofs = &system.model.dofs;
                let anchors: Vec<Option<usize>> = (0..m)
                    .map(|row| {
                        constraints
                            .anchor_vertex(row)
                            .and_then(|v| (0..3).rev().find_map(|k| dofs.free_index(3 * v + k)))
                    })
                    .collect();
                Linear::Direct(Box::new(
                    KktSolver::new(
                        system.hessian.pattern().symbolic(),
                        jacobian.pattern().symbolic(),
                        compliance.as_ref().map(|c| c.symbolic()),
                        &anchors,
                        KktOptions {
                            ordering: system.settings.ordering,
                            ..KktOptions::default()
                        },
                    )
                    .map_err(linear_error)?,
                ))
            }
        };
        Ok(SaddleNewton {
            linear,
            compliance,
            compliance_entries,
            jacobian_pattern: constraints.jacobian_pattern(),
            reusable: false,
        })
    }

    /// `theta = phi - C p`.
    fn theta(&self, phi: &[f64], p: &[f64]) -> Vec<f64> {
        let mut theta = phi.to_vec();
        for &(r, c, v) in &self.compliance_entries {
            theta[r] -= v * p[c];
        }
        theta
    }

    /// Residuals `(sigma_f, theta)` at `(x, p)`, and the full-space gradient `grad E + G^T p`.
    fn residuals(
        &self,
        system: &mut System<'_>,
        x: &[Vec3],
        p: &[f64],
        level: &LoadLevel,
    ) -> Result<Residuals, SolverError> {
        let constraints = system.model.constraints.clone().expect("checked in new");
        system.model.set_load_level(level);
        let eval = system.energy(x, level, true)?;
        let mut sigma = eval.gradient;
        let pattern = &self.jacobian_pattern;
        let mut g = vec![0.0; pattern.len()];
        constraints.jacobian_values(x, &mut g)?;
        for (&(row, dof), v) in pattern.iter().zip(&g) {
            sigma[dof] += v * p[row];
        }
        let mut phi = vec![0.0; p.len()];
        constraints.values(x, &mut phi)?;
        Ok((sigma, self.theta(&phi, p)))
    }

    /// The KKT system of the Newton step at `(x, p)` for `target` (eq. 24, or eq. 21 when
    /// the system carries inertia): residuals, right-hand sides with the prescribed
    /// increments moved over (`K_fc`, `G_c`), and the free blocks `K` and `G`; the matrix
    /// is `[[K, G^T], [G, -C]]` with `C` = [`SaddleNewton::compliance`].
    pub fn linearize(
        &self,
        system: &mut System<'_>,
        x: &[Vec3],
        p: &[f64],
        target: &StepTarget,
    ) -> Result<Linearized, SolverError> {
        let missing =
            || SolverError::InvalidProblem("saddle-point Newton without constraints".into());
        let constraints = system.model.constraints.clone().ok_or_else(missing)?;
        system.model.set_load_level(&target.level);
        let d_fixed = gap(x, &target.prescribed, 3 * x.len());
        let eval = system.assemble(x, &target.level, Some(p))?;
        let jacobian = system.jacobian.as_ref().ok_or_else(missing)?;
        let mut sigma = eval.gradient;
        for (&(row, dof), v) in self.jacobian_pattern.iter().zip(&system.jacobian_values) {
            sigma[dof] += v * p[row];
        }
        let mut phi = vec![0.0; p.len()];
        constraints.values(x, &mut phi)?;
        let theta = self.theta(&phi, p);
        let sigma_f = system.model.dofs.gather(&sigma);
        let (rhs_x, k) = newton_matrix(system, &sigma_f, &d_fixed)?;
        let mut rhs_p: Vec<f64> = theta.iter().map(|t| -t).collect();
        jacobian.add_coupling(&system.jacobian_values, &d_fixed, -1.0, &mut rhs_p);
        let g = jacobian.matrix(&system.jacobian_values)?;
        Ok(Linearized {
            d_fixed,
            sigma_f,
            theta,
            rhs_x,
            rhs_p,
            k,
            g,
        })
    }

    /// The compliance block `C` of the KKT matrix (`None` if identically zero).
    pub fn compliance(&self) -> Option<&SparseColMat<usize, f64>> {
        self.compliance.as_ref()
    }

    /// Solves one step of the constrained problem from `(x, p)`. Appends every iteration
    /// to `report`; on error `(x, p)` hold the last accepted iterate.
    pub fn solve(
        &mut self,
        system: &mut System<'_>,
        x: &mut [Vec3],
        p: &mut [f64],
        target: &StepTarget,
        report: &mut StepReport,
    ) -> Result<(), SolverError> {
        let settings = system.settings;
        let volumes = system.model.row_volumes.clone();
        let scaled = |theta: &[f64]| -> Vec<f64> {
            theta.iter().zip(&volumes).map(|(t, v)| t / v).collect()
        };
        let merit = |sigma_f: &[f64], theta: &[f64]| -> f64 {
            let f = norm(sigma_f) / target.force_tolerance;
            let c = norm(&scaled(theta)) / settings.constraint_tolerance;
            f * f + c * c
        };
        let n_dofs = 3 * x.len();
        let mut nonmonotone_budget = WATCHDOG_STEPS;
        if let Linear::Iterative(state) = &mut self.linear {
            state.forcing = Forcing::new(state.settings.tolerance);
            state.p_k.new_step();
        }
        // Every step starts with a fresh matrix.
        self.reusable = false;
        // The residual at `(x, p)` a reused iteration computed for its trial step.
        let mut known = None;
        for _ in 0..settings.max_iterations {
            if system.update_contact_pattern(x)? {
                // New contact pairs: the pattern changed, so does the symbolic analysis.
                let start = Instant::now();
                *self = SaddleNewton::new(system)?;
                report.timings.setup += start.elapsed();
            }
            if self.reusable {
                match self.reuse(system, (x, p), target, &merit, &mut known, report)? {
                    Reuse::Converged => {
                        report.converged = true;
                        return Ok(());
                    }
                    Reuse::Accepted => continue,
                    Reuse::Refused => self.reusable = false,
                }
            }
            // The exact barrier and cloth Hessians first (quadratic convergence), projected where
            // the matrix then has the wrong inertia (direct paths only).
            let exact = !matches!(self.linear, Linear::Iterative(_))
                && system.set_projected_hessians(false);
            let linearized = self.linearize(system, x, p, target);
            system.set_projected_hessians(true);
            let Linearized {
                d_fixed,
                sigma_f,
                theta,
                mut rhs_x,
                rhs_p,
                k,
                g,
            } = linearized?;
            let force = norm(&sigma_f);
            let constraint = max_abs(&scaled(&theta));
            let volume_error = volume_error(&theta, &volumes);
            report.force_residual = force;
            report.constraint_residual = constraint;
            report.volume_error = volume_error;
            if !(force.is_finite() && constraint.is_finite()) {
                return Err(SolverError::NonFinite("the saddle-point residual"));
            }
            let moving_boundary = max_abs(&d_fixed) > 0.0;
            if force <= target.force_tolerance
                && constraint <= settings.constraint_tolerance
                && !moving_boundary
            {
                report.converged = true;
                return Ok(());
            }
            report.timings.assembly += system.take_assembly_time();
            report.timings.contact += system.take_contact_time();

            if let Linear::Iterative(state) = &mut self.linear {
                // No single tolerance applies to the mixed force/volume norm: target 0.
                let b = norm(&rhs_x).hypot(norm(&rhs_p));
                state.eta = state.forcing.next(b, 0.0);
            }
            let free = system.model.dofs.free();
            let near_null_space = || NearNullSpace::rigid_body(free, x);
            let shifts = if exact {
                ShiftSchedule::NONE
            } else {
                ShiftSchedule::default()
            };
            let g_again = exact.then(|| g.clone());
            let mut shift = self.factorize(k, g, near_null_space, &shifts, report);
            let projected = exact && matches!(shift, Err(LinearError::RegularizationFailed { .. }));
            if let (true, Some(g)) = (projected, g_again) {
                system.project_hessians(x, &target.level)?;
                let k;
                (rhs_x, k) = newton_matrix(system, &sigma_f, &d_fixed)?;
                shift = self.factorize(k, g, near_null_space, &ShiftSchedule::default(), report);
            }
            let shift = shift.map_err(linear_error)?;
            let (dx, dp) = self.solve_factorized(rhs_x, rhs_p, report)?;

            let mut direction = d_fixed.clone();
            system.model.dofs.scatter(&dx, &mut direction);
            let merit0 = merit(&sigma_f, &theta);
            let acceptable = |m: f64, alpha: f64| {
                m.is_finite()
                    && (moving_boundary
                        || merit0 <= 100.0
                        || m <= (1.0 - 2.0 * ARMIJO * alpha) * merit0)
            };
            // No surface pair may cross on the way (continuous collision detection).
            let line_search = Instant::now();
            let mut alpha = system.max_step(x, &direction);
            report.timings.ccd += line_search.elapsed();
            let mut accepted = None;
            for backtracks in 0..=settings.max_backtracks {
                let mut trial_x = x.to_vec();
                add_scaled(&mut trial_x, &direction, alpha);
                let trial_p: Vec<f64> = p.iter().zip(&dp).map(|(a, b)| a + alpha * b).collect();
                if system.is_valid(&trial_x) {
                    let (s, t) = self.residuals(system, &trial_x, &trial_p, &target.level)?;
                    let s_f = system.model.dofs.gather(&s);
                    let m = merit(&s_f, &t);
                    // Watchdog: a few full steps may raise the merit (the Maratos effect of
                    // the curved volume constraints); Newton's quadratic convergence then
                    // brings it down within an iteration or two.
                    let watchdog = backtracks == 0 && m.is_finite() && nonmonotone_budget > 0;
                    if acceptable(m, alpha) || watchdog {
                        if !acceptable(m, alpha) {
                            nonmonotone_budget -= 1;
                        }
                        accepted = Some((trial_x, trial_p, backtracks));
                        break;
                    }
                    if backtracks == 0 {
                        // Second-order (chord) correction against the Maratos effect: one more
                        // solve with the same factorization from the full step.
                        let f: Vec<f64> = s_f.iter().map(|v| -v).collect();
                        let h: Vec<f64> = t.iter().map(|v| -v).collect();
                        let (cx, cp) = self.solve_factorized(f, h, report)?;
                        let mut corrected_x = trial_x.clone();
                        let mut full = vec![0.0; n_dofs];
                        system.model.dofs.scatter(&cx, &mut full);
                        add_scaled(&mut corrected_x, &full, 1.0);
                        let corrected_p: Vec<f64> =
                            trial_p.iter().zip(&cp).map(|(a, b)| a + b).collect();
                        // The corrected state is reached from `x` in a straight line too.
                        let path: Vec<f64> = corrected_x
                            .iter()
                            .zip(x.iter())
                            .flat_map(|(c, a)| (c - a).iter().copied().collect::<Vec<_>>())
                            .collect();
                        let clear = system.is_valid(&corrected_x) && {
                            let ccd = Instant::now();
                            let full_step = system.max_step(x, &path) == 1.0;
                            report.timings.ccd += ccd.elapsed();
                            full_step
                        };
                        if clear {
                            let (s, t) =
                                self.residuals(system, &corrected_x, &corrected_p, &target.level)?;
                            if acceptable(merit(&system.model.dofs.gather(&s), &t), 1.0) {
                                accepted = Some((corrected_x, corrected_p, 0));
                                break;
                            }
                        }
                    }
                }
                alpha *= 0.5;
            }
            report.timings.line_search += line_search.elapsed();
            report.timings.assembly += system.take_assembly_time();
            let Some((trial_x, trial_p, backtracks)) = accepted else {
                return Err(SolverError::LineSearch {
                    backtracks: settings.max_backtracks,
                    reason: "no step length gave a valid state with a smaller residual".into(),
                });
            };
            x.copy_from_slice(&trial_x);
            p.copy_from_slice(&trial_p);
            if alpha == 1.0 {
                snap(x, &target.prescribed);
            }
            // A full step is a sign of Newton's region, where the factorization may serve on.
            self.reusable = settings.jacobian == Jacobian::Modified
                && alpha == 1.0
                && !matches!(self.linear, Linear::Iterative(_));
            report.iterations.push(IterationReport {
                force_residual: force,
                constraint_residual: constraint,
                volume_error,
                step_length: alpha,
                backtracks,
                regularization: shift,
                linear_iterations: match &mut self.linear {
                    Linear::Iterative(state) => std::mem::take(&mut state.iterations),
                    _ => 0,
                },
                reused: false,
                hessian_projected: projected,
            });
        }
        if let Some(gap) = remaining_gap(x, target) {
            return Err(SolverError::BoundaryUnreachable {
                iterations: settings.max_iterations,
                gap,
            });
        }
        Err(SolverError::NotConverged {
            solver: "saddle-point Newton",
            iterations: settings.max_iterations,
            force_residual: report.force_residual,
            constraint_residual: report.constraint_residual,
        })
    }

    /// One modified-Newton iteration from `(x, p)` with the last factorization: the residual
    /// at the iterate (`known` if the previous reused iteration left it), the step it gives,
    /// taken whole if no surface pair crosses on the way, the state is valid and the merit
    /// falls to a quarter (the residual norm halves); an accepted step leaves its residual
    /// in `known`.
    fn reuse(
        &mut self,
        system: &mut System<'_>,
        (x, p): (&mut [Vec3], &mut [f64]),
        target: &StepTarget,
        merit: &dyn Fn(&[f64], &[f64]) -> f64,
        known: &mut Option<Residuals>,
        report: &mut StepReport,
    ) -> Result<Reuse, SolverError> {
        let settings = system.settings;
        let volumes = &system.model.row_volumes;
        let (sigma, theta) = match known.take() {
            Some(residuals) => residuals,
            None => self.residuals(system, x, p, &target.level)?,
        };
        let sigma_f = system.model.dofs.gather(&sigma);
        let force = norm(&sigma_f);
        let scaled: Vec<f64> = theta.iter().zip(volumes).map(|(t, v)| t / v).collect();
        let constraint = max_abs(&scaled);
        report.force_residual = force;
        report.constraint_residual = constraint;
        report.volume_error = volume_error(&theta, volumes);
        if !(force.is_finite() && constraint.is_finite()) {
            return Err(SolverError::NonFinite("the saddle-point residual"));
        }
        if force <= target.force_tolerance && constraint <= settings.constraint_tolerance {
            return Ok(Reuse::Converged);
        }
        let merit0 = merit(&sigma_f, &theta);
        let rhs_x = sigma_f.iter().map(|v| -v).collect();
        let rhs_p = theta.iter().map(|v| -v).collect();
        let (dx, dp) = self.solve_factorized(rhs_x, rhs_p, report)?;
        let mut direction = vec![0.0; 3 * x.len()];
        system.model.dofs.scatter(&dx, &mut direction);
        let line_search = Instant::now();
        let clear = system.max_step(x, &direction) == 1.0;
        report.timings.ccd += line_search.elapsed();
        let mut trial_x = x.to_vec();
        add_scaled(&mut trial_x, &direction, 1.0);
        let trial_p: Vec<f64> = p.iter().zip(&dp).map(|(a, b)| a + b).collect();
        let trial = if clear && system.is_valid(&trial_x) {
            Some(self.residuals(system, &trial_x, &trial_p, &target.level)?)
        } else {
            None
        };
        report.timings.line_search += line_search.elapsed();
        report.timings.assembly += system.take_assembly_time();
        let Some(residuals) =
            trial.filter(|(s, t)| merit(&system.model.dofs.gather(s), t) <= 0.25 * merit0)
        else {
            return Ok(Reuse::Refused);
        };
        *known = Some(residuals);
        x.copy_from_slice(&trial_x);
        p.copy_from_slice(&trial_p);
        report.iterations.push(IterationReport {
            force_residual: force,
            constraint_residual: constraint,
            volume_error: report.volume_error,
            step_length: 1.0,
            reused: true,
            ..IterationReport::default()
        });
        Ok(Reuse::Accepted)
    }

    /// Factorizes the KKT matrix, shifting `K` along `shifts` until the inertia is right;
    /// returns the shift used. A failed factorization is counted and timed too.
    fn factorize(
        &mut self,
        k: SparseColMat<usize, f64>,
        g: SparseColMat<usize, f64>,
        near_null_space: impl FnOnce() -> NearNullSpace,
        shifts: &ShiftSchedule,
        report: &mut StepReport,
    ) -> Result<f64, LinearError> {
        let start = Instant::now();
        let shift = self.factorize_unrecorded(k, g, near_null_space, shifts);
        report.timings.factorization += start.elapsed();
        match &self.linear {
            Linear::Direct(kkt) => report.factor_nnz = kkt.report().factor_nnz,
            Linear::Schur(schur) => report.factor_nnz = schur.cholesky.report().factor_nnz,
            Linear::Iterative(_) => return shift,
        }
        report.factorizations += 1;
        shift
    }

    /// [`Self::factorize`] without its report.
    fn factorize_unrecorded(
        &mut self,
        k: SparseColMat<usize, f64>,
        g: SparseColMat<usize, f64>,
        near_null_space: impl FnOnce() -> NearNullSpace,
        shifts: &ShiftSchedule,
    ) -> Result<f64, LinearError> {
        Ok(match &mut self.linear {
            Linear::Direct(kkt) => kkt.factorize_with_shifts(
                k.as_ref(),
                g.as_ref(),
                self.compliance.as_ref().map(|c| c.as_ref()),
                shifts,
            )?,
            Linear::Schur(schur) => {
                let shift = schur.cholesky.factorize_with_shifts(k.as_ref(), shifts)?;
                let (m, nf) = (g.nrows(), g.ncols());
                let mut rows = DMatrix::<f64>::zeros(m, nf);
                for col in 0..nf {
                    for (row, v) in g
                        .as_ref()
                        .row_idx_of_col(col)
                        .zip(g.as_ref().val_of_col(col))
                    {
                        rows[(row, col)] += v;
                    }
                }
                let mut z = DMatrix::<f64>::zeros(nf, m);
                for i in 0..m {
                    let mut col: Vec<f64> = rows.row(i).iter().copied().collect();
                    schur.cholesky.solve_in_place(&mut col)?;
                    z.set_column(i, &DVector::from_vec(col));
                }
                let mut s = &rows * &z;
                for &(r, c, v) in &self.compliance_entries {
                    s[(r, c)] += v;
                }
                schur.rows = rows;
                schur.z = z;
                schur.schur = s;
                shift
            }
            Linear::Iterative(state) => {
                state
                    .p_k
                    .update(state.settings.preconditioner, k.as_ref(), near_null_space)?;
                state.k = k;
                state.g = g;
                0.0
            }
        })
    }

    /// Solves `[[K, G^T], [G, -C]] (dx, dp) = (f, h)` with the current factorization.
    fn solve_factorized(
        &mut self,
        f: Vec<f64>,
        h: Vec<f64>,
        report: &mut StepReport,
    ) -> Result<(Vec<f64>, Vec<f64>), SolverError> {
        let start = Instant::now();
        let nf = f.len();
        let result = match &mut self.linear {
            Linear::Direct(kkt) => {
                let mut rhs = f;
                rhs.extend(h);
                kkt.solve_in_place(&mut rhs).map_err(linear_error)?;
                let dp = rhs.split_off(nf);
                (rhs, dp)
            }
            Linear::Schur(schur) => {
                // dp = (G K^-1 G^T + C)^-1 (G K^-1 f - h), dx = K^-1 f - Z dp.
                let mut y = f;
                schur
                    .cholesky
                    .solve_in_place(&mut y)
                    .map_err(linear_error)?;
                let y = DVector::from_vec(y);
                let b = &schur.rows * &y - DVector::from_vec(h);
                let dp = schur
                    .schur
                    .clone()
                    .cholesky()
                    .map(|c| c.solve(&b))
                    .or_else(|| schur.schur.clone().lu().solve(&b))
                    .ok_or_else(|| {
                        SolverError::Linear(
                            "the zone Schur complement G K^-1 G^T is singular (are two zones identical?)".into(),
                        )
                    })?;
                let dx = y - &schur.z * &dp;
                (dx.as_slice().to_vec(), dp.as_slice().to_vec())
            }
            Linear::Iterative(state) => {
                let saddle = SaddleSystem {
                    k: state.k.as_ref(),
                    g: state.g.as_ref(),
                    c: self.compliance.as_ref().map(|c| c.as_ref()),
                    row_volumes: &state.row_volumes,
                    mu: state.mu,
                };
                let mut b = f;
                b.extend(h);
                let p_k = state.p_k.get().map_err(linear_error)?;
                let (mut solution, iterations) =
                    solve_saddle(&state.settings, &saddle, p_k, &b, state.eta)
                        .map_err(linear_error)?;
                state.iterations += iterations;
                let dp = solution.split_off(nf);
                (solution, dp)
            }
        };
        report.timings.solve += start.elapsed();
        Ok(result)
    }
}
