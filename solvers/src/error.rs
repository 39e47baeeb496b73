//! Errors of the solver layer. A failed solve is a value that says why; the stepping driver
//! wraps it with the last converged state and the iteration log.

use isochor_constraints::ConstraintError;
use isochor_energies::{OutOfDomain, ParameterError};
use isochor_mesh::MeshError;

/// Why a model could not be built or a solve failed.
#[derive(Debug, Clone, thiserror::Error)]
pub enum SolverError {
    #[error("unknown method '{name}' (valid: {valid})")]
    UnknownMethod { name: String, valid: String },
    #[error(transparent)]
    Parameter(#[from] ParameterError),
    #[error("{0}")]
    Mesh(String),
    #[error("invalid problem: {0}")]
    InvalidProblem(String),
    #[error("method {method} cannot run at nu = {nu}: {reason}")]
    Unsupported {
        method: &'static str,
        nu: f64,
        reason: &'static str,
    },
    #[error("the initial state is outside the domain of the energy: {0}")]
    InvalidInitialState(String),
    #[error("{solver} did not converge in {iterations} iterations (force residual {force_residual:e}, constraint residual {constraint_residual:e})")]
    NotConverged {
        /// The iteration that ran out: "Newton", "saddle-point Newton" or "dual ascent".
        solver: &'static str,
        iterations: usize,
        force_residual: f64,
        constraint_residual: f64,
    },
    #[error("the prescribed motion was not reached in {iterations} iterations: the boundary is still {gap:e} away because full steps leave the energy's domain (inverted or flattened tets); use more steps or an invertible energy (zonal)")]
    BoundaryUnreachable { iterations: usize, gap: f64 },
    #[error("line search failed after {backtracks} backtracks: {reason}")]
    LineSearch { backtracks: usize, reason: String },
    #[error("contact did not converge in {iterations} multiplier updates (penetration {max_penetration:e} m)")]
    ContactNotConverged {
        iterations: usize,
        max_penetration: f64,
    },
    #[error("no convergence from load parameter or time {t} even with an increment of {increment:e} (the smallest allowed is {min:e}); the last attempt: {error}")]
    IncrementTooSmall {
        t: f64,
        increment: f64,
        min: f64,
        error: Box<SolverError>,
    },
    #[error("linear solver failed: {0}")]
    Linear(String),
    #[error("non-finite value in {0}")]
    NonFinite(&'static str),
    #[error(transparent)]
    Constraint(#[from] ConstraintError),
    #[error(transparent)]
    Energy(#[from] OutOfDomain),
}

impl From<MeshError> for SolverError {
    fn from(e: MeshError) -> Self {
        SolverError::Mesh(e.to_string())
    }
}
