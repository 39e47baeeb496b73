//! # isochor-validation
//!
//! The proof that the numerics are right: one finite-difference harness ([`fd`]) and one
//! set of proptest strategies ([`strategies`]) shared by every test in `tests/`, the pinned
//! results they compare against ([`pinned`], files in `reference/`), plus the
//! locking regressions and studies.

pub mod fd;
pub mod pinned;
pub mod strategies;
