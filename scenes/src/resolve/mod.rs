//! A scene resolved once: the mesh built (with its groups), every named selection resolved to node,
//! vertex, face and tet sets, the zones and the regions, in one pass, into one [`ResolvedScene`]
//! value that the problem, the probes and the outputs all read. Nothing after this layer
//! re-resolves a selection or rebuilds a mesh.
//!
//! Inside this layer: `mesh`, then `selections`, then `zones`, `material` and `problem`, then
//! this module on top.

pub mod bodies;
pub mod cloth;
pub mod friction;
pub mod material;
pub mod mesh;
pub mod problem;
pub mod selections;
pub mod zones;

pub use bodies::{build_bodies, SceneBodies};
pub use material::build_material;
pub use mesh::{build_mesh, mesh_with_groups, read_mesh_file, SceneMesh};
pub use selections::Selections;

use crate::error::SceneError;
use crate::format::{limits, validate, ContactSpec, Scene};
use isochor_mesh::element::Part;
use isochor_mesh::Zones;
use isochor_solvers::{
    FrictionSpec, MeshObstacle, Method, Problem, Settings, Stepping, SurfaceContactSpec,
};

/// The default reach of the contact barrier, relative to the rest mesh's bounding-box
/// diagonal (IPC's default, Li et al. 2020).
pub const DEFAULT_DHAT: f64 = 1e-3;

/// A scene made concrete, once: everything a run needs.
#[derive(Debug, Clone)]
pub struct ResolvedScene {
    /// The problem (mesh, method, material, regions, zones, conditions, loads, obstacles).
    pub problem: Problem,
    /// Quasi-static steps or implicit Euler frames.
    pub stepping: Stepping,
    /// Newton limits and tolerances.
    pub settings: Settings,
    /// Every named selection on the mesh.
    pub selections: Selections,
    /// The scene's zones, if the method constrains them or a probe measures them.
    pub zones: Option<Zones>,
    /// Where each body lies in the mesh, and its initial velocity.
    pub bodies: SceneBodies,
    /// Barrier contact between surfaces, if the scene has `[contact]`.
    pub surface_contact: Option<SurfaceContactSpec>,
    /// Friction against the obstacles and between surfaces, if `[contact]` gives a non-zero
    /// coefficient.
    pub friction: Option<FrictionSpec>,
    /// The meshed obstacles (in barrier contact: `surface_contact` is then on).
    pub mesh_obstacles: Vec<MeshObstacle>,
    /// What a user should know about how the meshes were taken (the run's warnings).
    pub notices: Vec<String>,
}

/// Resolves a scene: checks that its estimated memory fits ([`limits`]), builds every body's
/// mesh with its groups and joins them ([`bodies`]), resolves every selection, the regions and the zones, and converts the rest to
/// the solver's types; then refuses a quasi-static scene whose supports leave a rigid motion
/// free and an obstacle that overlaps the body at the start ([`validate::problem`]).
pub fn build(scene: &Scene) -> Result<ResolvedScene, SceneError> {
    limits::check_memory(scene, &format!("scene {}", scene.name))?;
    let wants_groups = scene.selections.values().any(|s| s.physical.is_some());
    let (mesh, bodies) = build_bodies(scene, scene.element(), wants_groups)?;
    let material = build_material(&scene.material)?;
    let selections = Selections::of_bodies(&mesh, &bodies, &scene.selections)?;
    let regions = material::regions(scene, &selections, &bodies)?;
    let dirichlet = problem::dirichlet(scene, &selections)?;
    let loads = problem::loads(scene, &selections)?;
    let obstacles = problem::obstacles(scene)?;
    let mesh_obstacles = problem::mesh_obstacles(scene)?;
    let method = scene.method();
    let zones = if zones::needed(scene) {
        Some(zones::zones(
            scene,
            mesh.mesh.corners(),
            &selections,
            &bodies,
        )?)
    } else {
        None
    };
    let settings = Settings {
        volume_projection: problem::volume_projection(&scene.stepping),
        ..problem::settings(&scene.solver)
    };
    let stepping = problem::stepping(&scene.stepping);
    // A meshed obstacle turns barrier contact on, with the `[contact]` defaults (those of
    // an empty table).
    let defaults: ContactSpec = toml::from_str("").map_err(|e| SceneError::Invalid {
        origin: format!("scene {}", scene.name),
        key: "contact".into(),
        message: format!("the defaults of [contact]: {e}"),
    })?;
    let contact = scene
        .contact
        .as_ref()
        .or((!mesh_obstacles.is_empty()).then_some(&defaults));
    let surface_contact = contact.map(|c| {
        let (lo, hi) = mesh.mesh.corners().bounding_box();
        SurfaceContactSpec {
            dhat: c.dhat.unwrap_or(DEFAULT_DHAT * (hi - lo).norm()),
            self_contact: c.self_contact,
            node_bodies: bodies.node_bodies(mesh.mesh.num_nodes()),
        }
    });
    let friction = scene
        .contact
        .as_ref()
        .zip(surface_contact.as_ref())
        .and_then(|(c, s)| {
            let (meshed, analytic): (Vec<usize>, Vec<usize>) =
                (0..scene.obstacles.len()).partition(|&i| scene.obstacles[i].is_mesh());
            friction::friction(c, &bodies, [&analytic, &meshed], s.dhat)
        });
    let problem = Problem {
        mesh: mesh.mesh,
        method,
        material,
        regions,
        zones: zones.clone().filter(|_| method == Method::Zonal),
        dirichlet,
        loads,
        obstacles,
        cloths: bodies.cloths.clone(),
    };
    // The cloths rest on obstacles and bodies: only the solids need supports.
    let named: Vec<(&str, &Part)> = bodies.solids().collect();
    validate::problem(scene, &problem, &named, settings.contact_tolerance)?;
    let notices = mesh.notices;
    Ok(ResolvedScene {
        problem,
        stepping,
        settings,
        selections,
        zones,
        bodies,
        surface_contact,
        friction,
        mesh_obstacles,
        notices,
    })
}
