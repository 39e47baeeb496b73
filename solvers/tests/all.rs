//! The integration tests of isochor-solvers as one test binary (`autotests = false` in its
//! `Cargo.toml`): one link and one copy of the dependencies' generic code instead of one per
//! file. Each module is one file of this folder; `.ci/run` checks that every file is listed.

mod common;
mod contact;
mod contact_threads;
mod equivalences;
mod examples;
mod inversion;
mod iterative;
mod linear;
mod matrices;
mod physics;
mod preconditioners;
mod refinement;
