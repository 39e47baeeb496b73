//! `[solver]`: Newton limits, tolerances and the linear solver.

use super::names::{JacobianName, LinearName, OrderingName, PreconditionerName};
use serde::{Deserialize, Serialize};

/// Newton limits and tolerances (defaults: the solver's).
#[derive(Debug, Clone, PartialEq, Default, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct SolverSpec {
    /// Newton iterations per step.
    pub max_iterations: Option<usize>,
    /// Force tolerance, relative to the force scale.
    pub force_tolerance: Option<f64>,
    /// Constraint tolerance, relative to the rest volumes.
    pub constraint_tolerance: Option<f64>,
    /// Line-search backtracks per iteration.
    pub max_backtracks: Option<usize>,
    /// Dual ascent iterations per step.
    pub max_dual_iterations: Option<usize>,
    /// Whether element Hessians are projected to PSD.
    pub project_hessians: Option<bool>,
    /// `direct`, `iterative`, or `auto` (direct up to
    /// [`isochor_solvers::AUTO_DIRECT_UNKNOWNS`] unknowns, iterative above).
    pub linear: Option<LinearName>,
    /// The tightest relative residual of the iterative linear solver (the floor of its
    /// inexact-Newton forcing terms; default 1e-8).
    pub linear_tolerance: Option<f64>,
    /// Iteration limit of the iterative linear solver.
    pub linear_max_iterations: Option<usize>,
    /// Fill-reducing ordering of the direct factorizations: `amd`, `nested-dissection`
    /// (METIS) or `auto` (the default: AMD on small systems, nested dissection on large).
    pub ordering: Option<OrderingName>,
    /// `full` (default: a fresh Newton matrix every iteration) or `modified` (the last
    /// factorization reused while the residual halves, a fresh one otherwise).
    pub jacobian: Option<JacobianName>,
    /// Preconditioner of the iterative linear solver's stiffness block:
    /// `incomplete-cholesky` (default) or `jacobi`.
    pub linear_preconditioner: Option<PreconditionerName>,
    /// Largest accepted penetration into an obstacle, relative to the mesh's bounding-box
    /// diagonal (default 1e-6).
    pub contact_tolerance: Option<f64>,
    /// Contact multiplier updates per step (default 30).
    pub max_contact_iterations: Option<usize>,
    /// Dynamics only: accept a step after `max_iterations` Newton iterations even if the
    /// tolerances are not met (a fixed iteration count, as in Fig. 9 of Francu et al. 2021);
    /// such steps and the run are reported as not converged.
    pub accept_unconverged: Option<bool>,
}

impl SolverSpec {
    /// The linear solver chosen: `linear`, else `iterative` when any `linear_*` key of the
    /// iterative solver is given, else `direct`.
    pub fn linear_choice(&self) -> LinearName {
        let iterative_key = self.linear_tolerance.is_some()
            || self.linear_max_iterations.is_some()
            || self.linear_preconditioner.is_some();
        match self.linear {
            Some(name) => name,
            None if iterative_key => LinearName::Iterative,
            None => LinearName::Direct,
        }
    }
}
