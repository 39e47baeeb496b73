//! The integration tests of isochor-validation as one test binary (`autotests = false` in its
//! `Cargo.toml`): one link and one copy of the dependencies' generic code instead of one per
//! file. Each module is one file of this folder; `.ci/run` checks that every file is listed.

mod assembled;
mod cloth;
mod cloth_sheets;
mod common;
mod constraints;
mod contact_forces;
mod contact_geometry;
mod contact_term;
mod dynamics;
mod elements;
mod enclosed_volume;
mod energies;
mod extremes;
mod friction;
mod hertz;
mod incline;
mod locking;
mod mesh_obstacle_friction;
mod mesh_obstacle_term;
mod modified_newton;
mod newton;
mod orderings;
mod quadratic;
mod reference;
mod shell;
mod stepping;
mod stresses;
mod surface_contact_term;
mod surface_readers;
mod terms;
mod volume;
