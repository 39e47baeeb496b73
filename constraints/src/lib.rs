//! # isochor-constraints
//!
//! Volume constraint sets seen by the solvers only through [`ConstraintSet`]: values
//! `phi(x)`, Jacobian `G`, geometric stiffness `sum_i p_i Hess(phi_i)` and compliance `C`
//! (Francu et al. 2021, eq. 15-19 and 23; Sheen et al. 2021, eq. 6-8).
//!
//! - [`volume`]: the signed tet volume, its gradient and Hessian (eq. 25-26), the only
//!   geometric kernels; everything else assembles them.
//! - [`Measure`]: linear `J - 1` or logarithmic `log J` (sec. 6) per element.
//! - [`ElementConstraints`] (P0, sec. 4.6), [`NodalConstraints`] (P1, eq. 27, consistent or
//!   lumped compliance) and [`ZonalConstraints`] (Sheen et al. eq. 6-9).
//! - [`jacobian_matrix`] and [`geometric_stiffness_matrix`] for analysis.
//!
//! Sign convention: the Lagrangian is `L = E + p^T phi` with `phi_e = v_e - V_e`, so the
//! multipliers are tension-positive pressures (`p = kappa (J - 1)` at equilibrium
//! `phi = C p` for the linear measure).

mod constraint_set;
mod element;
mod error;
mod matrix;
mod measure;
mod nodal;
mod tets;
pub mod volume;
mod zonal;

pub use constraint_set::{Compliance, ConstraintSet};
pub use element::ElementConstraints;
pub use error::ConstraintError;
pub use matrix::{geometric_stiffness_matrix, jacobian_matrix};
pub use measure::Measure;
pub use nodal::{NodalCompliance, NodalConstraints};
pub use zonal::ZonalConstraints;
