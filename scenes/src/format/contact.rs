//! `[contact]`: barrier contact between the bodies' surfaces, and of a surface with itself.

use super::common::yes;
use serde::{Deserialize, Serialize};

/// Surface contact (IPC's barrier with continuous collision detection); without this
/// section the bodies of a scene do not touch each other.
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
}
