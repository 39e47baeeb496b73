//! `[selections.NAME]`: named regions of space (and mesh groups) that conditions, loads,
//! regions, zones and probes refer to.

use super::common::Vector;
use super::common::{is_false, z_axis};
use serde::{Deserialize, Serialize};

/// A region of space given by the intersection of the listed primitives (all must hold),
/// optionally within a Gmsh physical group (`physical`). Used as a vertex set (Dirichlet, displacement probes), a boundary-face set (tractions,
/// pressure: faces whose three vertices are inside) or a tet set (centroid inside).
#[derive(Debug, Clone, PartialEq, Default, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct SelectionSpec {
    /// Axis-aligned box (closed, padded by the tolerance).
    #[serde(rename = "box")]
    pub aabb: Option<BoxSpec>,
    /// Points on a plane (within the tolerance).
    pub plane: Option<PlaneSpec>,
    /// Points on the side of the plane the normal points to.
    pub half_space: Option<PlaneSpec>,
    /// Points whose distance from an axis lies in `[min, max]` (within the tolerance).
    pub radial: Option<RadialSpec>,
    /// Points within `radius` of `center`.
    pub sphere: Option<SphereSpec>,
    /// Only vertices of the boundary surface.
    #[serde(default, skip_serializing_if = "is_false")]
    pub surface: bool,
    /// Everything (the whole mesh).
    #[serde(default, skip_serializing_if = "is_false")]
    pub all: bool,
    /// Explicit vertex indices (only for generated meshes whose numbering is known).
    pub vertices: Option<Vec<usize>>,
    /// A named group of the mesh, by name (or by number if unnamed): a Gmsh physical group or
    /// TetGen region of the mesh file, or a group the generator names (spine, cushion, bubble,
    /// finger, torso, creature). A surface group selects its triangles and their vertices, a volume group its
    /// tets and their vertices (with `surface`, its tets' boundary faces and their vertices).
    pub physical: Option<String>,
    /// Only what belongs to the named body (`[[bodies]]`, or `"body"` for the scene's own).
    pub body: Option<String>,
    /// Geometric tolerance (default: 1e-6 times the mesh's bounding-box diagonal).
    pub tolerance: Option<f64>,
}

/// A box.
#[derive(Debug, Clone, PartialEq, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct BoxSpec {
    /// Lower corner.
    pub min: Vector,
    /// Upper corner.
    pub max: Vector,
}

/// A plane through `point` with `normal`.
#[derive(Debug, Clone, PartialEq, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct PlaneSpec {
    /// A point of the plane.
    pub point: Vector,
    /// Its normal.
    pub normal: Vector,
}

/// Distance from the axis through `center` along `axis`, between `min` and `max`.
#[derive(Debug, Clone, PartialEq, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct RadialSpec {
    /// A point of the axis (default the origin).
    #[serde(default)]
    pub center: Vector,
    /// Direction of the axis (default `+z`).
    #[serde(default = "z_axis")]
    pub axis: Vector,
    /// Smallest distance (default 0).
    #[serde(default)]
    pub min: f64,
    /// Largest distance (default infinite).
    #[serde(default = "infinity")]
    pub max: f64,
}

/// A ball.
#[derive(Debug, Clone, PartialEq, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct SphereSpec {
    /// Centre.
    pub center: Vector,
    /// Radius.
    pub radius: f64,
}

fn infinity() -> f64 {
    f64::INFINITY
}
