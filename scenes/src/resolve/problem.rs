//! The scene's conditions, loads, obstacles, stepping and solver settings in the solver's
//! types, on the resolved selections.

use super::selections::Selections;
use crate::error::SceneError;
use crate::format::{
    CurveSpec, JacobianName, LinearName, MotionSpec, ObstacleSpec, OrderingName, PlacementSpec,
    PreconditionerName, Scene, SolverSpec, SteppingSpec, DEFAULT_VOLUME_RECOVERY,
};
use isochor_mesh::io::read_surface;
use isochor_mesh::Vec3;
use isochor_solvers::linear::Ordering;
use isochor_solvers::{
    Adaptive, AxisRotation, Curve, Dirichlet, IterativeSettings, Jacobian, LinearSolver, Load,
    MeshObstacle, Motion, Obstacle, PreconditionerKind, ScheduledLoad, Settings, Shape,
    StepControl, Stepping, VolumeProjection,
};

/// The Dirichlet conditions on their selections' nodes.
pub fn dirichlet(scene: &Scene, selections: &Selections) -> Result<Vec<Dirichlet>, SceneError> {
    scene
        .dirichlet
        .iter()
        .enumerate()
        .map(|(i, d)| {
            Ok(Dirichlet {
                nodes: selections.nodes(&d.selection)?.to_vec(),
                axes: ['x', 'y', 'z'].map(|c| d.axes.contains(c)),
                motion: motion(&d.motion),
                curve: curve(&d.curve, &format!("dirichlet.{i}.curve"))?,
            })
        })
        .collect()
}

/// Gravity, then the tractions and pressures on their selections' boundary faces.
pub fn loads(scene: &Scene, selections: &Selections) -> Result<Vec<ScheduledLoad>, SceneError> {
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
                faces: selections.faces(&t.selection)?.to_vec(),
                traction: vec3(t.traction),
            },
            curve: curve(&t.curve, &format!("loads.traction.{i}.curve"))?,
        });
    }
    for (i, p) in scene.loads.pressure.iter().enumerate() {
        let faces = selections.faces(&p.selection)?.to_vec();
        let origin = vec3(p.origin.unwrap_or_default());
        let cap_openings = p.cap_openings;
        loads.push(ScheduledLoad {
            load: match p.volume_ratio {
                Some(volume_ratio) => Load::Cavity {
                    faces,
                    volume_ratio,
                    origin,
                    cap_openings,
                },
                None => Load::Pressure {
                    faces,
                    pressure: p.pressure.unwrap_or(0.0),
                    origin,
                    cap_openings,
                },
            },
            curve: curve(&p.curve, &format!("loads.pressure.{i}.curve"))?,
        });
    }
    Ok(loads)
}

/// The obstacles.
pub fn obstacles(scene: &Scene) -> Result<Vec<Obstacle>, SceneError> {
    scene
        .obstacles
        .iter()
        .enumerate()
        .filter(|(_, o)| !o.is_mesh())
        .map(|(i, o)| obstacle(o, i))
        .collect()
}

/// The meshed obstacles of `[[obstacles]]` (`shape = "mesh"`), in the scene's order: each
/// surface file read, placed, with its motion.
pub fn mesh_obstacles(scene: &Scene) -> Result<Vec<MeshObstacle>, SceneError> {
    let mut meshed = Vec::new();
    for (i, spec) in scene.obstacles.iter().enumerate() {
        let ObstacleSpec::Mesh {
            path,
            place,
            translate,
            rotate,
            curve: points,
            ..
        } = spec
        else {
            continue;
        };
        let surface = read_surface(path)?;
        let place = super::bodies::placement(place.as_ref().unwrap_or(&PlacementSpec::default()));
        meshed.push(MeshObstacle {
            name: spec.name(i),
            vertices: surface.vertices.iter().map(place).collect(),
            triangles: surface.triangles,
            translate: vec3(*translate),
            rotate: rotate.as_ref().map(|r| AxisRotation {
                center: vec3(r.center),
                axis: vec3(r.axis),
                angle: r.degrees.to_radians(),
            }),
            curve: curve(points, &format!("obstacles.{i}.curve"))?,
        });
    }
    Ok(meshed)
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
        ObstacleSpec::Mesh { .. } => {
            return Err(SceneError::Invalid {
                origin: "scene".into(),
                key: format!("obstacles.{index}"),
                message: "a meshed obstacle is no analytic shape".into(),
            })
        }
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
    if let Some(v) = spec.jacobian {
        s.jacobian = match v {
            JacobianName::Full => Jacobian::Full,
            JacobianName::Modified => Jacobian::Modified,
        };
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
