//! `[[obstacles]]`: rigid obstacles the body's boundary meets: analytic shapes in
//! frictionless augmented-Lagrangian contact, and meshed surfaces (`shape = "mesh"`) in the
//! barrier contact of `[contact]`.

use super::bodies::{PlacementSpec, RotationSpec};
use super::common::Vector;
use super::common::{is_zero, z_axis};
use super::conditions::CurveSpec;
use serde::{Deserialize, Serialize};
use std::path::PathBuf;

/// A rigid obstacle, translated by `translate` (and a round one's radius changed by
/// `radius_change`) over the stepping (quasi-static load parameter or `time / duration`),
/// e.g. `{ shape = "half-space" }` for the ground `z = 0`.
#[derive(Debug, Clone, PartialEq, Deserialize, Serialize)]
#[serde(tag = "shape", rename_all = "kebab-case", deny_unknown_fields)]
pub enum ObstacleSpec {
    /// The solid below the plane through `point` (default origin) with outward `normal`
    /// (default `+z`).
    HalfSpace {
        /// A point of the boundary plane (default the origin).
        #[serde(default)]
        point: Vector,
        /// Outward normal (default `+z`).
        #[serde(default = "z_axis")]
        normal: Vector,
        /// Displacement at the end of the run (default none).
        #[serde(default)]
        translate: Vector,
        /// The motion over the run (default: the fraction of the run).
        #[serde(default, skip_serializing_if = "Option::is_none")]
        curve: Option<CurveSpec>,
    },
    /// A solid sphere.
    Sphere {
        /// Centre.
        center: Vector,
        /// Radius.
        radius: f64,
        /// Displacement at the end of the run (default none).
        #[serde(default)]
        translate: Vector,
        /// Change of the radius at the end of the run (default none).
        #[serde(default, skip_serializing_if = "is_zero")]
        radius_change: f64,
        /// The motion over the run (default: the fraction of the run).
        #[serde(default, skip_serializing_if = "Option::is_none")]
        curve: Option<CurveSpec>,
    },
    /// An infinite solid cylinder about the line through `point` along `axis`.
    Cylinder {
        /// A point of the axis.
        point: Vector,
        /// Direction of the axis.
        axis: Vector,
        /// Radius.
        radius: f64,
        /// Displacement at the end of the run (default none).
        #[serde(default)]
        translate: Vector,
        /// Change of the radius at the end of the run (default none).
        #[serde(default, skip_serializing_if = "is_zero")]
        radius_change: f64,
        /// The motion over the run (default: the fraction of the run).
        #[serde(default, skip_serializing_if = "Option::is_none")]
        curve: Option<CurveSpec>,
    },
    /// A solid torus around the axis through `center` along `axis`: a ring (a tight band)
    /// whose hole, of radius `radius - tube`, a body passes through; `radius_change` moves the
    /// major radius, so a negative one tightens the band.
    Ring {
        /// The ring's centre.
        center: Vector,
        /// Direction of the axis (default `+z`).
        #[serde(default = "z_axis")]
        axis: Vector,
        /// Major radius, from the axis to the tube's centre circle.
        radius: f64,
        /// The tube's radius.
        tube: f64,
        /// Displacement at the end of the run (default none).
        #[serde(default)]
        translate: Vector,
        /// Change of the major radius at the end of the run (default none).
        #[serde(default, skip_serializing_if = "is_zero")]
        radius_change: f64,
        /// The motion over the run (default: the fraction of the run).
        #[serde(default, skip_serializing_if = "Option::is_none")]
        curve: Option<CurveSpec>,
    },
    /// A rigid triangle surface, open (a plate) or closed, read from an OBJ, STL (ASCII or
    /// binary) or Gmsh `.msh` file (its triangles), placed by `place` before anything else
    /// and moved by `translate` and `rotate`, both reached at the end of the run. It meets
    /// the bodies' surfaces in barrier contact (turned on with the `[contact]` defaults
    /// when the scene has no `[contact]` table).
    Mesh {
        /// The surface file; a relative path is resolved against the scene file's folder.
        path: PathBuf,
        /// Its name in output columns and files (default `obstacle<i>`, `i` its index in
        /// `[[obstacles]]`).
        #[serde(default, skip_serializing_if = "Option::is_none")]
        name: Option<String>,
        /// A rigid placement of the file's surface (as a body's `place`).
        #[serde(default, skip_serializing_if = "Option::is_none")]
        place: Option<PlacementSpec>,
        /// Displacement at the end of the run (default none).
        #[serde(default)]
        translate: Vector,
        /// A rotation reached at the end of the run (spelled as a Dirichlet `rotate`),
        /// before the translation.
        #[serde(default, skip_serializing_if = "Option::is_none")]
        rotate: Option<RotationSpec>,
        /// The motion over the run (default: the fraction of the run).
        #[serde(default, skip_serializing_if = "Option::is_none")]
        curve: Option<CurveSpec>,
    },
}

impl ObstacleSpec {
    /// Whether it is a meshed obstacle (barrier contact) rather than an analytic shape.
    pub fn is_mesh(&self) -> bool {
        matches!(self, ObstacleSpec::Mesh { .. })
    }

    /// The name of obstacle `index` in output columns and files.
    pub fn name(&self, index: usize) -> String {
        match self {
            ObstacleSpec::Mesh {
                name: Some(name), ..
            } => name.clone(),
            _ => format!("obstacle{index}"),
        }
    }

    /// The obstacle's motion curve, if it has one.
    pub fn curve(&self) -> &Option<CurveSpec> {
        match self {
            ObstacleSpec::HalfSpace { curve, .. }
            | ObstacleSpec::Sphere { curve, .. }
            | ObstacleSpec::Cylinder { curve, .. }
            | ObstacleSpec::Ring { curve, .. }
            | ObstacleSpec::Mesh { curve, .. } => curve,
        }
    }
}
