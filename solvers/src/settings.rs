//! Solver settings: Newton limits, tolerances and the linear solver choice.

use crate::linear::Ordering;
use crate::VolumeProjection;

/// How linear systems are solved.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub enum LinearSolver {
    /// Sparse direct factorization (Cholesky for SPD systems, LDL^T for saddle points),
    /// symbolic factorization reused.
    #[default]
    Direct,
    /// Preconditioned iterative solve (CG for SPD, MINRES for saddle points), for meshes too
    /// large to factor (sec. 8 of Francu et al.).
    Iterative(IterativeSettings),
    /// [`LinearSolver::Direct`] for systems of at most [`AUTO_DIRECT_UNKNOWNS`] unknowns,
    /// [`LinearSolver::Iterative`] with these settings above.
    Auto(IterativeSettings),
}

/// Systems of at most this many unknowns (free DOFs plus constraint rows) are solved
/// directly by [`LinearSolver::Auto`]. On the cantilever at nu = 0.4999 the direct solver was
/// faster than the iterative one at every size measured (README, "The iterative linear
/// path"), so the switch sits where the direct factor's memory becomes the limit: the scenes'
/// memory model (`410 B * n^(4/3)` of fill) reaches 4 GiB, a sixth of a 24 GiB machine, at
/// about 180k unknowns.
pub const AUTO_DIRECT_UNKNOWNS: usize = 180_000;

impl LinearSolver {
    /// The iterative settings to use for a system of `unknowns` unknowns, or `None` for
    /// the direct solver.
    pub fn iterative_for(self, unknowns: usize) -> Option<IterativeSettings> {
        match self {
            LinearSolver::Direct => None,
            LinearSolver::Iterative(s) => Some(s),
            LinearSolver::Auto(s) => (unknowns > AUTO_DIRECT_UNKNOWNS).then_some(s),
        }
    }
}

/// Settings of the iterative linear solver.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct IterativeSettings {
    /// The tightest relative residual a solve is asked for: the floor of the inexact-Newton
    /// forcing terms, which loosen the solves far from convergence (Eisenstat and Walker
    /// 1996, choice 2).
    pub tolerance: f64,
    /// Iterations allowed per linear solve.
    pub max_iterations: usize,
    /// Preconditioner of the stiffness block.
    pub preconditioner: PreconditionerKind,
}

impl Default for IterativeSettings {
    fn default() -> Self {
        IterativeSettings {
            tolerance: 1e-8,
            max_iterations: 1000,
            preconditioner: PreconditionerKind::default(),
        }
    }
}

/// Preconditioner of the stiffness block `K` in CG, and of the `K` block of the
/// block-diagonal saddle-point preconditioner in MINRES.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum PreconditionerKind {
    /// `diag(K)` (sec. 8 of Francu et al. 2021).
    Jacobi,
    /// Zero-fill incomplete Cholesky of `K`, shifted if a pivot breaks down.
    #[default]
    IncompleteCholesky,
    /// One V-cycle of smoothed-aggregation algebraic multigrid on `K` with the rigid-body
    /// modes as near null space.
    Multigrid,
}

/// Limits and tolerances of the nonlinear solvers.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Settings {
    /// Newton iterations per step (or primal iterations per dual iteration).
    pub max_iterations: usize,
    /// Force residual tolerance, relative to the problem's force scale (see
    /// [`crate::Simulation::force_scale`]).
    pub force_tolerance: f64,
    /// Constraint residual tolerance: `max_i |phi_i - (C p)_i| / V_i` with `V_i` the rest
    /// volume measured by constraint `i`.
    pub constraint_tolerance: f64,
    /// Line-search halvings before a step is declared failed.
    pub max_backtracks: usize,
    /// Outer iterations of the dual solver per step.
    pub max_dual_iterations: usize,
    /// Conjugate the dual ascent directions (otherwise plain steepest ascent, eq. 41).
    pub dual_conjugate: bool,
    /// Project element Hessians to PSD (displacement-only Newton).
    pub project_hessians: bool,
    /// Linear solver.
    pub linear: LinearSolver,
    /// Fill-reducing ordering of the direct factorizations (`K` and the KKT matrix).
    pub ordering: Ordering,
    /// Largest penetration of a vertex into an obstacle accepted at convergence, relative to
    /// the diagonal of the mesh's rest bounding box.
    pub contact_tolerance: f64,
    /// Multiplier updates (outer augmented-Lagrangian iterations) of the contact per step.
    pub max_contact_iterations: usize,
    /// Accept a step of implicit Euler after `max_iterations` Newton iterations even if the
    /// tolerances are not met, as interactive simulators do (Francu et al. 2021, Fig. 9: 3
    /// Newton iterations per 16 ms step); the step's report says it did not converge.
    /// Refused in quasi-static stepping (whose steps must be equilibria) and for `dual`
    /// (whose `max_iterations` counts primal iterations per dual iteration).
    pub accept_unconverged: bool,
    /// The volume correction after each implicit Euler step (none by default): the
    /// baselines of Fig. 8 of Sheen et al. 2021. Refused in quasi-static stepping.
    pub volume_projection: VolumeProjection,
}

impl Default for Settings {
    fn default() -> Self {
        Settings {
            max_iterations: 50,
            force_tolerance: 1e-9,
            constraint_tolerance: 1e-10,
            max_backtracks: 30,
            max_dual_iterations: 500,
            dual_conjugate: true,
            project_hessians: false,
            linear: LinearSolver::Direct,
            ordering: Ordering::Auto,
            contact_tolerance: 1e-6,
            max_contact_iterations: 30,
            accept_unconverged: false,
            volume_projection: VolumeProjection::None,
        }
    }
}
