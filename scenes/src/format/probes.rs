//! `[probes.NAME]`: named scalars measured on the final state or over the run.

use super::common::z_axis;
use super::common::Vector;
use super::names::{ComponentName, EnergyName, LengthUnit, Reduce};
use serde::{Deserialize, Serialize};

/// A named scalar measured on the final state.
#[derive(Debug, Clone, PartialEq, Deserialize, Serialize)]
#[serde(tag = "kind", rename_all = "kebab-case", deny_unknown_fields)]
pub enum ProbeSpec {
    /// `scale * u_component` at a point (barycentric in the containing rest tet), or reduced
    /// over the vertices of a selection.
    Displacement {
        /// The rest point (instead of a selection).
        point: Option<Vector>,
        /// The selection reduced over (instead of a point).
        selection: Option<String>,
        /// `x`, `y`, `z` or `norm`.
        component: ComponentName,
        /// Factor applied to the value (default 1).
        #[serde(default = "unit")]
        scale: f64,
        /// Over a selection: `mean` (default), `max` or `min`.
        #[serde(default)]
        reduce: Reduce,
        /// The unit tables and plots show it in (JSON and CSV stay in metres).
        #[serde(default, skip_serializing_if = "Option::is_none")]
        unit: Option<LengthUnit>,
    },
    /// The deformed coordinate `component` of the nodes of a selection (every node if none),
    /// reduced by `reduce`: e.g. the lowest point of a sagging body (`z`, `min`, negative
    /// below the rest body's base at z = 0: z is up in the built-in scenes; Fig. 10 of Francu
    /// et al. 2021). `norm` is the distance from the origin.
    Position {
        /// The selection reduced over (every node if none).
        selection: Option<String>,
        /// `x`, `y`, `z` or `norm`.
        component: ComponentName,
        /// `mean` (default), `max` or `min`.
        #[serde(default)]
        reduce: Reduce,
    },
    /// Whole-body deformed/rest volume minus one.
    VolumeChange,
    /// Deformed/rest volume of the tets whose centroid lies in a selection (all tets if none).
    VolumeRatio {
        /// The selection (all tets if none).
        selection: Option<String>,
    },
    /// Deformed/rest volume minus one of zone `zone` (counted from 0) of the scene's
    /// `[zones]`: the volume the zonal method constrains, measured the same way whatever the
    /// method (the zones are built from the scene even when the method ignores them).
    ZoneVolumeChange {
        /// The zone's index in `[zones]` (for `painted`, the index in `paint`).
        zone: usize,
    },
    /// Smallest deformed/rest volume ratio of a tet.
    MinVolumeRatio,
    /// Largest deformed/rest volume ratio of a tet.
    MaxVolumeRatio,
    /// Inverted tets in the final state.
    InvertedTets,
    /// The final step's constraint residual (max-norm).
    ConstraintResidual,
    /// The most iterations any accepted step needed to bring its volume error (the L1 norm
    /// of the constraint residual over the rest volume, Francu et al. 2021, Fig. 8) to
    /// `level` or below, counting at least one iteration per step that iterates (NaN if a
    /// step never did, or if no error was measured: a method without multipliers).
    VolumeErrorIterations {
        /// The volume error to reach (Fig. 8: 0.01).
        level: f64,
    },
    /// `(V - V_expected) / V_rest`, with `V_expected = sum_e V_e (1 + p_e / kappa)` the volume the
    /// per-tet pressures imply (tension-positive pressures, `kappa` of the mixed methods).
    PressureVolumeMismatch,
    /// Mean jump of the per-tet pressure across interior faces divided by the pressure's
    /// standard deviation (about 1.13 for white noise, small for a smooth field).
    PressureCheckerboard,
    /// Deformed over rest volume enclosed by the boundary faces of a selection that form a
    /// closed surface, such as a chamber's walls (divergence theorem, exact on 3- and 6-node
    /// faces): above 1 for an inflated chamber.
    ChamberVolumeRatio {
        /// The selection of faces (e.g. `physical = "chamber"`).
        selection: String,
    },
    /// The pressure of pressure load `load` (its index in `loads.pressure`, from 0): given
    /// (times its load scale) or solved for (`volume_ratio`), positive inflating; 0 at rest.
    LoadPressure {
        /// The pressure load's index.
        load: usize,
    },
    /// The volume the faces of pressure load `load` enclose about its origin over their rest
    /// one (1 at rest).
    EnclosedVolumeRatio {
        /// The pressure load's index.
        load: usize,
    },
    /// The angle, in degrees, of the rotation that best maps the rest positions of the nodes
    /// of a selection onto their deformed ones (about their centroids; Kabsch's least-squares
    /// rotation, in `[0, 180]`), or the signed angle about `axis` if given (right-handed):
    /// a bending angle.
    Rotation {
        /// The selection whose nodes are measured.
        selection: String,
        /// The rotation axis (default: the best-fit rotation's own).
        #[serde(default, skip_serializing_if = "Option::is_none")]
        axis: Option<Vector>,
    },
    /// Mean increase of the distance from an axis of the vertices of a selection.
    RadiusIncrease {
        /// The selection whose vertices are measured.
        selection: String,
        /// A point of the axis (default the origin).
        #[serde(default)]
        center: Vector,
        /// Direction of the axis (default `+z`).
        #[serde(default = "z_axis")]
        axis: Vector,
        /// The unit tables and plots show it in (JSON and CSV stay in metres).
        #[serde(default, skip_serializing_if = "Option::is_none")]
        unit: Option<LengthUnit>,
    },
    /// An energy of the final frame: `kinetic`, `elastic`, `external`, `constraint`,
    /// `potential` (elastic + constraint + external) or `total` (potential + kinetic).
    Energy {
        /// Which energy.
        which: EnergyName,
    },
    /// Whole-body deformed/rest volume over the run's accepted steps, reduced by `reduce`
    /// (`min`, `max` or `mean`; e.g. the volume extremes of Figs. 10-11 of Sheen et al.).
    RunVolumeRatio {
        /// How the steps are reduced.
        reduce: Reduce,
    },
    /// Largest penetration of a vertex into an obstacle over the run.
    MaxPenetration,
    /// The first step or frame with a vertex in contact (NaN if none).
    FirstContact,
    /// The smallest distance between two contact primitives (point-triangle or edge-edge,
    /// between bodies, a body and itself or a body and a meshed obstacle) over the run's
    /// accepted steps, in metres; only pairs within the barrier's `dhat` are measured (NaN
    /// when no pair came that close, or without barrier contact).
    MinDistance,
    /// The deformed length (m) of the cloth edges with both ends in a selection: with the
    /// middle ring of a band selected, the band's middle loop (a waistband's circumference).
    LoopLength {
        /// The selection (nodes of a cloth body).
        selection: String,
    },
    /// Largest norm of the total contact force over the run, or of the force of obstacle
    /// `obstacle` alone (its index in `obstacles`, from 0): two obstacles squeezing a body
    /// push with opposite forces that cancel in the total.
    MaxContactForce {
        /// The obstacle (default: all, summed).
        #[serde(default, skip_serializing_if = "Option::is_none")]
        obstacle: Option<usize>,
    },
}

fn unit() -> f64 {
    1.0
}

impl ProbeSpec {
    /// The unit a length probe is shown in, if its scene names one.
    pub fn unit(&self) -> Option<LengthUnit> {
        match self {
            ProbeSpec::Displacement { unit, .. } | ProbeSpec::RadiusIncrease { unit, .. } => *unit,
            _ => None,
        }
    }
}
