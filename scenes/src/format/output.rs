//! `[output]`: what `--out` writes.

use super::common::{one, yes};
use super::names::{PointsName, PreviewField, VtuEncodingName};
use serde::{Deserialize, Serialize};

/// What `--out` writes.
#[derive(Debug, Clone, PartialEq, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct OutputSpec {
    /// Write a VTU every `every` steps or frames (the last one is always written).
    #[serde(default = "one")]
    pub every: usize,
    /// Write VTU frames and the `.pvd` collection.
    #[serde(default = "yes")]
    pub vtu: bool,
    /// Write PNG plots.
    #[serde(default = "yes")]
    pub plots: bool,
    /// How the VTU frames store their arrays.
    #[serde(default)]
    pub vtu_encoding: VtuEncodingName,
    /// Write `preview.png`, a picture of the deformed body (default: as `plots`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub preview: Option<bool>,
    /// The field that colors the preview.
    #[serde(default)]
    pub preview_field: PreviewField,
    /// Outline the rest configuration in the preview.
    #[serde(default = "yes")]
    pub preview_rest: bool,
    /// The points of the VTU frames: `rest` (default; warp them by the point field
    /// `displacement` to see the deformed body) or `deformed`.
    #[serde(default)]
    pub points: PointsName,
    /// A probe evaluated after every step: `potential.csv` and (with `plots`)
    /// `potential.png` give the total potential energy against it, the minimum marked
    /// (Fig. 9 of Francu et al. 2021: energy against the tip's deflection in dynamics).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub potential_against: Option<String>,
}

impl OutputSpec {
    /// Whether `preview.png` is written: `preview` if given, else `plots`.
    pub fn writes_preview(&self) -> bool {
        self.preview.unwrap_or(self.plots)
    }
}

impl Default for OutputSpec {
    fn default() -> Self {
        OutputSpec {
            every: 1,
            vtu: true,
            plots: true,
            vtu_encoding: VtuEncodingName::Auto,
            points: PointsName::Rest,
            preview: None,
            preview_field: PreviewField::Displacement,
            preview_rest: true,
            potential_against: None,
        }
    }
}
