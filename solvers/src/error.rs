//! Errors of the solver layer. A failed solve is a value that says why; the stepping driver
//! wraps it with the last converged state and the iteration log.

use isochor_constraints::ConstraintError;
use isochor_energies::{OutOfDomain, ParameterError};
use isochor_mesh::MeshError;

/// Why a model could not be built or a solve failed.
#[derive(Debug, Clone, thiserror::Error)]
pub enum SolverError {
    /// Unknown method '`name`' (valid: `valid`).
    #[error("unknown method '{name}' (valid: {valid})")]
    UnknownMethod {
        /// The name given.
        name: String,
        /// The valid names, comma-separated.
        valid: String,
    },
    /// A material parameter is invalid.
    #[error(transparent)]
    Parameter(#[from] ParameterError),
    /// The mesh layer refused the mesh (its message).
    #[error("{0}")]
    Mesh(String),
    /// The problem or a setting is invalid (the message names the index or key).
    #[error("invalid problem: {0}")]
    InvalidProblem(String),
    /// Method `method` cannot run at nu = `nu`: `reason`.
    #[error("method {method} cannot run at nu = {nu}: {reason}")]
    Unsupported {
        /// The method's name.
        method: &'static str,
        /// Poisson's ratio of the material.
        nu: f64,
        /// Why.
        reason: &'static str,
    },
    /// The initial state has inverted or degenerate elements where the energy is undefined.
    #[error("the initial state is outside the domain of the energy: {0}")]
    InvalidInitialState(String),
    /// A step converged to a state with inverted elements where the energy has no meaning:
    /// the attempt fails, as a negative Jacobian does in FEBio, and the increment is cut.
    #[error("the step converged to a state with {inverted} inverted elements (J <= 0 at a corner or quadrature point), where the energy is undefined; use smaller increments or an invertible energy (the zonal method, or the stable-neo-hookean model)")]
    InvertedState {
        /// Elements with `J <= 0` at a corner or quadrature point.
        inverted: usize,
    },
    /// A nonlinear iteration ran out of iterations before the tolerances were met.
    #[error("{solver} did not converge in {iterations} iterations (force residual {force_residual:e}, constraint residual {constraint_residual:e})")]
    NotConverged {
        /// The iteration that ran out: "Newton", "saddle-point Newton" or "dual ascent".
        solver: &'static str,
        /// Iterations done.
        iterations: usize,
        /// The force residual reached.
        force_residual: f64,
        /// The constraint residual reached.
        constraint_residual: f64,
    },
    /// The prescribed motion was not reached: full steps leave the energy's domain.
    #[error("the prescribed motion was not reached in {iterations} iterations: the boundary is still {gap:e} away because full steps leave the energy's domain (inverted or flattened tets); use more steps or an invertible energy (zonal)")]
    BoundaryUnreachable {
        /// Iterations done.
        iterations: usize,
        /// Distance still to go to the prescribed motion.
        gap: f64,
    },
    /// Line search failed after `backtracks` backtracks: `reason`.
    #[error("line search failed after {backtracks} backtracks: {reason}")]
    LineSearch {
        /// Backtracks done.
        backtracks: usize,
        /// Why.
        reason: String,
    },
    /// Contact did not converge in `iterations` multiplier updates (penetration `max_penetration` m).
    #[error("contact did not converge in {iterations} multiplier updates (penetration {max_penetration:e} m)")]
    ContactNotConverged {
        /// Iterations done.
        iterations: usize,
        /// The deepest penetration, in metres.
        max_penetration: f64,
    },
    /// Stepping cut the increment below its smallest allowed value without convergence.
    #[error("no convergence from load parameter or time {t} even with an increment of {increment:e} (the smallest allowed is {min:e}); the last attempt: {error}")]
    IncrementTooSmall {
        /// Load parameter or time of the step.
        t: f64,
        /// The last increment tried.
        increment: f64,
        /// The smallest increment allowed.
        min: f64,
        /// The last attempt's error.
        error: Box<SolverError>,
    },
    /// A meshed obstacle's motion over a step would cross a body's surface (the barrier
    /// cannot stop a motion that is prescribed): the step is cut.
    #[error("meshed obstacle '{obstacle}' would cross a body's surface moving to load parameter or time {t}: the step is too large")]
    ObstacleCrossing {
        /// The obstacle's name.
        obstacle: String,
        /// The load parameter or time of the attempt.
        t: f64,
    },
    /// The run's observer stopped the stepping after accepted step `after_step`
    /// ([`Simulation::run_until`](crate::Simulation::run_until)).
    #[error("interrupted after step {after_step}")]
    Interrupted {
        /// The last accepted step.
        after_step: usize,
    },
    /// Pressure load `load` met its limit point: past it no equilibrium holds a higher
    /// given pressure.
    #[error("pressure load {load} (loads.pressure.{load}) has reached its limit point: no equilibrium holds a pressure much above {pressure:e} Pa (the cavity at {volume_ratio:.4} times its rest volume; the pressure-volume slope along the accepted steps has fallen to {slope_fraction:.3} of its largest), so the increments are being cut in vain; drive the cavity by its volume instead: `volume_ratio = R` in place of `pressure` on that load traces the curve through and past the limit point")]
    PressureLimitPoint {
        /// Index of the pressure load (among the pressure loads).
        load: usize,
        /// The pressure of the last accepted step.
        pressure: f64,
        /// The enclosed volume over the rest volume there.
        volume_ratio: f64,
        /// The last pressure-volume slope over the largest.
        slope_fraction: f64,
    },
    /// The linear solver failed (its message).
    #[error("linear solver failed: {0}")]
    Linear(String),
    /// A non-finite value appeared in the named quantity.
    #[error("non-finite value in {0}")]
    NonFinite(&'static str),
    /// The constraint set could not be built or evaluated.
    #[error(transparent)]
    Constraint(#[from] ConstraintError),
    /// A state left the domain of the energy.
    #[error(transparent)]
    Energy(#[from] OutOfDomain),
}

impl From<MeshError> for SolverError {
    fn from(e: MeshError) -> Self {
        SolverError::Mesh(e.to_string())
    }
}
