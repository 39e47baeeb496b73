//! A checkpoint checked as a scene file is before a run trusts it: the scene inside it
//! validated as a scene, `every` at least 1, the records one per accepted step, the state
//! arrays finite, the frames plain file names. The progress is checked against the stepping
//! once the problem is built ([`isochor_solvers::Simulation::check_progress`]), and the array
//! lengths against the mesh when the state is restored.

use super::checkpoint::RunCheckpoint;
use crate::error::SceneError;
use crate::format::{limits, Scene};

impl RunCheckpoint {
    /// Refuses a checkpoint (read from `origin`) that no run of this program writes, naming
    /// the field at fault.
    pub fn check(&self, origin: &str) -> Result<(), SceneError> {
        let scene_origin = format!("{origin}: [scene]");
        let scene = Scene::from_value(self.scene.to_value(), &scene_origin)?;
        limits::check_memory(&scene, &scene_origin)?;
        let invalid = |key: &str, message: String| SceneError::Invalid {
            origin: origin.to_string(),
            key: key.to_string(),
            message,
        };
        if self.every == 0 {
            return Err(invalid("every", "must be at least 1".into()));
        }
        let solver = &self.solver;
        if self.history.len() != solver.steps {
            return Err(invalid(
                "history",
                format!(
                    "{} step records for solver.steps = {}",
                    self.history.len(),
                    solver.steps
                ),
            ));
        }
        let mut previous_t = f64::NEG_INFINITY;
        for (i, record) in self.history.iter().enumerate() {
            if record.step != i + 1 || !(record.t.is_finite() && record.t >= previous_t) {
                return Err(invalid(
                    &format!("history.{i}"),
                    format!(
                        "step {} at t = {}: records must count the steps from 1 at non-decreasing t",
                        record.step, record.t
                    ),
                ));
            }
            previous_t = record.t;
        }
        let vectors = [
            ("solver.positions", &solver.positions),
            ("solver.velocities", &solver.velocities),
        ];
        for (key, values) in vectors {
            if let Some(i) = values.iter().position(|v| v.iter().any(|c| !c.is_finite())) {
                return Err(invalid(
                    key,
                    format!("entry {i} is not finite: {:?}", values[i]),
                ));
            }
        }
        if solver.velocities.len() != solver.positions.len() {
            return Err(invalid(
                "solver.velocities",
                format!(
                    "{} velocities for {} positions",
                    solver.velocities.len(),
                    solver.positions.len()
                ),
            ));
        }
        let scalars = [
            ("solver.multipliers", &solver.multipliers),
            ("solver.contact_multipliers", &solver.contact_multipliers),
        ];
        for (key, values) in scalars {
            if let Some(i) = values.iter().position(|v| !v.is_finite()) {
                return Err(invalid(
                    key,
                    format!("entry {i} is not finite: {}", values[i]),
                ));
            }
        }
        for (key, value) in [
            ("solver.t", solver.t),
            ("solver.progress_t", solver.progress_t),
        ] {
            if !value.is_finite() {
                return Err(invalid(key, format!("{value} is not finite")));
            }
        }
        if !(self.wall_time_s.is_finite() && self.wall_time_s >= 0.0) {
            return Err(invalid(
                "wall_time_s",
                format!("{} must be finite and non-negative", self.wall_time_s),
            ));
        }
        if self.frames.len() > self.history.len() + 1 {
            return Err(invalid(
                "frames",
                format!(
                    "{} frames for {} steps",
                    self.frames.len(),
                    self.history.len()
                ),
            ));
        }
        for (i, (t, name)) in self.frames.iter().enumerate() {
            if !is_plain_file_name(name) || !t.is_finite() {
                return Err(invalid(
                    &format!("frames.{i}"),
                    format!(
                        "'{}' at t = {t}: a frame is a file name in the output folder (no \
                         path separators, not '..')",
                        isochor_mesh::io::excerpt(name)
                    ),
                ));
            }
        }
        Ok(())
    }
}

/// A name of a file in the folder itself: not empty, no path separator, not `.` or `..`.
fn is_plain_file_name(name: &str) -> bool {
    !name.is_empty()
        && name != "."
        && name != ".."
        && !name.contains(['/', '\\'])
        && !name.contains('\0')
}
