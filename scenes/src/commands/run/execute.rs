//! A run in named steps: resolve the scene, check the probes on the rest state, set up the
//! frames, step, finish.

use super::body::Body;
use super::checkpoint::RunCheckpoint;
use super::finish::{finish, Outcome};
use super::observer::Observer;
use super::options::RunOptions;
use crate::error::SceneError;
use crate::format::{PointsName, Scene};
use crate::output::{FrameFields, FrameWriter, OutputDir};
use crate::probes;
use crate::record::RunResult;
use crate::resolve::{self, ResolvedScene};
use isochor_mesh::Vec3;
use isochor_solvers::{Checkpoint, MeshObstacle, Simulation};
use std::path::{Path, PathBuf};
use std::time::Instant;

/// Runs `scene` into `out`, from the start or from `resume`.
pub(super) fn execute(
    scene: &Scene,
    options: &RunOptions,
    mut out: Option<OutputDir>,
    resume: Option<RunCheckpoint>,
) -> Result<(RunResult, Option<PathBuf>), SceneError> {
    let model_start = Instant::now();
    let ResolvedScene {
        problem,
        stepping,
        settings,
        selections,
        zones,
        bodies,
        surface_contact,
        friction,
        mesh_obstacles,
        notices,
    } = resolve::build(scene)?;
    let mut body = Body::new(&problem, selections, zones);
    body.notices = notices;
    check_probes_at_rest(scene, &body)?;
    let zone_ids = match &problem.zones {
        Some(z) => Some(z.tet_zone_ids(body.mesh.num_elements())?),
        None => None,
    };
    let velocities = bodies.initial_velocities(problem.mesh.num_nodes());
    let mut sim = Simulation::new(problem, settings)?;
    if let Some(v) = velocities {
        sim.set_velocities(v)?;
    }
    if let Some(spec) = surface_contact {
        sim.set_surface_contact(spec)?;
    }
    let obstacle_surfaces = mesh_obstacles.clone();
    if !mesh_obstacles.is_empty() {
        sim.set_mesh_obstacles(mesh_obstacles)?;
    }
    if let Some(spec) = friction {
        sim.set_friction(spec)?;
    }
    let model_s = model_start.elapsed().as_secs_f64();
    // Only a run that has got this far replaces what an earlier run left.
    if let Some(dir) = out.as_mut() {
        dir.start()?;
    }
    let body_ids = (bodies.parts.len() > 1).then(|| bodies.element_bodies());
    let frames = frame_writer(
        scene,
        out.as_ref(),
        &sim,
        &body,
        zone_ids,
        body_ids,
        &obstacle_surfaces,
    )?;
    let mut observer = Observer::new(scene, options, &body, out.as_ref(), frames);
    if let Some(checkpoint) = resume {
        let solver: Checkpoint = (&checkpoint.solver).into();
        sim.check_progress(stepping, &solver.progress)
            .map_err(|message| SceneError::Invalid {
                origin: format!(
                    "the checkpoint in {}",
                    options.out.as_deref().unwrap_or(Path::new(".")).display()
                ),
                key: "solver".into(),
                message,
            })?;
        sim.restore(solver)?;
        observer.resume(checkpoint);
    }
    let outcome = sim.run_until(stepping, |frame| observer.observe(frame));
    let wall_time_s = observer.wall_time();
    observer.finish_stepping();
    if let Some(e) = observer.error.take() {
        return Err(e);
    }
    let outcome = Outcome {
        solver: outcome,
        dofs: sim.num_dofs(),
        wall_time_s,
        model_s,
    };
    finish(scene, options, &body, observer, outcome, out)
}

/// Evaluates the probes on the rest state, so that a bad probe fails before the run.
fn check_probes_at_rest(scene: &Scene, body: &Body) -> Result<(), SceneError> {
    let zeros = vec![0.0; body.mesh.num_elements()];
    probes::evaluate(scene, &body.probe_input(&body.rest(&zeros)))?;
    Ok(())
}

/// The frame writer of a run into `out` that writes VTU frames (and the surfaces of the
/// meshed `obstacles`), its rest frame written.
fn frame_writer(
    scene: &Scene,
    out: Option<&OutputDir>,
    sim: &Simulation,
    body: &Body,
    zone_ids: Option<Vec<i32>>,
    body_ids: Option<Vec<i32>>,
    obstacles: &[MeshObstacle],
) -> Result<Option<FrameWriter>, SceneError> {
    let (Some(dir), true) = (out, scene.output.vtu) else {
        return Ok(None);
    };
    let mesh = &body.mesh;
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
        scene.output.vtu_encoding.resolve(mesh.num_nodes()),
        zone_ids,
        region_ids,
    )
    .with_bodies(body_ids)
    .with_deformed_points(scene.output.points == PointsName::Deformed)
    .with_obstacles(
        obstacles
            .iter()
            .map(|o| (o.name.clone(), o.triangles.clone()))
            .collect(),
    )
    .with_cloths(&body.cloths);
    let starts: Vec<Vec<Vec3>> = obstacles.iter().map(|o| o.vertices.clone()).collect();
    let rest = FrameFields {
        obstacle_positions: &starts,
        ..FrameFields::rest(mesh)
    };
    w.write(mesh, 0, 0.0, &rest)?;
    Ok(Some(w))
}
