//! Checkpoints: what `isochor resume DIR` needs to finish an interrupted run exactly as the
//! uninterrupted run would have: the scene as it ran (after variant and overrides), the
//! solver's state and progress, and the records of the steps so far. Written as TOML
//! (floats in shortest round-trip form, so the state is restored bit for bit, and NaN or
//! infinite values survive) into the run's output folder, atomically: a new file renamed
//! over the old one.

use super::options::RunOptions;
use crate::error::SceneError;
use crate::format::Scene;
use crate::output::CHECKPOINT_FILE;
use crate::record::StepRecord;
use isochor_mesh::Vec3;
use isochor_solvers::{Checkpoint, Progress, State};
use serde::{Deserialize, Serialize};
use std::io::Write;
use std::path::Path;

/// The format version; a checkpoint of another version is refused.
const VERSION: u32 = 1;

/// A run's checkpoint.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct RunCheckpoint {
    /// Format version.
    pub version: u32,
    /// The scene as it ran.
    pub scene: Scene,
    /// The variant's name, if any (recorded in the result).
    pub variant: Option<String>,
    /// The overrides applied, as `KEY=VALUE` (recorded in the result).
    pub overrides: Vec<String>,
    /// Accepted steps between checkpoints.
    pub every: usize,
    /// Whether the run had finished when this was written.
    pub finished: bool,
    /// The solver's state and progress.
    pub solver: SolverCheckpoint,
    /// Records of the accepted steps so far.
    pub history: Vec<StepRecord>,
    /// The frames written so far: time or load parameter, file name.
    pub frames: Vec<(f64, String)>,
    /// Wall time of the run so far, in seconds.
    pub wall_time_s: f64,
}

/// [`Checkpoint`] in serializable form.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct SolverCheckpoint {
    /// Positions.
    pub positions: Vec<[f64; 3]>,
    /// Velocities.
    pub velocities: Vec<[f64; 3]>,
    /// Pressures or multipliers.
    pub multipliers: Vec<f64>,
    /// Load parameter or time of the state.
    pub t: f64,
    /// The stepping's load parameter or time reached.
    pub progress_t: f64,
    /// Accepted steps so far.
    pub steps: usize,
    /// Levels reached so far.
    pub levels: usize,
    /// The next increment to try.
    pub increment: f64,
    /// The contact multipliers (empty without obstacles).
    pub contact_multipliers: Vec<f64>,
}

impl From<&Checkpoint> for SolverCheckpoint {
    fn from(c: &Checkpoint) -> Self {
        let arrays = |v: &[Vec3]| v.iter().map(|p| [p.x, p.y, p.z]).collect();
        SolverCheckpoint {
            positions: arrays(&c.state.positions),
            velocities: arrays(&c.state.velocities),
            multipliers: c.state.multipliers.clone(),
            t: c.state.t,
            progress_t: c.progress.t,
            steps: c.progress.steps,
            levels: c.progress.levels,
            increment: c.progress.increment,
            contact_multipliers: c.contact_multipliers.clone(),
        }
    }
}

impl From<&SolverCheckpoint> for Checkpoint {
    fn from(c: &SolverCheckpoint) -> Self {
        let vectors = |v: &[[f64; 3]]| v.iter().map(|p| Vec3::new(p[0], p[1], p[2])).collect();
        Checkpoint {
            state: State {
                positions: vectors(&c.positions),
                velocities: vectors(&c.velocities),
                multipliers: c.multipliers.clone(),
                t: c.t,
            },
            progress: Progress {
                t: c.progress_t,
                steps: c.steps,
                levels: c.levels,
                increment: c.increment,
            },
            contact_multipliers: c.contact_multipliers.clone(),
        }
    }
}

impl RunCheckpoint {
    /// A checkpoint of the current format of a run of `scene` with `options` (which must ask
    /// for checkpoints).
    pub fn new(
        scene: &Scene,
        options: &RunOptions,
        finished: bool,
        solver: &Checkpoint,
        history: Vec<StepRecord>,
        frames: Vec<(f64, String)>,
        wall_time_s: f64,
    ) -> Self {
        RunCheckpoint {
            version: VERSION,
            scene: scene.clone(),
            variant: options.variant.clone(),
            overrides: options.overrides.clone(),
            every: options.checkpoint_every.unwrap_or(1),
            finished,
            solver: solver.into(),
            history,
            frames,
            wall_time_s,
        }
    }

    /// Writes the checkpoint into `dir`, replacing the previous one atomically.
    pub fn write(&self, dir: &Path) -> Result<(), SceneError> {
        let text = toml::to_string(self).map_err(|e| SceneError::Output(e.to_string()))?;
        let temp = dir.join(format!("{CHECKPOINT_FILE}.new"));
        write_synced(&temp, text.as_bytes())?;
        let path = dir.join(CHECKPOINT_FILE);
        std::fs::rename(&temp, &path).map_err(|e| SceneError::io(&path, e))
    }

    /// Reads the checkpoint of `dir`.
    pub fn read(dir: &Path) -> Result<Self, SceneError> {
        let path = dir.join(CHECKPOINT_FILE);
        let text = std::fs::read_to_string(&path).map_err(|e| SceneError::io(&path, e))?;
        let checkpoint: RunCheckpoint = toml::from_str(&text).map_err(|e| SceneError::Invalid {
            origin: path.display().to_string(),
            key: String::new(),
            message: format!("not a readable checkpoint: {e}"),
        })?;
        if checkpoint.version != VERSION {
            return Err(SceneError::Invalid {
                origin: path.display().to_string(),
                key: "version".into(),
                message: format!(
                    "checkpoint format {} (this program reads format {VERSION})",
                    checkpoint.version
                ),
            });
        }
        checkpoint.check(&path.display().to_string())?;
        Ok(checkpoint)
    }
}

/// Writes a whole file and fsyncs it, so the rename that follows never exposes an empty one.
fn write_synced(path: &Path, bytes: &[u8]) -> Result<(), SceneError> {
    std::fs::File::create(path)
        .and_then(|mut f| f.write_all(bytes).and_then(|()| f.sync_all()))
        .map_err(|e| SceneError::io(path, e))
}
