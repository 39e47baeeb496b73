//! Reports of every Newton iteration and step: how users see the speed/accuracy trade.

use crate::terms::ContactSummary;
use std::time::Duration;

/// One Newton (or dual) iteration.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct IterationReport {
    /// Norm of the force residual (free DOFs) before the step.
    pub force_residual: f64,
    /// Max-norm of the constraint residual `phi - C p`, relative to each row's rest volume,
    /// before the step (for dual ascent: at the start of the dual iteration this Newton
    /// iteration belongs to; 0 without multipliers).
    pub constraint_residual: f64,
    /// The volume error of Francu et al. 2021, Fig. 8: the L1 norm of `phi - C p` over the
    /// rest volume, at the same point as `constraint_residual`.
    pub volume_error: f64,
    /// Accepted step length.
    pub step_length: f64,
    /// Line-search backtracks.
    pub backtracks: usize,
    /// Shift added to the stiffness to restore the right inertia (0 if none).
    pub regularization: f64,
    /// Krylov iterations of the iteration's linear solves (0 on the direct path).
    pub linear_iterations: usize,
    /// Whether the iteration reused an earlier factorization ([`crate::Jacobian::Modified`]).
    pub reused: bool,
    /// Whether the barrier contact's and cloth's element Hessians were PSD-projected because
    /// the matrix with the exact ones did not factorize unshifted (or the inertia was wrong).
    pub hessian_projected: bool,
}

/// Where the time of a step went.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Timings {
    /// Sparsity patterns and symbolic factorizations: at a run's first attempt, and again
    /// where the surface contact's pairs change the pattern.
    pub setup: Duration,
    /// Element evaluation and sparse assembly.
    pub assembly: Duration,
    /// Numeric (and first symbolic) factorization.
    pub factorization: Duration,
    /// Triangular solves, refinement and iterative solves.
    pub solve: Duration,
    /// Part of `assembly`: the surface contact's broad phase at each pattern update and the
    /// barrier and surface friction terms of the Newton-matrix assemblies.
    pub contact: Duration,
    /// The line searches: continuous collision detection, trial states' validity checks and
    /// evaluations (those evaluations count in `assembly` too).
    pub line_search: Duration,
    /// Part of `line_search`: the continuous collision detection bounding each step.
    pub ccd: Duration,
}

impl std::ops::AddAssign for Timings {
    fn add_assign(&mut self, other: Self) {
        self.setup += other.setup;
        self.assembly += other.assembly;
        self.factorization += other.factorization;
        self.solve += other.solve;
        self.contact += other.contact;
        self.line_search += other.line_search;
        self.ccd += other.ccd;
    }
}

/// One load step or time step.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct StepReport {
    /// Step index, from 1.
    pub step: usize,
    /// Load parameter in `[0, 1]` (quasi-static) or time in seconds (dynamics) at its end.
    pub t: f64,
    /// The increment of the load parameter or time it took.
    pub increment: f64,
    /// Every iteration, in order.
    pub iterations: Vec<IterationReport>,
    /// Final force residual norm.
    pub force_residual: f64,
    /// Final constraint residual (max-norm).
    pub constraint_residual: f64,
    /// Final volume error (see [`IterationReport::volume_error`]).
    pub volume_error: f64,
    /// Whether the step met both tolerances.
    pub converged: bool,
    /// Where the time went.
    pub timings: Timings,
    /// Stored entries of the direct factorization's factor `L` (its memory is 8 bytes
    /// each; 0 for the iterative linear solvers): the fill its ordering left.
    pub factor_nnz: usize,
    /// Numeric factorizations of the direct linear solvers (each counted once, however many
    /// shifts it tried; 0 on the iterative path).
    pub factorizations: usize,
    /// Wall time of the whole step.
    pub wall_time: Duration,
    /// Contact multiplier updates (outer augmented-Lagrangian iterations; 0 without obstacles).
    pub contact_iterations: usize,
    /// Lags of the friction's normal forces after the first (0 without friction): the solves
    /// the friction took beyond the contact's own.
    pub friction_lags: usize,
    /// Rebuilds of the Newton matrix's sparsity pattern, each with a new symbolic
    /// factorization, because the surface contact's or friction's pairs changed (0 without
    /// surface contact).
    pub pattern_rebuilds: usize,
    /// Contact forces at the accepted state (zero without obstacles).
    pub contact: ContactSummary,
    /// Why the attempt failed, if it was cut (retried with a smaller increment) or ended
    /// the run.
    pub failure: Option<String>,
}

impl StepReport {
    /// Number of Newton (or dual) iterations.
    pub fn newton_iterations(&self) -> usize {
        self.iterations.len()
    }

    /// Total line-search backtracks.
    pub fn backtracks(&self) -> usize {
        self.iterations.iter().map(|i| i.backtracks).sum()
    }
}
