//! Probes: named scalars measured on a state (the final one of a run), the numbers the
//! papers' tables and figures report.

use crate::result::StepRecord;
use crate::scene::{ComponentName, EnergyName, ProbeSpec, Reduce, Scene};
use crate::selection::Selections;
use crate::SceneError;
use isochor_mesh::element::deformation_gradient;
use isochor_mesh::{ElementMesh, TetMesh, Vec3, TET_FACES};
use isochor_solvers::Energies;
use std::collections::{BTreeMap, HashMap};

/// What probes read.
#[derive(Debug, Clone, Copy)]
pub struct ProbeInput<'a> {
    /// The rest mesh.
    pub mesh: &'a ElementMesh,
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
}

/// Evaluates every probe of `scene` (named, in name order).
pub fn evaluate(
    scene: &Scene,
    input: &ProbeInput<'_>,
) -> Result<BTreeMap<String, f64>, SceneError> {
    let selections = Selections::new(input.mesh, &scene.mesh, &scene.selections)?;
    scene
        .probes
        .iter()
        .map(|(name, spec)| {
            let value = probe(spec, input, &selections).map_err(|e| match e {
                ProbeError::Scene(e) => e,
                ProbeError::Message(message) => SceneError::Probe {
                    name: name.clone(),
                    message,
                },
            })?;
            Ok((name.clone(), value))
        })
        .collect()
}

enum ProbeError {
    Scene(SceneError),
    Message(String),
}

impl From<SceneError> for ProbeError {
    fn from(e: SceneError) -> Self {
        ProbeError::Scene(e)
    }
}

/// The largest `value` over the accepted steps (0 before a run).
fn over_run(input: &ProbeInput<'_>, value: impl Fn(&StepRecord) -> f64) -> f64 {
    input.history.iter().map(value).fold(0.0, f64::max)
}

fn probe(
    spec: &ProbeSpec,
    input: &ProbeInput<'_>,
    selections: &Selections<'_>,
) -> Result<f64, ProbeError> {
    let ProbeInput {
        mesh, positions: x, ..
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
        } => {
            let pick = |u: Vec3| match component {
                ComponentName::X => u.x,
                ComponentName::Y => u.y,
                ComponentName::Z => u.z,
                ComponentName::Norm => u.norm(),
            };
            if let Some(p) = point {
                let u = displacement_at(mesh, x, &Vec3::new(p[0], p[1], p[2]))
                    .map_err(ProbeError::Message)?;
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
        ProbeSpec::VolumeChange => mesh.total_volume_at(x) / mesh.rest_volume() - 1.0,
        ProbeSpec::VolumeRatio { selection } => {
            let elements: Vec<usize> = match selection {
                Some(name) => selections.tets(name)?,
                None => (0..mesh.num_elements()).collect(),
            };
            let (deformed, rest) = (mesh.volumes_at(x), rest_volumes());
            let sum = |v: &[f64]| elements.iter().map(|&e| v[e]).sum::<f64>();
            sum(&deformed) / sum(&rest)
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
        ProbeSpec::MaxContactForce => over_run(input, |s| {
            let [x, y, z] = s.contact.force;
            (x * x + y * y + z * z).sqrt()
        }),
        ProbeSpec::FirstContact => input
            .history
            .iter()
            .find(|s| s.contact.active_vertices > 0)
            .map_or(f64::NAN, |s| s.step as f64),
        ProbeSpec::ConstraintResidual => input.constraint_residual,
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
                EnergyName::Total => e.kinetic + e.elastic + e.external,
            }
        }
    })
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

/// Barycentric coordinates of `p` in rest tet `e`.
fn barycentric(mesh: &TetMesh, e: usize, p: &Vec3) -> [f64; 4] {
    let t = mesh.tets()[e];
    let l = mesh.inverse_rest_shapes()[e] * (p - mesh.positions()[t[0]]);
    [1.0 - l.x - l.y - l.z, l.x, l.y, l.z]
}

/// The displacement at rest point `p`, interpolated with the shape functions of the rest
/// element containing it (or, for a point slightly outside the mesh, the nearest element in
/// barycentric terms). The element is found by its corners; on a curved 10-node element the
/// reference point then comes from Newton's method on the isoparametric map `X(xi) = p`.
pub fn displacement_at(mesh: &ElementMesh, x: &[Vec3], p: &Vec3) -> Result<Vec3, String> {
    let corners = mesh.corners();
    let mut best: Option<(usize, f64)> = None;
    for e in 0..corners.num_tets() {
        let min = barycentric(corners, e, p)
            .into_iter()
            .fold(f64::INFINITY, f64::min);
        if best.is_none_or(|(_, b)| min > b) {
            best = Some((e, min));
            if min >= 0.0 {
                break;
            }
        }
    }
    let (e, min) = best.ok_or("the mesh has no tets")?;
    if min < -0.25 {
        return Err(format!(
            "point ({}, {}, {}) lies outside the mesh",
            p.x, p.y, p.z
        ));
    }
    let [_, l1, l2, l3] = barycentric(corners, e, p);
    let kind = mesh.kind();
    let (nodes, rest) = (mesh.element(e), mesh.nodes());
    let n = kind.num_nodes();
    let (mut values, mut gradients) = (vec![0.0; n], vec![Vec3::zeros(); n]);
    let mut xi = Vec3::new(l1, l2, l3);
    for _ in 0..20 {
        kind.shape_values(&xi, &mut values);
        kind.shape_gradients(&xi, &mut gradients);
        let mapped: Vec3 = nodes.iter().zip(&values).map(|(&a, v)| *v * rest[a]).sum();
        let jacobian = deformation_gradient(rest, nodes, &gradients);
        let Some(step) = jacobian.try_inverse().map(|inverse| inverse * (p - mapped)) else {
            break;
        };
        xi += step;
        if step.norm() < 1e-14 {
            break;
        }
    }
    kind.shape_values(&xi, &mut values);
    Ok(nodes
        .iter()
        .zip(&values)
        .map(|(&a, v)| *v * (x[a] - rest[a]))
        .sum())
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

    #[test]
    fn point_displacement_interpolates_linear_fields_exactly() {
        let mesh = box_grid(Vec3::zeros(), Vec3::new(0.2, 0.05, 0.05), [8, 2, 2]).unwrap();
        let mesh = ElementMesh::linear(mesh);
        let u = |p: &Vec3| Vec3::new(0.1 * p.y, -0.3 * p.x + 0.2 * p.z, 0.05);
        let x: Vec<Vec3> = mesh.nodes().iter().map(|p| p + u(p)).collect();
        for p in [
            Vec3::new(0.2, 0.025, 0.025),
            Vec3::new(0.013, 0.011, 0.049),
            Vec3::zeros(),
        ] {
            let got = displacement_at(&mesh, &x, &p).unwrap();
            assert!((got - u(&p)).norm() < 1e-12, "{got} vs {}", u(&p));
        }
        assert!(displacement_at(&mesh, &x, &Vec3::new(1.0, 1.0, 1.0)).is_err());
    }

    /// On curved 10-node tets (a cylinder's wall on the true surface) the probe reproduces a
    /// quadratic displacement field exactly, at points inside curved boundary elements too.
    #[test]
    fn point_displacement_interpolates_quadratic_fields_on_curved_tets() {
        use isochor_mesh::generate::{cylinder, cylinder_surface};
        let mesh = cylinder(0.1, 0.2, 2).unwrap();
        let mesh = ElementMesh::quadratic_on_surface(mesh, cylinder_surface(0.1)).unwrap();
        let u = |p: &Vec3| Vec3::new(p.x * p.y, p.z * p.z - p.x, 0.3 * p.y * p.z + 0.01);
        let x: Vec<Vec3> = mesh.nodes().iter().map(|p| p + u(p)).collect();
        for p in [
            Vec3::new(0.0, 0.0, 0.1),
            Vec3::new(0.099, 0.0, 0.05),
            Vec3::new(0.07, 0.07, 0.2),
            Vec3::new(-0.03, 0.05, 0.13),
        ] {
            let got = displacement_at(&mesh, &x, &p).unwrap();
            assert!((got - u(&p)).norm() < 1e-13, "at {p}: {got} vs {}", u(&p));
        }
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
}
