//! # isochor-constraints
//!
//! Volume constraint sets seen by the solvers only through [`ConstraintSet`]: values
//! `phi(x)`, Jacobian `G`, geometric stiffness `sum_i p_i Hess(phi_i)` and compliance `C`
//! (Francu et al. 2021, eq. 15-19 and 23; Sheen et al. 2021, eq. 6-8).

mod constraint_set;
mod error;

pub use constraint_set::{Compliance, ConstraintSet};
pub use error::ConstraintError;
