//! Running a scene (`isochor run`, `isochor resume`): resolve it, drive
//! [`isochor_solvers::Simulation`], record every step, evaluate the probes and write the
//! outputs. The only module that touches the solver's stepping API.
//!
//! Inside: `options`, `records` and `body` at the bottom, then `checkpoint`, `observer`
//! (after every step), `finish` (after the last), `execute` (the steps in order), and this
//! module and `resume` on top.

mod body;
pub mod checkpoint;
mod execute;
mod finish;
mod observer;
mod options;
mod records;
mod resume;
mod verify;

pub use options::{RunOptions, StepFn, StepHook};
pub use resume::resume_run;

use crate::error::SceneError;
use crate::format::{load_scene, Override, Scene};
use crate::output::{OutputDir, OutputIdentity};
use crate::record::RunResult;
use std::path::{Path, PathBuf};

/// Runs a scene. A solver failure is not an error: the result says `converged: false` with
/// the error and the failed step, and the outputs hold every accepted step. Errors are for
/// scenes that cannot be built and outputs that cannot be written; they leave no output
/// (but a checkpointed run keeps its unfinished folder, to be resumed).
pub fn run_scene(
    scene: &Scene,
    options: &RunOptions,
) -> Result<(RunResult, Option<PathBuf>), SceneError> {
    if options.checkpoint_every.is_some() && options.out.is_none() {
        return Err(SceneError::Output(
            "--checkpoint-every needs --out DIR (the checkpoint is kept there)".into(),
        ));
    }
    if options.checkpoint_every == Some(0) {
        return Err(SceneError::Output(
            "--checkpoint-every must be at least 1".into(),
        ));
    }
    let out = options
        .out
        .as_deref()
        .map(|d| OutputDir::prepare(d, OutputIdentity::new("run", &scene.name)))
        .transpose()?;
    let ran = execute::execute(scene, options, out, None)?;
    for warning in &ran.0.warnings {
        eprintln!("warning: {warning}");
    }
    Ok(ran)
}

/// Runs a scene by name or path with a variant and `--set` overrides (the library entry of
/// `isochor run`).
pub fn run_named(
    spec: &str,
    variant: Option<&str>,
    overrides: &[Override],
    out: Option<&Path>,
    progress: bool,
    checkpoint_every: Option<usize>,
) -> Result<(RunResult, Option<PathBuf>), SceneError> {
    let scene = load_scene(spec, variant, overrides)?;
    run_scene(
        &scene,
        &RunOptions {
            out: out.map(Path::to_path_buf),
            progress,
            variant: variant.map(str::to_string),
            overrides: options::recorded(overrides),
            checkpoint_every,
            on_step: None,
            preview: None,
        },
    )
}
