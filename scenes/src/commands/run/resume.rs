//! `isochor resume DIR`: an interrupted run continued from its last checkpoint.

use super::checkpoint::RunCheckpoint;
use super::execute::execute;
use super::options::RunOptions;
use crate::error::SceneError;
use crate::output::OutputDir;
use crate::record::RunResult;
use std::path::{Path, PathBuf};

/// Continues the interrupted run whose output folder is `dir` (`isochor resume DIR`) from its
/// last checkpoint; the results equal the uninterrupted run's bit for bit.
pub fn resume_run(dir: &Path, progress: bool) -> Result<(RunResult, Option<PathBuf>), SceneError> {
    let out = OutputDir::reopen(dir)?;
    let checkpoint = RunCheckpoint::read(out.path())?;
    if checkpoint.finished {
        return Err(SceneError::Output(format!(
            "the run in {} has already finished",
            dir.display()
        )));
    }
    let options = RunOptions {
        out: Some(dir.to_path_buf()),
        progress,
        variant: checkpoint.variant.clone(),
        overrides: checkpoint.overrides.clone(),
        checkpoint_every: Some(checkpoint.every),
        on_step: None,
        preview: None,
    };
    let scene = checkpoint.scene.clone();
    execute(&scene, &options, Some(out), Some(checkpoint))
}
