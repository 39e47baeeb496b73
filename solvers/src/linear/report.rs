//! Where the time of a linear solve went, and how trustworthy its result is.

use super::Ordering;
use std::time::Duration;

/// Signs of the pivots `D` of an `LDL^T` factorization (Sylvester's law of inertia:
/// they are the signs of the eigenvalues of the factorized matrix).
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct Inertia {
    /// Positive pivots.
    pub positive: usize,
    /// Negative pivots.
    pub negative: usize,
    /// Pivots below the zero threshold (without pivot regularization) or not finite.
    pub zero: usize,
}

/// Which factorization produced the last solution.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub enum Factorization {
    /// Nothing factorized yet.
    #[default]
    None,
    /// Sparse `LL^T` (SPD systems).
    Cholesky,
    /// Supernodal `LDL^T` without pivot regularization.
    Ldlt,
    /// Supernodal `LDL^T` with tiny pivots regularized, and iterative refinement.
    RegularizedLdlt,
    /// Sparse `LU` with partial pivoting (fallback).
    Lu,
}

/// Timings and diagnostics of the latest factorization and solve.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct SolveReport {
    /// The factorization in use.
    pub factorization: Factorization,
    /// Time of the symbolic analysis (ordering, elimination tree); paid once per pattern.
    pub symbolic_time: Duration,
    /// Time of the latest numeric factorization, including copying values into the
    /// factorization's matrix and any retries (regularized `LDL^T`, `LU` fallback).
    pub numeric_time: Duration,
    /// Time of the latest solve, including iterative refinement.
    pub solve_time: Duration,
    /// Number of numeric factorizations performed for the latest system (retries count).
    pub factorizations: usize,
    /// Stored entries of the `LL^T` or `LDL^T` factor `L` (from the symbolic analysis).
    pub factor_nnz: usize,
    /// The fill-reducing ordering the symbolic analysis used (`Auto` resolved by size).
    pub ordering: Ordering,
    /// Shift added to the diagonal of `K` (absolute).
    pub shift: f64,
    /// Pivots replaced by the regularization of the `LDL^T` (0 if none).
    pub regularized_pivots: usize,
    /// Inertia of the accepted `LDL^T` factorization (`None` for `LL^T` and `LU`).
    pub inertia: Option<Inertia>,
    /// Iterative refinement steps of the latest solve.
    pub refinement_steps: usize,
    /// Final relative residual of the latest solve (against the unregularized matrix,
    /// `NaN` if not computed): `|b - A x| / |b|` for `LL^T`; for the KKT solver the smaller
    /// of that and `|S (b - A x)| / |S b|`, `S` its diagonal scaling.
    pub residual: f64,
}
