//! # isochor-validation
//!
//! The proof that the numerics are right: one finite-difference harness ([`fd`], and
//! [`constraint_checks`] for constraint sets, [`terms`] for energy terms) and one set of proptest strategies
//! ([`strategies`]) shared by every test in `tests/`, the pinned
//! results they compare against ([`pinned`], files in `reference/`), plus the
//! locking regressions and studies.

#![deny(missing_docs)]

pub mod constraint_checks;
pub mod fd;
pub mod pinned;
pub mod strategies;
pub mod terms;
