//! `[[bodies]]`: several bodies in one scene, each with its mesh, the material keys in which
//! it differs from `[material]`, a rigid placement and an initial velocity; a body of
//! `kind = "cloth"` is a sheet of fabric on a triangle surface instead ([`ClothMaterialSpec`]).

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
    /// A solid (tets, default) or a cloth (a triangle surface).
    #[serde(default, skip_serializing_if = "BodyKind::is_solid")]
    pub kind: BodyKind,
    /// Its mesh: every key of `[mesh]` (a generator or a file); a cloth's is the `band`
    /// generator or a surface file (OBJ, STL, Gmsh).
    pub mesh: MeshSpec,
    /// The keys of `[material]` in which this body differs (as a region's); every other key
    /// is the scene's `[material]`. A cloth's are the fabric's, [`ClothMaterialSpec`].
    #[serde(default, skip_serializing_if = "toml::Table::is_empty")]
    pub material: toml::Table,
    /// A rigid placement applied to the mesh before anything else.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub place: Option<PlacementSpec>,
    /// Initial velocity (m/s) of every node, for dynamics.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub velocity: Option<Vector>,
    /// A cloth's rest lengths are its placed lengths times this factor (below 1: tighter
    /// than placed).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub rest_scale: Option<f64>,
}

/// What a body is made of.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Deserialize, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum BodyKind {
    /// A solid of tets, of the scene's method and element.
    #[default]
    Solid,
    /// A sheet of fabric on a triangle surface (`isochor_solvers::ClothSheet`).
    Cloth,
}

impl BodyKind {
    fn is_solid(&self) -> bool {
        *self == BodyKind::Solid
    }
}

/// The `material` table of a cloth body: the fabric's constants, named as
/// `isochor_energies::cloth::Fabric::new` and `isochor_solvers::ClothSheet` name them. The
/// bending stiffness is the plate's, `D = E h^3 / (12 (1 - nu^2))`, not a key.
#[derive(Debug, Clone, Copy, PartialEq, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct ClothMaterialSpec {
    /// Young's modulus `E` of the fabric's material (Pa).
    pub young: f64,
    /// Poisson's ratio `nu` of the fabric's material, in `(-1, 0.5]`.
    pub poisson: f64,
    /// The sheet's thickness `h` (m).
    pub thickness: f64,
    /// Density of the fabric's material (kg/m^3): mass per rest area `density * thickness`.
    pub density: f64,
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
    /// A cloth's `rest_scale`.
    pub rest_scale: Option<f64>,
    /// Its index among `[[bodies]]` (`None`: the scene's own), for the keys of errors.
    pub index: Option<usize>,
}

impl<'a> BodyRef<'a> {
    /// The `[[bodies]]` entry number `index`.
    pub fn entry(index: usize, b: &'a BodySpec) -> Self {
        BodyRef {
            name: &b.name,
            mesh: &b.mesh,
            material: Some(&b.material),
            place: b.place.as_ref(),
            velocity: b.velocity,
            rest_scale: b.rest_scale,
            index: Some(index),
        }
    }

    /// The key of this body's `field`: `mesh` for the scene's own, `bodies.N.field` else.
    pub fn key(&self, field: &str) -> String {
        match self.index {
            Some(i) => format!("bodies.{i}.{field}"),
            None => field.to_string(),
        }
    }
}
