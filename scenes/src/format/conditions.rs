//! `[[dirichlet]]` and `[loads]`: prescribed motions, gravity, tractions and pressures, each
//! with its curve over the run.

use super::common::Vector;
use serde::{Deserialize, Serialize};

/// A Dirichlet condition on a selection.
#[derive(Debug, Clone, PartialEq, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct DirichletSpec {
    /// The selection's name.
    pub selection: String,
    /// Prescribed components: any of `"x"`, `"y"`, `"z"` in one string (default `"xyz"`).
    #[serde(default = "xyz")]
    pub axes: String,
    /// How the vertices move with the load parameter (default `fixed`).
    #[serde(default)]
    pub motion: MotionSpec,
    /// The motion's parameter over the run (default: the fraction of the run).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub curve: Option<CurveSpec>,
}

/// A piecewise-linear curve: `[[s0, y0], [s1, y1], ...]` with increasing `s`, the load
/// parameter (quasi-static) or time in seconds (dynamics); `y` scales a load or is the
/// parameter of a motion (1: the full motion). Constant beyond its first and last point.
pub type CurveSpec = Vec<[f64; 2]>;

fn xyz() -> String {
    "xyz".to_string()
}

/// A prescribed motion, reached at the end of the stepping.
#[derive(Debug, Clone, PartialEq, Default, Deserialize, Serialize)]
#[serde(rename_all = "kebab-case", deny_unknown_fields)]
pub enum MotionSpec {
    /// Held at rest.
    #[default]
    Fixed,
    /// Translated by `offset`.
    Translate(Vector),
    /// Rotated by `degrees` about `axis` through `center`.
    Rotate {
        /// A point of the axis.
        center: Vector,
        /// Direction of the axis.
        axis: Vector,
        /// Angle at the end of the run, in degrees.
        degrees: f64,
    },
    /// Scaled about `center` by `factors`.
    Scale {
        /// The fixed point.
        center: Vector,
        /// Scale factors along x, y, z at the end of the run.
        factors: Vector,
    },
}

/// External loads.
#[derive(Debug, Clone, PartialEq, Default, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct LoadsSpec {
    /// Gravitational acceleration (m/s^2), e.g. `[0, -9.8, 0]`.
    pub gravity: Option<Vector>,
    /// The gravity's scale over the run (default: ramped in quasi-static stepping, constant
    /// in dynamics).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub gravity_curve: Option<CurveSpec>,
    /// Dead tractions on boundary faces.
    #[serde(default)]
    pub traction: Vec<TractionSpec>,
    /// Follower pressures on boundary faces.
    #[serde(default)]
    pub pressure: Vec<PressureSpec>,
}

/// A dead traction (Pa) on the boundary faces of a selection.
#[derive(Debug, Clone, PartialEq, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct TractionSpec {
    /// The selection whose boundary faces are loaded.
    pub selection: String,
    /// Force per unit rest area (Pa).
    pub traction: Vector,
    /// Scale over the run (default: the load ramp).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub curve: Option<CurveSpec>,
}

/// A follower pressure (Pa, positive pushes into the body) on the boundary faces of a
/// selection, given (`pressure`) or solved for to hold the cavity the faces line at a volume
/// (`volume_ratio`); exactly one of the two.
#[derive(Debug, Clone, PartialEq, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct PressureSpec {
    /// The selection whose boundary faces are loaded.
    pub selection: String,
    /// Pressure (Pa).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub pressure: Option<f64>,
    /// The cavity's volume over its rest volume at full load, its pressure the unknown.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub volume_ratio: Option<f64>,
    /// The point the enclosed volume is measured about (default the origin): any point for
    /// closed faces, a point on the symmetry planes of a cut chamber.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub origin: Option<Vector>,
    /// Cap every boundary loop of the faces (a chamber's opening) by the fan from its
    /// centroid (default false: the faces are closed, or closed by symmetry planes through
    /// `origin`, or their openings are held).
    #[serde(default, skip_serializing_if = "std::ops::Not::not")]
    pub cap_openings: bool,
    /// Scale over the run (default: the load ramp).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub curve: Option<CurveSpec>,
}
