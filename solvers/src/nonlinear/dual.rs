//! Dual ascent / nonlinear Uzawa (eq. 39-41 of Francu et al. 2021): alternate a primal
//! Newton solve of `min_x L(x, p_k)` (eq. 39) with an ascent step on the multipliers,
//! `p_{k+1} = p_k + omega d` (eq. 40), along the dual gradient `theta = phi(x) - C p`, with
//! the exact step of eq. 41 generalized to a direction `d`:
//! `omega = theta^T d / d^T (A_2 + C) d`, where `A_2 d = G z` and `(M/h^2 + K) z = G^T d`
//! reuse the primal factorization. With [`crate::Settings::dual_conjugate`] the directions
//! are conjugated (Polak-Ribiere, restarted when not an ascent direction): the conjugate
//! gradient counterpart, in Shewchuk 1994 (the paper's reference for eq. 41), of its
//! steepest ascent, which it reduces to on the first iteration and when disabled. With a
//! base Poisson ratio the primal energy carries the augmented term of sec. 8.3 (see
//! [`crate::terms::AugmentedConstraints`]).

use crate::assembly::System;
use crate::error::SolverError;
use crate::nonlinear::newton::Newton;
use crate::nonlinear::report::{IterationReport, StepReport};
use crate::nonlinear::target::{max_abs, volume_error, StepTarget};
use isochor_constraints::Compliance;
use isochor_mesh::Vec3;
use std::time::Instant;

/// Runs dual ascent for one step from `(x, p)`.
pub fn solve(
    newton: &mut Newton,
    system: &mut System<'_>,
    x: &mut [Vec3],
    p: &mut [f64],
    target: &StepTarget,
    report: &mut StepReport,
) -> Result<(), SolverError> {
    let settings = system.settings;
    let model = system.model;
    let constraints = model
        .constraints
        .clone()
        .ok_or_else(|| SolverError::InvalidProblem("dual ascent without constraints".into()))?;
    let augmented = model
        .augmented
        .as_ref()
        .ok_or_else(|| SolverError::InvalidProblem("dual ascent without a primal term".into()))?;
    let compliance = match constraints.compliance() {
        Compliance::Diagonal(d) => d,
        Compliance::Sparse(_) => {
            return Err(SolverError::InvalidProblem(
                "dual ascent needs a lumped compliance".into(),
            ))
        }
    };
    let m = p.len();
    let mut phi = vec![0.0; m];
    constraints.values(x, &mut phi)?;
    let residuals = |phi: &[f64], p: &[f64]| {
        let theta: Vec<f64> = (0..m).map(|i| phi[i] - compliance[i] * p[i]).collect();
        let scaled: Vec<f64> = theta
            .iter()
            .zip(&model.row_volumes)
            .map(|(t, v)| t / v)
            .collect();
        let (residual, error) = (max_abs(&scaled), volume_error(&theta, &model.row_volumes));
        (theta, residual, error)
    };
    let mut previous: Option<(Vec<f64>, Vec<f64>)> = None;
    let mut dual_converged = false;
    for _ in 0..settings.max_dual_iterations {
        augmented.set_multipliers(p);
        // The constraint residual and volume error at the start of this dual iteration,
        // recorded on its Newton iterations (which record residuals before their step).
        let (_, start_residual, start_error) = residuals(&phi, p);
        // Inexact primal solves: one Newton iteration per dual update (the "single linear
        // solve" of sec. 8.3) until the constraints are met, then a converged primal solve.
        let mut primal = StepReport::default();
        let limit = if dual_converged {
            settings.max_iterations
        } else {
            1
        };
        let result = newton.iterate(system, x, target, &mut primal, limit);
        report
            .iterations
            .extend(primal.iterations.into_iter().map(|i| IterationReport {
                constraint_residual: start_residual,
                volume_error: start_error,
                ..i
            }));
        report.timings += primal.timings;
        report.factorizations += primal.factorizations;
        report.force_residual = primal.force_residual;
        let primal_converged = result?;
        constraints.values(x, &mut phi)?;
        let (theta, residual, error) = residuals(&phi, p);
        report.constraint_residual = residual;
        report.volume_error = error;
        dual_converged = residual <= settings.constraint_tolerance;
        if dual_converged && primal_converged {
            report.converged = true;
            return Ok(());
        }
        if dual_converged {
            continue;
        }
        // Direction: theta, conjugated against the previous one (Polak-Ribiere+).
        let theta_sq: f64 = theta.iter().map(|t| t * t).sum();
        let mut direction = theta.clone();
        if let (true, Some((prev_theta, prev_direction))) = (settings.dual_conjugate, &previous) {
            let prev_sq: f64 = prev_theta.iter().map(|t: &f64| t * t).sum();
            let beta = (theta
                .iter()
                .zip(prev_theta)
                .map(|(a, b)| a * (a - b))
                .sum::<f64>()
                / prev_sq)
                .max(0.0);
            for (d, pd) in direction.iter_mut().zip(prev_direction) {
                *d += beta * pd;
            }
            if direction
                .iter()
                .zip(&theta)
                .map(|(d, t)| d * t)
                .sum::<f64>()
                <= 0.0
            {
                direction.clone_from(&theta);
            }
        }
        // A_2 d = G z with (M/h^2 + K) z = G^T d, on free DOFs, reusing the factor.
        let start = Instant::now();
        let jacobian = system
            .jacobian
            .as_ref()
            .expect("dual system has a Jacobian layout");
        constraints.jacobian_values(x, &mut system.jacobian_values)?;
        let g = jacobian.matrix(&system.jacobian_values)?;
        let g = g.as_ref();
        let nf = model.dofs.num_free();
        let mut z = vec![0.0; nf];
        for (col, zc) in z.iter_mut().enumerate() {
            *zc = g
                .row_idx_of_col(col)
                .zip(g.val_of_col(col))
                .map(|(r, v)| v * direction[r])
                .sum();
        }
        newton
            .cholesky()
            .ok_or_else(|| {
                SolverError::InvalidProblem("the dual solver needs the direct linear solver".into())
            })?
            .solve_in_place(&mut z)
            .map_err(|e| SolverError::Linear(e.to_string()))?;
        let mut a2_d = vec![0.0; m];
        for (col, zc) in z.iter().enumerate() {
            for (r, v) in g.row_idx_of_col(col).zip(g.val_of_col(col)) {
                a2_d[r] += v * zc;
            }
        }
        let numerator: f64 = theta.iter().zip(&direction).map(|(t, d)| t * d).sum();
        let denominator: f64 = (0..m)
            .map(|i| direction[i] * (a2_d[i] + compliance[i] * direction[i]))
            .sum();
        report.timings.solve += start.elapsed();
        if !(denominator > 0.0 && numerator.is_finite() && theta_sq.is_finite()) {
            return Err(SolverError::Linear(format!(
                "the dual step (eq. 41) is undefined: d^T (A2 + C) d = {denominator:e}"
            )));
        }
        let omega = numerator / denominator;
        for i in 0..m {
            p[i] += omega * direction[i];
        }
        previous = Some((theta, direction));
    }
    Err(SolverError::NotConverged {
        solver: "dual ascent",
        iterations: report.iterations.len(),
        force_residual: report.force_residual,
        constraint_residual: report.constraint_residual,
    })
}
