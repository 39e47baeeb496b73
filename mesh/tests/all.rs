//! The integration tests of isochor-mesh as one test binary (`autotests = false` in its
//! `Cargo.toml`): one link and one copy of the dependencies' generic code instead of one per
//! file. Each module is one file of this folder; `.ci/run` checks that every file is listed.

mod element;
mod generators;
mod io;
mod surface;
