//! The end of a run: its result from the records and the solver's outcome, its final probes,
//! and the outputs committed.

use super::body::{Body, ProbedState};
use super::observer::meshed_obstacles;
use super::observer::Observer;
use super::options::RunOptions;
use super::records::record;
use crate::error::SceneError;
use crate::format::{validate, Scene, SteppingSpec};
use crate::output::{
    obstacle_triangles, run_title, write_preview, write_run_outputs, FrameFields, OutputDir,
    PreviewOptions,
};
use crate::probes;
use crate::record::{RunResult, RunTimings, StepRecord};
use crate::resolve::problem;
use isochor_mesh::{ElementMesh, Vec3};
use isochor_solvers::{LoadLevel, RunSummary, SimulationFailure, SolverError, State, StepReport};
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

/// What the stepping ended with.
pub(super) struct Outcome {
    /// The solver's summary, or its failure.
    pub solver: Result<RunSummary, Box<SimulationFailure>>,
    /// Unknowns of the problem.
    pub dofs: usize,
    /// Wall time of the whole run, in seconds.
    pub wall_time_s: f64,
    /// Wall time of resolving the scene and building its model, in seconds.
    pub model_s: f64,
}

/// The last state of a run and how it ended.
struct Ending {
    state: State,
    reports: Vec<StepReport>,
    max_inverted: usize,
    error: Option<String>,
    failed_step: Option<usize>,
}

impl Ending {
    fn of(outcome: Result<RunSummary, Box<SimulationFailure>>) -> Self {
        match outcome {
            Ok(summary) => Ending {
                state: summary.final_state,
                reports: summary.reports,
                max_inverted: summary.max_inverted_tets,
                error: None,
                failed_step: None,
            },
            Err(failure) => Ending {
                // An interrupted run has no failed step: it stopped between two.
                failed_step: (!matches!(failure.error, SolverError::Interrupted { .. }))
                    .then_some(failure.failed_step),
                state: failure.last_state,
                reports: failure.reports,
                max_inverted: 0,
                error: Some(failure.error.to_string()),
            },
        }
    }
}

/// Builds the result of a run, evaluates its probes on the final state and writes and
/// commits its outputs into `out`.
pub(super) fn finish(
    scene: &Scene,
    options: &RunOptions,
    body: &Body,
    mut observer: Observer<'_>,
    outcome: Outcome,
    out: Option<OutputDir>,
) -> Result<(RunResult, Option<PathBuf>), SceneError> {
    let ending = Ending::of(outcome.solver);
    let history = std::mem::take(&mut observer.history);
    let run = Run {
        scene,
        options,
        body,
        observer: &observer,
        ending: &ending,
        dofs: outcome.dofs,
        wall_time_s: outcome.wall_time_s,
        model_s: outcome.model_s,
    };
    let result = run.result(history)?;
    let Some(dir) = out else {
        if let (Some(path), true) = (&options.preview, scene.output.writes_preview()) {
            preview(scene, body, &observer, &ending.state, &result, path)?;
        }
        return Ok((result, None));
    };
    if let Some(w) = &observer.frames {
        w.finish()?;
    }
    if let Some(solver) = &observer.last_solver {
        observer
            .run_checkpoint(
                result.error.is_none(),
                solver,
                result.history.clone(),
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
        let path = dir.path().join("preview.png");
        preview(scene, body, &observer, &ending.state, &result, &path)?;
    }
    Ok((result, Some(dir.commit()?)))
}

/// Everything a run's result is made of.
struct Run<'a> {
    scene: &'a Scene,
    options: &'a RunOptions,
    body: &'a Body,
    observer: &'a Observer<'a>,
    ending: &'a Ending,
    dofs: usize,
    wall_time_s: f64,
    model_s: f64,
}

impl Run<'_> {
    /// The result of the run with the records `history`, its probes evaluated on the final
    /// state.
    fn result(&self, history: Vec<StepRecord>) -> Result<RunResult, SceneError> {
        let Run {
            scene,
            options,
            body,
            observer,
            ending,
            ..
        } = *self;
        let mesh = &body.mesh;
        let max_inverted = history
            .iter()
            .map(|s| s.inverted_tets)
            .max()
            .unwrap_or(0)
            .max(ending.max_inverted);
        let failed = ending.failed_step.and(ending.reports.last()).map(|report| {
            let inverted = history.last().map_or(0, |s| s.inverted_tets);
            record(
                mesh,
                &ending.state,
                report,
                inverted,
                observer.last_energies,
                None,
                &meshed_obstacles(scene),
            )
        });
        let constraint_residual = ending.reports.last().map_or(0.0, |r| r.constraint_residual);
        let state = ProbedState {
            positions: &ending.state.positions,
            tet_pressures: &observer.last_pressures,
            constraint_residual,
            energies: observer.last_energies,
            history: &history,
        };
        let probes = match probes::evaluate(scene, &body.probe_input(&state)) {
            Ok(p) => p,
            // After a failure there may be no accepted state to measure: report what can be.
            Err(_) if ending.error.is_some() => nan_probes(scene),
            Err(e) => return Err(e),
        };
        // Iterations of every attempt: the accepted steps', their cut attempts', the failed one's.
        let attempts = |s: &StepRecord| {
            s.newton_iterations
                + s.cuts
                    .iter()
                    .map(|c| c.iterations.force_residuals.len() - 1)
                    .sum::<usize>()
        };
        Ok(RunResult {
            scene: scene.name.clone(),
            variant: options.variant.clone(),
            method: scene.method().name().to_string(),
            element: scene.element().name().to_string(),
            nu: scene.material.nu,
            vertices: mesh.num_vertices(),
            nodes: mesh.num_nodes(),
            tets: mesh.num_elements(),
            dofs: self.dofs,
            steps: history.len(),
            steps_requested: scene.num_steps(),
            newton_iterations: history.iter().chain(&failed).map(attempts).sum(),
            converged: ending.error.is_none() && history.iter().all(|r| r.converged),
            cuts: history.iter().map(|s| s.cuts.len()).sum(),
            wall_time_s: self.wall_time_s,
            timings: RunTimings::of(self.model_s, &ending.reports),
            volume_change: mesh.total_volume_at(&ending.state.positions) / mesh.rest_volume() - 1.0,
            probes,
            max_inverted_tets: max_inverted,
            constraint_residual,
            error: ending.error.clone(),
            failed_step: ending.failed_step,
            overrides: options.overrides.clone(),
            warnings: warnings(scene, &history, &body.notices),
            history,
            failed,
            dynamic: scene.is_dynamic(),
            obstacles: scene
                .obstacles
                .iter()
                .enumerate()
                .map(|(i, o)| o.name(i))
                .collect(),
            body_pairs: body_pairs(scene),
        })
    }
}

/// The notices of how the meshes were taken, the scene's warnings ([`validate::warnings`]),
/// one for accepted states with inverted elements (an invertible energy's; any other fails
/// the step) and one per obstacle that exerted no force in any accepted step.
fn warnings(scene: &Scene, history: &[StepRecord], notices: &[String]) -> Vec<String> {
    let mut warnings = notices.to_vec();
    warnings.extend(validate::warnings(scene));
    let inverted = history.iter().filter(|s| s.inverted_tets > 0);
    if let Some(worst) = inverted.clone().max_by_key(|s| s.inverted_tets) {
        warnings.push(format!(
            "{} accepted steps have inverted elements (at most {}, at step {}): the energy is invertible and defined there, but such a state is not physical",
            inverted.count(),
            worst.inverted_tets,
            worst.step
        ));
    }
    for i in 0..scene.obstacles.len() {
        let touched = history.iter().any(|s| {
            s.contact
                .obstacle_forces
                .get(i)
                .is_some_and(|f| f.iter().any(|&c| c != 0.0))
        });
        if !history.is_empty() && !touched {
            warnings.push(format!(
                "obstacles.{i} touched nothing: it exerted no force in any accepted step"
            ));
        }
    }
    warnings
}

/// The pairs of bodies of `scene` as `a_b`, `a` before `b` in its order (the solids, then
/// the cloths: the order of the joined mesh; none with one body).
fn body_pairs(scene: &Scene) -> Vec<String> {
    let bodies = scene.bodies().into_iter().chain(scene.cloths());
    let names: Vec<&str> = bodies.map(|b| b.name).collect();
    if names.len() < 2 {
        return Vec::new();
    }
    names
        .iter()
        .enumerate()
        .flat_map(|(i, a)| names[i + 1..].iter().map(move |b| format!("{a}_{b}")))
        .collect()
}

/// Every probe of `scene` as NaN.
fn nan_probes(scene: &Scene) -> BTreeMap<String, f64> {
    scene.probes.keys().map(|k| (k.clone(), f64::NAN)).collect()
}

/// Draws the final state of the body (`preview.png`) to `path`.
fn preview(
    scene: &Scene,
    body: &Body,
    observer: &Observer<'_>,
    state: &State,
    result: &RunResult,
    path: &Path,
) -> Result<(), SceneError> {
    write_preview(
        path,
        &body.mesh,
        &FrameFields {
            positions: &state.positions,
            velocities: &[],
            von_mises: &observer.last_von_mises,
            stress: &observer.last_stress,
            nodal_pressures: &[],
            contact_forces: &[],
            obstacle_positions: &[],
        },
        &PreviewOptions {
            field: scene.output.preview_field,
            rest_outline: scene.output.preview_rest,
            gravity: scene.loads.gravity,
            title: &run_title(result),
            obstacles: &obstacles_at(scene, &body.mesh, observer, state)?,
            cloths: &body
                .cloths
                .iter()
                .flat_map(|sheet| &sheet.triangles)
                .map(|t| t.map(|v| state.positions[v]))
                .collect::<Vec<_>>(),
        },
    )
}

/// The triangles of every obstacle where it stands at `state`, for the preview: the
/// analytic shapes tessellated around the rest mesh, the meshed ones as the last accepted
/// step placed them.
fn obstacles_at(
    scene: &Scene,
    mesh: &ElementMesh,
    observer: &Observer<'_>,
    state: &State,
) -> Result<Vec<[Vec3; 3]>, SceneError> {
    let level = match scene.stepping {
        SteppingSpec::Dynamic { dt, frames, .. } => LoadLevel::dynamic(state.t, dt * frames as f64),
        _ => LoadLevel::quasi_static(state.t),
    };
    let around = mesh.corners().bounding_box();
    let mut triangles = Vec::new();
    for o in &problem::obstacles(scene)? {
        let s = level.motion_parameter(o.curve.as_ref());
        triangles.extend(obstacle_triangles(o, s, around));
    }
    for (k, o) in problem::mesh_obstacles(scene)?.iter().enumerate() {
        let placed = observer.last_obstacles.get(k).unwrap_or(&o.vertices);
        triangles.extend(o.triangles.iter().map(|t| t.map(|v| placed[v])));
    }
    Ok(triangles)
}
