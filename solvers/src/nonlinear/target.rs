//! What one step asks of a nonlinear solver, and small vector helpers shared by them.

use crate::problem::schedule::LoadLevel;
use isochor_mesh::Vec3;

/// The goal of one load or time step.
#[derive(Debug, Clone)]
pub struct StepTarget {
    /// Where the external loads stand.
    pub level: LoadLevel,
    /// Target values of the prescribed DOFs.
    pub prescribed: Vec<(usize, f64)>,
    /// Absolute force residual tolerance.
    pub force_tolerance: f64,
}

/// Full-space vector of prescribed increments `target - x` (zero on free DOFs).
pub fn gap(x: &[Vec3], prescribed: &[(usize, f64)], len: usize) -> Vec<f64> {
    let mut d = vec![0.0; len];
    for &(dof, value) in prescribed {
        d[dof] = value - x[dof / 3][dof % 3];
    }
    d
}

/// `x += alpha d` for positions and a full-space vector.
pub fn add_scaled(x: &mut [Vec3], d: &[f64], alpha: f64) {
    for (i, xi) in x.iter_mut().enumerate() {
        for k in 0..3 {
            xi[k] += alpha * d[3 * i + k];
        }
    }
}

/// The dot product of two vectors of equal length.
pub fn dot(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| x * y).sum()
}

/// Euclidean norm.
pub fn norm(v: &[f64]) -> f64 {
    v.iter().map(|a| a * a).sum::<f64>().sqrt()
}

/// Max norm.
pub fn max_abs(v: &[f64]) -> f64 {
    v.iter().fold(0.0, |m, a| m.max(a.abs()))
}

/// The volume error of Francu et al. 2021, Fig. 8: the L1 norm of the constraint residual
/// `theta` over the rest volume its rows cover, `sum_i |theta_i| / sum_i V_i`.
pub fn volume_error(theta: &[f64], row_volumes: &[f64]) -> f64 {
    theta.iter().map(|t| t.abs()).sum::<f64>() / row_volumes.iter().sum::<f64>()
}

/// Sets the prescribed DOFs exactly to their targets (after a full step, so that rounding
/// in `x + (target - x)` never leaves a spurious gap).
pub fn snap(x: &mut [Vec3], prescribed: &[(usize, f64)]) {
    for &(dof, value) in prescribed {
        x[dof / 3][dof % 3] = value;
    }
}

/// The largest distance of a prescribed DOF from its target, if any is not reached.
pub fn remaining_gap(x: &[Vec3], target: &StepTarget) -> Option<f64> {
    let gap = max_abs(&gap(x, &target.prescribed, 3 * x.len()));
    (gap > 0.0).then_some(gap)
}
