//! How time or load advances: quasi-static load levels or implicit Euler time steps.

use super::stepper::{Adaptive, StepControl, MIN_INCREMENT_FLOOR};
use crate::error::SolverError;

/// How time or load advances.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Stepping {
    /// Loads and prescribed motions follow the load parameter from 0 to 1; the levels
    /// `k / steps` are the frames, and `control` chooses the increments between them.
    QuasiStatic {
        /// Number of frames: the levels `k / steps`, `k = 1..=steps`.
        steps: usize,
        /// How the increments between frames are chosen.
        control: StepControl,
    },
    /// Implicit Euler (eq. 20-21) with time step `dt` for `frames` steps; prescribed motions
    /// follow `time / (dt * frames)`, loads are constant (unless they follow curves). A failed
    /// step is retried in substeps (`dt/2`, `dt/4`, ... down to `dt/1024`) that end on the
    /// frame's time.
    ImplicitEuler {
        /// Time step, in seconds.
        dt: f64,
        /// Number of steps (each a frame).
        frames: usize,
    },
}

impl Stepping {
    /// Quasi-static stepping with one solve per level `k / steps`.
    pub fn quasi_static(steps: usize) -> Self {
        Stepping::QuasiStatic {
            steps,
            control: StepControl::Fixed,
        }
    }

    /// Quasi-static stepping with adaptive increments (the defaults of [`Adaptive`]) and
    /// frames at the levels `k / steps`.
    pub fn adaptive(steps: usize) -> Self {
        Stepping::QuasiStatic {
            steps,
            control: StepControl::Adaptive(Adaptive::default()),
        }
    }

    /// The number of frames (levels written as results).
    pub fn frames(&self) -> usize {
        match *self {
            Stepping::QuasiStatic { steps, .. } => steps,
            Stepping::ImplicitEuler { frames, .. } => frames,
        }
    }
}

/// Checks a stepping before a run: at least one frame, a valid adaptive range, a positive
/// time step.
pub(super) fn check_stepping(stepping: Stepping) -> Result<(), SolverError> {
    match stepping {
        Stepping::QuasiStatic { steps: 0, .. } => Err(SolverError::InvalidProblem(
            "steps must be at least 1".into(),
        )),
        Stepping::QuasiStatic {
            control: StepControl::Adaptive(a),
            ..
        } if !(a.first > 0.0 && a.first <= 1.0 && a.min >= MIN_INCREMENT_FLOOR && a.min <= a.first) => {
            Err(SolverError::InvalidProblem(format!(
                "adaptive stepping needs {MIN_INCREMENT_FLOOR:e} <= min increment ({}) <= first increment ({}) <= 1",
                a.min, a.first
            )))
        }
        Stepping::ImplicitEuler { frames: 0, .. } => Err(SolverError::InvalidProblem(
            "frames must be at least 1".into(),
        )),
        Stepping::ImplicitEuler { dt, .. } if !(dt > 0.0 && dt.is_finite()) => Err(
            SolverError::InvalidProblem(format!("dt = {dt} must be positive")),
        ),
        _ => Ok(()),
    }
}
