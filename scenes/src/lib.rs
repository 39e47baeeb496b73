//! # isochor-scenes
//!
//! The top layer of isochor: the TOML scene format, the built-in scene library (reproducing
//! the experiments of Francu et al. 2021 and Sheen et al. 2021), resolving a scene into the
//! solver's problem, probes, output writers and the commands of the `isochor` program.
//!
//! ## Layers
//!
//! Each layer imports only the layers below it (and the crates below this one), never one
//! above, and no two modules import each other:
//!
//! 1. [`error`](SceneError) and [`record`]: the errors, and the records of a run
//!    ([`RunResult`], [`StepRecord`]), which outputs and commands both read.
//! 2. [`format`](mod@format): the scene format, one file per section, the names, `--set` overrides,
//!    limits, loading built-in and file scenes, and every check before a run.
//! 3. [`resolve`]: scene -> [`resolve::Built`], once: the mesh and its groups, every named
//!    selection as node/vertex/face/tet sets, the regions, the zones, the solver's problem.
//! 4. [`probes`] and [`output`] (side by side, neither imports the other): named values
//!    measured on a resolved scene's states; frames, CSV, summary, plots, preview and the
//!    atomic output folder.
//! 5. [`commands`]: run, resume, check, compare, study and penalties.
//! 6. [`cli`] (and the `isochor` binary on top).
//!
//! Data flows one way: scene text -> [`Scene`] -> [`resolve::Built`] -> solver -> frames and
//! a [`RunResult`].

#![deny(missing_docs)]

pub mod cli;
pub mod commands;
mod error;
pub mod format;
pub mod output;
pub mod probes;
pub mod record;
pub mod resolve;

pub use commands::run::{resume_run, run_named, run_scene, RunOptions};
pub use error::SceneError;
pub use format::{builtin, load_scene, Override, Scene, SceneSource};
pub use record::{ContactRecord, RunResult, StepRecord};
