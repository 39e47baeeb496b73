//! # isochor-scenes
//!
//! The top layer of isochor: the TOML scene format ([`scene`]), `--set` overrides
//! ([`overrides`]), the built-in scene library ([`builtin`], reproducing the experiments of
//! Francu et al. 2021 and Sheen et al. 2021), problem construction ([`problem`]), probes
//! ([`probes`]), bounds checked before allocating ([`limits`]), output writers ([`output`]:
//! VTU frames, `summary.json`, CSV logs, PNG plots), checkpoints of long runs
//! ([`checkpoint`]), scene checks before a run ([`check`]), method comparisons ([`compare`])
//! beside published values ([`paper`]), the penalty plot of Fig. 3 of Sheen et al.
//! ([`penalty_plot`]) and the `isochor` command-line program ([`cli`]).
//!
//! Data flows one way: scene text -> [`Scene`] -> [`problem::Built`] -> solver -> frames and a
//! [`RunResult`].

#![deny(missing_docs)]

pub mod builtin;
pub mod check;
pub mod checkpoint;
mod checks;
pub mod cli;
pub mod compare;
mod error;
pub mod limits;
pub mod load;
pub mod output;
pub mod overrides;
pub mod paper;
pub mod penalty_plot;
pub mod probes;
pub mod problem;
pub mod result;
pub mod run;
pub mod scene;
pub mod selection;
pub mod study;

pub use error::SceneError;
pub use load::{load_scene, SceneSource};
pub use overrides::Override;
pub use result::{ContactRecord, RunResult, StepRecord};
pub use run::{resume_run, run_named, run_scene, RunOptions};
pub use scene::Scene;
