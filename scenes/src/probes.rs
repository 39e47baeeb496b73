//! Probes: named scalars measured on a state (the final one of a run), the numbers the
//! papers' tables and figures report.

use crate::error::SceneError;
use crate::format::{ComponentName, EnergyName, ProbeSpec, Reduce, Scene};
use crate::record::{PressureLoadRecord, StepRecord};
use crate::resolve::Selections;
use isochor_mesh::probes::{
    displacement_at, enclosed_volume_ratio, rotation_angle, volume_change, volume_ratio,
};
use isochor_mesh::{ElementMesh, TetMesh, Vec3, Zones, TET_FACES};
use isochor_solvers::{ClothSheet, Energies};
use std::collections::{BTreeMap, HashMap};

/// What probes read.
#[derive(Debug, Clone, Copy)]
pub struct ProbeInput<'a> {
    /// The rest mesh.
    pub mesh: &'a ElementMesh,
    /// The scene's selections on it.
    pub selections: &'a Selections,
    /// The scene's zones, if it has a zone probe (see [`crate::resolve::ResolvedScene::zones`]).
    pub zones: Option<&'a Zones>,
    /// Positions of the state.
    pub positions: &'a [Vec3],
    /// Pressure per element (empty if unknown).
    pub tet_pressures: &'a [f64],
    /// Constraint residual of the state's step (0 without constraints).
    pub constraint_residual: f64,
    /// Energies of the state.
    pub energies: Energies,
    /// Volumetric stiffness `kappa` of the mixed methods (`None` if it does not apply).
    pub kappa: Option<f64>,
    /// The accepted steps so far, for probes over the run (empty before a run).
    pub history: &'a [StepRecord],
    /// The cloth sheets (their triangles over the mesh's vertices).
    pub cloths: &'a [ClothSheet],
}

/// Evaluates every probe of `scene` (named, in name order).
pub fn evaluate(
    scene: &Scene,
    input: &ProbeInput<'_>,
) -> Result<BTreeMap<String, f64>, SceneError> {
    scene
        .probes
        .iter()
        .map(|(name, spec)| {
            let value = probe(spec, input).map_err(|e| e.named(name))?;
            Ok((name.clone(), value))
        })
        .collect()
}

/// Evaluates the probe `name` of `scene` alone (it runs after every step for
/// `output.potential_against`).
pub fn evaluate_one(scene: &Scene, name: &str, input: &ProbeInput<'_>) -> Result<f64, SceneError> {
    let spec = scene.probes.get(name).ok_or_else(|| SceneError::Probe {
        name: name.to_string(),
        message: "the scene has no such probe".into(),
    })?;
    probe(spec, input).map_err(|e| e.named(name))
}

enum ProbeError {
    Scene(SceneError),
    Message(String),
}

impl ProbeError {
    /// The error as the scene's, a message naming the probe `name`.
    fn named(self, name: &str) -> SceneError {
        match self {
            ProbeError::Scene(e) => e,
            ProbeError::Message(message) => SceneError::Probe {
                name: name.to_string(),
                message,
            },
        }
    }
}

impl From<SceneError> for ProbeError {
    fn from(e: SceneError) -> Self {
        ProbeError::Scene(e)
    }
}

/// Pressure load `load` at the last accepted step (at rest before a run: no pressure, the
/// rest volume).
fn pressure_load(input: &ProbeInput<'_>, load: usize) -> Result<PressureLoadRecord, ProbeError> {
    match input.history.last() {
        None => Ok(PressureLoadRecord {
            pressure: 0.0,
            volume_ratio: 1.0,
        }),
        Some(step) => step.pressure_loads.get(load).copied().ok_or_else(|| {
            ProbeError::Message(format!(
                "pressure load {load} does not exist: the scene has {}",
                step.pressure_loads.len()
            ))
        }),
    }
}

/// The summed deformed length of the cloth edges (each once) with both ends in `nodes`.
fn loop_length(cloths: &[ClothSheet], nodes: &[usize], x: &[Vec3]) -> Result<f64, ProbeError> {
    let mut selected = vec![false; x.len()];
    nodes.iter().for_each(|&v| selected[v] = true);
    let mut edges: Vec<[usize; 2]> = cloths
        .iter()
        .flat_map(|c| &c.triangles)
        .flat_map(|t| (0..3).map(move |k| [t[k], t[(k + 1) % 3]]))
        .filter(|&[a, b]| selected[a] && selected[b])
        .map(|[a, b]| [a.min(b), a.max(b)])
        .collect();
    edges.sort_unstable();
    edges.dedup();
    if edges.is_empty() {
        return Err(ProbeError::Message(
            "the selection holds no edge of a cloth's triangles".into(),
        ));
    }
    Ok(edges.iter().map(|&[a, b]| (x[a] - x[b]).norm()).sum())
}

/// The largest `value` over the accepted steps (0 before a run).
fn over_run(input: &ProbeInput<'_>, value: impl Fn(&StepRecord) -> f64) -> f64 {
    input.history.iter().map(value).fold(0.0, f64::max)
}

fn probe(spec: &ProbeSpec, input: &ProbeInput<'_>) -> Result<f64, ProbeError> {
    let ProbeInput {
        mesh,
        positions: x,
        selections,
        ..
    } = *input;
    let rest = mesh.nodes();
    let rest_volumes = || mesh.volumes_at(rest);
    Ok(match spec {
        ProbeSpec::Displacement {
            point,
            selection,
            component,
            scale,
            reduce,
            ..
        } => {
            let pick = |u: Vec3| pick(u, *component);
            if let Some(p) = point {
                let u = displacement_at(mesh, x, &Vec3::new(p[0], p[1], p[2])).map_err(message)?;
                scale * pick(u)
            } else {
                let name = selection.as_deref().unwrap_or_default();
                let values: Vec<f64> = selections
                    .nodes(name)?
                    .iter()
                    .map(|&v| scale * pick(x[v] - rest[v]))
                    .collect();
                reduce_values(&values, *reduce)
            }
        }
        ProbeSpec::Position {
            selection,
            component,
            reduce,
        } => {
            let values: Vec<f64> = match selection {
                Some(name) => selections
                    .nodes(name)?
                    .iter()
                    .map(|&v| pick(x[v], *component))
                    .collect(),
                None => x.iter().map(|p| pick(*p, *component)).collect(),
            };
            reduce_values(&values, *reduce)
        }
        ProbeSpec::VolumeChange => volume_change(mesh, x).map_err(message)?,
        ProbeSpec::VolumeRatio { selection } => {
            let elements: Vec<usize> = match selection {
                Some(name) => selections.tets(name)?.to_vec(),
                None => (0..mesh.num_elements()).collect(),
            };
            volume_ratio(mesh, x, &elements).map_err(message)?
        }
        ProbeSpec::ZoneVolumeChange { zone } => {
            let zones = input
                .zones
                .ok_or_else(|| ProbeError::Message("the scene's zones were not resolved".into()))?;
            let tets = zones.iter().nth(*zone).ok_or_else(|| {
                ProbeError::Message(format!(
                    "zone {zone} does not exist: the scene has {} zones",
                    zones.len()
                ))
            })?;
            volume_ratio(mesh, x, tets).map_err(message)? - 1.0
        }
        ProbeSpec::ChamberVolumeRatio { selection } => {
            enclosed_volume_ratio(mesh, x, selections.faces(selection)?).map_err(message)?
        }
        ProbeSpec::LoadPressure { load } => pressure_load(input, *load)?.pressure,
        ProbeSpec::EnclosedVolumeRatio { load } => pressure_load(input, *load)?.volume_ratio,
        ProbeSpec::Rotation { selection, axis } => {
            let axis = axis.map(|[a, b, c]| Vec3::new(a, b, c));
            rotation_angle(mesh, x, selections.nodes(selection)?, axis)
                .map_err(message)?
                .to_degrees()
        }
        ProbeSpec::MinVolumeRatio => volume_ratios(mesh, x).fold(f64::INFINITY, f64::min),
        ProbeSpec::MaxVolumeRatio => volume_ratios(mesh, x).fold(f64::NEG_INFINITY, f64::max),
        ProbeSpec::InvertedTets => mesh.count_inverted(x) as f64,
        ProbeSpec::RunVolumeRatio { reduce } => {
            let ratios: Vec<f64> = input
                .history
                .iter()
                .map(|s| 1.0 + s.volume_change)
                .collect();
            if ratios.is_empty() {
                f64::NAN
            } else {
                reduce_values(&ratios, *reduce)
            }
        }
        ProbeSpec::MaxPenetration => over_run(input, |s| s.contact.max_penetration),
        ProbeSpec::MaxContactForce { obstacle } => over_run(input, |s| {
            let force = match obstacle {
                Some(k) => s.contact.obstacle_forces.get(*k).copied(),
                None => Some(s.contact.force),
            };
            force.map_or(0.0, |[x, y, z]| (x * x + y * y + z * z).sqrt())
        }),
        ProbeSpec::LoopLength { selection } => {
            loop_length(input.cloths, selections.nodes(selection)?, x)?
        }
        ProbeSpec::MinDistance => input
            .history
            .iter()
            .filter_map(|s| s.contact.min_distance)
            .reduce(f64::min)
            .unwrap_or(f64::NAN),
        ProbeSpec::FirstContact => input
            .history
            .iter()
            .find(|s| s.contact.active_vertices > 0)
            .map_or(f64::NAN, |s| s.step as f64),
        ProbeSpec::ConstraintResidual => input.constraint_residual,
        ProbeSpec::VolumeErrorIterations { level } => {
            iterations_to_reach(input.history, *level).map_or(f64::NAN, |n| n as f64)
        }
        ProbeSpec::PressureVolumeMismatch => {
            let p = pressures(input)?;
            let kappa = input.kappa.filter(|k| *k > 0.0).ok_or_else(|| {
                ProbeError::Message("needs the volumetric stiffness kappa of the material".into())
            })?;
            let expected: f64 = rest_volumes()
                .iter()
                .zip(p)
                .map(|(v, p)| v * (1.0 + p / kappa))
                .sum();
            (mesh.total_volume_at(x) - expected) / mesh.rest_volume()
        }
        ProbeSpec::PressureCheckerboard => checkerboard(mesh.corners(), pressures(input)?),
        ProbeSpec::RadiusIncrease {
            selection,
            center,
            axis,
            ..
        } => {
            let c = Vec3::new(center[0], center[1], center[2]);
            let a = Vec3::new(axis[0], axis[1], axis[2]);
            let norm = a.norm();
            if !(norm.is_finite() && norm > 0.0) {
                return Err(ProbeError::Message("axis must be non-zero".into()));
            }
            let a = a / norm;
            let radius = |p: &Vec3| {
                let d = p - c;
                (d - d.dot(&a) * a).norm()
            };
            let nodes = selections.nodes(selection)?;
            nodes
                .iter()
                .map(|&v| radius(&x[v]) - radius(&rest[v]))
                .sum::<f64>()
                / nodes.len() as f64
        }
        ProbeSpec::Energy { which } => {
            let e = input.energies;
            match which {
                EnergyName::Kinetic => e.kinetic,
                EnergyName::Elastic => e.elastic,
                EnergyName::External => e.external,
                EnergyName::Constraint => e.constraint,
                EnergyName::Potential => e.elastic + e.constraint + e.external,
                EnergyName::Total => e.kinetic + e.elastic + e.constraint + e.external,
            }
        }
    })
}

/// The most iterations any step of `history` needed to bring its volume error to `level`
/// (each step's errors are recorded before every iteration, then after the last; a step
/// that iterates counts at least one iteration, since it starts from a state that met its
/// constraints before the load moved). `None` if a step never reached it, or if no error
/// was measured (a method without multipliers records zeros).
fn iterations_to_reach(history: &[StepRecord], level: f64) -> Option<usize> {
    let measured = history
        .iter()
        .flat_map(|s| &s.iterations.volume_errors)
        .any(|&e| e != 0.0);
    if !measured {
        return None;
    }
    history.iter().try_fold(0, |most, s| {
        let reached = match s.iterations.volume_errors.as_slice() {
            [] => return None,
            [_] => 0,
            [_, after @ ..] => after.iter().position(|&e| e <= level)? + 1,
        };
        Some(most.max(reached))
    })
}

/// The component of a vector a probe reads.
fn pick(u: Vec3, component: ComponentName) -> f64 {
    match component {
        ComponentName::X => u.x,
        ComponentName::Y => u.y,
        ComponentName::Z => u.z,
        ComponentName::Norm => u.norm(),
    }
}

/// A mesh layer's refusal as a probe's message.
fn message(e: isochor_mesh::MeshError) -> ProbeError {
    ProbeError::Message(e.to_string())
}

fn pressures<'a>(input: &ProbeInput<'a>) -> Result<&'a [f64], ProbeError> {
    if input.tet_pressures.len() == input.mesh.num_elements() {
        Ok(input.tet_pressures)
    } else {
        Err(ProbeError::Message(format!(
            "needs one pressure per element ({} given for {} elements)",
            input.tet_pressures.len(),
            input.mesh.num_elements()
        )))
    }
}

fn reduce_values(values: &[f64], reduce: Reduce) -> f64 {
    match reduce {
        Reduce::Mean => values.iter().sum::<f64>() / values.len() as f64,
        Reduce::Max => values.iter().copied().fold(f64::NEG_INFINITY, f64::max),
        Reduce::Min => values.iter().copied().fold(f64::INFINITY, f64::min),
    }
}

fn volume_ratios(mesh: &ElementMesh, x: &[Vec3]) -> impl Iterator<Item = f64> {
    let rest = mesh.volumes_at(mesh.nodes());
    mesh.volumes_at(x)
        .into_iter()
        .zip(rest)
        .map(|(v, v0)| v / v0)
}

/// Mean absolute jump of a per-tet field across interior faces, divided by the field's
/// standard deviation (0 for a constant field).
pub fn checkerboard(mesh: &TetMesh, field: &[f64]) -> f64 {
    let n = field.len() as f64;
    let mean = field.iter().sum::<f64>() / n;
    let std = (field.iter().map(|p| (p - mean).powi(2)).sum::<f64>() / n).sqrt();
    if std.is_nan() || std <= 0.0 {
        return 0.0;
    }
    let mut owner: HashMap<[usize; 3], usize> = HashMap::with_capacity(2 * mesh.num_tets());
    let (mut sum, mut count) = (0.0, 0usize);
    for (e, t) in mesh.tets().iter().enumerate() {
        for local in TET_FACES {
            let mut key = local.map(|a| t[a]);
            key.sort_unstable();
            if let Some(other) = owner.remove(&key) {
                sum += (field[e] - field[other]).abs();
                count += 1;
            } else {
                owner.insert(key, e);
            }
        }
    }
    if count == 0 {
        0.0
    } else {
        sum / count as f64 / std
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use isochor_mesh::generate::box_grid;

    /// The unit cube of 2 x 2 x 2 cells (`standard`, E = 1e5, nu = 0.3) clamped at its
    /// `bottom` selection, one quasi-static step; `extra` (TOML) adds the selections, `bottom`
    /// among them, zones and probes.
    fn unit_cube(extra: &str) -> Scene {
        let text = format!(
            r#"
            name = "cube"
            method = "standard"
            [mesh]
            generator = "box"
            min = [0.0, 0.0, 0.0]
            max = [1.0, 1.0, 1.0]
            res = 2
            [material]
            young = 1e5
            nu = 0.3
            [[dirichlet]]
            selection = "bottom"
            axes = "xyz"
            [stepping]
            mode = "quasi-static"
            steps = 1
            {extra}
            "#
        );
        Scene::from_toml_str(&text, "test").unwrap()
    }

    /// The probes of `scene` with its mesh's nodes moved by `deform`.
    fn probes_at(
        scene: &Scene,
        deform: impl Fn(&Vec3) -> Vec3,
    ) -> Result<BTreeMap<String, f64>, SceneError> {
        let built = crate::resolve::build(scene).unwrap();
        let mesh = built.problem.mesh;
        let positions: Vec<Vec3> = mesh.nodes().iter().map(deform).collect();
        evaluate(
            scene,
            &ProbeInput {
                mesh: &mesh,
                selections: &built.selections,
                zones: built.zones.as_ref(),
                positions: &positions,
                tet_pressures: &[],
                constraint_residual: 0.0,
                energies: Energies::default(),
                kappa: None,
                history: &[],
                cloths: &[],
            },
        )
    }

    /// A position probe reads the deformed coordinates: after a rigid translation by `t` of
    /// the unit cube, the lowest z is `t_z`, the highest `1 + t_z`, the mean over the top
    /// face `1 + t_z`, and the distance from the origin of the farthest corner `|(1,1,1) + t|`.
    #[test]
    fn position_probe_follows_a_rigid_translation() {
        let scene = unit_cube(
            r#"
            [selections.bottom]
            plane = { point = [0.0, 0.0, 0.0], normal = [0.0, 0.0, 1.0] }
            [selections.top]
            plane = { point = [0.0, 0.0, 1.0], normal = [0.0, 0.0, 1.0] }
            [probes.lowest]
            kind = "position"
            component = "z"
            reduce = "min"
            [probes.highest]
            kind = "position"
            component = "z"
            reduce = "max"
            [probes.top]
            kind = "position"
            selection = "top"
            component = "z"
            [probes.farthest]
            kind = "position"
            component = "norm"
            reduce = "max"
            "#,
        );
        let t = Vec3::new(0.3, -0.2, -0.45);
        let values = probes_at(&scene, |p| p + t).unwrap();
        // Sums of two exact binary fractions: equal to rounding.
        let close = |a: f64, b: f64| (a - b).abs() <= 4.0 * f64::EPSILON;
        assert!(close(values["lowest"], t.z), "{values:?}");
        assert!(close(values["highest"], 1.0 + t.z), "{values:?}");
        assert!(close(values["top"], 1.0 + t.z), "{values:?}");
        assert!(
            close(values["farthest"], (Vec3::repeat(1.0) + t).norm()),
            "{values:?}"
        );
    }

    /// A zone-volume probe reads the zones the scene paints, whatever the method: a 2 x 2 x 2
    /// cube painted bottom (zone 0) and top (zone 1) half, its top layer stretched to twice
    /// its height (piecewise linear, so every tet's volume is exact): the bottom zone keeps
    /// its volume, the top one doubles it; a zone past the last is an error naming the count.
    #[test]
    fn zone_volume_change_reads_the_painted_zones() {
        let change = |zone: usize| {
            let scene = unit_cube(&format!(
                r#"
            [selections.bottom]
            box = {{ min = [0.0, 0.0, 0.0], max = [1.0, 1.0, 0.5] }}
            surface = true
            [selections.top]
            box = {{ min = [0.0, 0.0, 0.5], max = [1.0, 1.0, 1.0] }}
            surface = true
            [zones]
            kind = "painted"
            paint = ["bottom", "top"]
            [probes.zone]
            kind = "zone-volume-change"
            zone = {zone}
            "#
            ));
            probes_at(&scene, |p| Vec3::new(p.x, p.y, p.z.max(2.0 * p.z - 0.5)))
                .map(|values| values["zone"])
        };
        assert!(change(0).unwrap().abs() <= 4.0 * f64::EPSILON);
        assert!((change(1).unwrap() - 1.0).abs() <= 4.0 * f64::EPSILON);
        let error = change(2).unwrap_err().to_string();
        assert!(error.contains("2 zones"), "{error}");
    }

    #[test]
    fn checkerboard_separates_smooth_from_alternating_fields() {
        let mesh = box_grid(Vec3::zeros(), Vec3::repeat(1.0), [4, 4, 4]).unwrap();
        let smooth: Vec<f64> = (0..mesh.num_tets()).map(|e| mesh.centroid(e).z).collect();
        let alternating: Vec<f64> = (0..mesh.num_tets()).map(|e| (e % 2) as f64).collect();
        let s = checkerboard(&mesh, &smooth);
        let a = checkerboard(&mesh, &alternating);
        assert!(s < 0.5 && a > 1.0, "smooth {s}, alternating {a}");
        assert_eq!(checkerboard(&mesh, &vec![1.0; mesh.num_tets()]), 0.0);
    }

    /// Fig. 8's count: per step the first iteration after which the volume error is at the
    /// level, the most over the steps; at least one for a step that iterates; `None` when
    /// a step never gets there or nothing was measured.
    #[test]
    fn iterations_to_reach_counts_the_worst_step() {
        let step = |errors: &[f64]| StepRecord {
            iterations: crate::record::Iterations {
                volume_errors: errors.to_vec(),
                ..Default::default()
            },
            ..StepRecord::default()
        };
        let history = [
            step(&[0.0, 0.05, 0.02, 0.009, 0.001]),
            step(&[0.03, 0.008, 1e-5]),
            step(&[0.0]),
        ];
        assert_eq!(iterations_to_reach(&history, 0.01), Some(3));
        assert_eq!(iterations_to_reach(&history, 0.025), Some(2));
        assert_eq!(iterations_to_reach(&history[1..], 0.01), Some(1));
        assert_eq!(iterations_to_reach(&history, 1e-4), None);
        assert_eq!(iterations_to_reach(&[step(&[0.0, 0.0])], 0.01), None);
    }
}
