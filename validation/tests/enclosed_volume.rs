//! The cone volume of a face set about a point (`EnclosedVolume`: the follower pressure's
//! potential and the row of a volume-controlled cavity) against the body's volume by
//! quadrature and against central differences of itself: on the closed boundary of deformed
//! boxes about a random origin, and on a box cut by the three coordinate planes (the faces
//! on the planes left out, the origin on them, the nodes of each plane kept on it: the
//! symmetry cut of an octant), and on a box opened on one plane with the opening capped by
//! the fan from its centroid (`EnclosedVolume::capped`), with 3-node faces on 4-node tets and 6-node faces on curved
//! 10-node tets. The value is exact (degree 1 and 4 integrands, see the module docs), so it
//! matches the volume to rounding; gradient and Hessian match central differences to the
//! bound of the term harness (`terms.rs`).

use isochor_mesh::{probes, ElementMesh, Vec3};
use isochor_solvers::terms::{EnclosedVolume, Faces};
use isochor_validation::fd;
use isochor_validation::strategies::{deformed_box, quadratic};
use nalgebra::{DMatrix, DVector};
use proptest::prelude::*;

/// Agreement of gradient and Hessian with central differences, relative to their max norm
/// (the term harness' bound: its step and error budget apply, the boxes being alike).
const TOLERANCE: f64 = 1e-6;

/// Agreement of the value with the body's volume, relative: rounding only.
const EXACT: f64 = 1e-12;

/// The boundary faces of `mesh` (corner triangles), all of them or only those off the first
/// `planes` coordinate planes.
fn faces(mesh: &ElementMesh, planes: usize) -> Vec<[usize; 3]> {
    let rest = mesh.nodes();
    let on_plane =
        |f: &[usize; 3]| (0..planes).any(|k| f.iter().all(|&v| rest[v][k].abs() < 1e-12));
    mesh.boundary()
        .expect("boundary")
        .corners()
        .triangles()
        .iter()
        .filter(|f| !on_plane(f))
        .copied()
        .collect()
}

/// `x` with the faces on the first `planes` coordinate planes (every node of their face
/// elements, the mid-edge nodes of curved ones too) put back on their plane.
fn onto_planes(mesh: &ElementMesh, mut x: Vec<Vec3>, planes: usize) -> Vec<Vec3> {
    let rest = mesh.nodes();
    let triangles = faces(mesh, 0);
    let nodes = mesh.face_elements(&triangles).expect("face elements");
    let per_face = nodes.len() / triangles.len();
    for (t, face) in triangles.iter().zip(nodes.chunks_exact(per_face)) {
        for k in 0..planes {
            if t.iter().all(|&v| rest[v][k].abs() < 1e-12) {
                face.iter().for_each(|&v| x[v][k] = 0.0);
            }
        }
    }
    x
}

fn flatten(x: &[Vec3]) -> DVector<f64> {
    DVector::from_iterator(3 * x.len(), x.iter().flat_map(|p| p.iter().copied()))
}

fn unflatten(z: &DVector<f64>) -> Vec<Vec3> {
    z.as_slice()
        .chunks_exact(3)
        .map(|c| Vec3::new(c[0], c[1], c[2]))
        .collect()
}

/// Value against the body's volume, gradient and Hessian against central differences; the
/// relative errors.
fn errors(volume: &EnclosedVolume, x: &[Vec3], body: f64) -> (f64, f64, f64) {
    let n = 3 * x.len();
    let gradient = |z: &DVector<f64>| {
        let mut g = vec![0.0; n];
        volume.accumulate(&unflatten(z), 1.0, Some(&mut g), None);
        DVector::from_vec(g)
    };
    let z = flatten(x);
    let g = gradient(&z);
    let g_fd = fd::gradient(|z| volume.value(&unflatten(z)), &z, fd::STEP);
    let mut blocks = vec![0.0; volume.hessian_pattern().len()];
    volume.evaluate(x, 1.0, None, Some(&mut blocks));
    let mut h = DMatrix::zeros(n, n);
    for (&(r, c), v) in volume.hessian_pattern().iter().zip(&blocks) {
        h[(r, c)] += v;
    }
    let h_fd = fd::jacobian(gradient, &z, fd::STEP);
    let value = (volume.value(x) - body).abs() / body.abs();
    let scale = g.amax();
    (
        value,
        fd::relative_error_vec(&g, &g_fd, scale),
        fd::relative_error(&h, &h_fd, h.amax()),
    )
}

/// What is measured: the closed boundary about `origin`, the box cut by the three
/// coordinate planes about the origin of coordinates, or the box opened on the plane
/// `x = 0` and capped, about `origin`.
#[derive(Debug, Clone, Copy)]
enum Surface {
    Closed,
    Cut,
    Capped,
}

fn check(
    mesh: &ElementMesh,
    x: Vec<Vec3>,
    origin: Vec3,
    surface: Surface,
) -> Result<(), TestCaseError> {
    let planes = match surface {
        Surface::Closed => 0,
        Surface::Cut => 3,
        Surface::Capped => 1,
    };
    let x = onto_planes(mesh, x, planes);
    let all: Vec<usize> = (0..mesh.num_elements()).collect();
    let body = probes::volume(mesh, &x, &all).expect("volume");
    let faces = Faces::new(mesh, &faces(mesh, planes)).expect("faces");
    let volume = match surface {
        Surface::Closed => EnclosedVolume::new(faces, origin),
        Surface::Cut => EnclosedVolume::new(faces, Vec3::zeros()),
        Surface::Capped => EnclosedVolume::new(faces, origin).capped().expect("capped"),
    };
    let (value, gradient, hessian) = errors(&volume, &x, body);
    prop_assert!(value < EXACT, "value off by {value:e}");
    prop_assert!(gradient < TOLERANCE, "gradient off by {gradient:e}");
    prop_assert!(hessian < TOLERANCE, "Hessian off by {hessian:e}");
    Ok(())
}

fn origin() -> impl Strategy<Value = Vec3> {
    proptest::array::uniform3(-2.0..2.0f64).prop_map(Vec3::from)
}

fn surface() -> impl Strategy<Value = Surface> {
    prop_oneof![
        Just(Surface::Closed),
        Just(Surface::Cut),
        Just(Surface::Capped)
    ]
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(16))]

    /// 3-node faces: the closed boundary about any origin, the symmetry cut, and an opening
    /// capped by its fan (planar here, so the capped volume is the body's).
    #[test]
    fn cone_volume_of_3_node_faces_is_exact_with_its_derivatives(
        d in deformed_box([2, 2, 2], 0.1, 0.5),
        o in origin(),
        s in surface(),
    ) {
        let mesh = ElementMesh::linear(d.mesh.clone());
        check(&mesh, d.x.clone(), o, s)?;
    }

    /// 6-node faces of curved 10-node tets (the capped loop's edges curved): the same.
    #[test]
    fn cone_volume_of_6_node_faces_is_exact_with_its_derivatives(
        d in quadratic(deformed_box([1, 1, 2], 0.1, 0.5), 0.05, 0.05, 0.3),
        o in origin(),
        s in surface(),
    ) {
        check(&d.mesh, d.x.clone(), o, s)?;
    }
}

/// The check rejects a wrong origin on a cut surface: about a point `o` off the planes, the
/// cone volume of the cut box is its volume minus `o . A / 3`, `A` the area vector of the
/// missing faces' closure (here `o = 0.1 e_x` and `A = e_x`).
#[test]
fn an_origin_off_the_planes_of_a_cut_is_not_exact() {
    let mesh = ElementMesh::linear(
        isochor_mesh::generate::box_grid(Vec3::zeros(), Vec3::repeat(1.0), [2, 2, 2]).unwrap(),
    );
    let faces = Faces::new(&mesh, &faces(&mesh, 3)).unwrap();
    let on = EnclosedVolume::new(faces.clone(), Vec3::zeros()).value(mesh.nodes());
    let off = EnclosedVolume::new(faces, Vec3::new(0.1, 0.0, 0.0)).value(mesh.nodes());
    assert!((on - 1.0).abs() < EXACT, "{on}");
    assert!((off - (1.0 - 0.1 / 3.0)).abs() < EXACT, "{off}");
}

/// An opening capped by its fan closes the volume whatever the origin; uncapped, the cone
/// volume misses the cone from the origin to the opening.
#[test]
fn a_capped_opening_closes_the_volume() {
    let mesh = ElementMesh::quadratic(
        isochor_mesh::generate::box_grid(Vec3::zeros(), Vec3::repeat(1.0), [2, 1, 2]).unwrap(),
    );
    let faces = Faces::new(&mesh, &faces(&mesh, 1)).unwrap();
    let o = Vec3::new(0.7, -0.3, 0.2);
    let open = EnclosedVolume::new(faces.clone(), o).value(mesh.nodes());
    let capped = EnclosedVolume::new(faces, o)
        .capped()
        .unwrap()
        .value(mesh.nodes());
    assert!((capped - 1.0).abs() < EXACT, "{capped}");
    assert!((open - (1.0 - 0.7 / 3.0)).abs() < EXACT, "{open}");
}
