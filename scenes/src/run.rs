//! Running a scene: build the problem, drive [`isochor_solvers::Simulation`], record every
//! step, evaluate the probes and write the outputs. The only module that touches the solver's
//! stepping API.

use crate::output::{write_run_outputs, FrameWriter, OutputDir};
use crate::probes::{self, ProbeInput};
use crate::result::{ContactRecord, RunResult, StepRecord};
use crate::scene::Scene;
use crate::{problem, SceneError};
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use isochor_solvers::{Energies, Frame, Simulation, State, StepReport};
use std::io::IsTerminal;
use std::path::{Path, PathBuf};
use std::time::Instant;

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
}

/// Runs a scene. A solver failure is not an error: the result says `converged: false` with
/// the error and the failed step, and the outputs hold every accepted step. Errors are for
/// scenes that cannot be built and outputs that cannot be written; they leave no output.
pub fn run_scene(
    scene: &Scene,
    options: &RunOptions,
) -> Result<(RunResult, Option<PathBuf>), SceneError> {
    let out = options.out.as_deref().map(OutputDir::create).transpose()?;
    let built = problem::build(scene)?;
    let mesh = built.problem.mesh.clone();
    let material = built.problem.material;
    let kappa = material.mixed_kappa().ok();
    let zone_ids = match &built.problem.zones {
        Some(z) => Some(z.tet_zone_ids(mesh.num_elements())?),
        None => None,
    };
    // Probes are checked on the rest state first, so that a bad probe fails before the run.
    let zeros = vec![0.0; mesh.num_elements()];
    probes::evaluate(
        scene,
        &ProbeInput {
            mesh: &mesh,
            positions: mesh.nodes(),
            tet_pressures: &zeros,
            constraint_residual: 0.0,
            energies: Energies::default(),
            kappa,
            history: &[],
        },
    )?;

    let total = scene.num_steps();
    let mut sim = Simulation::new(built.problem, built.settings)?;
    let dofs = sim.num_dofs();
    let mut frames = match (&out, scene.output.vtu) {
        (Some(dir), true) => {
            let mut w = FrameWriter::new(dir.path(), "frame", scene.output.every, zone_ids);
            w.write(&mesh, 0, 0.0, mesh.nodes(), &zeros, &[])?;
            Some(w)
        }
        _ => None,
    };
    let bar = progress_bar(options.progress, total, &scene.name);

    let mut history: Vec<StepRecord> = Vec::new();
    let mut last_pressures: Vec<f64> = Vec::new();
    let mut last_energies = Energies::default();
    let mut write_error: Option<SceneError> = None;
    let start = Instant::now();
    let outcome = sim.run(built.stepping, |frame: &Frame<'_>| {
        history.push(record(
            &mesh,
            frame.state,
            frame.report,
            frame.inverted_tets,
            frame.energies,
        ));
        last_pressures.clone_from(&frame.tet_pressures);
        last_energies = frame.energies;
        if let (Some(w), None) = (frames.as_mut(), write_error.as_ref()) {
            if w.wants(frame.index, total) {
                let x = &frame.state.positions;
                let p = &frame.tet_pressures;
                let f = &frame.contact_forces;
                if let Err(e) = w.write(&mesh, frame.index, frame.state.t, x, p, f) {
                    write_error = Some(e);
                }
            }
        }
        bar.set_position(frame.index as u64);
        bar.set_message(format!(
            "{} Newton iterations",
            frame.report.newton_iterations()
        ));
    });
    let elapsed = start.elapsed();
    bar.finish_and_clear();
    if let Some(e) = write_error {
        return Err(e);
    }

    let (final_state, reports, wall_time, max_inverted, error, failed_step): (
        State,
        Vec<StepReport>,
        _,
        _,
        _,
        _,
    ) = match outcome {
        Ok(summary) => (
            summary.final_state,
            summary.reports,
            summary.wall_time,
            summary.max_inverted_tets,
            None,
            None,
        ),
        Err(failure) => {
            let max_inverted = history.iter().map(|s| s.inverted_tets).max().unwrap_or(0);
            (
                failure.last_state,
                failure.reports,
                elapsed,
                max_inverted,
                Some(failure.error.to_string()),
                Some(failure.failed_step),
            )
        }
    };
    let failed = failed_step.and(reports.last()).map(|report| {
        let inverted = history.last().map_or(0, |s| s.inverted_tets);
        record(&mesh, &final_state, report, inverted, last_energies)
    });
    let constraint_residual = reports.last().map_or(0.0, |r| r.constraint_residual);
    let input = ProbeInput {
        mesh: &mesh,
        positions: &final_state.positions,
        tet_pressures: &last_pressures,
        constraint_residual,
        energies: last_energies,
        kappa,
        history: &history,
    };
    let probes = match probes::evaluate(scene, &input) {
        Ok(p) => p,
        Err(e) if error.is_some() => {
            // After a failure there may be no accepted state to measure: report what can be.
            let _ = e;
            scene.probes.keys().map(|k| (k.clone(), f64::NAN)).collect()
        }
        Err(e) => return Err(e),
    };
    let result = RunResult {
        scene: scene.name.clone(),
        variant: options.variant.clone(),
        method: scene.method().name().to_string(),
        element: scene.element().name().to_string(),
        nu: scene.material.nu,
        vertices: mesh.num_vertices(),
        nodes: mesh.num_nodes(),
        tets: mesh.num_elements(),
        dofs,
        steps: history.len(),
        steps_requested: total,
        newton_iterations: reports.iter().map(|r| r.newton_iterations()).sum(),
        converged: error.is_none() && reports.iter().all(|r| r.converged),
        wall_time_s: wall_time.as_secs_f64(),
        volume_change: mesh.total_volume_at(&final_state.positions) / mesh.rest_volume() - 1.0,
        probes,
        max_inverted_tets: max_inverted,
        constraint_residual,
        error,
        failed_step,
        overrides: options.overrides.clone(),
        history,
        failed,
        dynamic: scene.is_dynamic(),
    };
    let written = match out {
        Some(dir) => {
            if let Some(w) = &frames {
                w.finish()?;
            }
            write_run_outputs(dir.path(), &result, scene.output.plots)?;
            Some(dir.commit()?)
        }
        None => None,
    };
    Ok((result, written))
}

/// The record of one step: its iterations and the state it ended in.
fn record(
    mesh: &isochor_mesh::ElementMesh,
    state: &State,
    report: &StepReport,
    inverted_tets: usize,
    energies: Energies,
) -> StepRecord {
    let mut force: Vec<f64> = report.iterations.iter().map(|i| i.force_residual).collect();
    let mut constraint: Vec<f64> = report
        .iterations
        .iter()
        .map(|i| i.constraint_residual)
        .collect();
    force.push(report.force_residual);
    constraint.push(report.constraint_residual);
    StepRecord {
        step: report.step,
        t: report.t,
        newton_iterations: report.newton_iterations(),
        converged: report.converged,
        force_residuals: force,
        constraint_residuals: constraint,
        step_lengths: report.iterations.iter().map(|i| i.step_length).collect(),
        backtracks: report.iterations.iter().map(|i| i.backtracks).collect(),
        shifts: report.iterations.iter().map(|i| i.regularization).collect(),
        volume_change: mesh.total_volume_at(&state.positions) / mesh.rest_volume() - 1.0,
        inverted_tets,
        kinetic_energy: energies.kinetic,
        elastic_energy: energies.elastic,
        external_energy: energies.external,
        wall_time_s: report.wall_time.as_secs_f64(),
        contact: ContactRecord {
            force: report.contact.force.into(),
            active_vertices: report.contact.active_vertices,
            max_penetration: report.contact.max_penetration,
            iterations: report.contact_iterations,
        },
    }
}

fn progress_bar(wanted: bool, total: usize, name: &str) -> ProgressBar {
    if !(wanted && std::io::stderr().is_terminal()) {
        return ProgressBar::hidden();
    }
    let bar = ProgressBar::with_draw_target(Some(total as u64), ProgressDrawTarget::stderr());
    if let Ok(style) =
        ProgressStyle::with_template("{prefix} [{bar:30}] {pos}/{len} steps, {elapsed} ({msg})")
    {
        bar.set_style(style.progress_chars("=> "));
    }
    bar.set_prefix(name.to_string());
    bar
}

/// Runs a scene by name or path with a variant and `--set` overrides (the library entry of
/// `isochor run`).
pub fn run_named(
    spec: &str,
    variant: Option<&str>,
    overrides: &[crate::Override],
    out: Option<&Path>,
    progress: bool,
) -> Result<(RunResult, Option<PathBuf>), SceneError> {
    let scene = crate::load_scene(spec, variant, overrides)?;
    run_scene(
        &scene,
        &RunOptions {
            out: out.map(Path::to_path_buf),
            progress,
            variant: variant.map(str::to_string),
            overrides: overrides
                .iter()
                .map(|o| format!("{}={}", o.key, o.display_value()))
                .collect(),
        },
    )
}
