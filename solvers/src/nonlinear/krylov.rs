//! The iterative linear path of the Newton solvers: CG on `K dx = b` and MINRES on the
//! saddle-point system, with the preconditioners the settings name.

use crate::linear::{
    cg, diagonal, minres, BlockDiagonal, IncompleteCholesky, IterativeOptions, Jacobi, LinearError,
    LinearOperator, NearNullSpace, Preconditioner, SaddlePoint, SmoothedAggregation,
    SymmetricLower,
};
use crate::settings::{IterativeSettings, PreconditionerKind};
use faer::sparse::SparseColMatRef;

/// The SPD preconditioner of the stiffness block `K` (lower triangle) that `kind` names;
/// `near_null_space` is called only by multigrid (the rigid-body modes of the free DOFs).
fn stiffness_preconditioner(
    kind: PreconditionerKind,
    k: SparseColMatRef<'_, usize, f64>,
    near_null_space: impl FnOnce() -> NearNullSpace,
) -> Result<Box<dyn Preconditioner>, LinearError> {
    Ok(match kind {
        PreconditionerKind::Jacobi => Box::new(Jacobi::from_diagonal(&diagonal(k))),
        PreconditionerKind::IncompleteCholesky => Box::new(IncompleteCholesky::new(k)?),
        PreconditionerKind::Multigrid => Box::new(SmoothedAggregation::new(k, near_null_space())?),
    })
}

/// The preconditioner of `K` over the Newton iterations of a step: rebuilt at every
/// iteration, except multigrid, whose setup costs many Krylov iterations' worth: it is built
/// at a step's first iteration and kept for the rest of the step (a lagged preconditioner:
/// the Krylov solvers need it SPD, not built from the current `K`).
#[derive(Debug, Default)]
pub struct StiffnessPreconditioner {
    built: Option<Box<dyn Preconditioner>>,
}

impl StiffnessPreconditioner {
    /// Builds the preconditioner `kind` names from `k`, unless a lagged one is kept.
    pub fn update(
        &mut self,
        kind: PreconditionerKind,
        k: SparseColMatRef<'_, usize, f64>,
        near_null_space: impl FnOnce() -> NearNullSpace,
    ) -> Result<(), LinearError> {
        if kind != PreconditionerKind::Multigrid || self.built.is_none() {
            self.built = Some(stiffness_preconditioner(kind, k, near_null_space)?);
        }
        Ok(())
    }

    /// The current preconditioner ([`LinearError::NotFactorized`] before the first update).
    pub fn get(&self) -> Result<&dyn Preconditioner, LinearError> {
        self.built.as_deref().ok_or(LinearError::NotFactorized)
    }

    /// Drops a kept preconditioner: the next update builds a new one (a new step).
    pub fn new_step(&mut self) {
        self.built = None;
    }
}

/// Solves `K x = b` by CG with `preconditioner` from `x = 0` to the relative residual
/// `tolerance`; returns `x` and the iterations.
pub fn solve_stiffness(
    settings: &IterativeSettings,
    k: SparseColMatRef<'_, usize, f64>,
    preconditioner: &dyn Preconditioner,
    b: &[f64],
    tolerance: f64,
) -> Result<(Vec<f64>, usize), LinearError> {
    let mut x = vec![0.0; b.len()];
    let options = IterativeOptions {
        tolerance,
        max_iterations: settings.max_iterations,
    };
    let report = cg(&SymmetricLower(k), preconditioner, b, &mut x, options)?;
    Ok((x, report.iterations))
}

/// The saddle-point system `[[K, G^T], [G, -C]]` of one Newton step, with what its
/// pressure-block preconditioner needs.
pub struct SaddleSystem<'a> {
    /// `K` (lower triangle).
    pub k: SparseColMatRef<'a, usize, f64>,
    /// `G`.
    pub g: SparseColMatRef<'a, usize, f64>,
    /// `C`, `None` if zero.
    pub c: Option<SparseColMatRef<'a, usize, f64>>,
    /// The rest volume of every constraint row: the lumped pressure mass matrix.
    pub row_volumes: &'a [f64],
    /// The shear modulus.
    pub mu: f64,
}

/// Solves the saddle-point system for `b = (f, h)` by MINRES from zero (returns the
/// solution and the iterations) with the
/// block-diagonal preconditioner `diag(P_K, S)`: `P_K` the stiffness preconditioner `p_k`, and
/// `S = diag(V_i / mu + C_ii)` the lumped pressure mass matrix scaled by the shear modulus
/// plus the compliance (Elman, Silvester and Wathen, "Finite Elements and Fast Iterative
/// Solvers", 2nd ed., sec. 4.2 and 9.2: `G K^-1 G^T` is spectrally equivalent to
/// `M_p / mu` for a stable pair).
pub fn solve_saddle(
    settings: &IterativeSettings,
    system: &SaddleSystem<'_>,
    p_k: &dyn Preconditioner,
    b: &[f64],
    tolerance: f64,
) -> Result<(Vec<f64>, usize), LinearError> {
    let c_diag = system.c.map(diagonal);
    let schur: Vec<f64> = system
        .row_volumes
        .iter()
        .enumerate()
        .map(|(i, v)| v / system.mu + c_diag.as_ref().map_or(0.0, |c| c[i].abs()))
        .collect();
    let p_s = Jacobi::from_diagonal(&schur);
    let preconditioner = BlockDiagonal {
        first: p_k,
        second: &p_s,
    };
    let k_op = SymmetricLower(system.k);
    let c_op = system.c.as_ref().map(|c| c as &dyn LinearOperator);
    let operator = SaddlePoint {
        k: &k_op,
        g: system.g,
        c: c_op,
    };
    let mut x = vec![0.0; b.len()];
    let options = IterativeOptions {
        tolerance,
        max_iterations: settings.max_iterations,
    };
    let report = minres(&operator, &preconditioner, b, &mut x, options)?;
    Ok((x, report.iterations))
}
