//! What `--out DIR` writes: VTU frames and a `.pvd` collection, `summary.json`, CSV logs,
//! PNG plots and `preview.png`, a picture of the final deformed body (see [`write_preview`];
//! for a run that failed, its last accepted state). Everything goes to a temporary folder
//! next to `DIR` that replaces `DIR` only when the run's outputs are complete and synced, so
//! an error leaves no partial output ([`OutputDir`]); a marker file says the folder is
//! isochor's, and a lock keeps a second run out of it.

mod atomic;
mod csv;
mod frames;
mod lock;
mod marker;
mod obstacle_shapes;
mod plots;
mod potential;
mod preview;

pub use atomic::{write_file, OutputDir, CHECKPOINT_FILE};
pub use csv::{write_iterations_csv, write_probes_csv, write_steps_csv};
pub use frames::{FrameFields, FrameWriter};
pub use marker::{OutputIdentity, MARKER_FILE};
pub use obstacle_shapes::obstacle_triangles;
pub(crate) use plots::{draw_legend, finish_plot, plot_error, range, register_font, tick};
pub use plots::{plot_energy, plot_pressure_volume, plot_residuals};
pub use potential::{minimum, plot_potential, potential_series, write_potential_csv};
pub use preview::{write_preview, PreviewOptions};

use crate::error::SceneError;
use crate::record::{RunResult, StepRecord};
use std::path::Path;

/// Writes `summary.json`, the CSV logs and (if `plots`) the PNG plots of a finished run into
/// `dir` (the temporary output folder), with the potential energy against the probe
/// `potential_against` if one is named. The iteration log and the residual plot include the
/// failed step of a run that failed.
pub fn write_run_outputs(
    dir: &Path,
    result: &RunResult,
    plots: bool,
    potential_against: Option<&str>,
) -> Result<(), SceneError> {
    let json = serde_json::to_string_pretty(&result.to_json())
        .map_err(|e| SceneError::Output(e.to_string()))?;
    write_file(&dir.join("summary.json"), json.as_bytes())?;
    let attempted: Vec<StepRecord> = result
        .history
        .iter()
        .chain(&result.failed)
        .cloned()
        .collect();
    write_iterations_csv(&dir.join("iterations.csv"), &attempted)?;
    write_steps_csv(
        &dir.join("steps.csv"),
        &result.history,
        &result.obstacles,
        &result.body_pairs,
    )?;
    write_probes_csv(&dir.join("probes.csv"), &result.history, result.dynamic)?;
    if plots {
        let title = run_title(result);
        plot_residuals(&dir.join("residuals.png"), &title, &attempted)?;
        plot_pressure_volume(&dir.join("pressure-volume.png"), &title, &result.history)?;
        if result.dynamic {
            plot_energy(&dir.join("energy.png"), &title, &result.history)?;
        }
    }
    if let Some(probe) = potential_against {
        write_potential_csv(&dir.join("potential.csv"), probe, &result.history)?;
        if plots {
            let label = result.variant.clone().unwrap_or(result.method.clone());
            let series = [(label, potential_series(&result.history))];
            plot_potential(
                &dir.join("potential.png"),
                &run_title(result),
                probe,
                &series,
            )?;
        }
    }
    Ok(())
}

/// The title of a run's pictures: scene and variant, method and element, and the step at
/// which it failed.
pub fn run_title(result: &RunResult) -> String {
    let scene = match &result.variant {
        Some(v) => format!("{} {v}", result.scene),
        None => result.scene.clone(),
    };
    let mut title = format!("{scene} ({}, {})", result.method, result.element);
    if result.error.is_some() {
        title += &match result.failed_step {
            Some(step) => format!(", failed at step {step}"),
            None => ", failed".to_string(),
        };
    }
    title
}
