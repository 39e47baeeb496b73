//! How a run is asked for.

use std::path::PathBuf;

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
}
