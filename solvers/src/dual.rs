//! Dual ascent / nonlinear Uzawa (eq. 39-41 of Francu et al. 2021): alternate a primal
//! Newton solve of `min_x L(x, p_k)` with a steepest-ascent step on the multipliers,
//! `p_{k+1} = p_k + omega theta`, `theta = phi(x) - C p` and
//! `omega = theta^T theta / theta^T (A_2 + C) theta` (eq. 41) where `A_2 theta = G z`,
//! `(M/h^2 + K) z = G^T theta` reuses the primal factorization. With a base Poisson ratio the
//! primal energy carries the augmented term of sec. 8.3 (see [`crate::terms::AugmentedConstraints`]).

use crate::newton::Newton;
use crate::step::{max_abs, StepTarget};
use crate::system::System;
use crate::{SolverError, StepReport};
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
    let constraints = model.constraints.clone().ok_or_else(|| SolverError::InvalidProblem("dual ascent without constraints".into()))?;
    let augmented = model.augmented.as_ref().ok_or_else(|| SolverError::InvalidProblem("dual ascent without a primal term".into()))?;
    let compliance = match constraints.compliance() {
        Compliance::Diagonal(d) => d,
        Compliance::Sparse(_) => return Err(SolverError::InvalidProblem("dual ascent needs a lumped compliance".into())),
    };
    let m = p.len();
    let mut phi = vec![0.0; m];
    for _ in 0..settings.max_dual_iterations {
        augmented.set_multipliers(p);
        let mut primal = StepReport::default();
        let result = newton.minimize(system, x, target, &mut primal);
        report.iterations.extend(primal.iterations);
        report.timings += primal.timings;
        report.force_residual = primal.force_residual;
        result?;
        constraints.values(x, &mut phi)?;
        let theta: Vec<f64> = (0..m).map(|i| phi[i] - compliance[i] * p[i]).collect();
        let residual = max_abs(
            &theta
                .iter()
                .zip(&model.row_volumes)
                .map(|(t, v)| t / v)
                .collect::<Vec<_>>(),
        );
        report.constraint_residual = residual;
        if residual <= settings.constraint_tolerance {
            report.converged = true;
            return Ok(());
        }
        // A_2 theta = G z with (M/h^2 + K) z = G^T theta, on free DOFs, reusing the factor.
        let start = Instant::now();
        let jacobian = system.jacobian.as_ref().expect("dual system has a Jacobian layout");
        constraints.jacobian_values(x, &mut system.jacobian_values)?;
        let g = jacobian.matrix(&system.jacobian_values)?;
        let g = g.as_ref();
        let nf = model.dofs.num_free();
        let mut z = vec![0.0; nf];
        for col in 0..nf {
            z[col] = g.row_idx_of_col(col).zip(g.val_of_col(col)).map(|(r, v)| v * theta[r]).sum();
        }
        newton
            .cholesky()
            .solve_in_place(&mut z)
            .map_err(|e| SolverError::Linear(e.to_string()))?;
        let mut a2_theta = vec![0.0; m];
        for col in 0..nf {
            for (r, v) in g.row_idx_of_col(col).zip(g.val_of_col(col)) {
                a2_theta[r] += v * z[col];
            }
        }
        let numerator: f64 = theta.iter().map(|t| t * t).sum();
        let denominator: f64 = (0..m).map(|i| theta[i] * (a2_theta[i] + compliance[i] * theta[i])).sum();
        report.timings.solve += start.elapsed();
        if !(denominator > 0.0 && numerator.is_finite()) {
            return Err(SolverError::Linear(format!(
                "the dual step (eq. 41) is undefined: theta^T (A2 + C) theta = {denominator:e}"
            )));
        }
        let omega = numerator / denominator;
        for i in 0..m {
            p[i] += omega * theta[i];
        }
    }
    Err(SolverError::NotConverged {
        iterations: report.iterations.len(),
        force_residual: report.force_residual,
        constraint_residual: report.constraint_residual,
    })
}
