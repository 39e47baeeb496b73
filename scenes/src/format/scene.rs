//! The whole scene: one field per section of the file.

use super::bodies::{BodyKind, BodyRef, BodySpec, SCENE_BODY};
use super::conditions::{DirichletSpec, LoadsSpec};
use super::contact::ContactSpec;
use super::material::{MaterialSpec, RegionSpec};
use super::mesh::MeshSpec;
use super::names::{ElementName, MethodName};
use super::obstacles::ObstacleSpec;
use super::output::OutputSpec;
use super::paper::PaperSpec;
use super::probes::ProbeSpec;
use super::selections::SelectionSpec;
use super::solver::SolverSpec;
use super::stepping::SteppingSpec;
use super::zones::ZonesSpec;
use isochor_mesh::element::TetElement;
use isochor_solvers::Method;
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;

/// A whole scene file.
#[derive(Debug, Clone, PartialEq, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct Scene {
    /// Short name (the built-in name, or the file stem).
    pub name: String,
    /// What the scene reproduces.
    #[serde(default)]
    pub description: String,
    /// The method (see [`Method::ALL`] for the names).
    pub method: MethodName,
    /// The element: `"tet4"` (default) or `"tet10"`, orthogonal to the method.
    #[serde(default)]
    pub element: ElementName,
    /// The mesh of the scene's own body (named `"body"`); may be left out when `[[bodies]]`
    /// lists every body.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub mesh: Option<MeshSpec>,
    /// Material parameters of the scene's own body, and the keys every other body and region
    /// inherits.
    pub material: MaterialSpec,
    /// More bodies (`[[bodies]]`), each with its mesh, its differing material keys, a rigid
    /// placement and an initial velocity.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub bodies: Vec<BodySpec>,
    /// Parts of the body with their own material (`[[regions]]`), each the tets of a
    /// selection; elements no region claims are made of `[material]`.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub regions: Vec<RegionSpec>,
    /// Named geometric selections, referenced by boundary conditions, loads and probes.
    #[serde(default)]
    pub selections: BTreeMap<String, SelectionSpec>,
    /// Dirichlet conditions.
    #[serde(default)]
    pub dirichlet: Vec<DirichletSpec>,
    /// External loads.
    #[serde(default)]
    pub loads: LoadsSpec,
    /// Rigid obstacles (frictionless contact with the boundary vertices).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub obstacles: Vec<ObstacleSpec>,
    /// Barrier contact between the bodies' surfaces and of a surface with itself.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub contact: Option<ContactSpec>,
    /// Zones of the `zonal` method (one global zone if absent; `kind = "none"` for none).
    #[serde(default)]
    pub zones: Option<ZonesSpec>,
    /// Quasi-static steps or implicit Euler frames.
    pub stepping: SteppingSpec,
    /// Newton limits, tolerances and the linear solver.
    #[serde(default)]
    pub solver: SolverSpec,
    /// Named scalar results measured on the final state.
    #[serde(default)]
    pub probes: BTreeMap<String, ProbeSpec>,
    /// What `--out` writes.
    #[serde(default)]
    pub output: OutputSpec,
    /// The overrides of the scene's quick version (`--set` strings, applied in order), used
    /// by the test suite: the same physics on a coarse mesh with few steps or frames, so that
    /// every variant runs in well under a second in the dev profile (the overrides are part
    /// of each pinned value's key, so changing one means pinning anew).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub reduced: Vec<String>,
    /// Named sets of overrides (flat or dotted keys, as `--set`), e.g. the columns of a figure.
    #[serde(default)]
    pub variants: BTreeMap<String, BTreeMap<String, toml::Value>>,
    /// Published values of the probes over a swept parameter, which `isochor compare` prints
    /// beside its own.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub paper: Option<PaperSpec>,
}

impl Scene {
    /// The method.
    pub fn method(&self) -> Method {
        self.method.0
    }

    /// The element.
    pub fn element(&self) -> TetElement {
        self.element.0
    }

    /// The stepping's number of steps or frames.
    pub fn num_steps(&self) -> usize {
        match self.stepping {
            SteppingSpec::QuasiStatic { steps, .. } => steps,
            SteppingSpec::Dynamic { frames, .. } => frames,
        }
    }

    /// Every solid body in order: the scene's own (`[mesh]`, named `"body"`) if it has one,
    /// then the solid `[[bodies]]` entries.
    pub fn bodies(&self) -> Vec<BodyRef<'_>> {
        let own = self.mesh.as_ref().map(|mesh| BodyRef {
            name: SCENE_BODY,
            mesh,
            material: None,
            place: None,
            velocity: None,
            rest_scale: None,
            index: None,
        });
        let solids = self.entries(BodyKind::Solid);
        own.into_iter().chain(solids).collect()
    }

    /// The cloth bodies (`[[bodies]]` with `kind = "cloth"`), in order.
    pub fn cloths(&self) -> Vec<BodyRef<'_>> {
        self.entries(BodyKind::Cloth).collect()
    }

    /// The `[[bodies]]` entries of one kind.
    fn entries(&self, kind: BodyKind) -> impl Iterator<Item = BodyRef<'_>> {
        let entries = self.bodies.iter().enumerate();
        entries
            .filter(move |(_, b)| b.kind == kind)
            .map(|(i, b)| BodyRef::entry(i, b))
    }

    /// Every solid body's mesh, in the order of [`Scene::bodies`].
    pub fn meshes(&self) -> impl Iterator<Item = &MeshSpec> {
        let solids = self.bodies.iter().filter(|b| b.kind == BodyKind::Solid);
        self.mesh.iter().chain(solids.map(|b| &b.mesh))
    }

    /// Whether the scene is dynamic.
    pub fn is_dynamic(&self) -> bool {
        matches!(self.stepping, SteppingSpec::Dynamic { .. })
    }
}
