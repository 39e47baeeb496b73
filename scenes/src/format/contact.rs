//! `[contact]`: barrier contact between the bodies' surfaces, and of a surface with itself,
//! and friction (between surfaces and against the analytic obstacles).

use super::common::{is_zero, yes};
use serde::{Deserialize, Serialize};

/// Surface contact (IPC's barrier with continuous collision detection); without this
/// section the bodies of a scene do not touch each other, and nothing has friction.
///
/// In a scene of one body, `self = false` leaves no pair of surfaces to touch: the section
/// then only sets the friction against the `[[obstacles]]`.
#[derive(Debug, Clone, PartialEq, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct ContactSpec {
    /// The distance (m) below which the barrier acts (default `1e-3` times the bounding-box
    /// diagonal of the rest mesh).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub dhat: Option<f64>,
    /// Whether a body's surface may touch itself (default `true`); pairs that share a node
    /// never count.
    #[serde(rename = "self", default = "yes")]
    pub self_contact: bool,
    /// The Coulomb friction coefficient between surfaces and against every obstacle
    /// (default 0: frictionless).
    #[serde(default, skip_serializing_if = "is_zero")]
    pub friction: f64,
    /// The slip (m) over a step below which friction is static, smoothed (default
    /// [`DEFAULT_EPSV`] times `dhat`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub epsv: Option<f64>,
    /// The coefficient between two bodies, overriding `friction`.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub pairs: Vec<PairFrictionSpec>,
    /// The coefficient against one obstacle, overriding `friction`.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub obstacles: Vec<ObstacleFrictionSpec>,
}

/// The default slip length of friction, relative to the barrier's reach `dhat`.
pub const DEFAULT_EPSV: f64 = 0.1;

/// `[[contact.pairs]]`: the friction between two bodies.
#[derive(Debug, Clone, PartialEq, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct PairFrictionSpec {
    /// The two bodies' names (the same name twice: the body's friction with itself).
    pub bodies: [String; 2],
    /// Their coefficient.
    pub friction: f64,
}

/// `[[contact.obstacles]]`: the friction against one obstacle.
#[derive(Debug, Clone, PartialEq, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct ObstacleFrictionSpec {
    /// The obstacle's index in `[[obstacles]]` (from 0).
    pub obstacle: usize,
    /// Its coefficient.
    pub friction: f64,
}
