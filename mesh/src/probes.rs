//! Probes: the quantities measured on a deformed state, from the mesh and the node positions
//! alone. The displacement at any rest point (by the element's shape functions, on curved
//! 10-node elements too), the mean displacement of a node set, and the deformed volume of
//! the body or of an element set.
//!
//! ```
//! use isochor_mesh::generate::box_grid;
//! use isochor_mesh::{probes, ElementMesh, Vec3};
//!
//! let mesh = ElementMesh::linear(box_grid(Vec3::zeros(), Vec3::repeat(1.0), [2, 2, 2])?);
//! // Stretch by 10 % along x.
//! let x: Vec<Vec3> = mesh.nodes().iter().map(|p| Vec3::new(1.1 * p.x, p.y, p.z)).collect();
//! let u = probes::displacement_at(&mesh, &x, &Vec3::new(0.5, 0.3, 0.2))?;
//! assert!((u - Vec3::new(0.05, 0.0, 0.0)).norm() < 1e-12);
//! assert!((probes::volume_change(&mesh, &x)? - 0.1).abs() < 1e-12);
//! # Ok::<(), isochor_mesh::MeshError>(())
//! ```

use crate::element::{deformation_gradient, faces_enclosed_volume};
use crate::{check_closed_manifold, ElementMesh, MeshError, TetMesh, Vec3};

/// How far outside every element (in barycentric terms) a point may lie and still be taken
/// as on the mesh (rest points on a curved surface lie slightly outside its corner tets).
const OUTSIDE: f64 = -0.25;

/// The displacement at rest point `p` under node positions `x`, interpolated with the shape
/// functions of the rest element containing it (or, for a point slightly outside the mesh,
/// the nearest element in barycentric terms). The element is found by its corners; on a
/// curved 10-node element the reference point then comes from Newton's method on the
/// isoparametric map `X(xi) = p`. Fails if `x` does not hold one position per node or if
/// `p` lies outside the mesh.
pub fn displacement_at(mesh: &ElementMesh, x: &[Vec3], p: &Vec3) -> Result<Vec3, MeshError> {
    check_positions(mesh, x)?;
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
    let (e, _) = best
        .filter(|&(_, min)| min >= OUTSIDE)
        .ok_or(MeshError::PointOutside {
            point: [p.x, p.y, p.z],
        })?;
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

/// The mean displacement `x_v - X_v` over the nodes `nodes` (an error if the set is empty or
/// names a node out of range).
pub fn mean_displacement(
    mesh: &ElementMesh,
    x: &[Vec3],
    nodes: &[usize],
) -> Result<Vec3, MeshError> {
    check_positions(mesh, x)?;
    if nodes.is_empty() {
        return Err(MeshError::parameter("nodes", 0, "the node set is empty"));
    }
    let rest = mesh.nodes();
    let mut sum = Vec3::zeros();
    for &v in nodes {
        if v >= rest.len() {
            return Err(MeshError::VertexOutOfRange {
                vertex: v,
                vertices: rest.len(),
            });
        }
        sum += x[v] - rest[v];
    }
    Ok(sum / nodes.len() as f64)
}

/// The volume of the elements `elements` at node positions `x` (exact, see
/// [`ElementMesh::volumes_at`]); at `x = mesh.nodes()`, their rest volume.
pub fn volume(mesh: &ElementMesh, x: &[Vec3], elements: &[usize]) -> Result<f64, MeshError> {
    check_positions(mesh, x)?;
    let volumes = mesh.volumes_at(x);
    elements
        .iter()
        .map(|&e| {
            volumes.get(e).ok_or(MeshError::TetOutOfRange {
                tet: e,
                tets: volumes.len(),
            })
        })
        .sum()
}

/// The deformed over the rest volume of the elements `elements` (1 when their volume is
/// kept).
pub fn volume_ratio(mesh: &ElementMesh, x: &[Vec3], elements: &[usize]) -> Result<f64, MeshError> {
    Ok(volume(mesh, x, elements)? / volume(mesh, mesh.nodes(), elements)?)
}

/// The relative volume change `V / V0 - 1` of the whole body at node positions `x` (0 for a
/// perfectly incompressible response).
pub fn volume_change(mesh: &ElementMesh, x: &[Vec3]) -> Result<f64, MeshError> {
    check_positions(mesh, x)?;
    Ok(mesh.total_volume_at(x) / mesh.rest_volume() - 1.0)
}

/// The volume enclosed by the boundary faces `faces` (corner triangles, forming a closed
/// surface such as a chamber's walls) at node positions `x`, by the divergence theorem over
/// the faces' elements: 3-node faces on 4-node tets, 6-node faces (with the mid-edge nodes)
/// on 10-node tets, integrated exactly in both cases. Positive when the faces point out of
/// the enclosed region: a chamber's walls, outward faces of the body, point into the cavity
/// and give minus its volume. Fails if the faces are not a closed surface (where the
/// enclosed volume would depend on the origin) or if an edge is not the mesh's.
pub fn enclosed_volume(
    mesh: &ElementMesh,
    x: &[Vec3],
    faces: &[[usize; 3]],
) -> Result<f64, MeshError> {
    check_positions(mesh, x)?;
    if faces.iter().flatten().any(|&v| v >= mesh.num_vertices()) {
        return Err(MeshError::parameter(
            "faces",
            faces.len(),
            "a face names a vertex out of range",
        ));
    }
    check_closed_manifold(faces)?;
    let nodes = mesh.face_elements(faces)?;
    Ok(faces_enclosed_volume(mesh.kind().face_element(), &nodes, x))
}

/// The deformed over the rest volume enclosed by the faces `faces` (see [`enclosed_volume`];
/// the ratio does not depend on which way the faces point): above 1 for an inflated
/// chamber.
pub fn enclosed_volume_ratio(
    mesh: &ElementMesh,
    x: &[Vec3],
    faces: &[[usize; 3]],
) -> Result<f64, MeshError> {
    Ok(enclosed_volume(mesh, x, faces)? / enclosed_volume(mesh, mesh.nodes(), faces)?)
}

/// The angle (radians, in `[0, pi]`) of the rotation that best maps the rest positions of
/// the nodes `nodes` onto their positions in `x`, both about their centroids (Kabsch's
/// least-squares rotation); about `axis` if given: the signed angle (right-handed about the
/// axis, in `(-pi, pi]`) that best maps their projections on the plane normal to the axis,
/// `atan2(sum (a_i x b_i) . n, sum a_i . b_i)`. A bending angle, whatever the translation.
/// Fails for an empty node set, a node out of range, or a zero axis.
pub fn rotation_angle(
    mesh: &ElementMesh,
    x: &[Vec3],
    nodes: &[usize],
    axis: Option<Vec3>,
) -> Result<f64, MeshError> {
    check_positions(mesh, x)?;
    let rest = mesh.nodes();
    if nodes.is_empty() || nodes.iter().any(|&v| v >= rest.len()) {
        return Err(MeshError::parameter(
            "nodes",
            nodes.len(),
            "the node set is empty or names a node out of range",
        ));
    }
    let count = nodes.len() as f64;
    let centroid = |p: &[Vec3]| nodes.iter().map(|&v| p[v]).sum::<Vec3>() / count;
    let (c0, c1) = (centroid(rest), centroid(x));
    let pairs = nodes.iter().map(|&v| (rest[v] - c0, x[v] - c1));
    match axis {
        Some(axis) => {
            let n = axis.try_normalize(0.0).ok_or_else(|| {
                MeshError::parameter("axis", 0, "the rotation axis must not be zero")
            })?;
            let flat = |a: Vec3| a - n * n.dot(&a);
            let (sin, cos) = pairs.fold((0.0, 0.0), |(s, c), (a, b)| {
                let (a, b) = (flat(a), flat(b));
                (s + a.cross(&b).dot(&n), c + a.dot(&b))
            });
            Ok(sin.atan2(cos))
        }
        None => {
            let h: nalgebra::Matrix3<f64> = pairs.map(|(a, b)| a * b.transpose()).sum();
            let svd = h.svd(true, true);
            let (Some(u), Some(v_t)) = (svd.u, svd.v_t) else {
                return Err(MeshError::parameter(
                    "nodes",
                    nodes.len(),
                    "no best-fit rotation",
                ));
            };
            let mut d = nalgebra::Matrix3::identity();
            d[(2, 2)] = (v_t.transpose() * u.transpose()).determinant().signum();
            let r = v_t.transpose() * d * u.transpose();
            Ok(((r.trace() - 1.0) / 2.0).clamp(-1.0, 1.0).acos())
        }
    }
}

/// Barycentric coordinates of `p` in rest tet `e`.
fn barycentric(mesh: &TetMesh, e: usize, p: &Vec3) -> [f64; 4] {
    let t = mesh.tets()[e];
    let l = mesh.inverse_rest_shapes()[e] * (p - mesh.positions()[t[0]]);
    [1.0 - l.x - l.y - l.z, l.x, l.y, l.z]
}

/// `x` must hold one position per node of `mesh`.
fn check_positions(mesh: &ElementMesh, x: &[Vec3]) -> Result<(), MeshError> {
    if x.len() == mesh.num_nodes() {
        Ok(())
    } else {
        Err(MeshError::parameter(
            "positions",
            x.len(),
            format!("the mesh has {} nodes", mesh.num_nodes()),
        ))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::generate::box_grid;

    #[test]
    fn rotation_angle_recovers_a_rigid_rotation_and_its_sign_about_an_axis() {
        let mesh = ElementMesh::linear(
            box_grid(Vec3::zeros(), Vec3::new(1.0, 0.5, 0.2), [2, 2, 1]).unwrap(),
        );
        let nodes: Vec<usize> = (0..mesh.num_nodes()).collect();
        let axis = Vec3::new(1.0, 2.0, -0.5).normalize();
        for angle in [0.3, -1.2, 2.9] {
            let r =
                nalgebra::Rotation3::from_axis_angle(&nalgebra::Unit::new_normalize(axis), angle);
            let x: Vec<Vec3> = mesh
                .nodes()
                .iter()
                .map(|p| r * p + Vec3::new(0.5, -1.0, 2.0))
                .collect();
            let free = rotation_angle(&mesh, &x, &nodes, None).unwrap();
            let about = rotation_angle(&mesh, &x, &nodes, Some(-axis)).unwrap();
            assert!((free - angle.abs()).abs() < 1e-12, "{free} {angle}");
            assert!((about + angle).abs() < 1e-12, "{about} {angle}");
        }
        assert!(rotation_angle(&mesh, mesh.nodes(), &[], None).is_err());
        assert!(rotation_angle(&mesh, mesh.nodes(), &nodes, Some(Vec3::zeros())).is_err());
    }

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
        assert!(matches!(
            displacement_at(&mesh, &x, &Vec3::new(1.0, 1.0, 1.0)),
            Err(MeshError::PointOutside { .. })
        ));
        assert!(displacement_at(&mesh, &x[1..], &Vec3::zeros()).is_err());
    }

    /// On curved 10-node tets (a cylinder's wall on the true surface) the probe reproduces a
    /// quadratic displacement field exactly, at points inside curved boundary elements too.
    #[test]
    fn point_displacement_interpolates_quadratic_fields_on_curved_tets() {
        use crate::generate::{cylinder, cylinder_surface};
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
    fn set_probes_check_their_indices() {
        let mesh =
            ElementMesh::linear(box_grid(Vec3::zeros(), Vec3::repeat(1.0), [1, 1, 1]).unwrap());
        let x: Vec<Vec3> = mesh.nodes().iter().map(|p| 2.0 * p).collect();
        let all: Vec<usize> = (0..mesh.num_elements()).collect();
        assert!((volume(&mesh, &x, &all).unwrap() - 8.0).abs() < 1e-12);
        assert!((volume_ratio(&mesh, &x, &all[..1]).unwrap() - 8.0).abs() < 1e-12);
        let mean = mean_displacement(&mesh, &x, &[0, 1]).unwrap();
        let expected = (mesh.nodes()[0] + mesh.nodes()[1]) / 2.0;
        assert!((mean - expected).norm() < 1e-12);
        assert!(volume(&mesh, &x, &[all.len()]).is_err());
        assert!(mean_displacement(&mesh, &x, &[]).is_err());
        assert!(mean_displacement(&mesh, &x, &[99]).is_err());
    }

    /// The cushion's chamber walls enclose minus the chamber's volume at rest and keep a
    /// uniform stretch's volume ratio, on 4- and 10-node tets; under an arbitrary smooth
    /// displacement of every node (curved 6-node faces) the whole boundary encloses exactly
    /// the elements' volume (itself exact), which a quadrature below the integrand's degree 4
    /// would miss; an open face set is refused.
    #[test]
    fn enclosed_volume_of_a_chamber_is_exact_on_both_elements() {
        use crate::generate::cushion;
        let (mesh, groups) = cushion(1).unwrap();
        let walls = &groups.get("chamber").unwrap().faces;
        let all = mesh.boundary().unwrap().triangles().to_vec();
        let chamber = 0.03 * 0.03 * 0.004;
        let wavy = |p: &Vec3| {
            p + 2e-3
                * Vec3::new(
                    (150.0 * p.y + 40.0 * p.z).sin(),
                    (90.0 * p.x).cos() * (300.0 * p.z).sin(),
                    (120.0 * p.x * p.y / 0.04).sin(),
                )
        };
        for elements in [
            ElementMesh::linear(mesh.clone()),
            ElementMesh::quadratic(mesh.clone()),
        ] {
            let rest = elements.nodes();
            let v0 = enclosed_volume(&elements, rest, walls).unwrap();
            assert!((v0 + chamber).abs() < 1e-12 * chamber, "{v0}");
            let stretched: Vec<Vec3> = rest.iter().map(|p| 1.1 * p).collect();
            let ratio = enclosed_volume_ratio(&elements, &stretched, walls).unwrap();
            assert!((ratio - 1.331).abs() < 1e-12, "{ratio}");
            let x: Vec<Vec3> = rest.iter().map(wavy).collect();
            let v = enclosed_volume(&elements, &x, &all).unwrap();
            let body = elements.total_volume_at(&x);
            assert!((v - body).abs() < 1e-12 * body, "{v} vs {body}");
        }
        let elements = ElementMesh::linear(mesh);
        assert!(enclosed_volume(&elements, elements.nodes(), &walls[1..]).is_err());
    }
}
