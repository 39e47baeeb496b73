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
//! 3. [`resolve`]: scene -> [`resolve::ResolvedScene`], once: the mesh and its groups, every named
//!    selection as node/vertex/face/tet sets, the regions, the zones, the solver's problem.
//! 4. [`probes`] and [`output`] (side by side, neither imports the other): named values
//!    measured on a resolved scene's states; frames, CSV, summary, plots, preview and the
//!    atomic output folder.
//! 5. [`commands`]: run, resume, check, compare, study and penalties.
//! 6. [`cli`] (and the `isochor` binary on top).
//!
//! Data flows one way: scene text -> [`Scene`] -> [`resolve::ResolvedScene`] -> solver -> frames and
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
pub use record::{ContactRecord, Iterations, RunResult, RunTimings, StepRecord};

// The module paths of isochor-scenes 0.1 before the crate was split by layer, kept for one
// release so that code written against them still builds (with a deprecation warning).

/// Moved to [`format`](mod@format).
#[deprecated(note = "moved to `isochor_scenes::format`")]
pub mod scene {
    pub use crate::format::*;
}
/// Moved to [`resolve`].
#[deprecated(note = "moved to `isochor_scenes::resolve` (`Built` is `ResolvedScene`)")]
pub mod problem {
    pub use crate::resolve::ResolvedScene as Built;
    pub use crate::resolve::*;
}
/// Moved to [`resolve::selections`].
#[deprecated(note = "moved to `isochor_scenes::resolve::selections`")]
pub mod selection {
    pub use crate::resolve::selections::*;
}
/// Moved to [`record`].
#[deprecated(note = "moved to `isochor_scenes::record`")]
pub mod result {
    pub use crate::record::*;
}
/// Moved to [`commands::run`].
#[deprecated(note = "moved to `isochor_scenes::commands::run`")]
pub mod run {
    pub use crate::commands::run::*;
}
/// Moved to [`commands::run::checkpoint`].
#[deprecated(note = "moved to `isochor_scenes::commands::run::checkpoint`")]
pub mod checkpoint {
    pub use crate::commands::run::checkpoint::*;
    pub use crate::output::CHECKPOINT_FILE;
}
/// Moved to [`commands::check`].
#[deprecated(note = "moved to `isochor_scenes::commands::check`")]
pub mod check {
    pub use crate::commands::check::*;
}
/// Moved to [`commands::compare`].
#[deprecated(note = "moved to `isochor_scenes::commands::compare` (`Config` is `Variant`)")]
pub mod compare {
    pub use crate::commands::compare::Variant as Config;
    pub use crate::commands::compare::*;
}
/// Moved to [`commands::study`].
#[deprecated(note = "moved to `isochor_scenes::commands::study`")]
pub mod study {
    pub use crate::commands::study::*;
}
/// Moved to [`commands::penalties`].
#[deprecated(note = "moved to `isochor_scenes::commands::penalties`")]
pub mod penalty_plot {
    pub use crate::commands::penalties::*;
}
/// Moved to [`format::limits`].
#[deprecated(note = "moved to `isochor_scenes::format::limits`")]
pub mod limits {
    pub use crate::format::limits::*;
}
/// Moved to [`format::overrides`].
#[deprecated(note = "moved to `isochor_scenes::format::overrides`")]
pub mod overrides {
    pub use crate::format::overrides::*;
}
/// Moved to [`format::load`].
#[deprecated(note = "moved to `isochor_scenes::format::load`")]
pub mod load {
    pub use crate::format::load::*;
}
/// Moved to [`format`](mod@format) (`PaperSpec`).
#[deprecated(note = "moved to `isochor_scenes::format::PaperSpec`")]
pub mod paper {
    pub use crate::format::PaperSpec;
}
