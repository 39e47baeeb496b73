//! Every check of a scene before a run, in one place: every number finite, the cross-key
//! rules serde cannot express (references to selections, ranges, choices), the `[paper]`
//! section, the bounds on steps ([`super::limits`]), and, once the problem is built, supports
//! that hold a quasi-static body and obstacles clear of the body at the start.

use super::bodies::{BodyKind, BodyRef, ClothMaterialSpec, SCENE_BODY};
use super::conditions::{CurveSpec, MotionSpec};
use super::limits;
use super::mesh::MeshSpec;
use super::names::{ZonalEnergyName, ZoneKind};
use super::obstacles::ObstacleSpec;
use super::overrides::check_key_syntax;
use super::paper::PaperSpec;
use super::probes::ProbeSpec;
use super::scene::Scene;
use super::stepping::{SteppingSpec, VOLUME_PROJECTIONS};
use crate::error::SceneError;
use isochor_mesh::element::Part;
use isochor_solvers::{Method, Problem, MIN_INCREMENT_FLOOR};
use serde::Deserialize;
use toml::Value;

/// Refuses NaN anywhere in a scene's TOML tree, and infinities except where a key accepts
/// one (`radial.max`), naming the key (`loads.gravity[1]`).
pub fn finite_numbers(tree: &Value, origin: &str) -> Result<(), SceneError> {
    let mut path = String::new();
    walk(tree, &mut path).map_err(|(key, message)| SceneError::Invalid {
        origin: origin.to_string(),
        key,
        message,
    })
}

fn walk(value: &Value, path: &mut String) -> Result<(), (String, String)> {
    match value {
        Value::Float(x) if x.is_nan() => Err((path.clone(), "NaN is not a number".into())),
        Value::Float(x) if x.is_infinite() && !(*x > 0.0 && path.ends_with("radial.max")) => {
            Err((path.clone(), format!("{x} is not a finite number")))
        }
        Value::Array(items) => items
            .iter()
            .enumerate()
            .try_for_each(|(i, item)| enter(path, &format!("[{i}]"), item)),
        Value::Table(table) => table.iter().try_for_each(|(key, item)| {
            let dot = if path.is_empty() { "" } else { "." };
            enter(path, &format!("{dot}{key}"), item)
        }),
        _ => Ok(()),
    }
}

/// Walks `item` with `segment` appended to `path`.
fn enter(path: &mut String, segment: &str, item: &Value) -> Result<(), (String, String)> {
    let len = path.len();
    path.push_str(segment);
    let result = walk(item, path);
    path.truncate(len);
    result
}

/// The key at fault and what is wrong with it.
type Fault = (String, String);

/// The check of one section of a scene.
type SectionCheck = fn(&Scene) -> Result<(), Fault>;

/// Checks the cross-key rules of `scene` (read from `origin`) that serde cannot express, one
/// section at a time, then the bounds on its steps.
pub fn scene(scene: &Scene, origin: &str) -> Result<(), SceneError> {
    let sections: [SectionCheck; 14] = [
        bodies,
        cloths,
        contact,
        obstacle_names,
        material_and_regions,
        selections,
        conditions,
        curves,
        zones,
        probes,
        stepping,
        solver_and_output,
        meshes,
        variants_and_paper,
    ];
    for check in sections {
        check(scene).map_err(|(key, message)| SceneError::Invalid {
            origin: origin.to_string(),
            key,
            message,
        })?;
    }
    limits::check_steps(scene, origin)
}

/// A fault at `key`.
fn fault(key: impl Into<String>, message: impl Into<String>) -> Fault {
    (key.into(), message.into())
}

/// Refuses a reference at `key` to a selection the scene does not define.
fn selection_defined(scene: &Scene, key: String, name: &str) -> Result<(), Fault> {
    if scene.selections.contains_key(name) {
        return Ok(());
    }
    let names = scene
        .selections
        .keys()
        .cloned()
        .collect::<Vec<_>>()
        .join(", ");
    Err(fault(
        key,
        format!("unknown selection '{name}' (defined: {names})"),
    ))
}

/// A body at least (`[mesh]` or `[[bodies]]`); bodies with distinct names, placements with a
/// non-zero axis, initial velocities only in dynamics; a selection's `body` names one.
fn bodies(scene: &Scene) -> Result<(), Fault> {
    if scene.mesh.is_none() && scene.bodies.is_empty() {
        return Err(fault(
            "mesh",
            "give [mesh] or at least one [[bodies]] entry",
        ));
    }
    let all: Vec<BodyRef> = scene.bodies().into_iter().chain(scene.cloths()).collect();
    for (i, body) in scene.bodies.iter().enumerate() {
        let key = format!("bodies.{i}");
        if body.name.is_empty() {
            return Err(fault(format!("{key}.name"), "must not be empty"));
        }
        if all.iter().filter(|b| b.name == body.name).count() > 1 {
            return Err(fault(
                format!("{key}.name"),
                format!(
                    "'{}' names two bodies (the scene's own [mesh] is '{SCENE_BODY}')",
                    body.name
                ),
            ));
        }
        if let Some(r) = body.place.as_ref().and_then(|p| p.rotate.as_ref()) {
            if r.axis.iter().all(|&a| a == 0.0) {
                return Err(fault(
                    format!("{key}.place.rotate.axis"),
                    "must not be zero",
                ));
            }
        }
        if body.velocity.is_some() && !scene.is_dynamic() {
            return Err(fault(
                format!("{key}.velocity"),
                "an initial velocity needs dynamic stepping",
            ));
        }
    }
    for (name, s) in &scene.selections {
        if let Some(body) = &s.body {
            if !all.iter().any(|b| b.name == body) {
                let names: Vec<&str> = all.iter().map(|b| b.name).collect();
                return Err(fault(
                    format!("selections.{name}.body"),
                    format!("no body named '{body}' (bodies: {})", names.join(", ")),
                ));
            }
        }
    }
    Ok(())
}

/// Cloth bodies (`kind = "cloth"`): a `band` or a surface file (`.obj`, `.stl`, `.msh`) for
/// mesh, the fabric's keys known and in range, a finite positive `rest_scale`, a solid body
/// beside it and 4-node tets; a solid body has no band and no
/// `rest_scale`. Each fault names the body.
fn cloths(scene: &Scene) -> Result<(), Fault> {
    for (i, body) in scene.bodies.iter().enumerate() {
        let key = |field: &str| format!("bodies.{i}.{field}");
        let name = &body.name;
        if body.kind == BodyKind::Solid {
            if matches!(body.mesh, MeshSpec::Band { .. }) {
                return Err(fault(
                    key("mesh.generator"),
                    format!(
                        "body '{name}': a band is a cloth surface: give the body kind = \"cloth\""
                    ),
                ));
            }
            if body.rest_scale.is_some() {
                return Err(fault(
                    key("rest_scale"),
                    format!("body '{name}': rest_scale is a cloth's key (kind = \"cloth\")"),
                ));
            }
            continue;
        }
        let cloth =
            |field: &str, message: String| fault(key(field), format!("cloth '{name}': {message}"));
        match &body.mesh {
            MeshSpec::Band { .. } => {}
            MeshSpec::File { path }
                if matches!(
                    path.extension()
                        .and_then(|e| e.to_str())
                        .map(str::to_ascii_lowercase)
                        .as_deref(),
                    Some("obj" | "stl" | "msh")
                ) => {}
            MeshSpec::File { path } => {
                return Err(cloth(
                    "mesh.path",
                    format!(
                        "{} is no surface file: give a .obj, .stl or .msh file",
                        path.display()
                    ),
                ))
            }
            other => {
                let generator = toml::Value::try_from(other)
                    .ok()
                    .and_then(|v| {
                        v.get("generator")
                            .and_then(|g| g.as_str().map(String::from))
                    })
                    .unwrap_or_default();
                return Err(cloth(
                    "mesh.generator",
                    format!("a cloth's mesh is the band generator or a surface file (path), not '{generator}'"),
                ));
            }
        }
        let fabric = ClothMaterialSpec::deserialize(toml::Value::Table(body.material.clone()))
            .map_err(|e| {
                cloth(
                    "material",
                    format!("{e} (the fabric's keys: young, poisson, thickness, density)"),
                )
            })?;
        if let Err(e) =
            isochor_energies::cloth::Fabric::new(fabric.young, fabric.poisson, fabric.thickness)
        {
            let field = match e.name {
                "E" => "young",
                "nu" => "poisson",
                other => other,
            };
            return Err(cloth(
                &format!("material.{field}"),
                format!("{} = {}: {}", field, e.value, e.reason),
            ));
        }
        if !(fabric.density.is_finite() && fabric.density > 0.0) {
            return Err(cloth(
                "material.density",
                format!(
                    "density = {} must be a finite, positive density (kg/m^3)",
                    fabric.density
                ),
            ));
        }
        if let Some(r) = body.rest_scale.filter(|r| !(r.is_finite() && *r > 0.0)) {
            return Err(cloth(
                "rest_scale",
                format!("rest_scale = {r} must be finite and positive"),
            ));
        }
        if scene.bodies().is_empty() {
            return Err(cloth(
                "kind",
                "needs a solid body beside it (a problem's mesh needs a tet)".into(),
            ));
        }
        if scene.element() != isochor_mesh::element::TetElement::Tet4 {
            return Err(fault(
                "element",
                format!("cloth '{name}' (bodies.{i}) sits beside 4-node tets only: element = \"tet10\" cannot take a cloth"),
            ));
        }
    }
    Ok(())
}

/// `[contact]`: a positive reach and slip length, finite non-negative friction
/// coefficients, pairs of bodies the scene has, obstacles it has.
fn contact(scene: &Scene) -> Result<(), Fault> {
    let Some(c) = scene.contact.as_ref() else {
        return Ok(());
    };
    for (key, value) in [("contact.dhat", c.dhat), ("contact.epsv", c.epsv)] {
        match value {
            Some(v) if !(v.is_finite() && v > 0.0) => {
                return Err(fault(key, format!("{v} must be a positive distance (m)")))
            }
            _ => {}
        }
    }
    let coefficient = |key: String, mu: f64| {
        if mu.is_finite() && mu >= 0.0 {
            Ok(())
        } else {
            Err(fault(
                key,
                format!("{mu} must be a finite, non-negative friction coefficient"),
            ))
        }
    };
    coefficient("contact.friction".into(), c.friction)?;
    let all = scene.bodies().into_iter().chain(scene.cloths());
    let names: Vec<&str> = all.map(|b| b.name).collect();
    for (i, pair) in c.pairs.iter().enumerate() {
        coefficient(format!("contact.pairs[{i}].friction"), pair.friction)?;
        if let Some(body) = pair.bodies.iter().find(|b| !names.contains(&b.as_str())) {
            return Err(fault(
                format!("contact.pairs[{i}].bodies"),
                format!("no body named '{body}' (bodies: {})", names.join(", ")),
            ));
        }
    }
    for (i, o) in c.obstacles.iter().enumerate() {
        coefficient(format!("contact.obstacles[{i}].friction"), o.friction)?;
        if o.obstacle >= scene.obstacles.len() {
            return Err(fault(
                format!("contact.obstacles[{i}].obstacle"),
                format!(
                    "no obstacle {} (the scene has {}, counted from 0)",
                    o.obstacle,
                    scene.obstacles.len()
                ),
            ));
        }
    }
    Ok(())
}

/// The obstacles' names (in output columns and file names): letters, digits, `-` and `_`,
/// each used once.
fn obstacle_names(scene: &Scene) -> Result<(), Fault> {
    let mut seen = std::collections::BTreeSet::new();
    for (i, o) in scene.obstacles.iter().enumerate() {
        let name = o.name(i);
        let plain = |c: char| c.is_ascii_alphanumeric() || c == '-' || c == '_';
        if name.is_empty() || !name.chars().all(plain) {
            return Err(fault(
                format!("obstacles.{i}.name"),
                format!(
                    "`{}` must be letters, digits, `-` and `_` (it names output columns and files)",
                    isochor_mesh::io::excerpt(&name)
                ),
            ));
        }
        if !seen.insert(name.clone()) {
            return Err(fault(
                format!("obstacles.{i}.name"),
                format!("`{name}` names an earlier obstacle too"),
            ));
        }
    }
    Ok(())
}

/// `[material]` gives one stiffness; every `[[regions]]` entry names a selection.
fn material_and_regions(scene: &Scene) -> Result<(), Fault> {
    if let (Some(_), Some(_)) = (scene.material.young, scene.material.mu) {
        return Err(fault("material", "give either young or mu, not both"));
    }
    for (i, r) in scene.regions.iter().enumerate() {
        selection_defined(scene, format!("regions.{i}.selection"), &r.selection)?;
        if r.material.is_empty() {
            return Err(fault(
                format!("regions.{i}.material"),
                format!(
                    "region '{}' changes nothing: give the keys of [material] that differ in it",
                    r.name
                ),
            ));
        }
    }
    Ok(())
}

/// Every selection selects something, with a valid tolerance.
fn selections(scene: &Scene) -> Result<(), Fault> {
    for (name, s) in &scene.selections {
        let key = format!("selections.{name}");
        let has_region = s.aabb.is_some()
            || s.plane.is_some()
            || s.half_space.is_some()
            || s.radial.is_some()
            || s.sphere.is_some()
            || s.vertices.is_some()
            || s.physical.is_some();
        if !(has_region || s.all || s.surface) {
            return Err(fault(
                key,
                "a selection needs at least one of box, plane, half_space, radial, sphere, vertices, physical, surface, all",
            ));
        }
        if let Some(t) = s.tolerance {
            if !(t.is_finite() && t >= 0.0) {
                return Err(fault(
                    format!("{key}.tolerance"),
                    format!("{t} must be finite and >= 0"),
                ));
            }
        }
    }
    Ok(())
}

/// Dirichlet conditions and loads name defined selections, and the conditions valid axes.
fn conditions(scene: &Scene) -> Result<(), Fault> {
    for (i, d) in scene.dirichlet.iter().enumerate() {
        selection_defined(scene, format!("dirichlet.{i}.selection"), &d.selection)?;
        if d.axes.is_empty() || !d.axes.chars().all(|c| matches!(c, 'x' | 'y' | 'z')) {
            return Err(fault(
                format!("dirichlet.{i}.axes"),
                format!(
                    "'{}' must be letters among x, y, z (e.g. \"xyz\", \"z\")",
                    d.axes
                ),
            ));
        }
    }
    for (i, t) in scene.loads.traction.iter().enumerate() {
        selection_defined(scene, format!("loads.traction.{i}.selection"), &t.selection)?;
    }
    for (i, p) in scene.loads.pressure.iter().enumerate() {
        let key = format!("loads.pressure.{i}");
        selection_defined(scene, format!("{key}.selection"), &p.selection)?;
        match (p.pressure, p.volume_ratio) {
            (Some(_), Some(_)) => return Err(fault(
                format!("{key}.volume_ratio"),
                "give either pressure (a given pressure) or volume_ratio (a held volume), not both",
            )),
            (None, None) => {
                return Err(fault(
                    key,
                    "give pressure (Pa) or volume_ratio (the cavity's volume over its rest volume)",
                ))
            }
            (_, Some(r)) if !(r > 0.0 && r.is_finite()) => {
                return Err(fault(
                    format!("{key}.volume_ratio"),
                    format!("{r} must be positive and finite"),
                ))
            }
            _ => {}
        }
        if p.origin.is_some_and(|o| !o.iter().all(|c| c.is_finite())) {
            return Err(fault(format!("{key}.origin"), "must be finite"));
        }
    }
    Ok(())
}

/// `[zones]`: what each kind needs, and painted zones on defined selections.
fn zones(scene: &Scene) -> Result<(), Fault> {
    let Some(z) = &scene.zones else {
        return Ok(());
    };
    match z.kind {
        ZoneKind::KRing if z.k.is_none_or(|k| k == 0) => {
            return Err(fault("zones.k", "k-ring zones need k >= 1"))
        }
        ZoneKind::Painted if z.paint.is_empty() => {
            return Err(fault(
                "zones.paint",
                "painted zones need a list of surface selections, one per zone",
            ))
        }
        ZoneKind::None
            if scene.material.zonal_penalty == Some(0.0)
                && scene.material.zonal_energy != Some(ZonalEnergyName::Standard) =>
        {
            return Err(fault(
                "material.zonal_penalty",
                "with zones.kind = \"none\" and zonal_penalty = 0 nothing resists a change of volume: give zonal_penalty > 0 or a zone",
            ))
        }
        _ => {}
    }
    for (i, name) in z.paint.iter().enumerate() {
        selection_defined(scene, format!("zones.paint.{i}"), name)?;
    }
    Ok(())
}

/// Every probe names what it needs: one of a point and a selection, defined selections,
/// an existing obstacle.
fn probes(scene: &Scene) -> Result<(), Fault> {
    for (name, p) in &scene.probes {
        let key = format!("probes.{name}");
        match p {
            ProbeSpec::Displacement {
                point, selection, ..
            } => {
                if point.is_some() == selection.is_some() {
                    return Err(fault(
                        key,
                        "a displacement probe needs exactly one of point and selection",
                    ));
                }
                if let Some(s) = selection {
                    selection_defined(scene, format!("{key}.selection"), s)?;
                }
            }
            ProbeSpec::VolumeRatio { selection: Some(s) }
            | ProbeSpec::LoopLength { selection: s }
            | ProbeSpec::Position {
                selection: Some(s), ..
            } => selection_defined(scene, format!("{key}.selection"), s)?,
            ProbeSpec::LoadPressure { load } | ProbeSpec::EnclosedVolumeRatio { load }
                if *load >= scene.loads.pressure.len() =>
            {
                return Err(fault(
                    format!("{key}.load"),
                    format!(
                        "pressure load {load} does not exist: the scene has {} [[loads.pressure]] (numbered from 0)",
                        scene.loads.pressure.len()
                    ),
                ));
            }
            ProbeSpec::Rotation { axis: Some(a), .. }
                if a.iter().all(|c| *c == 0.0) || !a.iter().all(|c| c.is_finite()) =>
            {
                return Err(fault(
                    format!("{key}.axis"),
                    "the axis must be finite and not zero",
                ));
            }
            ProbeSpec::RadiusIncrease { selection, .. }
            | ProbeSpec::Rotation { selection, .. }
            | ProbeSpec::ChamberVolumeRatio { selection } => {
                selection_defined(scene, format!("{key}.selection"), selection)?
            }
            ProbeSpec::MaxContactForce { obstacle: Some(k) } if *k >= scene.obstacles.len() => {
                return Err(fault(
                    format!("{key}.obstacle"),
                    format!(
                        "no obstacle {k}: the scene has {} (numbered from 0)",
                        scene.obstacles.len()
                    ),
                ))
            }
            _ => {}
        }
    }
    Ok(())
}

/// `[stepping]`: at least one step or frame, increments and time steps in range, the
/// volume projection's choices.
fn stepping(scene: &Scene) -> Result<(), Fault> {
    match scene.stepping {
        SteppingSpec::QuasiStatic { steps: 0, .. } => {
            Err(fault("stepping.steps", "at least one step is needed"))
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
                return Err(fault(
                    "stepping.increments",
                    format!("unknown value '{other}' (valid: adaptive, fixed)"),
                ));
            }
            if increments.as_deref() == Some("fixed") {
                for (key, value) in [
                    ("stepping.first_increment", first_increment),
                    ("stepping.min_increment", min_increment),
                ] {
                    if value.is_some() {
                        return Err(fault(
                            key,
                            "applies to increments = \"adaptive\" only (fixed stepping takes one solve per frame)",
                        ));
                    }
                }
            }
            let first = first_increment.unwrap_or(1.0);
            if !(first > 0.0 && first <= 1.0) {
                return Err(fault(
                    "stepping.first_increment",
                    format!("{first} must lie in (0, 1]"),
                ));
            }
            let min = min_increment.unwrap_or(1e-4);
            if !(min >= MIN_INCREMENT_FLOOR && min <= first) {
                return Err(fault(
                    "stepping.min_increment",
                    format!(
                        "{min:e} must lie in [{MIN_INCREMENT_FLOOR:e}, first_increment = {first}] \
                         (the floor is 30 halvings of the whole run)"
                    ),
                ));
            }
            Ok(())
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
                return Err(fault(
                    "stepping.volume_projection",
                    format!(
                        "unknown value '{other}' (valid: {})",
                        VOLUME_PROJECTIONS.join(", ")
                    ),
                ));
            }
            if let Some(r) = volume_recovery {
                if volume_projection.as_deref() != Some("one-ring") {
                    return Err(fault(
                        "stepping.volume_recovery",
                        "applies to volume_projection = \"one-ring\" only",
                    ));
                }
                if !(r > 0.0 && r <= 1.0) {
                    return Err(fault(
                        "stepping.volume_recovery",
                        format!("{r} must lie in (0, 1]"),
                    ));
                }
            }
            if frames == 0 {
                return Err(fault("stepping.frames", "at least one frame is needed"));
            }
            if !(dt.is_finite() && dt > 0.0) {
                return Err(fault("stepping.dt", format!("{dt} must be finite and > 0")));
            }
            Ok(())
        }
    }
}

/// Most points of one load curve. Every corner of a curve inside a quasi-static run is a
/// level the stepping stops at, a solve of its own: 10,001 corners took 79 s on two tets.
pub const MAX_CURVE_POINTS: usize = 10_000;

/// Every load curve of the scene, with its key.
fn all_curves(scene: &Scene) -> Vec<(String, &CurveSpec)> {
    let dirichlet = scene.dirichlet.iter().enumerate();
    let loads = &scene.loads;
    dirichlet
        .map(|(i, d)| (format!("dirichlet.{i}.curve"), d.curve.as_ref()))
        .chain([(
            "loads.gravity_curve".to_string(),
            loads.gravity_curve.as_ref(),
        )])
        .chain(
            loads
                .traction
                .iter()
                .enumerate()
                .map(|(i, t)| (format!("loads.traction.{i}.curve"), t.curve.as_ref())),
        )
        .chain(
            loads
                .pressure
                .iter()
                .enumerate()
                .map(|(i, p)| (format!("loads.pressure.{i}.curve"), p.curve.as_ref())),
        )
        .chain(
            scene
                .obstacles
                .iter()
                .enumerate()
                .map(|(i, o)| (format!("obstacles.{i}.curve"), o.curve().as_ref())),
        )
        .filter_map(|(key, curve)| Some((key, curve?)))
        .collect()
}

/// Each load curve has at most [`MAX_CURVE_POINTS`] points, and the levels of a quasi-static
/// run (its steps and the curves' corners inside the run) are at most
/// [`limits::MAX_STEPS`].
fn curves(scene: &Scene) -> Result<(), Fault> {
    let curves = all_curves(scene);
    for (key, curve) in &curves {
        if curve.len() > MAX_CURVE_POINTS {
            return Err(fault(
                key.clone(),
                format!(
                    "{} points: at most {MAX_CURVE_POINTS} (each corner inside the run is a solve of its own)",
                    curve.len()
                ),
            ));
        }
    }
    let end = match scene.stepping {
        SteppingSpec::QuasiStatic { .. } => 1.0,
        SteppingSpec::Dynamic { dt, frames, .. } => dt * frames as f64,
    };
    for (key, curve) in &curves {
        if let [first, _, ..] = curve.as_slice() {
            if first[0] >= end {
                return Err(fault(
                    key.clone(),
                    format!(
                        "every point lies at or beyond the run's end ({end}: {}), so the curve \
                         stays at its first value {} over the whole run",
                        if scene.is_dynamic() {
                            "frames * dt, in seconds"
                        } else {
                            "the load parameter of a quasi-static run"
                        },
                        first[1]
                    ),
                ));
            }
        }
    }
    if scene.loads.gravity_curve.is_some()
        && scene
            .loads
            .gravity
            .is_none_or(|g| g.iter().all(|&c| c == 0.0))
    {
        return Err(fault(
            "loads.gravity_curve",
            "the scene has no gravity (loads.gravity is missing or zero) for it to scale",
        ));
    }
    for (i, d) in scene.dirichlet.iter().enumerate() {
        if d.curve.is_some() && d.motion == MotionSpec::Fixed {
            return Err(fault(
                format!("dirichlet.{i}.curve"),
                "the support is fixed (no motion), so a curve changes nothing: give it a motion",
            ));
        }
    }
    if let SteppingSpec::QuasiStatic { steps, .. } = scene.stepping {
        let corners = curves
            .iter()
            .flat_map(|(_, c)| c.iter().map(|p| p[0]))
            .filter(|&s| s > 0.0 && s < 1.0)
            .count();
        if corners > 0 && steps.saturating_add(corners) > limits::MAX_STEPS {
            return Err(fault(
                "stepping.steps",
                format!(
                    "{steps} steps and {corners} load-curve corners inside the run: at most {} levels",
                    limits::MAX_STEPS
                ),
            ));
        }
    }
    Ok(())
}

/// `[solver]` and `[output]` keys that depend on the rest of the scene.
fn solver_and_output(scene: &Scene) -> Result<(), Fault> {
    if scene.solver.accept_unconverged == Some(true) && !scene.is_dynamic() {
        return Err(fault(
            "solver.accept_unconverged",
            "applies to dynamic stepping only: a quasi-static step must be an equilibrium",
        ));
    }
    if let Some(name) = scene
        .output
        .potential_against
        .as_ref()
        .filter(|n| !scene.probes.contains_key(*n))
    {
        return Err(fault(
            "output.potential_against",
            format!(
                "no probe named '{name}' (probes: {})",
                scene.probes.keys().cloned().collect::<Vec<_>>().join(", ")
            ),
        ));
    }
    if scene.output.every == 0 {
        return Err(fault("output.every", "must be at least 1"));
    }
    Ok(())
}

/// `[mesh]` and each body's mesh: resolutions and cell counts of the generators that have
/// them.
fn meshes(scene: &Scene) -> Result<(), Fault> {
    if let Some(spec) = &scene.mesh {
        mesh(spec).map_err(|(key, message)| (format!("mesh.{key}"), message))?;
    }
    for (i, body) in scene.bodies.iter().enumerate() {
        mesh(&body.mesh).map_err(|(key, message)| (format!("bodies.{i}.mesh.{key}"), message))?;
    }
    Ok(())
}

/// One mesh: its resolution and cell counts (the fault's key is within the mesh table).
fn mesh(spec: &MeshSpec) -> Result<(), Fault> {
    match spec {
        MeshSpec::Box {
            res,
            res_multiple_of,
            cells,
            ..
        } => {
            if *res == 0 || *res_multiple_of == 0 || res % res_multiple_of != 0 {
                return Err(fault(
                    "res",
                    format!("{res} must be a positive multiple of {res_multiple_of}"),
                ));
            }
            if cells.contains(&0) {
                return Err(fault("cells", "every entry must be at least 1"));
            }
            Ok(())
        }
        MeshSpec::Cylinder { res, .. }
        | MeshSpec::Puck { res, .. }
        | MeshSpec::Tube { res, .. }
        | MeshSpec::Ball { res, .. }
            if *res == 0 =>
        {
            Err(fault("res", "must be at least 1"))
        }
        _ => Ok(()),
    }
}

/// The keys of every variant, and the `[paper]` section.
fn variants_and_paper(scene: &Scene) -> Result<(), Fault> {
    for (variant, sets) in &scene.variants {
        for key in sets.keys() {
            check_key_syntax(key).map_err(|m| fault(format!("variants.{variant}.{key}"), m))?;
        }
    }
    match &scene.paper {
        Some(spec) => paper(spec, scene),
        None => Ok(()),
    }
}

/// Checks the section against its scene: the sweep key's syntax, distinct values, probes
/// the scene defines, method or variant names, and one value per swept value. The error
/// is the key at fault and what is wrong.
fn paper(spec: &PaperSpec, scene: &Scene) -> Result<(), Fault> {
    check_key_syntax(&spec.sweep).map_err(|m| ("paper.sweep".into(), m))?;
    if spec.values.is_empty() {
        return Err(("paper.values".into(), "give at least one value".into()));
    }
    for (i, v) in spec.values.iter().enumerate() {
        if spec.values[..i].contains(v) {
            return Err((format!("paper.values.{i}"), format!("{v} is given twice")));
        }
    }
    if spec.probes.is_empty() {
        return Err((
            "paper.probes".into(),
            "give the values of at least one probe".into(),
        ));
    }
    for (probe, labels) in &spec.probes {
        let key = format!("paper.probes.{probe}");
        if !scene.probes.contains_key(probe) {
            let defined: Vec<&str> = scene.probes.keys().map(String::as_str).collect();
            return Err((
                key,
                format!("unknown probe '{probe}' (defined: {})", defined.join(", ")),
            ));
        }
        for (label, values) in labels {
            let key = format!("{key}.{label}");
            if label.parse::<Method>().is_err() && !scene.variants.contains_key(label) {
                let variants: Vec<&str> = scene.variants.keys().map(String::as_str).collect();
                return Err((
                    key,
                    format!(
                        "'{label}' is neither a method ({}) nor a variant of the scene ({})",
                        Method::ALL.map(Method::name).join(", "),
                        variants.join(", ")
                    ),
                ));
            }
            if values.len() != spec.values.len() {
                return Err((
                    key,
                    format!(
                        "{} values, but paper.values has {}",
                        values.len(),
                        spec.values.len()
                    ),
                ));
            }
        }
    }
    Ok(())
}

/// The checks that need the built problem: supports that hold each quasi-static body (the
/// bodies by name and where they lie in the mesh), and
/// obstacles clear of the body at the start (`contact_tolerance` relative to the mesh's
/// bounding-box diagonal).
pub fn problem(
    scene: &Scene,
    problem: &Problem,
    bodies: &[(&str, &Part)],
    contact_tolerance: f64,
) -> Result<(), SceneError> {
    supports(scene, problem, bodies)?;
    obstacles_clear(scene, problem, contact_tolerance)
}

/// Refuses quasi-static stepping when the Dirichlet conditions leave a rigid motion of a body
/// free: the equilibrium is singular along it.
fn supports(scene: &Scene, problem: &Problem, bodies: &[(&str, &Part)]) -> Result<(), SceneError> {
    if scene.is_dynamic() {
        return Ok(());
    }
    for &(name, part) in bodies {
        let free = if let [_] = bodies {
            problem.unremoved_rigid_modes()
        } else {
            problem.unremoved_rigid_modes_of(&part.nodes().collect::<Vec<_>>())
        };
        if free == 0 {
            continue;
        }
        let body = if let [_] = bodies {
            "the body".to_string()
        } else {
            format!("body '{name}'")
        };
        return Err(SceneError::Invalid {
            origin: format!("scene {}", scene.name),
            key: "dirichlet".into(),
            message: format!(
                "quasi-static stepping needs supports that hold {body}, but the Dirichlet \
                 conditions leave {free} of its 6 rigid motions (3 translations, 3 rotations) \
                 free, and the equilibrium is singular along them: hold more of it (e.g. clamp \
                 a face, or three nodes not on one line in every axis), add an obstacle, or use \
                 dynamic stepping"
            ),
        });
    }
    Ok(())
}

/// Refuses an obstacle that holds nodes of the body at the start (signed distance below
/// `-tolerance` at the rest positions, `tolerance` relative to the mesh's bounding-box
/// diagonal as the contact tolerance is): contact would push them out in the first step, or
/// ignore an obstacle that lies inside the body.
fn obstacles_clear(scene: &Scene, problem: &Problem, tolerance: f64) -> Result<(), SceneError> {
    let nodes = problem.mesh.nodes();
    let (lo, hi) = nodes
        .iter()
        .fold((nodes[0], nodes[0]), |(lo, hi), x| (lo.inf(x), hi.sup(x)));
    let depth = tolerance * (hi - lo).norm();
    let analytic = scene
        .obstacles
        .iter()
        .enumerate()
        .filter(|(_, o)| !o.is_mesh());
    for (obstacle, (i, spec)) in problem.obstacles.iter().zip(analytic) {
        let (inside, deepest) = nodes
            .iter()
            .map(|x| obstacle.distance(x, 0.0).0)
            .filter(|&d| d < -depth)
            .fold((0usize, 0.0f64), |(n, deepest), d| (n + 1, deepest.min(d)));
        if inside > 0 {
            let kind = match spec {
                ObstacleSpec::HalfSpace { .. } => "half-space",
                ObstacleSpec::Sphere { .. } => "sphere",
                ObstacleSpec::Cylinder { .. } => "cylinder",
                ObstacleSpec::Ring { .. } => "ring",
                ObstacleSpec::Mesh { .. } => "meshed",
            };
            return Err(SceneError::Invalid {
                origin: format!("scene {}", scene.name),
                key: format!("obstacles[{i}]"),
                message: format!(
                    "the {kind} obstacle overlaps the body at the start: {inside} of its {} \
                     nodes lie inside it (the deepest {:.3e} inside); place it clear of the \
                     rest shape and move it in with `translate`",
                    nodes.len(),
                    -deepest
                ),
            });
        }
    }
    Ok(())
}

/// What a scene asks for that a user may mean but likely does not, as warnings (printed on
/// stderr and kept in the run's summary): a massless body whose only load is gravity.
pub fn warnings(scene: &Scene) -> Vec<String> {
    let mut warnings = Vec::new();
    let gravity = scene
        .loads
        .gravity
        .is_some_and(|g| g.iter().any(|&c| c != 0.0));
    let other_loads = !scene.loads.traction.is_empty()
        || !scene.loads.pressure.is_empty()
        || !scene.obstacles.is_empty()
        || scene
            .dirichlet
            .iter()
            .any(|d| d.motion != MotionSpec::Fixed);
    let massive_region = scene.regions.iter().any(|r| {
        r.material.get("rho").and_then(Value::as_float) != Some(0.0)
            && r.material.contains_key("rho")
    });
    if gravity && !other_loads && scene.material.rho == 0.0 && !massive_region {
        warnings
            .push("material.rho = 0 and gravity is the only load: the body carries no load".into());
    }
    warnings
}

#[cfg(test)]
mod tests {
    use super::*;

    fn check(text: &str) -> Result<(), (String, String)> {
        walk(&toml::from_str(text).unwrap(), &mut String::new())
    }

    #[test]
    fn non_finite_numbers_are_named_by_key() {
        assert_eq!(
            check("[loads]\ngravity = [0, nan, 0]"),
            Err(("loads.gravity[1]".into(), "NaN is not a number".into()))
        );
        assert_eq!(
            check("[[obstacles]]\ncenter = [0, 0, 0]\n[[obstacles]]\nradius = -inf"),
            Err((
                "obstacles[1].radius".into(),
                "-inf is not a finite number".into()
            ))
        );
        assert_eq!(
            check("[mesh]\npositions = [[0, 0, 0], [1, inf, 0]]"),
            Err((
                "mesh.positions[1][1]".into(),
                "inf is not a finite number".into()
            ))
        );
        assert!(check("[selections.a.radial]\nmax = inf\nmin = 0.5").is_ok());
        assert!(check("[selections.a.radial]\nmin = inf").is_err());
    }
}
