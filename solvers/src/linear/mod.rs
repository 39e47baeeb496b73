//! Sparse linear algebra for the Newton solvers: fixed sparsity patterns refilled every
//! iteration, sparse Cholesky for SPD systems, supernodal `LDL^T` with inertia check
//! for the saddle-point systems of eq. 21/24 (Francu et al. 2021), both under a
//! fill-reducing [`Ordering`] (AMD or METIS nested dissection), and matrix-free
//! CG / MINRES (sec. 8) with interchangeable preconditioners: diagonal scaling,
//! incomplete Cholesky, smoothed-aggregation multigrid, and the block-diagonal
//! saddle-point preconditioner.
//!
//! Symmetric matrices are given with both triangles (as the quadrature kernels emit them)
//! or only the lower one; the factorizations read the lower triangle (`row >= col`).
//!
//! Typical use in a Newton loop (patterns and symbolic factorizations built once):
//!
//! ```text
//! let k_pattern = SparsityPattern::new(n, n, &k_pairs, Triangle::Lower)?;   // once
//! let mut k = k_pattern.zeros();
//! let mut kkt = KktSolver::new(k.symbolic(), g.symbolic(), c.map(|c| c.symbolic()),
//!                              &anchors, KktOptions::default())?;          // once
//! loop {
//!     k_pattern.assemble_into(&element_values, &mut k)?;                  // every iteration
//!     let shift = kkt.factorize_with_shifts(k.as_ref(), g.as_ref(), c, &ShiftSchedule::default())?;
//!     kkt.solve_in_place(&mut rhs)?;            // rhs = (-sigma, -theta) -> (du, dp)
//!     let report = kkt.report();                // times, inertia, residual, shift
//! }
//! ```

mod aggregation;
mod amg;
mod chebyshev;
mod cholesky;
mod error;
mod fill_reducing;
mod incomplete_cholesky;
mod iterative;
mod jacobi;
mod kkt;
mod nested_dissection;
mod operator;
mod ordering;
mod pattern;
mod preconditioner;
mod report;
mod shift;

pub use aggregation::NearNullSpace;
pub use amg::SmoothedAggregation;
pub use cholesky::CholeskySolver;
pub use error::LinearError;
pub use fill_reducing::Ordering;
pub use incomplete_cholesky::IncompleteCholesky;
pub use iterative::{cg, minres, IterativeOptions, IterativeReport};
pub use jacobi::{diagonal, saddle_point_diagonal, Jacobi};
pub use kkt::{KktOptions, KktSolver, PivotRegularization};
pub use operator::{relative_residual, LinearOperator, SaddlePoint, SymmetricLower};
pub use pattern::{entry_pairs, SparsityPattern, Triangle};
pub use preconditioner::{BlockDiagonal, Preconditioner};
pub use report::{Factorization, Inertia, SolveReport};
pub use shift::{max_abs_diagonal, ShiftSchedule};
