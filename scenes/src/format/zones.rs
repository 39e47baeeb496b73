//! `[zones]`: the zones of the `zonal` method.

use super::names::ZoneKind;
use serde::{Deserialize, Serialize};

/// Zones of the `zonal` method.
#[derive(Debug, Clone, PartialEq, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct ZonesSpec {
    /// `global`, `k-ring`, `painted` or `none`.
    pub kind: ZoneKind,
    /// Ring size of `k-ring` zones.
    pub k: Option<usize>,
    /// For `painted`: one surface selection per zone.
    #[serde(default)]
    pub paint: Vec<String>,
}
