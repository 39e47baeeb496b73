//! What a run does after every accepted step: record it, track a probe, write its frame and
//! its checkpoint, move the progress bar.

use super::body::{Body, ProbedState};
use super::checkpoint::RunCheckpoint;
use super::options::RunOptions;
use super::records::{cut_record, record};
use crate::error::SceneError;
use crate::format::Scene;
use crate::output::{FrameFields, FrameWriter, OutputDir};
use crate::probes;
use crate::record::{PressureLoadRecord, StepRecord};
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use isochor_mesh::Vec3;
use isochor_solvers::{Checkpoint, Energies, Frame};
use nalgebra::Matrix3;
use std::collections::BTreeMap;
use std::io::IsTerminal;
use std::ops::ControlFlow;
use std::path::PathBuf;
use std::time::Instant;

/// The state of a run between steps.
pub(super) struct Observer<'a> {
    scene: &'a Scene,
    options: &'a RunOptions,
    body: &'a Body,
    /// The output folder being written.
    out: Option<PathBuf>,
    /// The VTU frames, if the run writes them.
    pub frames: Option<FrameWriter>,
    /// Records of the accepted steps.
    pub history: Vec<StepRecord>,
    /// Per element of the last accepted state: pressure, Cauchy stress, von Mises stress.
    pub last_pressures: Vec<f64>,
    pub last_stress: Vec<Matrix3<f64>>,
    pub last_von_mises: Vec<f64>,
    /// Energies of the last accepted state.
    pub last_energies: Energies,
    /// Where the meshed obstacles' vertices stood at the last accepted state.
    pub last_obstacles: Vec<Vec<Vec3>>,
    /// The solver's checkpoint of the last accepted state (with `--checkpoint-every`).
    pub last_solver: Option<Checkpoint>,
    /// Wall time of the run before it was resumed.
    pub earlier_wall_time: f64,
    /// The first error writing an output or tracking a probe; the steps after it write
    /// nothing.
    pub error: Option<SceneError>,
    start: Instant,
    bar: ProgressBar,
}

/// Whether each obstacle of `scene` is meshed, in its order.
pub(super) fn meshed_obstacles(scene: &Scene) -> Vec<bool> {
    scene.obstacles.iter().map(|o| o.is_mesh()).collect()
}

impl<'a> Observer<'a> {
    /// An observer of a run of `scene` from its first step.
    pub fn new(
        scene: &'a Scene,
        options: &'a RunOptions,
        body: &'a Body,
        out: Option<&OutputDir>,
        frames: Option<FrameWriter>,
    ) -> Self {
        Observer {
            scene,
            options,
            body,
            out: out.map(|d| d.path().to_path_buf()),
            frames,
            history: Vec::new(),
            last_pressures: Vec::new(),
            last_stress: Vec::new(),
            last_von_mises: Vec::new(),
            last_energies: Energies::default(),
            last_obstacles: Vec::new(),
            last_solver: None,
            earlier_wall_time: 0.0,
            error: None,
            start: Instant::now(),
            bar: progress_bar(options.progress, scene.num_steps(), &scene.name),
        }
    }

    /// Continues from a checkpoint's records and frames.
    pub fn resume(&mut self, checkpoint: RunCheckpoint) {
        self.history = checkpoint.history;
        self.earlier_wall_time = checkpoint.wall_time_s;
        if let Some(w) = self.frames.as_mut() {
            w.continue_after(checkpoint.frames);
        }
    }

    /// Wall time of the whole run so far, in seconds.
    pub fn wall_time(&self) -> f64 {
        self.earlier_wall_time + self.start.elapsed().as_secs_f64()
    }

    /// Handles one accepted step; the library caller's hook may stop the run there.
    pub fn observe(&mut self, frame: &Frame<'_>) -> ControlFlow<()> {
        let mut step = record(
            &self.body.mesh,
            frame.state,
            frame.report,
            frame.inverted_tets,
            frame.energies,
            frame.surface_contact.as_ref(),
            &meshed_obstacles(self.scene),
        );
        step.cuts = frame.cuts.iter().map(cut_record).collect();
        step.tracked_probe = self.tracked_probe(frame);
        step.pressure_loads = frame
            .pressure_loads
            .iter()
            .map(|r| PressureLoadRecord {
                pressure: r.pressure,
                volume_ratio: r.volume_ratio,
            })
            .collect();
        self.history.push(step);
        let probes = self.step_probes(frame);
        if let Some(step) = self.history.last_mut() {
            step.probes = probes;
        }
        self.last_pressures.clone_from(&frame.tet_pressures);
        self.last_stress.clone_from(&frame.stress);
        self.last_von_mises.clone_from(&frame.von_mises);
        self.last_energies = frame.energies;
        self.last_obstacles.clone_from(&frame.mesh_obstacles);
        if self.error.is_none() {
            if let Err(e) = self
                .write_frame(frame)
                .and_then(|()| self.checkpoint(frame))
            {
                self.error = Some(e);
            }
        }
        self.bar.set_position(frame.progress.levels as u64);
        self.bar.set_message(format!(
            "{} Newton iterations",
            frame.report.newton_iterations()
        ));
        match &self.options.on_step {
            Some(hook) => (hook.0)(frame),
            None => ControlFlow::Continue(()),
        }
    }

    /// The value of the probe `output.potential_against` at this step, if the scene names
    /// one (an error is kept for the end of the run).
    fn tracked_probe(&mut self, frame: &Frame<'_>) -> Option<f64> {
        let name = self.scene.output.potential_against.as_ref()?;
        let state = self.probed_state(frame);
        let input = self.body.probe_input(&state);
        match probes::evaluate_one(self.scene, name, &input) {
            Ok(v) => Some(v),
            Err(e) => {
                self.error = self.error.take().or(Some(e));
                None
            }
        }
    }

    /// What the probes read of this step's frame and the history so far.
    fn probed_state<'f>(&'f self, frame: &'f Frame<'_>) -> ProbedState<'f> {
        ProbedState {
            positions: &frame.state.positions,
            tet_pressures: &frame.tet_pressures,
            constraint_residual: frame.report.constraint_residual,
            energies: frame.energies,
            history: &self.history,
        }
    }

    /// Every probe of the scene at this step (the step already in the history), NaN where
    /// one fails: the errors are the final evaluation's to report.
    fn step_probes(&self, frame: &Frame<'_>) -> BTreeMap<String, f64> {
        let state = self.probed_state(frame);
        let input = self.body.probe_input(&state);
        self.scene
            .probes
            .keys()
            .map(|name| {
                let value = probes::evaluate_one(self.scene, name, &input).unwrap_or(f64::NAN);
                (name.clone(), value)
            })
            .collect()
    }

    /// Writes the step's VTU frame, if it is a frame the writer wants.
    fn write_frame(&mut self, frame: &Frame<'_>) -> Result<(), SceneError> {
        let total = self.scene.num_steps();
        let Some(w) = self.frames.as_mut() else {
            return Ok(());
        };
        let Some(index) = frame.frame.filter(|&k| w.wants(k, total)) else {
            return Ok(());
        };
        let fields = FrameFields {
            positions: &frame.state.positions,
            velocities: if self.scene.is_dynamic() {
                &frame.state.velocities
            } else {
                &[]
            },
            von_mises: &frame.von_mises,
            stress: &frame.stress,
            nodal_pressures: frame.nodal_pressures.as_deref().unwrap_or_default(),
            contact_forces: &frame.contact_forces,
            obstacle_positions: &frame.mesh_obstacles,
        };
        w.write(&self.body.mesh, index, frame.state.t, &fields)
    }

    /// Keeps the solver's checkpoint of the step and writes the run's every
    /// `--checkpoint-every` steps.
    fn checkpoint(&mut self, frame: &Frame<'_>) -> Result<(), SceneError> {
        let (Some(every), Some(dir)) = (self.options.checkpoint_every, self.out.as_deref()) else {
            return Ok(());
        };
        let solver = frame.checkpoint();
        if frame.progress.steps % every == 0 {
            self.run_checkpoint(false, &solver, self.history.clone(), self.wall_time())
                .write(dir)?;
        }
        self.last_solver = Some(solver);
        Ok(())
    }

    /// The run's checkpoint with the solver's `solver` and the records `history`.
    pub fn run_checkpoint(
        &self,
        finished: bool,
        solver: &Checkpoint,
        history: Vec<StepRecord>,
        wall_time_s: f64,
    ) -> RunCheckpoint {
        let frames = self
            .frames
            .as_ref()
            .map(|w| w.entries().to_vec())
            .unwrap_or_default();
        RunCheckpoint::new(
            self.scene,
            self.options,
            finished,
            solver,
            history,
            frames,
            wall_time_s,
        )
    }

    /// Clears the progress bar at the end of the stepping.
    pub fn finish_stepping(&self) {
        self.bar.finish_and_clear();
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
