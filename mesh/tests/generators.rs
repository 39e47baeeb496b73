//! Every generator: positive tets, closed outward surface, boundary vertices on the analytic
//! surface, and volumes converging to the analytic volume.

use isochor_mesh::generate::{ball, ball_surface, box_grid, cylinder, hemisphere, puck, tube};
use isochor_mesh::{ElementMesh, MeshError, TetMesh, Vec3};
use std::f64::consts::PI;

/// Checks orientation, surface closure and the divergence theorem; returns the mesh volume.
fn check_mesh(mesh: &TetMesh) -> f64 {
    assert_eq!(mesh.reoriented(), 0, "a generator produced a negative tet");
    let surface = mesh.boundary().unwrap();
    surface.check_closed().unwrap();
    let x = mesh.positions();
    let volume = mesh.rest_volume();
    assert!((surface.enclosed_volume(x) - volume).abs() < 1e-12 * volume);
    // Every vertex is used (no orphan vertices).
    let mut used = vec![false; mesh.num_vertices()];
    mesh.tets().iter().flatten().for_each(|&v| used[v] = true);
    assert!(used.iter().all(|&u| u));
    volume
}

/// Relative volume errors for `res = 1, 2, 4, 8`; asserts they decrease at second order
/// (each halving of the cell size divides the error by at least 3).
fn assert_second_order(name: &str, exact: f64, volume: impl Fn(usize) -> f64) -> Vec<f64> {
    let errors: Vec<f64> = [1, 2, 4, 8]
        .map(|res| (volume(res) - exact).abs() / exact)
        .to_vec();
    let shown: Vec<String> = errors.iter().map(|e| format!("{e:.3e}")).collect();
    eprintln!("{name}: relative volume errors for res 1, 2, 4, 8: {shown:?}");
    for w in errors.windows(2) {
        assert!(
            w[1] * 3.0 < w[0],
            "{name}: errors {errors:?} do not converge at second order"
        );
    }
    errors
}

#[test]
fn box_volume_and_area_are_exact() {
    let mesh = box_grid(
        Vec3::new(-0.5, 0.0, 1.0),
        Vec3::new(0.5, 0.3, 1.7),
        [5, 3, 4],
    )
    .unwrap();
    let volume = check_mesh(&mesh);
    let exact = 1.0 * 0.3 * 0.7;
    assert!((volume - exact).abs() < 1e-15);
    let area = mesh.boundary().unwrap().rest_area();
    assert!((area - 2.0 * (0.3 + 0.7 + 0.3 * 0.7)).abs() < 1e-14);
}

#[test]
fn cylinder_converges_and_lies_on_its_surface() {
    let (r, h) = (0.02, 0.1);
    for res in 1..=6 {
        let mesh = cylinder(r, h, res).unwrap();
        check_mesh(&mesh);
        let layers = (res as f64 * h / r).round() as usize;
        assert_eq!(mesh.num_tets(), 24 * res * res * layers);
        let surface = mesh.boundary().unwrap();
        for &v in surface.vertices() {
            let p = mesh.positions()[v];
            let rho = p.xy().norm();
            let on_side = (rho - r).abs() < 4.0 * f64::EPSILON * r;
            let on_cap = p.z == 0.0 || p.z == h;
            assert!(
                on_side || on_cap,
                "res {res}: surface vertex {v} at {p:?} is off the cylinder"
            );
            assert!(rho <= r * (1.0 + 4.0 * f64::EPSILON));
        }
    }
    let errors = assert_second_order("cylinder", PI * r * r * h, |res| {
        cylinder(r, h, res).unwrap().rest_volume()
    });
    assert!(errors[3] < 1e-2);
}

#[test]
fn puck_has_at_least_res_layers() {
    let mesh = puck(1.0, 0.5, 4).unwrap();
    check_mesh(&mesh);
    assert_eq!(mesh.num_tets(), 24 * 16 * 4);
    assert_eq!(cylinder(1.0, 0.5, 4).unwrap().num_tets(), 24 * 16 * 2);
}

#[test]
fn tube_converges_and_names_its_walls() {
    let (ri, ro, h) = (0.8, 1.0, 0.5);
    for res in 1..=4 {
        let t = tube(ri, ro, h, res).unwrap();
        check_mesh(&t.mesh);
        let x = t.mesh.positions();
        let radius = |v: usize| x[v].xy().norm();
        let on = |v: usize, r: f64| (radius(v) - r).abs() < 4.0 * f64::EPSILON * r;
        assert!(t.inner.faces.iter().flatten().all(|&v| on(v, ri)));
        assert!(t.outer.faces.iter().flatten().all(|&v| on(v, ro)));
        assert!(t.bottom.faces.iter().flatten().all(|&v| x[v].z == 0.0));
        assert!(t.top.faces.iter().flatten().all(|&v| x[v].z == h));
        let surface = t.mesh.boundary().unwrap();
        let parts = [&t.inner, &t.outer, &t.bottom, &t.top];
        assert_eq!(parts.iter().map(|p| p.len()).sum::<usize>(), surface.len());
        assert_eq!(
            parts.map(|p| p.name.as_str()),
            ["inner", "outer", "bottom", "top"]
        );
        // Inner normals point towards the axis, outer ones away from it.
        for (part, sign) in [(&t.inner, -1.0), (&t.outer, 1.0)] {
            for &[a, b, c] in &part.faces {
                let n = (x[b] - x[a]).cross(&(x[c] - x[a]));
                let centre = (x[a] + x[b] + x[c]) / 3.0;
                assert!(sign * n.xy().dot(&centre.xy()) > 0.0);
            }
        }
        // Ring areas are polygonal approximations of pi (ro^2 - ri^2).
        let ring = PI * (ro * ro - ri * ri);
        assert!((t.bottom.area(x) - ring).abs() < 0.1 * ring);
    }
    assert_second_order("tube", PI * (ro * ro - ri * ri) * h, |res| {
        tube(ri, ro, h, res).unwrap().mesh.rest_volume()
    });
}

#[test]
fn ball_converges_and_lies_on_its_sphere() {
    let r = 0.3;
    for res in 1..=5 {
        let mesh = ball(r, res).unwrap();
        check_mesh(&mesh);
        assert_eq!(mesh.num_tets(), 48 * res * res * res);
        let surface = mesh.boundary().unwrap();
        for &v in surface.vertices() {
            let d = mesh.positions()[v].norm();
            assert!(
                (d - r).abs() < 4.0 * f64::EPSILON * r,
                "res {res}: vertex {v} at radius {d}"
            );
        }
    }
    let errors = assert_second_order("ball", 4.0 / 3.0 * PI * r * r * r, |res| {
        ball(r, res).unwrap().rest_volume()
    });
    assert!(errors[3] < 2e-2);
}

/// The smallest normalized volume of a mesh's tets ([`TetMesh::quality`]).
fn worst_quality(mesh: &TetMesh) -> f64 {
    (0..mesh.num_tets())
        .map(|e| mesh.quality(e))
        .fold(f64::INFINITY, f64::min)
}

#[test]
fn hemisphere_is_the_lower_half_ball_graded_towards_its_pole() {
    let r = 0.3;
    for res in 1..=4 {
        // Ungraded: exactly the lower half of the ball (the ball is mirror symmetric in z).
        let half = hemisphere(r, res, 1.0).unwrap();
        let volume = check_mesh(&half);
        assert_eq!(half.num_tets(), 24 * res * res * res);
        let whole = ball(r, res).unwrap().rest_volume();
        assert!((2.0 * volume - whole).abs() < 1e-12 * whole, "res {res}");
        for grading in [1.0, 2.0, 3.0] {
            let mesh = hemisphere(r, res, grading).unwrap();
            check_mesh(&mesh);
            let x = mesh.positions();
            for &v in mesh.boundary().unwrap().vertices() {
                let (d, z) = (x[v].norm(), x[v].z);
                assert!(
                    z <= 0.0,
                    "res {res}, grading {grading}: vertex {v} above the equator"
                );
                assert!(
                    (d - r).abs() < 4.0 * f64::EPSILON * r || z == 0.0,
                    "res {res}, grading {grading}: boundary vertex {v} at radius {d}, z {z}"
                );
            }
            // The pole's neighbour on the axis sits at r res^-grading above it.
            let above = r * (1.0 - (res as f64).powf(-grading));
            assert!(
                x.iter()
                    .any(|p| p.xy().norm() == 0.0 && (p.z + above).abs() < 1e-15),
                "res {res}, grading {grading}: no node at z = -{above}"
            );
            eprintln!(
                "hemisphere res {res}, grading {grading}: worst tet quality {:.3}",
                worst_quality(&mesh)
            );
            // The 10-node promotion onto the sphere folds no element (its constructor checks
            // det(dX/dxi) > 0 at every quadrature rule's points).
            ElementMesh::quadratic_on_surface(mesh, ball_surface(r)).unwrap();
        }
    }
}

#[test]
fn bad_parameters_are_named() {
    let name = |e: MeshError| match e {
        MeshError::InvalidParameter { name, .. } => name,
        other => panic!("unexpected {other}"),
    };
    assert_eq!(name(cylinder(-1.0, 1.0, 2).unwrap_err()), "radius");
    assert_eq!(name(cylinder(1.0, f64::NAN, 2).unwrap_err()), "height");
    assert_eq!(name(cylinder(1.0, 1.0, 0).unwrap_err()), "res");
    assert_eq!(name(puck(1.0, 1e9, 4).unwrap_err()), "height");
    assert_eq!(name(tube(1.0, 0.5, 1.0, 2).unwrap_err()), "outer_radius");
    assert_eq!(name(tube(0.0, 0.5, 1.0, 2).unwrap_err()), "inner_radius");
    assert_eq!(name(ball(1.0, 100_000).unwrap_err()), "res");
    assert_eq!(name(hemisphere(1.0, 2, 0.0).unwrap_err()), "grading");
}
