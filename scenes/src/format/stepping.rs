//! `[stepping]`: quasi-static load steps or implicit Euler frames.

use serde::{Deserialize, Serialize};

/// Quasi-static load stepping or implicit Euler dynamics.
#[derive(Debug, Clone, PartialEq, Deserialize, Serialize)]
#[serde(tag = "mode", rename_all = "kebab-case", deny_unknown_fields)]
pub enum SteppingSpec {
    /// Loads and motions follow the load parameter from 0 to 1; the levels `k / steps` are
    /// written as frames. `increments = "adaptive"` (default) starts with `first_increment`
    /// of the load (default 1: all of it, never past a frame level), halves the increment
    /// after a failed solve down to `min_increment` (default 1e-3) and doubles it after easy
    /// steps; `"fixed"` takes one solve per frame and stops at the first failure.
    QuasiStatic {
        /// Number of frames.
        steps: usize,
        /// `"adaptive"` (default) or `"fixed"` (a string checked when the scene is loaded, so
        /// that a bad value names its key).
        #[serde(default, skip_serializing_if = "Option::is_none")]
        increments: Option<String>,
        /// The first increment (default 1).
        #[serde(default, skip_serializing_if = "Option::is_none")]
        first_increment: Option<f64>,
        /// The smallest increment (default 1e-3).
        #[serde(default, skip_serializing_if = "Option::is_none")]
        min_increment: Option<f64>,
    },
    /// Implicit Euler with time step `dt` (s) for `frames` frames, each step followed by the
    /// volume projection `volume_projection` (the baselines of Fig. 8 of Sheen et al. 2021,
    /// see `isochor_solvers::VolumeProjection`).
    Dynamic {
        /// Time step (s).
        dt: f64,
        /// Number of steps (each a frame).
        frames: usize,
        /// `none` (default), `one-ring` (Irving et al. 2007) or `global-rescale` (a string
        /// checked when the scene is loaded, so that a bad value names its key).
        #[serde(default, skip_serializing_if = "Option::is_none")]
        volume_projection: Option<String>,
        /// `one-ring` only: the largest change of a one ring's volume per step, relative to
        /// its rest volume (default [`DEFAULT_VOLUME_RECOVERY`]).
        #[serde(default, skip_serializing_if = "Option::is_none")]
        volume_recovery: Option<f64>,
    },
}

/// The one-ring projection's volume recovery per step when the scene gives none: 1% of a
/// one ring's rest volume (a choice of ours; Sheen et al. 2021 do not give theirs).
pub const DEFAULT_VOLUME_RECOVERY: f64 = 0.01;

/// The values of `stepping.volume_projection`.
pub const VOLUME_PROJECTIONS: [&str; 3] = ["none", "one-ring", "global-rescale"];
