//! # isochor-solvers
//!
//! Where the papers' methods become simulators: a model holding only the terms a problem
//! names, parallel assembly into fixed sparsity patterns, sparse direct and iterative linear
//! solvers, Newton on displacements (`standard`, `condensed`), saddle-point Newton (`mixed-*`,
//! `zonal`), dual ascent (`dual`), quasi-static load stepping and implicit Euler.
//!
//! ## Layers
//!
//! The modules, from the bottom up; each imports only from the modules above it in this
//! table, and from the module that defines an item (never through this crate's re-exports,
//! which are its public face):
//!
//! | layer | module | what it holds |
//! |---|---|---|
//! | 0 | `error` | [`SolverError`] |
//! | 1 | [`linear`] | sparse Cholesky, KKT `LDL^T`, CG and MINRES, orderings and shifts |
//! | 2 | `settings` | [`Settings`]: Newton limits, tolerances, the linear solver, the volume projection |
//! | 3 | `problem` | what a user states: the [`Problem`], its [`Method`], [`Material`]s, loads, motions, obstacles, [`Curve`]s |
//! | 4 | [`terms`] | the energy terms: elastic, loads, inertia, epidermis, contact, augmented constraints |
//! | 5 | `model` | the model built from a problem: its DOFs, the material of every element, only the terms it names |
//! | 6 | `assembly` | the assembled view the nonlinear solvers iterate on: fixed patterns, parallel refills |
//! | 7 | `nonlinear` | Newton, saddle-point Newton and dual ascent, the target of one step, the iteration reports |
//! | 8 | `simulation` | the stepping driver ([`Simulation`]: quasi-static and implicit Euler), its state and outputs |
//!
//! A problem is stated with [`Problem::builder`] (or as a [`Problem`] literal), run by
//! [`Simulation::run`], and measured with the probes of `isochor_mesh::probes`; the sparse
//! matrices of a Newton step come as `sprs::CsMat` from [`Simulation::matrices`] (faer is the
//! solvers' own type and stays inside, except in the [`linear`] layer).
//!
//! Re-exports: the mesh types a [`Problem`] holds and a [`State`] is read on
//! ([`ElementMesh`], [`TetMesh`], [`Vec3`], [`Zones`]), [`NodalCompliance`] of a [`Material`],
//! and the [`sprs`] crate of [`Matrices`], so that stating a problem and reading its results
//! needs this crate alone. Mesh generators, readers and probes stay in `isochor-mesh`.

#![deny(missing_docs)]

mod assembly;
mod error;
pub mod linear;
mod model;
mod nonlinear;
mod problem;
mod settings;
mod simulation;
pub mod terms;

pub use error::SolverError;
/// How [`Material::nodal_compliance`] integrates the nodal compliance (re-exported so that a
/// `Material` can be written without depending on `isochor-constraints`).
pub use isochor_constraints::NodalCompliance;
/// The mesh types a [`Problem`] holds and a [`State`] is read on.
pub use isochor_mesh::{ElementMesh, TetMesh, Vec3, Zones};
pub use model::dofs::Dofs;
pub use model::regions::Regions;
pub use nonlinear::report::{IterationReport, StepReport, Timings};
pub use problem::builder::ProblemBuilder;
pub use problem::loads::{Dirichlet, Load, Motion, ScheduledLoad};
pub use problem::material::{Epidermis, Kappa, Material, MaterialModel, ZonalEnergy};
pub use problem::method::Method;
pub use problem::obstacle::{Obstacle, Shape};
pub use problem::schedule::{Curve, LoadLevel};
pub use problem::{Problem, Region};
pub use settings::{
    IterativeSettings, LinearSolver, PreconditionerKind, Settings, VolumeProjection,
    AUTO_DIRECT_UNKNOWNS,
};
pub use simulation::{
    Adaptive, Checkpoint, Energies, Frame, Linearizer, Matrices, NewtonSystem, Progress,
    RunSummary, Simulation, SimulationFailure, State, StepControl, Stepping,
};
/// The sparse matrix crate of [`Matrices`] and [`isochor_constraints::SparseMatrix`].
pub use sprs;
pub use terms::ContactSummary;
