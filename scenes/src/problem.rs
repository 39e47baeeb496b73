//! From a scene to what the solver takes: the mesh, an [`isochor_solvers::Problem`] holding
//! only the terms the scene names, the [`Stepping`] and the [`Settings`].

use crate::checks;
use crate::scene::{
    CurveSpec, KappaName, LinearName, MaterialSpec, MeshSpec, ModelName, MotionSpec, ObstacleSpec,
    OrderingName, PreconditionerName, Scene, SolverSpec, SteppingSpec, ZonalEnergyName, ZoneKind,
    DEFAULT_VOLUME_RECOVERY,
};
use crate::selection::Selections;
use crate::SceneError;
use isochor_energies::ParameterError;
use isochor_mesh::element::TetElement;
use isochor_mesh::{generate, ElementMesh, TetMesh, Vec3, Zones};
use isochor_solvers::linear::Ordering;
use isochor_solvers::{
    Adaptive, Curve, Dirichlet, Epidermis, IterativeSettings, Kappa, LinearSolver, Load, Material,
    MaterialModel, Method, Motion, Obstacle, PreconditionerKind, Problem, Region, ScheduledLoad,
    Settings, Shape, StepControl, Stepping, VolumeProjection, ZonalEnergy,
};
use std::path::Path;

/// A scene made concrete: everything a run needs.
#[derive(Debug, Clone)]
pub struct Built {
    /// The problem (mesh, method, material, zones, conditions, loads).
    pub problem: Problem,
    /// Quasi-static steps or implicit Euler frames.
    pub stepping: Stepping,
    /// Newton limits and tolerances.
    pub settings: Settings,
}

/// Builds the mesh, problem, stepping and settings of a scene, after checking that its
/// estimated memory fits ([`crate::limits`]); refuses a quasi-static scene whose supports
/// leave a rigid motion free and an obstacle that overlaps the body at the start.
pub fn build(scene: &Scene) -> Result<Built, SceneError> {
    crate::limits::check_memory(scene, &format!("scene {}", scene.name))?;
    let mesh = build_mesh(&scene.mesh, scene.element())?;
    let material = build_material(&scene.material)?;
    let selections = Selections::new(&mesh, &scene.mesh, &scene.selections)?;
    let regions = scene
        .regions
        .iter()
        .enumerate()
        .map(|(i, r)| {
            Ok(Region {
                name: r.name.clone(),
                elements: selections.tets(&r.selection)?,
                material: region_material(&scene.material, &r.material, i)?,
            })
        })
        .collect::<Result<Vec<_>, SceneError>>()?;
    let dirichlet = scene
        .dirichlet
        .iter()
        .enumerate()
        .map(|(i, d)| {
            Ok(Dirichlet {
                nodes: selections.nodes(&d.selection)?,
                axes: ['x', 'y', 'z'].map(|c| d.axes.contains(c)),
                motion: motion(&d.motion),
                curve: curve(&d.curve, &format!("dirichlet.{i}.curve"))?,
            })
        })
        .collect::<Result<Vec<_>, SceneError>>()?;
    let mut loads = Vec::new();
    if let Some(g) = scene.loads.gravity {
        loads.push(ScheduledLoad {
            load: Load::Gravity(vec3(g)),
            curve: curve(&scene.loads.gravity_curve, "loads.gravity_curve")?,
        });
    }
    for (i, t) in scene.loads.traction.iter().enumerate() {
        loads.push(ScheduledLoad {
            load: Load::Traction {
                faces: selections.faces(&t.selection)?,
                traction: vec3(t.traction),
            },
            curve: curve(&t.curve, &format!("loads.traction.{i}.curve"))?,
        });
    }
    for (i, p) in scene.loads.pressure.iter().enumerate() {
        loads.push(ScheduledLoad {
            load: Load::Pressure {
                faces: selections.faces(&p.selection)?,
                pressure: p.pressure,
            },
            curve: curve(&p.curve, &format!("loads.pressure.{i}.curve"))?,
        });
    }
    let obstacles = scene
        .obstacles
        .iter()
        .enumerate()
        .map(|(i, o)| obstacle(o, i))
        .collect::<Result<Vec<_>, SceneError>>()?;
    let method = scene.method();
    let zones = if method == Method::Zonal {
        Some(build_zones(scene, mesh.corners(), &selections)?)
    } else {
        None
    };
    drop(selections);
    let problem = Problem {
        mesh,
        method,
        material,
        regions,
        zones,
        dirichlet,
        loads,
        obstacles,
    };
    let settings = Settings {
        volume_projection: volume_projection(&scene.stepping),
        ..settings(&scene.solver)
    };
    checks::supports(scene, &problem)?;
    checks::obstacles_clear(scene, &problem, settings.contact_tolerance)?;
    Ok(Built {
        problem,
        stepping: stepping(&scene.stepping),
        settings,
    })
}

/// The solver's curve of the scene key `key`.
fn curve(spec: &Option<CurveSpec>, key: &str) -> Result<Option<Curve>, SceneError> {
    spec.as_ref()
        .map(|points| {
            Curve::new(points.iter().map(|p| (p[0], p[1])).collect()).map_err(|e| {
                SceneError::Invalid {
                    origin: "scene".into(),
                    key: key.to_string(),
                    message: e.to_string(),
                }
            })
        })
        .transpose()
}

/// The solver's obstacle number `index` (its shape checked when the simulation is built).
fn obstacle(spec: &ObstacleSpec, index: usize) -> Result<Obstacle, SceneError> {
    let (shape, translate, radius_change, points) = match *spec {
        ObstacleSpec::HalfSpace {
            point,
            normal,
            translate,
            ref curve,
        } => (
            Shape::HalfSpace {
                point: vec3(point),
                normal: vec3(normal),
            },
            translate,
            0.0,
            curve,
        ),
        ObstacleSpec::Sphere {
            center,
            radius,
            translate,
            radius_change,
            ref curve,
        } => (
            Shape::Sphere {
                center: vec3(center),
                radius,
            },
            translate,
            radius_change,
            curve,
        ),
        ObstacleSpec::Cylinder {
            point,
            axis,
            radius,
            translate,
            radius_change,
            ref curve,
        } => (
            Shape::Cylinder {
                point: vec3(point),
                axis: vec3(axis),
                radius,
            },
            translate,
            radius_change,
            curve,
        ),
        ObstacleSpec::Ring {
            center,
            axis,
            radius,
            tube,
            translate,
            radius_change,
            ref curve,
        } => (
            Shape::Ring {
                center: vec3(center),
                axis: vec3(axis),
                radius,
                tube,
            },
            translate,
            radius_change,
            curve,
        ),
    };
    Ok(Obstacle {
        shape,
        translate: vec3(translate),
        radius_change,
        curve: curve(points, &format!("obstacles.{index}.curve"))?,
    })
}

fn vec3(a: [f64; 3]) -> Vec3 {
    Vec3::new(a[0], a[1], a[2])
}

/// Generates or reads the mesh, with elements of `element`: a linear mesh (generated or read)
/// becomes 10-node by adding mid-edge nodes, on the true surface for the curved generators
/// (cylinder, puck, tube, ball) and at edge midpoints otherwise (a file's true surface is
/// unknown); a 10-node file is used as it is, or reduced to its corners for `tet4`.
pub fn build_mesh(spec: &MeshSpec, element: TetElement) -> Result<ElementMesh, SceneError> {
    type Surface = Box<dyn Fn(&Vec3, &Vec3) -> Option<Vec3>>;
    let (mesh, surface): (TetMesh, Option<Surface>) = match spec {
        MeshSpec::Box {
            min,
            max,
            res,
            cells,
            ..
        } => (
            generate::box_grid(vec3(*min), vec3(*max), cells.map(|c| c * res))?,
            None,
        ),
        MeshSpec::Cylinder {
            radius,
            height,
            res,
        } => (
            generate::cylinder(*radius, *height, *res)?,
            Some(Box::new(generate::cylinder_surface(*radius))),
        ),
        MeshSpec::Puck {
            radius,
            height,
            res,
        } => (
            generate::puck(*radius, *height, *res)?,
            Some(Box::new(generate::cylinder_surface(*radius))),
        ),
        MeshSpec::Tube {
            inner_radius,
            outer_radius,
            height,
            res,
        } => (
            generate::tube(*inner_radius, *outer_radius, *height, *res)?.mesh,
            Some(Box::new(generate::tube_surface(
                *inner_radius,
                *outer_radius,
            ))),
        ),
        MeshSpec::Spine { res } => (generate::spine_arm(*res)?.0, None),
        MeshSpec::Cushion { res } => (generate::cushion(*res)?.0, None),
        MeshSpec::Bubble { res } => (generate::bubble(*res)?.0, None),
        MeshSpec::Finger { res } => (generate::finger(*res)?.0, None),
        MeshSpec::Torso { res } => (generate::torso(*res)?.0, None),
        MeshSpec::Creature { res } => (generate::creature(*res)?.0, None),
        MeshSpec::Ball {
            radius,
            res,
            center,
        } => {
            let ball = generate::ball(*radius, *res)?;
            let c = vec3(*center);
            let moved = ball.positions().iter().map(|x| x + c).collect();
            let sphere = generate::ball_surface(*radius);
            (
                TetMesh::new(moved, ball.tets().to_vec())?,
                Some(Box::new(move |a: &Vec3, b: &Vec3| {
                    sphere(&(a - c), &(b - c)).map(|p| p + c)
                })),
            )
        }
        MeshSpec::Explicit { positions, tets } => (
            TetMesh::new(positions.iter().map(|p| vec3(*p)).collect(), tets.clone())?,
            None,
        ),
        MeshSpec::File { path } => {
            let read = read_mesh_file(path)?;
            return Ok(match (element, read.kind()) {
                (TetElement::Tet4, TetElement::Tet10) => ElementMesh::linear(read.into_corners()),
                (TetElement::Tet10, TetElement::Tet4) => {
                    ElementMesh::quadratic(read.into_corners())
                }
                _ => read,
            });
        }
    };
    Ok(match (element, surface) {
        (TetElement::Tet4, _) => ElementMesh::linear(mesh),
        (TetElement::Tet10, None) => ElementMesh::quadratic(mesh),
        (TetElement::Tet10, Some(surface)) => ElementMesh::quadratic_on_surface(mesh, surface)?,
    })
}

/// Reads a mesh file of 4- or 10-node tets by its extension; a missing file or a folder is
/// said to be one.
pub fn read_mesh_file(path: &Path) -> Result<ElementMesh, SceneError> {
    const VALID: &str = ".msh (Gmsh), .node/.ele (TetGen), .vtu";
    let check = |p: &Path| -> Result<(), SceneError> {
        let message = if p.is_dir() {
            "is a directory, not a mesh file"
        } else if p.is_file() {
            return Ok(());
        } else {
            "mesh file not found"
        };
        Err(SceneError::io(
            p,
            std::io::Error::new(std::io::ErrorKind::NotFound, message),
        ))
    };
    let ext = path
        .extension()
        .and_then(|e| e.to_str())
        .unwrap_or("")
        .to_ascii_lowercase();
    match ext.as_str() {
        "node" | "ele" => {
            check(&path.with_extension("node"))?;
            check(&path.with_extension("ele"))?;
        }
        "msh" | "vtu" => check(path)?,
        _ if path.is_dir() => check(path)?,
        _ => {
            return Err(SceneError::Invalid {
                origin: path.display().to_string(),
                key: "mesh.path".into(),
                message: format!(
                    "unknown mesh file type '.{}' (valid: {VALID})",
                    isochor_mesh::io::excerpt(&ext)
                ),
            })
        }
    }
    Ok(isochor_mesh::io::read_mesh_elements(path)?)
}

/// Material parameters from a scene's `[material]` table.
pub fn build_material(spec: &MaterialSpec) -> Result<Material, SceneError> {
    let invalid = |message: String| SceneError::Invalid {
        origin: "scene".into(),
        key: "material".into(),
        message,
    };
    let model = material_model(spec).map_err(invalid)?;
    model.validate().map_err(|e| match model {
        // The terms are one key; the error names the term's parameter.
        MaterialModel::Ogden { .. } => SceneError::Invalid {
            origin: "scene".into(),
            key: "material.ogden".into(),
            message: e.to_string(),
        },
        _ => e.into(),
    })?;
    let young = match (spec.young, spec.mu, model.shear_modulus()) {
        (None, None, Some(mu)) => 2.0 * mu * (1.0 + spec.nu),
        (Some(_), _, Some(_)) | (_, Some(_), Some(_)) => {
            return Err(invalid(format!(
                "model {} takes its stiffness from its constants: drop young and mu",
                model.name()
            )))
        }
        (Some(e), _, None) => e,
        (None, Some(mu), None) => {
            // Checked as given, not as the Young's modulus it implies, so the error names mu.
            if !(mu.is_finite() && mu > 0.0) {
                return Err(ParameterError {
                    name: "mu",
                    value: mu,
                    reason: "shear modulus must be finite and positive",
                }
                .into());
            }
            2.0 * mu * (1.0 + spec.nu)
        }
        (None, None, None) => return Err(invalid("give young (E) or mu".into())),
    };
    let mut m = Material::from_young_poisson(young, spec.nu, spec.rho)?.with_model(model)?;
    if let Some(mu) = spec.mu {
        m.mu = mu;
    }
    if let Some(lambda) = spec.lambda {
        m.zonal_lambda = lambda;
    }
    if let Some(beta) = spec.beta {
        m.beta = beta;
    }
    if let Some(epsilon) = spec.epsilon {
        m.epsilon = epsilon;
    }
    if let Some(kappa) = spec.kappa {
        m.kappa = match kappa {
            KappaName::Bulk => Kappa::Bulk,
            KappaName::Lambda => Kappa::Lambda,
        };
    }
    if let Some(energy) = spec.zonal_energy {
        m.zonal_energy = match energy {
            ZonalEnergyName::Constrained => ZonalEnergy::Constrained,
            ZonalEnergyName::Standard => ZonalEnergy::Standard,
        };
    }
    if let Some(nu) = spec.dual_base_nu {
        m.dual_base_nu = (nu != 0.0).then_some(nu);
    }
    if spec.epidermis {
        m.epidermis = Some(Epidermis {
            young: spec.epidermis_young.unwrap_or(young),
            poisson: spec.epidermis_nu.unwrap_or(0.45),
            gamma: spec.epidermis_gamma.unwrap_or(1.0),
        });
    }
    m.validate()?;
    Ok(m)
}

/// The model of a `[material]` table, its constants checked against the model.
fn material_model(spec: &MaterialSpec) -> Result<MaterialModel, String> {
    let name = spec.model.unwrap_or(ModelName::NeoHookean);
    let given: Vec<&str> = [
        ("c10", spec.c10.is_some()),
        ("c01", spec.c01.is_some()),
        ("c20", spec.c20.is_some()),
        ("c30", spec.c30.is_some()),
        ("ogden", spec.ogden.is_some()),
    ]
    .into_iter()
    .filter_map(|(key, set)| set.then_some(key))
    .collect();
    let allowed: &[&str] = match name {
        ModelName::MooneyRivlin => &["c10", "c01"],
        ModelName::Yeoh => &["c10", "c20", "c30"],
        ModelName::Ogden => &["ogden"],
        _ => &[],
    };
    if let Some(key) = given.iter().find(|k| !allowed.contains(k)) {
        return Err(format!(
            "{key} is not a constant of model {} (its constants: {})",
            name.name(),
            if allowed.is_empty() {
                "none; give young or mu".to_string()
            } else {
                allowed.join(", ")
            }
        ));
    }
    let required = |key: &str, value: Option<f64>| {
        value.ok_or_else(|| format!("model {} needs {key}", name.name()))
    };
    Ok(match name {
        ModelName::NeoHookean => MaterialModel::NeoHookean,
        ModelName::StableNeoHookean => MaterialModel::StableNeoHookean,
        ModelName::BonetWood => MaterialModel::BonetWood,
        ModelName::MooneyRivlin => MaterialModel::MooneyRivlin {
            c10: required("c10", spec.c10)?,
            c01: spec.c01.unwrap_or(0.0),
        },
        ModelName::Yeoh => MaterialModel::Yeoh {
            c10: required("c10", spec.c10)?,
            c20: spec.c20.unwrap_or(0.0),
            c30: spec.c30.unwrap_or(0.0),
        },
        ModelName::Ogden => MaterialModel::Ogden {
            terms: spec
                .ogden
                .as_ref()
                .ok_or_else(|| "model ogden needs ogden = [[mu_p, alpha_p], ...]".to_string())?
                .iter()
                .map(|&[mu, alpha]| (mu, alpha))
                .collect(),
        },
    })
}

/// The material of region `index`: the body's `[material]` keys overlaid with the region's.
fn region_material(
    body: &MaterialSpec,
    overrides: &toml::Table,
    index: usize,
) -> Result<Material, SceneError> {
    let origin = format!("regions.{index}.material");
    let invalid = |key: String, message: String| SceneError::Invalid {
        origin: "scene".into(),
        key,
        message,
    };
    let mut merged =
        toml::Table::try_from(body).map_err(|e| invalid(origin.clone(), e.to_string()))?;
    // A region that gives any stiffness key replaces all of the body's.
    const STIFFNESS: [&str; 7] = ["young", "mu", "c10", "c01", "c20", "c30", "ogden"];
    if STIFFNESS.iter().any(|k| overrides.contains_key(*k)) {
        for key in STIFFNESS {
            merged.remove(key);
        }
    }
    merged.extend(overrides.clone());
    let spec: MaterialSpec = serde_path_to_error::deserialize(toml::Value::Table(merged))
        .map_err(|e| invalid(format!("{origin}.{}", e.path()), e.inner().to_string()))?;
    build_material(&spec).map_err(|e| invalid(origin, e.to_string()))
}

fn motion(spec: &MotionSpec) -> Motion {
    match spec {
        MotionSpec::Fixed => Motion::Fixed,
        MotionSpec::Translate(offset) => Motion::Translate(vec3(*offset)),
        MotionSpec::Rotate {
            center,
            axis,
            degrees,
        } => Motion::Rotate {
            center: vec3(*center),
            axis: vec3(*axis),
            angle: degrees.to_radians(),
        },
        MotionSpec::Scale { center, factors } => Motion::Scale {
            center: vec3(*center),
            factors: vec3(*factors),
        },
    }
}

/// The zones of the scene's `[zones]` on `mesh` (one global zone if absent).
pub(crate) fn build_zones(
    scene: &Scene,
    mesh: &TetMesh,
    selections: &Selections<'_>,
) -> Result<Zones, SceneError> {
    let Some(spec) = &scene.zones else {
        return Ok(Zones::global(mesh));
    };
    Ok(match spec.kind {
        ZoneKind::Global => Zones::global(mesh),
        ZoneKind::None => Zones::from_sets(Vec::new()),
        ZoneKind::KRing => Zones::k_ring_cover(mesh, spec.k.unwrap_or(1))?,
        ZoneKind::Painted => {
            let mut labels = vec![Vec::new(); mesh.num_vertices()];
            for (zone, name) in spec.paint.iter().enumerate() {
                for v in selections.vertices(name)? {
                    labels[v].push(zone);
                }
            }
            Zones::painted(mesh, &labels)?
        }
    })
}

/// The solver's stepping.
pub fn stepping(spec: &SteppingSpec) -> Stepping {
    match *spec {
        SteppingSpec::QuasiStatic {
            steps,
            ref increments,
            first_increment,
            min_increment,
        } => Stepping::QuasiStatic {
            steps,
            control: match increments.as_deref() {
                Some("fixed") => StepControl::Fixed,
                _ => {
                    let default = Adaptive::default();
                    StepControl::Adaptive(Adaptive {
                        first: first_increment.unwrap_or(default.first),
                        min: min_increment.unwrap_or(default.min),
                        ..default
                    })
                }
            },
        },
        SteppingSpec::Dynamic { dt, frames, .. } => Stepping::ImplicitEuler { dt, frames },
    }
}

/// The solver's volume projection of the scene's stepping (none in quasi-static stepping).
pub fn volume_projection(spec: &SteppingSpec) -> VolumeProjection {
    match spec {
        SteppingSpec::Dynamic {
            volume_projection: Some(name),
            volume_recovery,
            ..
        } => match name.as_str() {
            "one-ring" => VolumeProjection::OneRing {
                recovery: volume_recovery.unwrap_or(DEFAULT_VOLUME_RECOVERY),
            },
            "global-rescale" => VolumeProjection::GlobalRescale,
            _ => VolumeProjection::None,
        },
        _ => VolumeProjection::None,
    }
}

/// The solver's settings: its defaults, overridden by the scene's `[solver]` table.
pub fn settings(spec: &SolverSpec) -> Settings {
    let mut s = Settings::default();
    if let Some(v) = spec.max_iterations {
        s.max_iterations = v;
    }
    if let Some(v) = spec.force_tolerance {
        s.force_tolerance = v;
    }
    if let Some(v) = spec.constraint_tolerance {
        s.constraint_tolerance = v;
    }
    if let Some(v) = spec.max_backtracks {
        s.max_backtracks = v;
    }
    if let Some(v) = spec.max_dual_iterations {
        s.max_dual_iterations = v;
    }
    if let Some(v) = spec.project_hessians {
        s.project_hessians = v;
    }
    if let Some(v) = spec.contact_tolerance {
        s.contact_tolerance = v;
    }
    if let Some(v) = spec.accept_unconverged {
        s.accept_unconverged = v;
    }
    if let Some(v) = spec.max_contact_iterations {
        s.max_contact_iterations = v;
    }
    if let Some(v) = spec.ordering {
        s.ordering = match v {
            OrderingName::Amd => Ordering::Amd,
            OrderingName::NestedDissection => Ordering::NestedDissection,
            OrderingName::Auto => Ordering::Auto,
        };
    }
    let iterative = IterativeSettings {
        tolerance: spec.linear_tolerance.unwrap_or(1e-8),
        max_iterations: spec.linear_max_iterations.unwrap_or(1000),
        preconditioner: match spec.linear_preconditioner {
            Some(PreconditionerName::Jacobi) => PreconditionerKind::Jacobi,
            Some(PreconditionerName::Multigrid) => PreconditionerKind::Multigrid,
            Some(PreconditionerName::IncompleteCholesky) | None => {
                PreconditionerKind::IncompleteCholesky
            }
        },
    };
    s.linear = match spec.linear_choice() {
        LinearName::Direct => LinearSolver::Direct,
        LinearName::Iterative => LinearSolver::Iterative(iterative),
        LinearName::Auto => LinearSolver::Auto(iterative),
    };
    s
}
