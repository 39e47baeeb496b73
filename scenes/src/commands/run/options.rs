//! How a run is asked for.

use crate::format::Override;
use isochor_solvers::Frame;
use std::fmt;
use std::ops::ControlFlow;
use std::path::PathBuf;
use std::sync::Arc;

/// A function a library caller gives a run, called with every accepted step after the run has
/// recorded it (to copy the step's fields out of the run, or to report its progress). Its
/// [`ControlFlow::Break`] stops the run there: the result is the run's up to that step, with
/// the error "interrupted after step N".
#[derive(Clone)]
pub struct StepHook(pub Arc<StepFn>);

/// The function of a [`StepHook`].
pub type StepFn = dyn Fn(&Frame<'_>) -> ControlFlow<()> + Send + Sync;

impl fmt::Debug for StepHook {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str("StepHook")
    }
}

/// How to run.
#[derive(Debug, Clone, Default)]
pub struct RunOptions {
    /// Output folder (`--out`), written atomically when the run ends.
    pub out: Option<PathBuf>,
    /// Show a progress bar on stderr (only if stderr is a terminal).
    pub progress: bool,
    /// The variant's name, recorded in the result.
    pub variant: Option<String>,
    /// The overrides applied, recorded in the result as `KEY=VALUE`.
    pub overrides: Vec<String>,
    /// Write a checkpoint into the output folder every this many accepted steps (and at the
    /// end), so that an interrupted run can be resumed (needs `out`).
    pub checkpoint_every: Option<usize>,
    /// Called with every accepted step (none: the command line's runs).
    pub on_step: Option<StepHook>,
    /// Where to draw the final state's preview in a run without an output folder (one run of
    /// a comparison); a run with one draws `preview.png` there.
    pub preview: Option<PathBuf>,
}

impl RunOptions {
    /// A run without an output folder or checkpoints (one run of a comparison or a study),
    /// recording `variant` and `overrides`.
    pub fn in_memory(variant: Option<String>, overrides: &[Override], progress: bool) -> Self {
        RunOptions {
            out: None,
            progress,
            variant,
            overrides: recorded(overrides),
            checkpoint_every: None,
            on_step: None,
            preview: None,
        }
    }
}

/// The overrides as a result records them: `KEY=VALUE`.
pub(super) fn recorded(overrides: &[Override]) -> Vec<String> {
    overrides
        .iter()
        .map(|o| format!("{}={}", o.key, o.display_value()))
        .collect()
}
