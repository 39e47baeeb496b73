//! `[[bodies]]`: several bodies in one scene, each with its mesh, the material keys in which
//! it differs from `[material]`, a rigid placement and an initial velocity.

use super::common::Vector;
use super::mesh::MeshSpec;
use serde::{Deserialize, Serialize};

/// The name of the scene's own body (`[mesh]` with `[material]`) among its bodies.
pub const SCENE_BODY: &str = "body";

/// One body of a scene.
#[derive(Debug, Clone, PartialEq, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct BodySpec {
    /// Its name, for selections (`body = "NAME"`), outputs and errors.
    pub name: String,
    /// Its mesh: every key of `[mesh]` (a generator or a file).
    pub mesh: MeshSpec,
    /// The keys of `[material]` in which this body differs (as a region's); every other key
    /// is the scene's `[material]`.
    #[serde(default, skip_serializing_if = "toml::Table::is_empty")]
    pub material: toml::Table,
    /// A rigid placement applied to the mesh before anything else.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub place: Option<PlacementSpec>,
    /// Initial velocity (m/s) of every node, for dynamics.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub velocity: Option<Vector>,
}

/// A rigid placement: the rotation first, then the translation.
#[derive(Debug, Clone, PartialEq, Default, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct PlacementSpec {
    /// Offset added to every node.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub translate: Option<Vector>,
    /// A rotation by `degrees` about `axis` through `center`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub rotate: Option<RotationSpec>,
}

/// A rotation about an axis, spelled as a Dirichlet `rotate` motion.
#[derive(Debug, Clone, PartialEq, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct RotationSpec {
    /// A point of the axis (default the origin).
    #[serde(default)]
    pub center: Vector,
    /// Direction of the axis (need not be a unit vector).
    pub axis: Vector,
    /// Angle in degrees (right-handed about `axis`).
    pub degrees: f64,
}

/// A body of a scene as the layers above read it: the scene's own body or a `[[bodies]]`
/// entry.
#[derive(Debug, Clone, Copy)]
pub struct BodyRef<'a> {
    /// Its name ([`SCENE_BODY`] for the scene's own).
    pub name: &'a str,
    /// Its mesh.
    pub mesh: &'a MeshSpec,
    /// The material keys in which it differs from `[material]` (`None`: the scene's own).
    pub material: Option<&'a toml::Table>,
    /// Its placement.
    pub place: Option<&'a PlacementSpec>,
    /// Its initial velocity.
    pub velocity: Option<Vector>,
}

impl<'a> From<&'a BodySpec> for BodyRef<'a> {
    fn from(b: &'a BodySpec) -> Self {
        BodyRef {
            name: &b.name,
            mesh: &b.mesh,
            material: Some(&b.material),
            place: b.place.as_ref(),
            velocity: b.velocity,
        }
    }
}
