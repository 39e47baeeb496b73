//! # isochor-solvers
//!
//! Where the papers' methods become simulators: a model holding only the terms a problem
//! names, parallel assembly into fixed sparsity patterns, sparse direct and iterative linear
//! solvers, Newton on displacements (`standard`, `condensed`), saddle-point Newton (`mixed-*`,
//! `zonal`), dual ascent (`dual`), quasi-static load stepping and implicit Euler.

mod assembly;
mod dofs;
mod dual;
mod error;
pub mod linear;
mod model;
mod newton;
mod problem;
mod report;
mod saddle;
mod settings;
mod simulation;
mod step;
mod system;
pub mod terms;

pub use dofs::Dofs;
pub use error::SolverError;
pub use problem::{
    Dirichlet, Epidermis, Kappa, Load, Material, Method, Motion, Obstacle, Problem, Shape,
    ZonalEnergy,
};
pub use report::{IterationReport, StepReport, Timings};
pub use settings::{LinearSolver, Settings};
pub use simulation::{
    Energies, Frame, Linearizer, NewtonSystem, RunSummary, Simulation, SimulationFailure, State,
    Stepping,
};
pub use terms::ContactSummary;
