//! The element layer: reference elements, quadrature exactness, isoparametric rest geometry,
//! quadratic meshes (straight and curved) and their volumes.

use isochor_mesh::element::{
    deformation_gradient, TetElement, TetQuadrature, TriElement, TriQuadrature, TET_EDGES,
    TRI_EDGES,
};
use isochor_mesh::generate::{
    ball, ball_surface, box_grid, cylinder, cylinder_surface, tube, tube_surface,
};
use isochor_mesh::{ElementMesh, ElementSurface, MeshError, TetMesh, Vec3};
use nalgebra::{Matrix3, Vector2};
use std::f64::consts::PI;

/// Deterministic pseudo-random numbers in `[0, 1)` (a 64-bit LCG), for sample points.
struct Lcg(u64);

impl Lcg {
    fn next(&mut self) -> f64 {
        self.0 = self
            .0
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (self.0 >> 11) as f64 / (1u64 << 53) as f64
    }

    /// A point inside the reference tetrahedron.
    fn tet_point(&mut self) -> Vec3 {
        loop {
            let p = Vec3::new(self.next(), self.next(), self.next());
            if p.sum() < 1.0 {
                return p;
            }
        }
    }
}

const TETS: [TetElement; 2] = [TetElement::Tet4, TetElement::Tet10];
const TRIS: [TriElement; 2] = [TriElement::Tri3, TriElement::Tri6];

#[test]
fn shape_functions_are_a_partition_of_unity_and_interpolate_their_nodes() {
    let mut rng = Lcg(7);
    for kind in TETS {
        let n = kind.num_nodes();
        assert_eq!(kind.node_coordinates().len(), n);
        let mut values = vec![0.0; n];
        let mut gradients = vec![Vec3::zeros(); n];
        for (b, xi) in kind.node_coordinates().iter().enumerate() {
            kind.shape_values(xi, &mut values);
            for (a, v) in values.iter().enumerate() {
                assert_eq!(
                    *v,
                    f64::from(u8::from(a == b)),
                    "{kind:?} N_{a} at node {b}"
                );
            }
        }
        for _ in 0..50 {
            let xi = rng.tet_point();
            kind.shape_values(&xi, &mut values);
            kind.shape_gradients(&xi, &mut gradients);
            assert!((values.iter().sum::<f64>() - 1.0).abs() < 1e-15);
            assert!(gradients.iter().sum::<Vec3>().norm() < 1e-14);
            // The element reproduces the reference coordinates: sum_a xi_a N_a = xi.
            let mapped: Vec3 = kind
                .node_coordinates()
                .iter()
                .zip(&values)
                .map(|(p, v)| *v * p)
                .sum();
            assert!((mapped - xi).norm() < 1e-15);
        }
    }
    for kind in TRIS {
        let n = kind.num_nodes();
        let mut values = vec![0.0; n];
        let mut gradients = vec![Vector2::zeros(); n];
        for (b, xi) in kind.node_coordinates().iter().enumerate() {
            kind.shape_values(xi, &mut values);
            for (a, v) in values.iter().enumerate() {
                assert_eq!(
                    *v,
                    f64::from(u8::from(a == b)),
                    "{kind:?} N_{a} at node {b}"
                );
            }
        }
        for _ in 0..50 {
            let xi = rng.tet_point().xy() * 0.9;
            kind.shape_values(&xi, &mut values);
            kind.shape_gradients(&xi, &mut gradients);
            assert!((values.iter().sum::<f64>() - 1.0).abs() < 1e-15);
            assert!(gradients.iter().sum::<Vector2<f64>>().norm() < 1e-14);
        }
    }
}

#[test]
fn shape_gradients_match_central_differences() {
    let mut rng = Lcg(11);
    let h = 1e-6;
    let mut worst: f64 = 0.0;
    for kind in TETS {
        let n = kind.num_nodes();
        let (mut plus, mut minus) = (vec![0.0; n], vec![0.0; n]);
        let mut gradients = vec![Vec3::zeros(); n];
        for _ in 0..20 {
            let xi = rng.tet_point();
            kind.shape_gradients(&xi, &mut gradients);
            for axis in 0..3 {
                let step = h * Vec3::ith(axis, 1.0);
                kind.shape_values(&(xi + step), &mut plus);
                kind.shape_values(&(xi - step), &mut minus);
                for ((p, m), g) in plus.iter().zip(&minus).zip(&gradients) {
                    worst = worst.max(((p - m) / (2.0 * h) - g[axis]).abs());
                }
            }
        }
    }
    for kind in TRIS {
        let n = kind.num_nodes();
        let (mut plus, mut minus) = (vec![0.0; n], vec![0.0; n]);
        let mut gradients = vec![Vector2::zeros(); n];
        for _ in 0..20 {
            let xi = rng.tet_point().xy() * 0.9;
            kind.shape_gradients(&xi, &mut gradients);
            for axis in 0..2 {
                let step = h * Vector2::ith(axis, 1.0);
                kind.shape_values(&(xi + step), &mut plus);
                kind.shape_values(&(xi - step), &mut minus);
                for ((p, m), g) in plus.iter().zip(&minus).zip(&gradients) {
                    worst = worst.max(((p - m) / (2.0 * h) - g[axis]).abs());
                }
            }
        }
    }
    eprintln!("largest |dN/dxi - central difference| = {worst:.1e}");
    assert!(worst < 1e-9, "{worst}");
}

#[test]
fn faces_edges_and_vtk_order_agree() {
    for kind in TETS {
        let nodes = kind.node_coordinates();
        let face = kind.face_element();
        assert_eq!(face.order(), kind.order());
        let mut tri = vec![0.0; face.num_nodes()];
        let mut tet = vec![0.0; kind.num_nodes()];
        for f in 0..4 {
            let local = kind.face_nodes(f);
            assert_eq!(local.len(), face.num_nodes());
            assert!(!local.contains(&f), "face {f} is opposite corner {f}");
            // Mid-edge nodes of the face are the midpoints of its edges, in triangle order.
            for (k, [i, j]) in TRI_EDGES
                .into_iter()
                .enumerate()
                .filter(|_| face.order() == 2)
            {
                let midpoint = 0.5 * (nodes[local[i]] + nodes[local[j]]);
                assert_eq!(nodes[local[3 + k]], midpoint, "face {f}, edge {k}");
            }
            // On the face, the tet's shape functions are the triangle's (and the others vanish).
            for xi in TriQuadrature::Degree4.points() {
                face.shape_values(xi, &mut tri);
                let corners = &local[..3];
                let point = nodes[corners[0]]
                    + xi.x * (nodes[corners[1]] - nodes[corners[0]])
                    + xi.y * (nodes[corners[2]] - nodes[corners[0]]);
                kind.shape_values(&point, &mut tet);
                for (a, value) in tet.iter().enumerate() {
                    let expected = local.iter().position(|&b| b == a).map_or(0.0, |k| tri[k]);
                    assert!((value - expected).abs() < 1e-15, "face {f}, node {a}");
                }
            }
        }
        // VTK's order is a permutation that is its own inverse and keeps the corners.
        let vtk = kind.vtk_order();
        assert_eq!(vtk.len(), kind.num_nodes());
        assert!((0..vtk.len()).all(|k| vtk[vtk[k]] == k) && vtk[..4] == [0, 1, 2, 3]);
    }
    // VTK quadratic tetra: mid-edge nodes on (0,1), (1,2), (2,0), (0,3), (1,3), (2,3).
    let vtk_edges = [[0, 1], [1, 2], [2, 0], [0, 3], [1, 3], [2, 3]];
    let vtk = TetElement::Tet10.vtk_order();
    for (k, [a, b]) in vtk_edges.into_iter().enumerate() {
        let [i, j] = TET_EDGES[vtk[4 + k] - 4];
        assert!([i, j] == [a, b] || [j, i] == [a, b], "VTK node {}", 4 + k);
    }
}

/// `integral over the reference simplex of x^a y^b z^c = a! b! c! / (a + b + c + d)!`
/// (`d` = dimension).
fn monomial_integral(powers: &[u32]) -> f64 {
    let factorial = |n: u32| (1..=n).map(f64::from).product::<f64>();
    let total: u32 = powers.iter().sum();
    powers.iter().map(|&p| factorial(p)).product::<f64>() / factorial(total + powers.len() as u32)
}

/// Largest relative error of `rule` over the monomials of total degree exactly `degree`.
fn worst_monomial_error<const D: usize>(
    points: &[nalgebra::SVector<f64, D>],
    weights: &[f64],
    degree: u32,
) -> f64 {
    let mut worst: f64 = 0.0;
    let mut powers = [0u32; D];
    let count = (degree + 1).pow(D as u32);
    for code in 0..count {
        let mut c = code;
        for p in powers.iter_mut() {
            *p = c % (degree + 1);
            c /= degree + 1;
        }
        if powers.iter().sum::<u32>() != degree {
            continue;
        }
        let quadrature: f64 = points
            .iter()
            .zip(weights)
            .map(|(x, w)| w * (0..D).map(|i| x[i].powi(powers[i] as i32)).product::<f64>())
            .sum();
        let exact = monomial_integral(&powers);
        worst = worst.max((quadrature - exact).abs() / exact);
    }
    worst
}

#[test]
fn quadrature_rules_are_exact_to_their_degree_and_no_further() {
    eprintln!("rule | points | max rel. error, degree <= d | max rel. error, degree d + 1");
    for rule in TetQuadrature::ALL {
        let (points, weights) = (rule.points(), rule.weights());
        assert_eq!(points.len(), weights.len());
        assert!(weights.iter().all(|&w| w > 0.0));
        assert!(points.iter().all(|p| p.min() >= 0.0 && p.sum() <= 1.0));
        let d = rule.degree() as u32;
        let exact = (0..=d)
            .map(|k| worst_monomial_error(points, weights, k))
            .fold(0.0, f64::max);
        let beyond = worst_monomial_error(points, weights, d + 1);
        eprintln!(
            "tet {rule:?} | {} | {exact:.1e} | {beyond:.1e}",
            points.len()
        );
        assert!(exact < 4e-15, "{rule:?}: {exact}");
        assert!(beyond > 1e-4, "{rule:?} is exact one degree higher");
    }
    for rule in TriQuadrature::ALL {
        let (points, weights) = (rule.points(), rule.weights());
        assert!(weights.iter().all(|&w| w > 0.0));
        let d = rule.degree() as u32;
        let exact = (0..=d)
            .map(|k| worst_monomial_error(points, weights, k))
            .fold(0.0, f64::max);
        let beyond = worst_monomial_error(points, weights, d + 1);
        eprintln!(
            "triangle {rule:?} | {} | {exact:.1e} | {beyond:.1e}",
            points.len()
        );
        assert!(exact < 4e-15, "{rule:?}: {exact}");
        assert!(beyond > 1e-4, "{rule:?} is exact one degree higher");
    }
    let tet: Vec<_> = (0..=5)
        .map(|d| TetQuadrature::for_degree(d).unwrap())
        .collect();
    use TetQuadrature::{Degree1, Degree2, Degree3, Degree5};
    assert_eq!(tet, [Degree1, Degree1, Degree2, Degree3, Degree5, Degree5]);
    assert!(matches!(
        TetQuadrature::for_degree(6),
        Err(MeshError::InvalidParameter { .. })
    ));
    assert_eq!(
        TriQuadrature::for_degree(3).unwrap(),
        TriQuadrature::Degree4
    );
    assert!(TriQuadrature::for_degree(5).is_err());
}

/// A skewed box mesh, so that no element is axis-aligned.
fn skewed_box() -> TetMesh {
    let mesh = box_grid(Vec3::zeros(), Vec3::new(1.0, 0.6, 0.8), [3, 2, 2]).unwrap();
    let shear = Matrix3::new(1.0, 0.3, -0.1, 0.05, 1.1, 0.2, -0.2, 0.1, 0.9);
    let positions = mesh.positions().iter().map(|p| shear * p).collect();
    TetMesh::new(positions, mesh.tets().to_vec()).unwrap()
}

#[test]
fn straight_meshes_have_the_affine_geometry_of_their_corners() {
    let corners = skewed_box();
    for mesh in [
        ElementMesh::linear(corners.clone()),
        ElementMesh::quadratic(corners.clone()),
    ] {
        assert_eq!(mesh.num_vertices(), corners.num_vertices());
        assert_eq!(&mesh.nodes()[..mesh.num_vertices()], corners.positions());
        for rule in TetQuadrature::ALL {
            let geometry = mesh.rest_geometry(rule).unwrap();
            for e in 0..mesh.num_elements() {
                let exact = corners.rest_volumes()[e];
                let relative = (geometry.element_volume(e) - exact).abs() / exact;
                assert!(
                    relative < 1e-14,
                    "{:?} {rule:?} element {e}: {relative}",
                    mesh.kind()
                );
                // F of the rest positions is the identity at every point.
                for q in 0..geometry.num_points() {
                    let f = deformation_gradient(
                        mesh.nodes(),
                        mesh.element(e),
                        geometry.gradients(e, q),
                    );
                    assert!((f - Matrix3::identity()).norm() < 1e-13);
                }
            }
        }
        let relative = (mesh.rest_volume() - corners.rest_volume()).abs() / corners.rest_volume();
        assert!(relative < 1e-14);
    }
    // On 4-node tets, dN_a/dX are the columns of D_m^-T [-1 -1 -1; I].
    let mesh = ElementMesh::linear(corners.clone());
    let geometry = mesh.rest_geometry(TetQuadrature::Degree1).unwrap();
    for e in 0..mesh.num_elements() {
        let inverse = corners.inverse_rest_shapes()[e];
        let g = geometry.gradients(e, 0);
        for (a, ga) in g.iter().enumerate().skip(1) {
            assert!((ga - inverse.row(a - 1).transpose()).norm() < 1e-12);
        }
        assert!((g[0] + g[1] + g[2] + g[3]).norm() < 1e-12);
    }
    // The 10-node mesh has one node per vertex and edge, each edge node at its edge's midpoint.
    let quadratic = ElementMesh::quadratic(corners.clone());
    let nv = corners.num_vertices();
    assert_eq!(quadratic.num_nodes(), nv + quadratic.mid_edges().len());
    for (i, &[a, b]) in quadratic.mid_edges().iter().enumerate() {
        assert!(a < b);
        let x = quadratic.nodes();
        assert_eq!(x[nv + i], 0.5 * (x[a] + x[b]));
    }
    for e in 0..quadratic.num_elements() {
        let element = quadratic.element(e);
        assert_eq!(&element[..4], &corners.tets()[e]);
        for (k, [a, b]) in TET_EDGES.into_iter().enumerate() {
            let [i, j] = quadratic.mid_edges()[element[4 + k] - nv];
            assert!([i, j] == [element[a], element[b]] || [j, i] == [element[a], element[b]]);
        }
    }
}

/// `u(X)`: a quadratic displacement field and its gradient.
fn quadratic_field(p: &Vec3) -> (Vec3, Matrix3<f64>) {
    let (x, y, z) = (p.x, p.y, p.z);
    let u = Vec3::new(
        0.1 * x * x - 0.2 * x * y + 0.05 * z,
        0.3 * y * z + 0.1 * x - 0.07 * z * z,
        -0.15 * x * z + 0.2 * y * y + 0.02,
    );
    let grad = Matrix3::new(
        0.2 * x - 0.2 * y,
        -0.2 * x,
        0.05,
        0.1,
        0.3 * z,
        0.3 * y - 0.14 * z,
        -0.15 * z,
        0.4 * y,
        -0.15 * x,
    );
    (u, grad)
}

#[test]
fn ten_node_tets_reproduce_a_quadratic_field_and_its_gradient() {
    let mesh = ElementMesh::quadratic(skewed_box());
    let x: Vec<Vec3> = mesh
        .nodes()
        .iter()
        .map(|p| p + quadratic_field(p).0)
        .collect();
    let mut worst: (f64, f64) = (0.0, 0.0);
    for rule in TetQuadrature::ALL {
        let geometry = mesh.rest_geometry(rule).unwrap();
        for e in 0..mesh.num_elements() {
            let element = mesh.element(e);
            for q in 0..geometry.num_points() {
                let n = geometry.shape_values(q);
                let interpolate = |values: &[Vec3]| -> Vec3 {
                    element.iter().zip(n).map(|(&i, w)| *w * values[i]).sum()
                };
                let rest = interpolate(mesh.nodes());
                let (u, grad) = quadratic_field(&rest);
                worst.0 = worst.0.max((interpolate(&x) - rest - u).norm());
                let f = deformation_gradient(&x, element, geometry.gradients(e, q));
                worst.1 = worst.1.max((f - Matrix3::identity() - grad).norm());
            }
        }
    }
    eprintln!(
        "quadratic field: max |u_h - u| = {:.1e}, max |F_h - F| = {:.1e}",
        worst.0, worst.1
    );
    assert!(worst.0 < 1e-15 && worst.1 < 1e-13, "{worst:?}");
    // 4-node tets reproduce it only at their vertices: F is off by O(h).
    let linear = ElementMesh::linear(skewed_box());
    let geometry = linear.rest_geometry(TetQuadrature::Degree1).unwrap();
    let x: Vec<Vec3> = linear
        .nodes()
        .iter()
        .map(|p| p + quadratic_field(p).0)
        .collect();
    let error = (0..linear.num_elements())
        .map(|e| {
            let f = deformation_gradient(&x, linear.element(e), geometry.gradients(e, 0));
            let (_, grad) = quadratic_field(&linear.corners().centroid(e));
            (f - Matrix3::identity() - grad).norm()
        })
        .fold(0.0, f64::max);
    assert!(error > 1e-3, "{error}");
}

/// Relative volume errors of the linear and the curved 10-node meshes at `res = 1, 2, 4`,
/// printed as a table with the observed orders; checks the curved mesh's own consistency.
fn volume_table(
    name: &str,
    exact: f64,
    mesh: impl Fn(usize) -> TetMesh,
    surface: impl Fn(&Vec3, &Vec3) -> Option<Vec3> + Copy,
) -> Vec<(f64, f64)> {
    let mut rows = Vec::new();
    eprintln!("{name}: res | tets | linear error | order | curved tet10 error | order");
    for res in [1, 2, 4] {
        let corners = mesh(res);
        let tets = corners.num_tets();
        let linear = (corners.rest_volume() - exact).abs() / exact;
        let curved = ElementMesh::quadratic_on_surface(corners, surface).unwrap();
        let volume = curved.rest_volume();
        // The boundary of 6-node faces encloses the same volume, by the degree-4 rule.
        let boundary = curved.boundary().unwrap();
        let enclosed = boundary.enclosed_volume(curved.nodes());
        assert!(
            (enclosed - volume).abs() < 1e-12 * volume,
            "{enclosed} vs {volume}"
        );
        rows.push((linear, (volume - exact).abs() / exact));
        let order = |k: usize, pick: fn(&(f64, f64)) -> f64| {
            if k == 0 {
                String::from("-")
            } else {
                format!("{:.2}", (pick(&rows[k - 1]) / pick(&rows[k])).log2())
            }
        };
        let k = rows.len() - 1;
        eprintln!(
            "{name}: {res} | {tets} | {:.3e} | {} | {:.3e} | {}",
            rows[k].0,
            order(k, |r| r.0),
            rows[k].1,
            order(k, |r| r.1)
        );
    }
    rows
}

#[test]
fn curved_promotion_converges_faster_than_the_linear_mesh() {
    let (r, h) = (0.5, 1.0);
    let rows = volume_table(
        "cylinder",
        PI * r * r * h,
        |res| cylinder(r, h, res).unwrap(),
        cylinder_surface(r),
    );
    for (k, row) in rows.iter().enumerate() {
        assert!(row.1 < row.0 / 10.0, "res {}: {row:?}", 1 << k);
    }
    for w in rows.windows(2) {
        assert!((w[0].1 / w[1].1).log2() > 3.5, "{rows:?}");
    }
    let rows = volume_table(
        "ball",
        4.0 / 3.0 * PI * r * r * r,
        |res| ball(r, res).unwrap(),
        ball_surface(r),
    );
    for w in rows.windows(2) {
        assert!((w[0].1 / w[1].1).log2() > 3.5, "{rows:?}");
    }
    let (ri, ro) = (0.8, 1.0);
    let rows = volume_table(
        "tube",
        PI * (ro * ro - ri * ri) * h,
        |res| tube(ri, ro, h, res).unwrap().mesh,
        tube_surface(ri, ro),
    );
    assert!(rows.iter().all(|row| row.1 < row.0 / 10.0), "{rows:?}");
}

#[test]
fn curved_boundary_nodes_lie_on_the_surface() {
    let r = 0.3;
    let mesh = ElementMesh::quadratic_on_surface(ball(r, 2).unwrap(), ball_surface(r)).unwrap();
    let surface = mesh.boundary().unwrap();
    assert_eq!(surface.kind(), TriElement::Tri6);
    let nodes = surface.nodes();
    assert_eq!(
        nodes.len(),
        surface.corners().vertices().len() + 3 * surface.len() / 2
    );
    for &i in &nodes {
        let d = mesh.nodes()[i].norm();
        assert!(
            (d - r).abs() < 4.0 * f64::EPSILON * r,
            "node {i} at radius {d}"
        );
    }
    // Cylinder: side nodes on the side, cap nodes on the caps (rim edges follow the side).
    let (r, h) = (0.02, 0.1);
    let mesh =
        ElementMesh::quadratic_on_surface(cylinder(r, h, 2).unwrap(), cylinder_surface(r)).unwrap();
    let surface = mesh.boundary().unwrap();
    for f in 0..surface.len() {
        let face = surface.face(f);
        let x = |i: usize| mesh.nodes()[face[i]];
        let on_side = |p: Vec3| (p.xy().norm() - r).abs() < 8.0 * f64::EPSILON * r;
        if (0..3).all(|i| on_side(x(i))) {
            assert!((3..6).all(|i| on_side(x(i))), "side face {f}");
        } else {
            let z = x(0).z;
            assert!((0..6).all(|i| x(i).z == z), "cap face {f}");
        }
    }
    // A zone's boundary encloses the zone's volume.
    let zone: Vec<usize> = (0..mesh.num_elements()).filter(|e| e % 3 == 0).collect();
    let geometry = mesh.rest_geometry(TetQuadrature::Degree5).unwrap();
    let volume: f64 = zone.iter().map(|&e| geometry.element_volume(e)).sum();
    let enclosed = ElementSurface::of_elements(&mesh, &zone)
        .unwrap()
        .enclosed_volume(mesh.nodes());
    assert!((enclosed - volume).abs() < 1e-13 * volume);
}

#[test]
fn curved_elements_keep_affine_fields_exact() {
    // Isoparametric elements reproduce any field that is linear in X, however curved.
    let r = 0.5;
    let mesh = ElementMesh::quadratic_on_surface(cylinder(r, 1.0, 2).unwrap(), cylinder_surface(r))
        .unwrap();
    let a = Matrix3::new(1.1, 0.2, -0.1, 0.0, 0.9, 0.3, 0.05, -0.2, 1.2);
    let x: Vec<Vec3> = mesh
        .nodes()
        .iter()
        .map(|p| a * p + Vec3::new(1.0, 2.0, 3.0))
        .collect();
    let geometry = mesh.rest_geometry(TetQuadrature::Degree2).unwrap();
    let worst = (0..mesh.num_elements())
        .flat_map(|e| (0..4).map(move |q| (e, q)))
        .map(|(e, q)| {
            (deformation_gradient(&x, mesh.element(e), geometry.gradients(e, q)) - a).norm()
        })
        .fold(0.0, f64::max);
    assert!(worst < 1e-12, "{worst}");
}

#[test]
fn reoriented_ten_node_input_keeps_its_edges() {
    let mesh = ElementMesh::quadratic(skewed_box());
    // Every other element listed negatively: corners 2 and 3 swapped, edge nodes moved along.
    let swap = [0, 1, 3, 2, 4, 9, 7, 6, 8, 5];
    let connectivity: Vec<usize> = (0..mesh.num_elements())
        .flat_map(|e| {
            let element = mesh.element(e).to_vec();
            (0..10).map(move |a| element[if e % 2 == 1 { swap[a] } else { a }])
        })
        .collect();
    let read =
        ElementMesh::from_nodes(TetElement::Tet10, mesh.nodes().to_vec(), connectivity).unwrap();
    assert_eq!(read.corners().reoriented(), mesh.num_elements() / 2);
    assert_eq!(read.connectivity(), mesh.connectivity());
    assert_eq!(read.nodes(), mesh.nodes());
    assert_eq!(read.mid_edges(), mesh.mid_edges());
}

#[test]
fn folded_and_malformed_elements_are_named() {
    let corners = TetMesh::new(
        vec![
            Vec3::zeros(),
            Vec3::x(),
            Vec3::y(),
            Vec3::z(),
            Vec3::repeat(1.0),
        ],
        vec![[0, 1, 2, 3], [1, 2, 3, 4]],
    )
    .unwrap();
    let mesh = ElementMesh::quadratic(corners);
    // Pull the mid-edge node of edge (1, 2) of element 1 through the opposite face.
    let mut nodes = mesh.nodes().to_vec();
    let mid = mesh.element(1)[5];
    nodes[mid] = Vec3::new(-0.5, -0.5, 0.0);
    match ElementMesh::from_nodes(TetElement::Tet10, nodes, mesh.connectivity().to_vec()) {
        Err(e @ MeshError::FoldedElement { .. }) => {
            let MeshError::FoldedElement {
                element,
                determinant,
                ..
            } = e
            else {
                unreachable!()
            };
            assert!(determinant <= 0.0);
            assert!(element <= 1);
            assert!(e.to_string().contains(&format!("element {element}")));
        }
        other => panic!("expected a folded element, got {other:?}"),
    }
    let e =
        ElementMesh::from_nodes(TetElement::Tet10, mesh.nodes().to_vec(), vec![0; 9]).unwrap_err();
    assert!(matches!(e, MeshError::InvalidParameter { .. }));
    let mut bad = mesh.connectivity().to_vec();
    bad[13] = 99;
    let e = ElementMesh::from_nodes(TetElement::Tet10, mesh.nodes().to_vec(), bad).unwrap_err();
    assert!(
        matches!(
            e,
            MeshError::IndexOutOfRange {
                tet: 1,
                index: 99,
                ..
            }
        ),
        "{e}"
    );
    // A surface that sends a mid-edge node far away folds its elements.
    let e =
        ElementMesh::quadratic_on_surface(skewed_box(), |a, b| Some(10.0 * (a + b))).unwrap_err();
    assert!(matches!(e, MeshError::FoldedElement { .. }), "{e}");
}
