//! The scene format: serde structs of a TOML scene file. Every struct denies unknown keys, so a
//! typo is an error that names the key and lists the valid ones.
//!
//! A scene holds what a run needs and nothing derived: the mesh (a generator with its
//! parameters, or a file), the method, the material, named geometric selections, Dirichlet
//! conditions and loads on those selections, zones, stepping, solver limits, probes, outputs,
//! and named variants (sets of `--set` overrides that reproduce a figure's columns).

use crate::paper::PaperSpec;
use crate::SceneError;
use isochor_mesh::element::TetElement;
use isochor_mesh::io::VtuEncoding;
use isochor_solvers::Method;
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;
use std::path::PathBuf;

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
    /// The mesh.
    pub mesh: MeshSpec,
    /// Material parameters.
    pub material: MaterialSpec,
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
    /// Named sets of overrides (flat or dotted keys, as `--set`), e.g. the columns of a figure.
    #[serde(default)]
    pub variants: BTreeMap<String, BTreeMap<String, toml::Value>>,
    /// Published values of the probes over a swept parameter, which `isochor compare` prints
    /// beside its own.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub paper: Option<PaperSpec>,
}

/// A method name, checked against [`Method::ALL`] while parsing.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize, Serialize)]
#[serde(try_from = "String", into = "String")]
pub struct MethodName(pub Method);

impl TryFrom<String> for MethodName {
    type Error = String;
    fn try_from(s: String) -> Result<Self, String> {
        s.parse::<Method>()
            .map(MethodName)
            .map_err(|e| e.to_string())
    }
}

impl From<MethodName> for String {
    fn from(m: MethodName) -> String {
        m.0.name().to_string()
    }
}

/// An element name, `"tet4"` or `"tet10"`, checked while parsing.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize, Serialize)]
#[serde(try_from = "String", into = "String")]
pub struct ElementName(pub TetElement);

impl Default for ElementName {
    fn default() -> Self {
        ElementName(TetElement::Tet4)
    }
}

impl TryFrom<String> for ElementName {
    type Error = String;
    fn try_from(s: String) -> Result<Self, String> {
        TetElement::from_name(&s).map(ElementName).ok_or_else(|| {
            let valid: Vec<&str> = TetElement::ALL.iter().map(|e| e.name()).collect();
            format!("unknown element '{s}' (valid: {})", valid.join(", "))
        })
    }
}

impl From<ElementName> for String {
    fn from(e: ElementName) -> String {
        e.0.name().to_string()
    }
}

/// A point or vector `[x, y, z]`.
pub type Vector = [f64; 3];

/// Where the mesh comes from.
#[derive(Debug, Clone, PartialEq, Deserialize, Serialize)]
#[serde(tag = "generator", rename_all = "kebab-case", deny_unknown_fields)]
pub enum MeshSpec {
    /// A box `[min, max]` with `res * cells` hexes per axis, Kuhn-split into 6 tets each.
    Box {
        /// Lower corner.
        min: Vector,
        /// Upper corner.
        max: Vector,
        /// Resolution multiplier.
        res: usize,
        /// Cells per axis per unit of `res` (default `[1, 1, 1]`).
        #[serde(default = "ones")]
        cells: [usize; 3],
        /// `res` must be a multiple of this (so that load patches fall on grid lines).
        #[serde(default = "one")]
        res_multiple_of: usize,
    },
    /// A solid cylinder about the z axis from `z = 0` to `height`.
    Cylinder {
        /// Radius.
        radius: f64,
        /// Height.
        height: f64,
        /// Resolution: cells across the radius.
        res: usize,
    },
    /// A puck (short cylinder with at least `res` layers).
    Puck {
        /// Radius.
        radius: f64,
        /// Height.
        height: f64,
        /// Resolution: cells across the radius (and at least this many layers).
        res: usize,
    },
    /// A thick-walled tube about the z axis from `z = 0` to `height`.
    Tube {
        /// Inner radius.
        inner_radius: f64,
        /// Outer radius.
        outer_radius: f64,
        /// Height.
        height: f64,
        /// Resolution: cells across the wall.
        res: usize,
    },
    /// A ball centred at `center`.
    Ball {
        /// Radius.
        radius: f64,
        /// Resolution: cells across the radius.
        res: usize,
        /// Centre (default the origin).
        #[serde(default)]
        center: Vector,
    },
    /// The spine arm of Francu et al. 2021: a 0.25 x 0.03 x 0.03 m bar along x with five
    /// square through-holes (`isochor_mesh::generate::spine_arm`, `1260 res^3` tets).
    Spine {
        /// Resolution: cells per centimetre.
        res: usize,
    },
    /// The "cushion" of Francu et al. 2021, Fig. 6 (shape ours): a 40 x 40 x 13 mm pad with a
    /// closed 30 x 30 x 4 mm chamber (`isochor_mesh::generate::cushion`, `768 res^3` tets),
    /// groups `base`, `chamber`, `top`.
    Cushion {
        /// Resolution: cells across the thinnest wall.
        res: usize,
    },
    /// The "bubble" of Francu et al. 2021, Fig. 6 (shape ours): a 40 x 40 x 15 mm block with a
    /// closed 30 x 30 x 6 mm chamber under a 3 mm membrane (`isochor_mesh::generate::bubble`,
    /// `552 res^3` tets), groups `base`, `chamber`, `membrane`.
    Bubble {
        /// Resolution: cells across the membrane.
        res: usize,
    },
    /// The "finger" of Francu et al. 2021, Fig. 6 (shape ours): a 64 x 10 x 16 mm PneuNet-style
    /// bender with five chambers joined by a channel above a strain-limiting base
    /// (`isochor_mesh::generate::finger`, `1494 res^3` tets), groups `base`, `chamber`, `tip`.
    Finger {
        /// Resolution: cells across a chamber wall.
        res: usize,
    },
    /// A torso on the tops of two legs (Sheen et al. 2021, Figs. 1 and 4; shape ours): 0.34 m
    /// wide at the hips, 0.45 m tall, the waist at z = 0.34 m, rounded sections
    /// (`isochor_mesh::generate::torso`, `2016 res^3` tets), groups `legs` (the legs' cut
    /// faces, z = 0) and `top` (the cut at the chest).
    Torso {
        /// Resolution: cells about 4 cm wide at 1 (8 res across the hips), 2 cm high at the
        /// waist.
        res: usize,
    },
    /// A creature-like body standing in for the armadillo of Sheen et al. 2021, sec. 8.7
    /// (shape ours): a 160 x 80 x 50 mm torso on four legs, a thin neck and a head, 260 mm
    /// long (`isochor_mesh::generate::creature`, `942 res^3` tets), group `feet`.
    Creature {
        /// Resolution: cells across the neck.
        res: usize,
    },
    /// Explicit vertices and tets (small test scenes such as Fig. 2 of Sheen et al.).
    Explicit {
        /// Vertex positions.
        positions: Vec<Vector>,
        /// Tets, as four vertex indices each.
        tets: Vec<[usize; 4]>,
    },
    /// A mesh file: Gmsh `.msh`, TetGen `.node`/`.ele` (either name), or `.vtu`. A relative
    /// path is resolved against the scene file's folder (or the working directory).
    File {
        /// The file.
        path: PathBuf,
    },
}

/// The message without the "in `key`" line the TOML deserializer appends (the key is
/// reported separately).
fn first_line(message: &str) -> String {
    message
        .lines()
        .filter(|l| !l.trim().is_empty() && !l.starts_with("in `"))
        .collect::<Vec<_>>()
        .join(" ")
}

fn is_false(b: &bool) -> bool {
    !*b
}

fn ones() -> [usize; 3] {
    [1, 1, 1]
}

fn one() -> usize {
    1
}

/// Material parameters. Give exactly one of `young` and `mu`, or, for the models with
/// constants (`mooney-rivlin`, `yeoh`, `ogden`), the constants and neither.
#[derive(Debug, Clone, PartialEq, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct MaterialSpec {
    /// The hyperelastic model (default `neo-hookean`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub model: Option<ModelName>,
    /// Mooney-Rivlin and Yeoh: coefficient of `Ib1 - 3` (Pa).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub c10: Option<f64>,
    /// Mooney-Rivlin: coefficient of `Ib2 - 3` (Pa, default 0).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub c01: Option<f64>,
    /// Yeoh: coefficient of `(Ib1 - 3)^2` (Pa, default 0).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub c20: Option<f64>,
    /// Yeoh: coefficient of `(Ib1 - 3)^3` (Pa, default 0).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub c30: Option<f64>,
    /// Ogden: the terms `[[mu_p, alpha_p], ...]` (`mu_p` in Pa).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub ogden: Option<Vec<[f64; 2]>>,
    /// Young's modulus `E` (Pa).
    pub young: Option<f64>,
    /// Shear modulus `mu` (Pa), instead of `young`.
    pub mu: Option<f64>,
    /// Poisson's ratio.
    pub nu: f64,
    /// Density (kg/m^3).
    #[serde(default = "default_density")]
    pub rho: f64,
    /// Local penalty stiffness `lambda` of the zonal method (default: equivalent to nu = 0.45).
    pub lambda: Option<f64>,
    /// Steepness `beta` of `U(J; beta)` (eq. 13 of Sheen et al.).
    pub beta: Option<f64>,
    /// Threshold `epsilon` of the F-bar C2 extension (eq. 11 of Sheen et al.).
    pub epsilon: Option<f64>,
    /// Volumetric stiffness of the mixed methods: `bulk` or `lambda`.
    pub kappa: Option<KappaName>,
    /// The energy under the zonal constraints: `constrained` or `standard`.
    pub zonal_energy: Option<ZonalEnergyName>,
    /// Base Poisson ratio of the augmented dual solver, or `0` for plain dual ascent.
    pub dual_base_nu: Option<f64>,
    /// Whether the epidermis surface energy (eq. 16 of Sheen et al.) is on.
    #[serde(default, skip_serializing_if = "is_false")]
    pub epidermis: bool,
    /// Young's modulus of the epidermis (Pa).
    pub epidermis_young: Option<f64>,
    /// Poisson's ratio of the epidermis.
    pub epidermis_nu: Option<f64>,
    /// Steepness of the epidermis area penalty.
    pub epidermis_gamma: Option<f64>,
}

fn default_density() -> f64 {
    1000.0
}

/// A part of the body with its own material: the tets of a named selection (centroid inside
/// its region, or the elements of a physical volume group).
#[derive(Debug, Clone, PartialEq, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct RegionSpec {
    /// Name, for outputs and errors.
    pub name: String,
    /// The named selection (`[selections.NAME]`) whose tets form the region.
    pub selection: String,
    /// The keys of `[material]` that differ in this region (`young` replaces the body's `mu`
    /// and the other way round); every other key is the body's.
    pub material: toml::Table,
}

/// `model` choice (see `isochor_solvers::MaterialModel`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum ModelName {
    /// Neo-Hookean in each method's form.
    NeoHookean,
    /// Uncoupled Mooney-Rivlin (`c10`, `c01`).
    MooneyRivlin,
    /// Yeoh (`c10`, `c20`, `c30`).
    Yeoh,
    /// Uncoupled Ogden (`ogden` terms).
    Ogden,
    /// Stable neo-Hookean (`young` or `mu`).
    StableNeoHookean,
    /// Isochoric neo-Hookean of Bonet and Wood (`young` or `mu`).
    BonetWood,
}

impl ModelName {
    /// The name as scenes write it.
    pub fn name(self) -> &'static str {
        match self {
            ModelName::NeoHookean => "neo-hookean",
            ModelName::MooneyRivlin => "mooney-rivlin",
            ModelName::Yeoh => "yeoh",
            ModelName::Ogden => "ogden",
            ModelName::StableNeoHookean => "stable-neo-hookean",
            ModelName::BonetWood => "bonet-wood",
        }
    }
}

/// `kappa` choice.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum KappaName {
    /// The bulk modulus (the default).
    Bulk,
    /// The first Lame parameter.
    Lambda,
}

/// `zonal_energy` choice.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum ZonalEnergyName {
    /// F-bar deviatoric neo-Hookean plus `lambda U(J; beta)` (the default).
    Constrained,
    /// The standard coupled neo-Hookean.
    Standard,
}

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

fn z_axis() -> Vector {
    [0.0, 0.0, 1.0]
}

fn infinity() -> f64 {
    f64::INFINITY
}

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
}

fn is_zero(x: &f64) -> bool {
    *x == 0.0
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

/// A follower pressure (Pa, positive pushes into the body) on the boundary faces of a selection.
#[derive(Debug, Clone, PartialEq, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct PressureSpec {
    /// The selection whose boundary faces are loaded.
    pub selection: String,
    /// Pressure (Pa).
    pub pressure: f64,
    /// Scale over the run (default: the load ramp).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub curve: Option<CurveSpec>,
}

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

/// Zone layout.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum ZoneKind {
    /// One zone holding every tet.
    Global,
    /// Overlapping k-ring zones covering the mesh.
    KRing,
    /// Zones painted on the surface (labels of the scene).
    Painted,
    /// No zone: the zonal energy (`lambda U(J; beta)` under the F-bar energy) alone holds the
    /// volume, "ours without volume constraint" of Table 1 of Sheen et al. 2021. An error
    /// with `lambda = 0`, which leaves the volume free.
    None,
}

/// Quasi-static load stepping or implicit Euler dynamics.
#[derive(Debug, Clone, PartialEq, Deserialize, Serialize)]
#[serde(tag = "mode", rename_all = "kebab-case", deny_unknown_fields)]
pub enum SteppingSpec {
    /// Loads and motions follow the load parameter from 0 to 1; the levels `k / steps` are
    /// written as frames. `increments = "adaptive"` (default) starts with `first_increment`
    /// of the load (default 1: all of it, never past a frame level), halves the increment
    /// after a failed solve down to `min_increment` (default 1e-3) and doubles it after easy
    /// steps; `"fixed"` takes one solve per frame and stops at the first failure.
    QuasiStatic {
        /// Number of frames.
        steps: usize,
        /// `"adaptive"` (default) or `"fixed"` (a string checked when the scene is loaded, so
        /// that a bad value names its key).
        #[serde(default, skip_serializing_if = "Option::is_none")]
        increments: Option<String>,
        /// The first increment (default 1).
        #[serde(default, skip_serializing_if = "Option::is_none")]
        first_increment: Option<f64>,
        /// The smallest increment (default 1e-3).
        #[serde(default, skip_serializing_if = "Option::is_none")]
        min_increment: Option<f64>,
    },
    /// Implicit Euler with time step `dt` (s) for `frames` frames, each step followed by the
    /// volume projection `volume_projection` (the baselines of Fig. 8 of Sheen et al. 2021,
    /// see `isochor_solvers::VolumeProjection`).
    Dynamic {
        /// Time step (s).
        dt: f64,
        /// Number of steps (each a frame).
        frames: usize,
        /// `none` (default), `one-ring` (Irving et al. 2007) or `global-rescale` (a string
        /// checked when the scene is loaded, so that a bad value names its key).
        #[serde(default, skip_serializing_if = "Option::is_none")]
        volume_projection: Option<String>,
        /// `one-ring` only: the largest change of a one ring's volume per step, relative to
        /// its rest volume (default [`DEFAULT_VOLUME_RECOVERY`]).
        #[serde(default, skip_serializing_if = "Option::is_none")]
        volume_recovery: Option<f64>,
    },
}

/// The one-ring projection's volume recovery per step when the scene gives none: 1% of a
/// one ring's rest volume (a choice of ours; Sheen et al. 2021 do not give theirs).
pub const DEFAULT_VOLUME_RECOVERY: f64 = 0.01;

/// The values of `stepping.volume_projection`.
pub const VOLUME_PROJECTIONS: [&str; 3] = ["none", "one-ring", "global-rescale"];

/// Newton limits and tolerances (defaults: the solver's).
#[derive(Debug, Clone, PartialEq, Default, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct SolverSpec {
    /// Newton iterations per step.
    pub max_iterations: Option<usize>,
    /// Force tolerance, relative to the force scale.
    pub force_tolerance: Option<f64>,
    /// Constraint tolerance, relative to the rest volumes.
    pub constraint_tolerance: Option<f64>,
    /// Line-search backtracks per iteration.
    pub max_backtracks: Option<usize>,
    /// Dual ascent iterations per step.
    pub max_dual_iterations: Option<usize>,
    /// Whether element Hessians are projected to PSD.
    pub project_hessians: Option<bool>,
    /// `direct`, `iterative`, or `auto` (direct up to
    /// [`isochor_solvers::AUTO_DIRECT_UNKNOWNS`] unknowns, iterative above).
    pub linear: Option<LinearName>,
    /// The tightest relative residual of the iterative linear solver (the floor of its
    /// inexact-Newton forcing terms; default 1e-8).
    pub linear_tolerance: Option<f64>,
    /// Iteration limit of the iterative linear solver.
    pub linear_max_iterations: Option<usize>,
    /// Fill-reducing ordering of the direct factorizations: `amd`, `nested-dissection`
    /// (METIS) or `auto` (the default: AMD on small systems, nested dissection on large).
    pub ordering: Option<OrderingName>,
    /// Preconditioner of the iterative linear solver's stiffness block:
    /// `incomplete-cholesky` (default) or `jacobi`.
    pub linear_preconditioner: Option<PreconditionerName>,
    /// Largest accepted penetration into an obstacle, relative to the mesh's bounding-box
    /// diagonal (default 1e-6).
    pub contact_tolerance: Option<f64>,
    /// Contact multiplier updates per step (default 30).
    pub max_contact_iterations: Option<usize>,
    /// Dynamics only: accept a step after `max_iterations` Newton iterations even if the
    /// tolerances are not met (a fixed iteration count, as in Fig. 9 of Francu et al. 2021);
    /// such steps and the run are reported as not converged.
    pub accept_unconverged: Option<bool>,
}

impl SolverSpec {
    /// The linear solver chosen: `linear`, else `iterative` when any `linear_*` key of the
    /// iterative solver is given, else `direct`.
    pub fn linear_choice(&self) -> LinearName {
        let iterative_key = self.linear_tolerance.is_some()
            || self.linear_max_iterations.is_some()
            || self.linear_preconditioner.is_some();
        match self.linear {
            Some(name) => name,
            None if iterative_key => LinearName::Iterative,
            None => LinearName::Direct,
        }
    }
}

/// Linear solver choice.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum LinearName {
    /// Sparse direct factorization.
    Direct,
    /// CG or MINRES.
    Iterative,
    /// Direct for small systems, iterative for large ones.
    Auto,
}

/// Preconditioner of the iterative linear solver.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum PreconditionerName {
    /// Diagonal scaling.
    Jacobi,
    /// Zero-fill incomplete Cholesky.
    IncompleteCholesky,
    /// Smoothed-aggregation algebraic multigrid.
    Multigrid,
}

/// Fill-reducing ordering choice.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum OrderingName {
    /// Approximate minimum degree.
    Amd,
    /// Nested dissection (METIS).
    NestedDissection,
    /// By size (see `isochor_solvers::linear::Ordering::AUTO_THRESHOLD`).
    Auto,
}

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

/// A unit of length for showing a probe.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize, Serialize)]
pub enum LengthUnit {
    /// Metres.
    #[serde(rename = "m")]
    Metre,
    /// Centimetres.
    #[serde(rename = "cm")]
    Centimetre,
    /// Millimetres.
    #[serde(rename = "mm")]
    Millimetre,
}

impl LengthUnit {
    /// The unit's symbol.
    pub fn symbol(self) -> &'static str {
        match self {
            LengthUnit::Metre => "m",
            LengthUnit::Centimetre => "cm",
            LengthUnit::Millimetre => "mm",
        }
    }

    /// A length in metres, in this unit.
    pub fn from_metres(self, metres: f64) -> f64 {
        match self {
            LengthUnit::Metre => metres,
            LengthUnit::Centimetre => 100.0 * metres,
            LengthUnit::Millimetre => 1000.0 * metres,
        }
    }
}

/// A displacement component.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum ComponentName {
    /// The x component.
    X,
    /// The y component.
    Y,
    /// The z component.
    Z,
    /// The length.
    Norm,
}

/// How a probe reduces over a selection.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Deserialize, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Reduce {
    /// The mean (the default).
    #[default]
    Mean,
    /// The largest value.
    Max,
    /// The smallest value.
    Min,
}

/// An energy name.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum EnergyName {
    /// Kinetic energy.
    Kinetic,
    /// Stored elastic energy.
    Elastic,
    /// Potential of the external loads.
    External,
    /// Energy of the compliant volume constraints (the mixed methods' volumetric energy).
    Constraint,
    /// Elastic, constraint and external: the total potential energy.
    Potential,
    /// Kinetic plus potential.
    Total,
}

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

fn yes() -> bool {
    true
}

impl Default for OutputSpec {
    fn default() -> Self {
        OutputSpec {
            every: 1,
            vtu: true,
            plots: true,
            vtu_encoding: VtuEncodingName::Auto,
            preview: None,
            preview_field: PreviewField::Displacement,
            preview_rest: true,
            potential_against: None,
        }
    }
}

/// The `output.preview_field` key: what colors the preview, with the values of the VTU
/// frames' field of that name.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Deserialize, Serialize)]
pub enum PreviewField {
    /// Length of the node displacement, averaged over the nodes of each drawn triangle.
    #[default]
    #[serde(rename = "displacement")]
    Displacement,
    /// Von Mises stress of the tet behind each boundary face.
    #[serde(rename = "von_mises")]
    VonMises,
    /// Mean stress `tr(sigma)/3` (tension positive) of the tet behind each boundary face.
    #[serde(rename = "mean_stress")]
    MeanStress,
    /// Volume ratio of the tet behind each boundary face.
    #[serde(rename = "J")]
    J,
}

impl PreviewField {
    /// The key's value, which is also the name of the VTU field.
    pub fn name(self) -> &'static str {
        match self {
            PreviewField::Displacement => "displacement",
            PreviewField::VonMises => "von_mises",
            PreviewField::MeanStress => "mean_stress",
            PreviewField::J => "J",
        }
    }
}

/// The `output.vtu_encoding` key.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Deserialize, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum VtuEncodingName {
    /// Binary for meshes of at least [`VtuEncodingName::AUTO_BINARY_NODES`] nodes, ASCII below
    /// (small outputs stay readable as text).
    #[default]
    Auto,
    /// zlib-compressed appended binary.
    Binary,
    /// Text.
    Ascii,
}

impl VtuEncodingName {
    /// Nodes from which `auto` writes binary frames.
    pub const AUTO_BINARY_NODES: usize = 10_000;

    /// The encoding of the frames of a mesh of `nodes` nodes.
    pub fn resolve(self, nodes: usize) -> VtuEncoding {
        match self {
            VtuEncodingName::Binary => VtuEncoding::Binary,
            VtuEncodingName::Ascii => VtuEncoding::Ascii,
            VtuEncodingName::Auto if nodes >= Self::AUTO_BINARY_NODES => VtuEncoding::Binary,
            VtuEncodingName::Auto => VtuEncoding::Ascii,
        }
    }
}

impl Scene {
    /// Parses a scene from TOML text. `origin` names the source in errors.
    pub fn from_toml_str(text: &str, origin: &str) -> Result<Scene, SceneError> {
        let value: toml::Value = toml::from_str(text).map_err(|e| SceneError::Toml {
            origin: origin.to_string(),
            message: e.to_string(),
        })?;
        Scene::from_value(value, origin)
    }

    /// Deserializes a scene from a TOML value tree, naming the key of the first error.
    pub fn from_value(value: toml::Value, origin: &str) -> Result<Scene, SceneError> {
        crate::checks::finite_numbers(&value, origin)?;
        let scene: Scene = serde_path_to_error::deserialize(value).map_err(|e| {
            let key = e.path().to_string();
            SceneError::Invalid {
                origin: origin.to_string(),
                key: if key == "." { String::new() } else { key },
                message: first_line(&e.into_inner().to_string()),
            }
        })?;
        scene.validate(origin)?;
        Ok(scene)
    }

    /// The scene as a TOML value tree.
    pub fn to_value(&self) -> toml::Value {
        toml::Value::try_from(self).expect("a scene always serializes")
    }

    /// The scene as TOML text.
    pub fn to_toml_string(&self) -> String {
        toml::to_string(self).expect("a scene always serializes")
    }

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

    /// Whether the scene is dynamic.
    pub fn is_dynamic(&self) -> bool {
        matches!(self.stepping, SteppingSpec::Dynamic { .. })
    }

    /// Checks the cross-key rules serde cannot: references to selections, ranges, choices.
    fn validate(&self, origin: &str) -> Result<(), SceneError> {
        let bad = |key: &str, message: String| SceneError::Invalid {
            origin: origin.to_string(),
            key: key.to_string(),
            message,
        };
        let names = || {
            self.selections
                .keys()
                .cloned()
                .collect::<Vec<_>>()
                .join(", ")
        };
        let check_selection = |key: String, name: &str| {
            if self.selections.contains_key(name) {
                Ok(())
            } else {
                Err(bad(
                    &key,
                    format!("unknown selection '{name}' (defined: {})", names()),
                ))
            }
        };
        if let (Some(_), Some(_)) = (self.material.young, self.material.mu) {
            return Err(bad("material", "give either young or mu, not both".into()));
        }
        for (i, r) in self.regions.iter().enumerate() {
            check_selection(format!("regions.{i}.selection"), &r.selection)?;
        }
        for (name, s) in &self.selections {
            let key = format!("selections.{name}");
            let has_region = s.aabb.is_some()
                || s.plane.is_some()
                || s.half_space.is_some()
                || s.radial.is_some()
                || s.sphere.is_some()
                || s.vertices.is_some()
                || s.physical.is_some();
            if !(has_region || s.all || s.surface) {
                return Err(bad(
                    &key,
                    "a selection needs at least one of box, plane, half_space, radial, sphere, vertices, physical, surface, all".into(),
                ));
            }
            if let Some(t) = s.tolerance {
                if !(t.is_finite() && t >= 0.0) {
                    return Err(bad(
                        &format!("{key}.tolerance"),
                        format!("{t} must be finite and >= 0"),
                    ));
                }
            }
        }
        for (i, d) in self.dirichlet.iter().enumerate() {
            check_selection(format!("dirichlet.{i}.selection"), &d.selection)?;
            if d.axes.is_empty() || !d.axes.chars().all(|c| matches!(c, 'x' | 'y' | 'z')) {
                return Err(bad(
                    &format!("dirichlet.{i}.axes"),
                    format!(
                        "'{}' must be letters among x, y, z (e.g. \"xyz\", \"z\")",
                        d.axes
                    ),
                ));
            }
        }
        for (i, t) in self.loads.traction.iter().enumerate() {
            check_selection(format!("loads.traction.{i}.selection"), &t.selection)?;
        }
        for (i, p) in self.loads.pressure.iter().enumerate() {
            check_selection(format!("loads.pressure.{i}.selection"), &p.selection)?;
        }
        if let Some(z) = &self.zones {
            match z.kind {
                ZoneKind::KRing if z.k.is_none_or(|k| k == 0) => {
                    return Err(bad("zones.k", "k-ring zones need k >= 1".into()))
                }
                ZoneKind::Painted if z.paint.is_empty() => {
                    return Err(bad(
                        "zones.paint",
                        "painted zones need a list of surface selections, one per zone".into(),
                    ))
                }
                ZoneKind::None
                    if self.material.lambda == Some(0.0)
                        && self.material.zonal_energy != Some(ZonalEnergyName::Standard) =>
                {
                    return Err(bad(
                        "material.lambda",
                        "with zones.kind = \"none\" and lambda = 0 nothing resists a change of volume: give lambda > 0 or a zone".into(),
                    ))
                }
                _ => {}
            }
            for (i, name) in z.paint.iter().enumerate() {
                check_selection(format!("zones.paint.{i}"), name)?;
            }
        }
        for (name, p) in &self.probes {
            let key = format!("probes.{name}");
            match p {
                ProbeSpec::Displacement {
                    point, selection, ..
                } => {
                    if point.is_some() == selection.is_some() {
                        return Err(bad(
                            &key,
                            "a displacement probe needs exactly one of point and selection".into(),
                        ));
                    }
                    if let Some(s) = selection {
                        check_selection(format!("{key}.selection"), s)?;
                    }
                }
                ProbeSpec::VolumeRatio { selection: Some(s) }
                | ProbeSpec::Position {
                    selection: Some(s), ..
                } => check_selection(format!("{key}.selection"), s)?,
                ProbeSpec::RadiusIncrease { selection, .. }
                | ProbeSpec::ChamberVolumeRatio { selection } => {
                    check_selection(format!("{key}.selection"), selection)?
                }
                ProbeSpec::MaxContactForce { obstacle: Some(k) } if *k >= self.obstacles.len() => {
                    return Err(bad(
                        &format!("{key}.obstacle"),
                        format!(
                            "no obstacle {k}: the scene has {} (numbered from 0)",
                            self.obstacles.len()
                        ),
                    ))
                }
                _ => {}
            }
        }
        match self.stepping {
            SteppingSpec::QuasiStatic { steps: 0, .. } => {
                return Err(bad("stepping.steps", "at least one step is needed".into()))
            }
            SteppingSpec::QuasiStatic {
                ref increments,
                first_increment,
                min_increment,
                ..
            } => {
                if let Some(other) = increments
                    .as_deref()
                    .filter(|i| !["adaptive", "fixed"].contains(i))
                {
                    return Err(bad(
                        "stepping.increments",
                        format!("unknown value '{other}' (valid: adaptive, fixed)"),
                    ));
                }
                let first = first_increment.unwrap_or(1.0);
                if !(first > 0.0 && first <= 1.0) {
                    return Err(bad(
                        "stepping.first_increment",
                        format!("{first} must lie in (0, 1]"),
                    ));
                }
                let min = min_increment.unwrap_or(1e-4);
                if !(min > 0.0 && min <= first) {
                    return Err(bad(
                        "stepping.min_increment",
                        format!("{min} must lie in (0, first_increment = {first}]"),
                    ));
                }
            }
            SteppingSpec::Dynamic {
                dt,
                frames,
                ref volume_projection,
                volume_recovery,
            } => {
                if let Some(other) = volume_projection
                    .as_deref()
                    .filter(|p| !VOLUME_PROJECTIONS.contains(p))
                {
                    return Err(bad(
                        "stepping.volume_projection",
                        format!(
                            "unknown value '{other}' (valid: {})",
                            VOLUME_PROJECTIONS.join(", ")
                        ),
                    ));
                }
                if let Some(r) = volume_recovery {
                    if volume_projection.as_deref() != Some("one-ring") {
                        return Err(bad(
                            "stepping.volume_recovery",
                            "applies to volume_projection = \"one-ring\" only".into(),
                        ));
                    }
                    if !(r > 0.0 && r <= 1.0) {
                        return Err(bad(
                            "stepping.volume_recovery",
                            format!("{r} must lie in (0, 1]"),
                        ));
                    }
                }
                if frames == 0 {
                    return Err(bad(
                        "stepping.frames",
                        "at least one frame is needed".into(),
                    ));
                }
                if !(dt.is_finite() && dt > 0.0) {
                    return Err(bad("stepping.dt", format!("{dt} must be finite and > 0")));
                }
            }
        }
        if self.solver.accept_unconverged == Some(true) && !self.is_dynamic() {
            return Err(bad(
                "solver.accept_unconverged",
                "applies to dynamic stepping only: a quasi-static step must be an equilibrium"
                    .into(),
            ));
        }
        if let Some(name) = self
            .output
            .potential_against
            .as_ref()
            .filter(|n| !self.probes.contains_key(*n))
        {
            return Err(bad(
                "output.potential_against",
                format!(
                    "no probe named '{name}' (probes: {})",
                    self.probes.keys().cloned().collect::<Vec<_>>().join(", ")
                ),
            ));
        }
        if self.output.every == 0 {
            return Err(bad("output.every", "must be at least 1".into()));
        }
        match &self.mesh {
            MeshSpec::Box {
                res,
                res_multiple_of,
                cells,
                ..
            } => {
                if *res == 0 || *res_multiple_of == 0 || res % res_multiple_of != 0 {
                    return Err(bad(
                        "mesh.res",
                        format!("{res} must be a positive multiple of {res_multiple_of}"),
                    ));
                }
                if cells.contains(&0) {
                    return Err(bad("mesh.cells", "every entry must be at least 1".into()));
                }
            }
            MeshSpec::Cylinder { res, .. }
            | MeshSpec::Puck { res, .. }
            | MeshSpec::Tube { res, .. }
            | MeshSpec::Ball { res, .. }
                if *res == 0 =>
            {
                return Err(bad("mesh.res", "must be at least 1".into()))
            }
            _ => {}
        }
        for (variant, sets) in &self.variants {
            for key in sets.keys() {
                crate::overrides::check_key_syntax(key)
                    .map_err(|m| bad(&format!("variants.{variant}.{key}"), m))?;
            }
        }
        if let Some(paper) = &self.paper {
            paper.validate(self).map_err(|(key, m)| bad(&key, m))?;
        }
        crate::limits::check_steps(self, origin)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn auto_encoding_is_binary_from_ten_thousand_nodes() {
        let auto = VtuEncodingName::Auto;
        assert_eq!(auto.resolve(9_999), VtuEncoding::Ascii);
        assert_eq!(auto.resolve(10_000), VtuEncoding::Binary);
        assert_eq!(VtuEncodingName::Ascii.resolve(1 << 20), VtuEncoding::Ascii);
        assert_eq!(VtuEncodingName::Binary.resolve(4), VtuEncoding::Binary);
    }
}
