//! Running a scene: build the problem, drive [`isochor_solvers::Simulation`], record every
//! step, evaluate the probes and write the outputs. The only module that touches the solver's
//! stepping API.

use crate::checkpoint::RunCheckpoint;
use crate::output::{
    run_title, write_preview, write_run_outputs, FrameFields, FrameWriter, OutputDir,
    PreviewOptions,
};
use crate::probes::{self, ProbeInput};
use crate::result::{ContactRecord, CutRecord, RunResult, StepRecord};
use crate::scene::Scene;
use crate::selection::Selections;
use crate::{problem, SceneError};
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use isochor_solvers::{Energies, Frame, IterationReport, Simulation, State, StepReport};
use nalgebra::Matrix3;
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
    /// Write a checkpoint into the output folder every this many accepted steps (and at the
    /// end), so that an interrupted run can be resumed (needs `out`).
    pub checkpoint_every: Option<usize>,
}

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
    let out = options.out.as_deref().map(OutputDir::create).transpose()?;
    execute(scene, options, out, None)
}

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
    };
    let scene = checkpoint.scene.clone();
    execute(&scene, &options, Some(out), Some(checkpoint))
}

/// Runs `scene` into `out`, from the start or from `resume`.
fn execute(
    scene: &Scene,
    options: &RunOptions,
    out: Option<OutputDir>,
    resume: Option<RunCheckpoint>,
) -> Result<(RunResult, Option<PathBuf>), SceneError> {
    let built = problem::build(scene)?;
    let mesh = built.problem.mesh.clone();
    let material = &built.problem.material;
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
    let stepping = built.stepping;
    let dynamic = scene.is_dynamic();
    let mut sim = Simulation::new(built.problem, built.settings)?;
    let dofs = sim.num_dofs();
    let mut frames = match (&out, scene.output.vtu) {
        (Some(dir), true) => {
            let encoding = scene.output.vtu_encoding.resolve(mesh.num_nodes());
            let region_ids = sim
                .regions()
                .element_regions()
                .iter()
                .map(|&r| r as i32)
                .collect();
            let mut w = FrameWriter::new(
                dir.path(),
                "frame",
                scene.output.every,
                encoding,
                zone_ids,
                region_ids,
            );
            w.write(&mesh, 0, 0.0, &FrameFields::rest(&mesh))?;
            Some(w)
        }
        _ => None,
    };
    let mut history: Vec<StepRecord> = Vec::new();
    let mut earlier_wall_time = 0.0;
    if let Some(checkpoint) = resume {
        sim.restore((&checkpoint.solver).into())?;
        history = checkpoint.history;
        earlier_wall_time = checkpoint.wall_time_s;
        if let Some(w) = frames.as_mut() {
            w.continue_after(checkpoint.frames);
        }
    }
    let bar = progress_bar(options.progress, total, &scene.name);
    let mut last_pressures: Vec<f64> = Vec::new();
    let mut last_stress: Vec<Matrix3<f64>> = Vec::new();
    let mut last_von_mises: Vec<f64> = Vec::new();
    let mut last_energies = Energies::default();
    let mut write_error: Option<SceneError> = None;
    let mut last_solver = None;
    // The selections of the probe tracked per step, built once (not per step).
    let tracked = match &scene.output.potential_against {
        Some(name) => Some((
            name,
            Selections::new(&mesh, &scene.mesh, &scene.selections)?,
        )),
        None => None,
    };
    let start = Instant::now();
    let outcome = sim.run(stepping, |frame: &Frame<'_>| {
        let mut step = record(
            &mesh,
            frame.state,
            frame.report,
            frame.inverted_tets,
            frame.energies,
        );
        step.cuts = frame.cuts.iter().map(cut_record).collect();
        if let Some((name, selections)) = &tracked {
            let input = ProbeInput {
                mesh: &mesh,
                positions: &frame.state.positions,
                tet_pressures: &frame.tet_pressures,
                constraint_residual: frame.report.constraint_residual,
                energies: frame.energies,
                kappa,
                history: &history,
            };
            match probes::evaluate_one(scene, name, &input, selections) {
                Ok(v) => step.tracked_probe = Some(v),
                Err(e) => write_error = write_error.take().or(Some(e)),
            }
        }
        history.push(step);
        last_pressures.clone_from(&frame.tet_pressures);
        last_stress.clone_from(&frame.stress);
        last_von_mises.clone_from(&frame.von_mises);
        last_energies = frame.energies;
        if write_error.is_some() {
            return;
        }
        if let Some(w) = frames.as_mut() {
            if let Some(index) = frame.frame.filter(|&k| w.wants(k, total)) {
                let fields = FrameFields {
                    positions: &frame.state.positions,
                    velocities: if dynamic {
                        &frame.state.velocities
                    } else {
                        &[]
                    },
                    von_mises: &frame.von_mises,
                    stress: &frame.stress,
                    nodal_pressures: frame.nodal_pressures.as_deref().unwrap_or_default(),
                    contact_forces: &frame.contact_forces,
                };
                if let Err(e) = w.write(&mesh, index, frame.state.t, &fields) {
                    write_error = Some(e);
                }
            }
        }
        if let (Some(every), Some(dir)) = (options.checkpoint_every, out.as_ref()) {
            let solver = frame.checkpoint();
            if frame.progress.steps % every == 0 {
                let checkpoint = RunCheckpoint::new(
                    scene,
                    options,
                    false,
                    &solver,
                    history.clone(),
                    frames
                        .as_ref()
                        .map(|w| w.entries().to_vec())
                        .unwrap_or_default(),
                    earlier_wall_time + start.elapsed().as_secs_f64(),
                );
                if let Err(e) = checkpoint.write(dir.path()) {
                    write_error = Some(e);
                }
            }
            last_solver = Some(solver);
        }
        bar.set_position(frame.progress.levels as u64);
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

    let (final_state, reports, max_inverted, error, failed_step): (
        State,
        Vec<StepReport>,
        _,
        _,
        _,
    ) = match outcome {
        Ok(summary) => (
            summary.final_state,
            summary.reports,
            summary.max_inverted_tets,
            None,
            None,
        ),
        Err(failure) => (
            failure.last_state,
            failure.reports,
            0,
            Some(failure.error.to_string()),
            Some(failure.failed_step),
        ),
    };
    let max_inverted = history
        .iter()
        .map(|s| s.inverted_tets)
        .max()
        .unwrap_or(0)
        .max(max_inverted);
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
    // Iterations of every attempt: the accepted steps', their cut attempts', the failed one's.
    let attempts = |s: &StepRecord| {
        s.newton_iterations
            + s.cuts
                .iter()
                .map(|c| c.force_residuals.len() - 1)
                .sum::<usize>()
    };
    let cuts = history.iter().map(|s| s.cuts.len()).sum();
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
        newton_iterations: history.iter().chain(&failed).map(attempts).sum(),
        converged: error.is_none() && history.iter().all(|r| r.converged),
        cuts,
        wall_time_s: earlier_wall_time + elapsed.as_secs_f64(),
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
            if let Some(solver) = &last_solver {
                RunCheckpoint::new(
                    scene,
                    options,
                    result.error.is_none(),
                    solver,
                    result.history.clone(),
                    frames
                        .as_ref()
                        .map(|w| w.entries().to_vec())
                        .unwrap_or_default(),
                    result.wall_time_s,
                )
                .write(dir.path())?;
            }
            write_run_outputs(
                dir.path(),
                &result,
                scene.output.plots,
                scene.output.potential_against.as_deref(),
            )?;
            if scene.output.writes_preview() {
                write_preview(
                    &dir.path().join("preview.png"),
                    &mesh,
                    &FrameFields {
                        positions: &final_state.positions,
                        velocities: &[],
                        von_mises: &last_von_mises,
                        stress: &last_stress,
                        nodal_pressures: &[],
                        contact_forces: &[],
                    },
                    &PreviewOptions {
                        field: scene.output.preview_field,
                        rest_outline: scene.output.preview_rest,
                        gravity: scene.loads.gravity,
                        title: &run_title(&result),
                    },
                )?;
            }
            Some(dir.commit()?)
        }
        None => None,
    };
    Ok((result, written))
}

/// The residual histories of a step: per iteration, then the final one.
struct Residuals {
    force: Vec<f64>,
    constraint: Vec<f64>,
    volume_error: Vec<f64>,
}

impl Residuals {
    fn of(report: &StepReport) -> Self {
        let history = |each: fn(&IterationReport) -> f64, last: f64| {
            report.iterations.iter().map(each).chain([last]).collect()
        };
        Residuals {
            force: history(|i| i.force_residual, report.force_residual),
            constraint: history(|i| i.constraint_residual, report.constraint_residual),
            volume_error: history(|i| i.volume_error, report.volume_error),
        }
    }
}

/// The record of a failed attempt that was retried with a smaller increment.
fn cut_record(report: &StepReport) -> CutRecord {
    let residuals = Residuals::of(report);
    CutRecord {
        t: report.t,
        increment: report.increment,
        force_residuals: residuals.force,
        constraint_residuals: residuals.constraint,
        volume_errors: residuals.volume_error,
        error: report.failure.clone().unwrap_or_default(),
    }
}

/// The record of one step: its iterations and the state it ended in.
fn record(
    mesh: &isochor_mesh::ElementMesh,
    state: &State,
    report: &StepReport,
    inverted_tets: usize,
    energies: Energies,
) -> StepRecord {
    let residuals = Residuals::of(report);
    StepRecord {
        step: report.step,
        t: report.t,
        increment: report.increment,
        cuts: Vec::new(),
        newton_iterations: report.newton_iterations(),
        converged: report.converged,
        force_residuals: residuals.force,
        constraint_residuals: residuals.constraint,
        volume_errors: residuals.volume_error,
        step_lengths: report.iterations.iter().map(|i| i.step_length).collect(),
        backtracks: report.iterations.iter().map(|i| i.backtracks).collect(),
        shifts: report.iterations.iter().map(|i| i.regularization).collect(),
        volume_change: mesh.total_volume_at(&state.positions) / mesh.rest_volume() - 1.0,
        inverted_tets,
        kinetic_energy: energies.kinetic,
        elastic_energy: energies.elastic,
        constraint_energy: energies.constraint,
        external_energy: energies.external,
        wall_time_s: report.wall_time.as_secs_f64(),
        tracked_probe: None,
        contact: ContactRecord {
            force: report.contact.force.into(),
            obstacle_forces: report
                .contact
                .obstacle_forces
                .iter()
                .map(|&f| f.into())
                .collect(),
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
    checkpoint_every: Option<usize>,
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
            checkpoint_every,
        },
    )
}
