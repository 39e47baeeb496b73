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
//! | 0 | [`contact`] | IPC's barrier, adaptive stiffness, smoothed friction and barrier potential (on `isochor_mesh::contact`) |
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
//! ## Every scene feature in Rust
//!
//! What a scene file states, stated as a [`Problem`]: a generated mesh, vertices and boundary
//! faces picked by a predicate (a scene's selections), a second material on a set of tets
//! (`[[regions]]`), a Dirichlet condition with a [`Motion`] that follows a [`Curve`], a
//! traction on the selected faces scheduled by a [`Curve`] ([`ScheduledLoad`]; a
//! [`Load::Pressure`] takes the same faces), and a rigid [`Obstacle`]. Curves are functions
//! of the load parameter (quasi-static) or of time in seconds (implicit Euler).
//!
//! ```
//! use isochor_mesh::generate::box_grid;
//! use isochor_mesh::{BoundarySurface, FaceSelection};
//! use isochor_solvers::{
//!     Curve, Dirichlet, Load, Material, Method, Motion, Obstacle, Problem, ScheduledLoad,
//!     Settings, Shape, Simulation, Stepping, Vec3,
//! };
//!
//! // A 4 x 1 x 1 cm bar (coordinates in metres).
//! let mesh = box_grid(Vec3::zeros(), Vec3::new(0.04, 0.01, 0.01), [4, 1, 1])?;
//! let x = mesh.positions().to_vec();
//!
//! // Selections: the vertices of either end, and the boundary faces on top.
//! let at = |pick: fn(&Vec3) -> bool| (0..x.len()).filter(|&v| pick(&x[v])).collect::<Vec<_>>();
//! let left = at(|p| p.x < 1e-9);
//! let right = at(|p| p.x > 0.04 - 1e-9);
//! let surface = BoundarySurface::new(&mesh)?;
//! let top = FaceSelection::from_filter("top", &surface, |face| {
//!     face.iter().all(|&v| x[v].z > 0.01 - 1e-9)
//! });
//!
//! // A region: the tets of the first centimetre are of a stiffer Yeoh rubber.
//! let stiff: Vec<usize> = (0..mesh.num_tets()).filter(|&t| mesh.centroid(t).x < 0.01).collect();
//! let yeoh = Material::yeoh(1e5, 1e3, 0.0, 0.49, 1100.0)?;
//!
//! // The right end moves 2 mm along x in the first half of the run and holds.
//! let ramp_and_hold = Curve::new(vec![(0.0, 0.0), (0.5, 1.0), (1.0, 1.0)])?;
//! let pull = Dirichlet {
//!     nodes: right,
//!     axes: [true, true, true],
//!     motion: Motion::Translate(Vec3::new(0.002, 0.0, 0.0)),
//!     curve: Some(ramp_and_hold),
//! };
//!
//! // A downward traction of 100 Pa on the top faces, reaching full scale at the end.
//! let press = ScheduledLoad {
//!     load: Load::Traction { faces: top.faces, traction: Vec3::new(0.0, 0.0, -100.0) },
//!     curve: Some(Curve::new(vec![(0.0, 0.0), (1.0, 1.0)])?),
//! };
//!
//! // A floor 1 mm below the bar.
//! let floor = Obstacle::fixed(Shape::HalfSpace {
//!     point: Vec3::new(0.0, 0.0, -0.001),
//!     normal: Vec3::z(),
//! });
//!
//! let problem = Problem::builder(mesh)
//!     .method(Method::MixedP1)
//!     .material(Material::from_young_poisson(5e4, 0.49, 1070.0)?)
//!     .region("stiff", stiff, yeoh)
//!     .clamp(left)
//!     .dirichlet(pull)
//!     .load(press)
//!     .obstacle(floor)
//!     .build()?;
//! let mut simulation = Simulation::new(problem, Settings::default())?;
//! let summary = simulation.run(Stepping::quasi_static(2), |_| {})?;
//! let end = summary.final_state.positions[x.len() - 1]; // the corner (4, 1, 1) cm
//! assert!((end.x - 0.042).abs() < 1e-12);
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```
//!
//! Re-exports: the mesh types a [`Problem`] holds and a [`State`] is read on
//! ([`ElementMesh`], [`TetMesh`], [`Vec3`], [`Zones`]), [`NodalCompliance`] of a [`Material`],
//! and the [`sprs`] crate of [`Matrices`], so that stating a problem and reading its results
//! needs this crate alone. Mesh generators, readers and probes stay in `isochor-mesh`.

#![deny(missing_docs)]

mod assembly;
pub mod contact;
mod error;
pub mod linear;
mod model;
mod nonlinear;
mod problem;
mod settings;
mod simulation;
pub mod terms;

pub use assembly::{HessianBlock, NodePattern};
pub use error::SolverError;
/// How [`Material::nodal_compliance`] integrates the nodal compliance (re-exported so that a
/// `Material` can be written without depending on `isochor-constraints`).
pub use isochor_constraints::NodalCompliance;
/// The mesh types a [`Problem`] holds and a [`State`] is read on.
pub use isochor_mesh::{ElementMesh, TetMesh, Vec3, Zones};
pub use model::dofs::Dofs;
pub use model::pressure_gauges::PressureReading;
pub use model::regions::Regions;
pub use nonlinear::report::{IterationReport, StepReport, Timings};
pub use problem::builder::ProblemBuilder;
pub use problem::cloth::ClothSheet;
pub use problem::friction::{FrictionSpec, SurfaceFrictionSpec};
pub use problem::loads::{Dirichlet, Load, Motion, ScheduledLoad};
pub use problem::material::{Epidermis, Kappa, Material, ZonalEnergy};
pub use problem::material_model::{
    Constant, ConstantError, ConstantKind, ConstantValue, DensityForm, MaterialModel, ModelInfo,
};
pub use problem::mesh_obstacle::{AxisRotation, MeshObstacle};
pub use problem::method::Method;
pub use problem::obstacle::{Obstacle, Shape};
pub use problem::schedule::{Curve, LoadLevel};
pub use problem::{Problem, Region};
pub use settings::{
    IterativeSettings, Jacobian, LinearSolver, PreconditionerKind, Settings, VolumeProjection,
    AUTO_DIRECT_UNKNOWNS,
};
pub use simulation::{
    Adaptive, Checkpoint, Energies, Frame, Linearizer, Matrices, NewtonSystem, Progress,
    RunSummary, Simulation, SimulationFailure, State, StepControl, Stepping, MIN_INCREMENT_FLOOR,
};
/// The sparse matrix crate of [`Matrices`] and [`isochor_constraints::SparseMatrix`].
pub use sprs;
pub use terms::{ContactSummary, SurfaceContactSpec, SurfaceContactSummary};
