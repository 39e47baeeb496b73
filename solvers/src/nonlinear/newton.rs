//! Newton's method on the total energy (methods `standard` and `condensed`, and the primal
//! step of `dual`): a sparse Cholesky step, shifted until positive definite, and a
//! backtracking line search that rejects states outside the energy's domain (inverted
//! elements under `log J`) and enforces sufficient decrease (Armijo), starting from the
//! longest step no pair of contact surfaces crosses.

use crate::assembly::{Evaluation, System};
use crate::error::SolverError;
use crate::linear::NearNullSpace;
use crate::linear::{CholeskySolver, LinearError, ShiftSchedule};
use crate::model::NonlinearScheme;
use crate::nonlinear::forcing::Forcing;
use crate::nonlinear::krylov::{solve_stiffness, StiffnessPreconditioner};
use crate::nonlinear::report::{IterationReport, StepReport};
use crate::nonlinear::target::{
    add_scaled, dot, gap, max_abs, norm, remaining_gap, snap, StepTarget,
};
use crate::settings::{IterativeSettings, Jacobian};
use faer::sparse::SparseColMat;
use isochor_mesh::Vec3;
use std::time::Instant;

/// Armijo sufficient-decrease constant.
const ARMIJO: f64 = 1e-4;

/// How a Newton step is solved.
#[derive(Debug)]
enum Linear {
    /// Sparse Cholesky, symbolic analysis kept across steps and iterations.
    Direct(Box<CholeskySolver>),
    /// Preconditioned CG with inexact-Newton forcing terms (reset every step).
    Iterative(IterativeSettings, Forcing, StiffnessPreconditioner),
}

/// A Newton minimizer with its linear solver, kept across steps and iterations.
#[derive(Debug)]
pub struct Newton {
    linear: Linear,
    /// Whether the next iteration may reuse the factorization ([`Jacobian::Modified`]).
    reusable: bool,
}

impl Newton {
    /// The linear solver the settings choose for the system's size (always direct for the
    /// dual solver, which reuses the factorization); symbolic analysis of the Hessian
    /// pattern for the direct one (once per run).
    pub fn new(system: &System<'_>) -> Result<Self, SolverError> {
        let pattern = system.hessian.pattern();
        let iterative = match system.model.scheme {
            NonlinearScheme::Dual => None,
            _ => system
                .settings
                .linear
                .iterative_for(pattern.symbolic().nrows()),
        };
        let linear = match iterative {
            Some(settings) => Linear::Iterative(
                settings,
                Forcing::new(settings.tolerance),
                StiffnessPreconditioner::default(),
            ),
            None => Linear::Direct(Box::new(
                CholeskySolver::with_ordering(pattern.symbolic(), system.settings.ordering)
                    .map_err(|e| SolverError::Linear(e.to_string()))?,
            )),
        };
        Ok(Newton {
            linear,
            reusable: false,
        })
    }

    /// The factorization of the latest Newton matrix (reused by the dual solver, eq. 41);
    /// `None` on the iterative path.
    pub fn cholesky(&mut self) -> Option<&mut CholeskySolver> {
        match &mut self.linear {
            Linear::Direct(cholesky) => Some(cholesky),
            Linear::Iterative(..) => None,
        }
    }

    /// Minimizes the energy of `system` over the free DOFs of `x`, driving prescribed DOFs
    /// to their targets. Appends every iteration to `report`; on error `x` holds the last
    /// accepted iterate.
    pub fn minimize(
        &mut self,
        system: &mut System<'_>,
        x: &mut [Vec3],
        target: &StepTarget,
        report: &mut StepReport,
    ) -> Result<(), SolverError> {
        let iterations = system.settings.max_iterations;
        self.restart_forcing();
        if self.iterate(system, x, target, report, iterations)? {
            Ok(())
        } else if let Some(gap) = remaining_gap(x, target) {
            Err(SolverError::BoundaryUnreachable { iterations, gap })
        } else {
            Err(SolverError::NotConverged {
                solver: "Newton",
                iterations: system.settings.max_iterations,
                force_residual: report.force_residual,
                constraint_residual: 0.0,
            })
        }
    }

    /// Solves `K dx = rhs` in place, by Cholesky (shifting `K` until positive definite) or
    /// by preconditioned CG to the forcing term of the residual `force` (relative to the
    /// nonlinear tolerance `target`); returns the shift of `K` and the Krylov iterations.
    fn solve_linear(
        &mut self,
        k: faer::sparse::SparseColMatRef<'_, usize, f64>,
        rhs: &mut [f64],
        (force, target): (f64, f64),
        near_null_space: impl FnOnce() -> NearNullSpace,
        shifts: &ShiftSchedule,
        report: &mut StepReport,
    ) -> Result<(f64, usize), LinearError> {
        match &mut self.linear {
            Linear::Direct(cholesky) => {
                report.factor_nnz = cholesky.report().factor_nnz;
                let start = Instant::now();
                let shift = cholesky.factorize_with_shifts(k, shifts);
                report.timings.factorization += start.elapsed();
                report.factorizations += 1;
                let shift = shift?;
                let start = Instant::now();
                cholesky.solve_in_place(rhs)?;
                report.timings.solve += start.elapsed();
                Ok((shift, 0))
            }
            Linear::Iterative(settings, forcing, preconditioner) => {
                let start = Instant::now();
                preconditioner.update(settings.preconditioner, k, near_null_space)?;
                report.timings.factorization += start.elapsed();
                let start = Instant::now();
                let eta = forcing.next(force, target);
                let (x, iterations) =
                    solve_stiffness(settings, k, preconditioner.get()?, rhs, eta)?;
                rhs.copy_from_slice(&x);
                report.timings.solve += start.elapsed();
                Ok((0.0, iterations))
            }
        }
    }

    /// One modified-Newton iteration from `x` with the last factorization: the gradient at
    /// the iterate (`known` if the previous reused iteration left it; an accepted step leaves
    /// its trial's there), the step it gives, taken whole if no surface pair crosses on the way, the
    /// state is valid, the energy decreases sufficiently (Armijo) and the force residual
    /// halves. `Some(true)`: `x` met the tolerances; `Some(false)`: the step was taken;
    /// `None`: it was refused (the iteration is redone with a fresh matrix).
    fn reuse(
        &mut self,
        system: &mut System<'_>,
        x: &mut [Vec3],
        target: &StepTarget,
        known: &mut Option<Evaluation>,
        report: &mut StepReport,
    ) -> Result<Option<bool>, SolverError> {
        let Linear::Direct(cholesky) = &mut self.linear else {
            return Ok(None);
        };
        let dofs = &system.model.dofs;
        let eval = match known.take() {
            Some(eval) => eval,
            None => system.energy(x, &target.level, true)?,
        };
        let mut rhs: Vec<f64> = dofs.gather(&eval.gradient).iter().map(|g| -g).collect();
        let force = norm(&rhs);
        report.force_residual = force;
        if !force.is_finite() {
            return Err(SolverError::NonFinite("the force residual"));
        }
        if force <= target.force_tolerance {
            return Ok(Some(true));
        }
        let start = Instant::now();
        cholesky
            .solve_in_place(&mut rhs)
            .map_err(|e| SolverError::Linear(e.to_string()))?;
        report.timings.solve += start.elapsed();
        let mut direction = vec![0.0; 3 * x.len()];
        dofs.scatter(&rhs, &mut direction);
        let slope = dot(&eval.gradient, &direction);
        let line_search = Instant::now();
        let clear = system.max_step(x, &direction) == 1.0;
        report.timings.ccd += line_search.elapsed();
        let mut trial = x.to_vec();
        add_scaled(&mut trial, &direction, 1.0);
        let next = if clear && system.is_valid(&trial) {
            Some(system.energy(&trial, &target.level, true)?)
        } else {
            None
        };
        report.timings.line_search += line_search.elapsed();
        report.timings.assembly += system.take_assembly_time();
        let Some(next) = next.filter(|next| {
            next.energy <= eval.energy + ARMIJO * slope
                && norm(&dofs.gather(&next.gradient)) <= 0.5 * force
        }) else {
            return Ok(None);
        };
        *known = Some(next);
        x.copy_from_slice(&trial);
        report.iterations.push(IterationReport {
            force_residual: force,
            step_length: 1.0,
            reused: true,
            ..IterationReport::default()
        });
        Ok(Some(false))
    }

    /// Starts a new load or time step: a new forcing-term sequence, and a fresh matrix at
    /// its first iteration.
    pub fn restart_forcing(&mut self) {
        self.reusable = false;
        if let Linear::Iterative(settings, forcing, preconditioner) = &mut self.linear {
            *forcing = Forcing::new(settings.tolerance);
            preconditioner.new_step();
        }
    }

    /// At most `iterations` Newton iterations; returns whether the tolerances were met
    /// (the check costs an assembly, so `iterations = 1` may return `false` after a step
    /// that reached them).
    pub fn iterate(
        &mut self,
        system: &mut System<'_>,
        x: &mut [Vec3],
        target: &StepTarget,
        report: &mut StepReport,
        iterations: usize,
    ) -> Result<bool, SolverError> {
        let settings = system.settings;
        let dofs = &system.model.dofs;
        // The energy and gradient at `x` a reused iteration computed for its trial step.
        let mut known = None;
        for _ in 0..iterations {
            if system.update_contact_pattern(x)? {
                // New contact pairs: the pattern changed, so does the symbolic analysis.
                let start = Instant::now();
                *self = Newton::new(system)?;
                report.timings.setup += start.elapsed();
            }
            if self.reusable {
                match self.reuse(system, x, target, &mut known, report)? {
                    Some(converged) => {
                        if converged {
                            report.converged = true;
                            return Ok(true);
                        }
                        continue;
                    }
                    None => self.reusable = false,
                }
            }
            // The exact barrier and cloth Hessians first (quadratic convergence), projected where
            // that does not factorize (the direct path only: an iterative solve cannot tell).
            let exact =
                matches!(self.linear, Linear::Direct(_)) && system.set_projected_hessians(false);
            let linearized = linearize(system, x, target);
            system.set_projected_hessians(true);
            let Linearized {
                eval,
                d_fixed,
                residual,
                mut rhs,
                mut k,
            } = linearized?;
            let force = norm(&residual);
            report.force_residual = force;
            if !force.is_finite() {
                return Err(SolverError::NonFinite("the force residual"));
            }
            if force <= target.force_tolerance && max_abs(&d_fixed) == 0.0 {
                report.converged = true;
                return Ok(true);
            }
            report.timings.assembly += system.take_assembly_time();
            report.timings.contact += system.take_contact_time();

            let tolerances = (force, target.force_tolerance);
            let near_null_space = || NearNullSpace::rigid_body(dofs.free(), x);
            let shifts = if exact {
                ShiftSchedule::NONE
            } else {
                ShiftSchedule::default()
            };
            let solved = self.solve_linear(
                k.as_ref(),
                &mut rhs,
                tolerances,
                near_null_space,
                &shifts,
                report,
            );
            let projected =
                exact && matches!(solved, Err(LinearError::RegularizationFailed { .. }));
            let (shift, linear_iterations) = if projected {
                system.project_hessians(x, &target.level)?;
                (rhs, k) = newton_matrix(system, &residual, &d_fixed)?;
                self.solve_linear(
                    k.as_ref(),
                    &mut rhs,
                    tolerances,
                    near_null_space,
                    &ShiftSchedule::default(),
                    report,
                )
            } else {
                solved
            }
            .map_err(|e| SolverError::Linear(e.to_string()))?;

            let mut direction = d_fixed.clone();
            dofs.scatter(&rhs, &mut direction);
            let slope = dot(&eval.gradient, &direction);
            let moving_boundary = max_abs(&d_fixed) > 0.0;
            // Energy differences below this are rounding noise; there, a smaller gradient
            // decides instead of the Armijo condition.
            let noise = 1e3 * f64::EPSILON * eval.magnitude;
            // No surface pair may cross on the way (continuous collision detection).
            let line_search = Instant::now();
            let mut alpha = system.max_step(x, &direction);
            report.timings.ccd += line_search.elapsed();
            let mut accepted = None;
            for backtracks in 0..=settings.max_backtracks {
                let mut trial = x.to_vec();
                add_scaled(&mut trial, &direction, alpha);
                if system.is_valid(&trial) {
                    let e = system.energy(&trial, &target.level, false)?.energy;
                    let armijo = e <= eval.energy + ARMIJO * alpha * slope;
                    let accept = e.is_finite()
                        && (moving_boundary
                            || armijo
                            || (e <= eval.energy + noise && {
                                let g = system.energy(&trial, &target.level, true)?.gradient;
                                norm(&dofs.gather(&g)) < force
                            }));
                    if accept {
                        accepted = Some((trial, backtracks));
                        break;
                    }
                }
                alpha *= 0.5;
            }
            report.timings.line_search += line_search.elapsed();
            report.timings.assembly += system.take_assembly_time();
            let Some((trial, backtracks)) = accepted else {
                return Err(SolverError::LineSearch {
                    backtracks: settings.max_backtracks,
                    reason: "no step length gave a valid state with sufficient decrease".into(),
                });
            };
            x.copy_from_slice(&trial);
            if alpha == 1.0 {
                snap(x, &target.prescribed);
            }
            // A full step is a sign of Newton's region, where the factorization may serve on.
            // (Not in dual ascent, whose steps read the factorization at the iterate, eq. 41.)
            self.reusable = settings.jacobian == Jacobian::Modified
                && alpha == 1.0
                && system.model.scheme != NonlinearScheme::Dual
                && matches!(self.linear, Linear::Direct(_));
            report.iterations.push(IterationReport {
                force_residual: force,
                step_length: alpha,
                backtracks,
                regularization: shift,
                linear_iterations,
                hessian_projected: projected,
                ..IterationReport::default()
            });
        }
        Ok(false)
    }
}

/// The Newton system at `x`: `K dx = rhs` over the free DOFs.
pub struct Linearized {
    /// Energy and full-space gradient.
    pub eval: Evaluation,
    /// Prescribed increments `target - x` (full space, zero on free DOFs).
    pub d_fixed: Vec<f64>,
    /// The force residual: the gradient on the free DOFs.
    pub residual: Vec<f64>,
    /// `-residual - K_fc d_fixed`: the prescribed increments moved to the right-hand side.
    pub rhs: Vec<f64>,
    /// The free-free Hessian `K_ff` (lower triangle).
    pub k: SparseColMat<usize, f64>,
}

/// The Newton right-hand side `-r - K_fc d_fixed` (free residual `r`, prescribed motion
/// `d_fixed`) and the free matrix `K_ff`, from the system's assembled Hessian values (the
/// saddle-point Newton's force block too).
pub(crate) fn newton_matrix(
    system: &System<'_>,
    residual: &[f64],
    d_fixed: &[f64],
) -> Result<(Vec<f64>, SparseColMat<usize, f64>), SolverError> {
    let mut rhs: Vec<f64> = residual.iter().map(|r| -r).collect();
    system
        .hessian
        .add_coupling(&system.hessian_values, d_fixed, -1.0, &mut rhs);
    Ok((rhs, system.hessian.matrix(&system.hessian_values)?))
}

/// Assembles the Newton system of `system` at `x` for `target`.
pub fn linearize(
    system: &mut System<'_>,
    x: &[Vec3],
    target: &StepTarget,
) -> Result<Linearized, SolverError> {
    let d_fixed = gap(x, &target.prescribed, 3 * x.len());
    let eval = system.assemble(x, &target.level, None)?;
    let residual = system.model.dofs.gather(&eval.gradient);
    let (rhs, k) = newton_matrix(system, &residual, &d_fixed)?;
    Ok(Linearized {
        eval,
        d_fixed,
        residual,
        rhs,
        k,
    })
}
