//! Errors of the linear-algebra layer, returned as values.

use thiserror::Error;

/// Why a linear-algebra operation failed.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum LinearError {
    /// An index pair or matrix entry lies outside the declared shape.
    #[error("entry ({row}, {col}) is outside a {nrows} x {ncols} matrix")]
    IndexOutOfBounds {
        /// Row of the offending entry.
        row: usize,
        /// Column of the offending entry.
        col: usize,
        /// Declared number of rows.
        nrows: usize,
        /// Declared number of columns.
        ncols: usize,
    },
    /// Two sizes that must agree do not.
    #[error("{what}: expected {expected}, got {got}")]
    DimensionMismatch {
        /// What was being compared.
        what: &'static str,
        /// The size required.
        expected: usize,
        /// The size received.
        got: usize,
    },
    /// A matrix was given whose sparsity pattern differs from the one analysed.
    #[error(
        "the sparsity pattern of {what} differs from the one used for the symbolic factorization"
    )]
    PatternMismatch {
        /// Which matrix.
        what: &'static str,
    },
    /// A matrix that must be square is not.
    #[error("{what} must be square, got {nrows} x {ncols}")]
    NotSquare {
        /// Which matrix.
        what: &'static str,
        /// Rows.
        nrows: usize,
        /// Columns.
        ncols: usize,
    },
    /// A constraint anchor names a DOF that does not exist.
    #[error("constraint {constraint} is anchored to DOF {dof}, but there are only {n} DOFs")]
    BadAnchor {
        /// Constraint row.
        constraint: usize,
        /// Anchor DOF.
        dof: usize,
        /// Number of DOFs.
        n: usize,
    },
    /// A numeric input (matrix entry, right-hand side, shift) is NaN or infinite.
    #[error("non-finite value in {what}")]
    NonFiniteInput {
        /// Which input.
        what: &'static str,
    },
    /// The LL^T factorization met a non-positive pivot: the matrix is not SPD.
    #[error("matrix is not positive definite (non-positive pivot at elimination step {pivot})")]
    NotPositiveDefinite {
        /// Elimination step (in the fill-reducing order) of the failing pivot.
        pivot: usize,
    },
    /// The saddle-point matrix has the wrong inertia: `K` is not positive definite on
    /// the null space of `G` (the Newton step would not be a descent direction).
    #[error("wrong KKT inertia: {positive} positive, {negative} negative, {zero} zero pivots; expected {expected_positive} positive and {expected_negative} negative")]
    WrongInertia {
        /// Positive pivots of `D`.
        positive: usize,
        /// Negative pivots of `D`.
        negative: usize,
        /// Pivots below the zero threshold (or regularized pivots).
        zero: usize,
        /// Expected positive pivots (`n`).
        expected_positive: usize,
        /// Expected negative pivots (`m`).
        expected_negative: usize,
    },
    /// The factorization broke down (zero pivot) and no fallback was allowed.
    #[error("factorization broke down at pivot {pivot} (singular matrix)")]
    Singular {
        /// Elimination step of the failing pivot.
        pivot: usize,
    },
    /// The solution contains NaN or infinite entries.
    #[error("the solution contains NaN or infinite entries")]
    NonFiniteSolution,
    /// The residual after iterative refinement stays above the accepted tolerance.
    #[error("relative residual {residual:e} after {refinement_steps} refinement steps exceeds {tolerance:e}")]
    InaccurateSolution {
        /// Final relative residual `|b - A x| / |b|`.
        residual: f64,
        /// Refinement steps performed.
        refinement_steps: usize,
        /// The accepted tolerance.
        tolerance: f64,
    },
    /// An iterative solver did not reach its tolerance.
    #[error("{method} did not converge: relative residual {residual:e} after {iterations} iterations (tolerance {tolerance:e})")]
    NotConverged {
        /// Solver name.
        method: &'static str,
        /// Iterations performed.
        iterations: usize,
        /// Final relative residual.
        residual: f64,
        /// Requested tolerance.
        tolerance: f64,
    },
    /// An iterative solver broke down (e.g. CG on an indefinite operator).
    #[error("{method} broke down after {iterations} iterations: {reason}")]
    Breakdown {
        /// Solver name.
        method: &'static str,
        /// Iterations performed.
        iterations: usize,
        /// What happened.
        reason: &'static str,
    },
    /// Every shift of a regularization schedule failed.
    #[error(
        "regularization failed after {attempts} attempts (last shift {last_shift:e}): {last_error}"
    )]
    RegularizationFailed {
        /// Factorization attempts made.
        attempts: usize,
        /// The largest shift tried.
        last_shift: f64,
        /// The error of the last attempt.
        last_error: Box<LinearError>,
    },
    /// `solve` was called before a successful numeric factorization.
    #[error("no numeric factorization available; call factorize first")]
    NotFactorized,
    /// The fill-reducing ordering could not be computed.
    #[error("{algorithm} ordering failed: {message}")]
    Ordering {
        /// Which ordering.
        algorithm: &'static str,
        /// What went wrong.
        message: String,
    },
    /// An error reported by faer (allocation, index overflow, ...).
    #[error("faer: {0}")]
    Faer(String),
    /// The multigrid hierarchy could not be built.
    #[error("multigrid setup: {0}")]
    Multigrid(String),
}

impl LinearError {
    /// Whether adding a positive shift to the diagonal of `K` may cure this error:
    /// the Newton solvers regularize and retry on these (see [`super::ShiftSchedule`]).
    pub fn is_regularizable(&self) -> bool {
        matches!(
            self,
            Self::NotPositiveDefinite { .. } | Self::WrongInertia { .. } | Self::Singular { .. }
        )
    }
}

impl From<faer::sparse::FaerError> for LinearError {
    fn from(e: faer::sparse::FaerError) -> Self {
        Self::Faer(format!("{e:?}"))
    }
}

impl LinearError {
    /// The dimension of a square `nrows x ncols` matrix, else [`LinearError::NotSquare`].
    pub(crate) fn square(what: &'static str, nrows: usize, ncols: usize) -> Result<usize, Self> {
        if nrows == ncols {
            Ok(nrows)
        } else {
            Err(LinearError::NotSquare { what, nrows, ncols })
        }
    }
}
