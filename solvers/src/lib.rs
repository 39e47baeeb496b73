//! # isochor-solvers
//!
//! Where the papers' methods become simulators: a model holding only the terms a problem
//! names, parallel assembly into fixed sparsity patterns, sparse direct and iterative linear
//! solvers, Newton on displacements (`standard`, `condensed`), saddle-point Newton (`mixed-*`,
//! `zonal`), dual ascent (`dual`), quasi-static load stepping and implicit Euler.
//!
//! | module | what it holds |
//! |---|---|
//! | `model` | what is solved: the [`Problem`] a user states, its DOFs, and the model holding only the terms it names |
//! | [`terms`] | the energy terms: elastic, loads, inertia, epidermis, contact, augmented constraints |
//! | `assembly` | the assembled view the nonlinear solvers iterate on: fixed patterns, parallel refills |
//! | `nonlinear` | Newton, saddle-point Newton and dual ascent, and the target of one step |
//! | [`linear`] | sparse Cholesky, KKT `LDL^T`, CG and MINRES, orderings and shifts |
//! | `simulation` | the stepping driver ([`Simulation`]: quasi-static and implicit Euler) and its reports |
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
mod settings;
mod simulation;
pub mod terms;

pub use error::SolverError;
/// How [`Material::nodal_compliance`] integrates the nodal compliance (re-exported so that a
/// `Material` can be written without depending on `isochor-constraints`).
pub use isochor_constraints::NodalCompliance;
/// The mesh types a [`Problem`] holds and a [`State`] is read on.
pub use isochor_mesh::{ElementMesh, TetMesh, Vec3, Zones};
pub use model::{
    Curve, Dirichlet, Dofs, Epidermis, Kappa, Load, LoadLevel, Material, MaterialModel, Method,
    Motion, Obstacle, Problem, ProblemBuilder, Region, Regions, ScheduledLoad, Shape, ZonalEnergy,
};
pub use settings::{
    IterativeSettings, LinearSolver, PreconditionerKind, Settings, AUTO_DIRECT_UNKNOWNS,
};
pub use simulation::{
    Adaptive, Checkpoint, Energies, Frame, Linearizer, Matrices, NewtonSystem, Progress,
    RunSummary, Simulation, SimulationFailure, State, StepControl, Stepping, VolumeProjection,
};
pub use simulation::{IterationReport, StepReport, Timings};
/// The sparse matrix crate of [`Matrices`] and [`isochor_constraints::SparseMatrix`].
pub use sprs;
pub use terms::ContactSummary;
