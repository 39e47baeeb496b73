//! The scene format: serde structs of a TOML scene file, one file per section, the names a
//! scene chooses from ([`names`]), parsing (`parse`), every check before a run
//! ([`validate`], [`limits`]), `--set` overrides ([`overrides`]) and finding a scene
//! ([`load`], [`builtin`]). Every struct denies unknown keys, so a typo is an error that names
//! the key and lists the valid ones.
//!
//! A scene holds what a run needs and nothing derived: the mesh (a generator with its
//! parameters, or a file), the method, the material, named geometric selections, Dirichlet
//! conditions and loads on those selections, zones, stepping, solver limits, probes, outputs,
//! and named variants (sets of `--set` overrides that reproduce a figure's columns).
//!
//! Inside this layer: `common` and `names` at the bottom, then the sections, then `scene`,
//! then `limits`, `overrides`, `validate`, `parse`, and `builtin`, `load` on top.

mod bodies;
pub mod builtin;
mod common;
mod conditions;
mod contact;
pub mod limits;
pub mod load;
mod material;
mod mesh;
pub mod names;
mod obstacles;
mod output;
pub mod overrides;
mod paper;
mod parse;
mod probes;
mod scene;
mod selections;
mod solver;
mod stepping;
pub mod validate;
mod zones;

pub use bodies::{
    BodyKind, BodyRef, BodySpec, ClothMaterialSpec, PlacementSpec, RotationSpec, SCENE_BODY,
};
pub use common::Vector;
pub use conditions::{CurveSpec, DirichletSpec, LoadsSpec, MotionSpec, PressureSpec, TractionSpec};
pub use contact::{ContactSpec, ObstacleFrictionSpec, PairFrictionSpec, DEFAULT_EPSV};
pub use load::{load_scene, SceneSource};
pub use material::{
    material_keys, rename_aliases, ConstantSpec, MaterialSpec, RegionSpec, MATERIAL_ALIASES,
};
pub use mesh::{Generated, GroupSpec, MeshSpec, Surface};
pub use names::{
    ComponentName, ElementName, EnergyName, JacobianName, KappaName, LengthUnit, LinearName,
    MethodName, ModelName, OrderingName, PointsName, PreconditionerName, PreviewField, Reduce,
    UnknownName, VtuEncodingName, ZonalEnergyName, ZoneKind,
};
pub use obstacles::ObstacleSpec;
pub use output::OutputSpec;
pub use overrides::Override;
pub use paper::PaperSpec;
pub use probes::ProbeSpec;
pub use scene::Scene;
pub use selections::{BoxSpec, PlaneSpec, RadialSpec, SelectionSpec, SphereSpec};
pub use solver::SolverSpec;
pub use stepping::{SteppingSpec, DEFAULT_VOLUME_RECOVERY, VOLUME_PROJECTIONS};
pub use zones::ZonesSpec;
