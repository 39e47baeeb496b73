//! The cloth kernels of `isochor_energies::cloth`:
//! - the plane-stress Saint Venant-Kirchhoff membrane of a triangle and the discrete-shell
//!   hinge (Grinspun et al. 2003): energy, gradient and Hessian against central differences at
//!   stretched, compressed and sheared triangles and at flat, bent and nearly folded hinges;
//! - the membrane under a uniform in-plane stretch against the closed form of its stress;
//! - a strip bent to a circular arc against the plate energy `(D / 2) int kappa^2 dA`;
//! - the assembled cloth term of `isochor_solvers::terms::Cloth` on a small sheet.

use isochor_energies::cloth::bending::{dihedral_angle, RestHinge};
use isochor_energies::cloth::membrane::{energy_gradient_hessian, second_piola_kirchhoff};
use isochor_energies::cloth::Fabric;
use isochor_energies::triangle::{reduced_deformation_gradient, RestTriangle};
use isochor_mesh::{hinges, Vec3};
use isochor_solvers::terms::{Cloth, EnergyTerm};
use isochor_solvers::LoadLevel;
use isochor_validation::fd;
use isochor_validation::terms::evaluate_dense;
use nalgebra::{DMatrix, DVector, Matrix2, Matrix3, Rotation3, Unit, Vector3};
use proptest::prelude::*;

/// A cotton-like fabric: E = 5 MPa, nu = 0.3, 0.5 mm thick.
fn fabric() -> Fabric {
    Fabric::new(5e6, 0.3, 5e-4).unwrap()
}

fn points<const N: usize>(x: &DVector<f64>) -> [Vector3<f64>; N] {
    std::array::from_fn(|a| Vector3::new(x[3 * a], x[3 * a + 1], x[3 * a + 2]))
}

fn flatten<const N: usize>(x: &[Vector3<f64>; N]) -> DVector<f64> {
    DVector::from_iterator(3 * N, x.iter().flat_map(|p| p.iter().copied()))
}

/// The rest triangle: a generic one in the plane z = 0, 1 cm across.
fn rest_triangle() -> [Vector3<f64>; 3] {
    [
        Vector3::new(0.0, 0.0, 0.0),
        Vector3::new(0.011, 0.001, 0.0),
        Vector3::new(0.003, 0.009, 0.0),
    ]
}

/// An in-plane deformation `[[s1, g], [0, s2]]` of the rest triangle, rotated and moved off
/// its plane.
fn deformed_triangle(s1: f64, s2: f64, shear: f64, angle: f64) -> [Vector3<f64>; 3] {
    let stretch = Matrix3::new(s1, shear, 0.0, 0.0, s2, 0.0, 0.0, 0.0, 1.0);
    let rotation =
        Rotation3::from_axis_angle(&Unit::new_normalize(Vector3::new(1.0, 2.0, 0.5)), angle);
    rest_triangle().map(|p| rotation * (stretch * p) + Vector3::new(0.1, -0.2, 0.05))
}

fn membrane_check(x: [Vector3<f64>; 3]) -> Result<(), TestCaseError> {
    let fabric = fabric();
    let rest = RestTriangle::new(&rest_triangle()).unwrap();
    let terms = energy_gradient_hessian(&fabric, &x, &rest);
    let at = flatten(&x);
    let h = 1e-6 * 0.01;
    let energy = |y: &DVector<f64>| energy_gradient_hessian(&fabric, &points(y), &rest).energy;
    let gradient = |y: &DVector<f64>| {
        let g = energy_gradient_hessian(&fabric, &points(y), &rest).gradient;
        DVector::from_column_slice(g.as_slice())
    };
    let g = DVector::from_column_slice(terms.gradient.as_slice());
    let scale = fabric.mu() * fabric.thickness() * 0.01;
    let g_error = fd::relative_error_vec(&g, &fd::gradient(energy, &at, h), scale * 1e-3);
    let hess = DMatrix::from_column_slice(9, 9, terms.hessian.as_slice());
    let h_error = fd::relative_error(&hess, &fd::jacobian(gradient, &at, h), scale * 1e-3);
    prop_assert!(g_error < 1e-6, "gradient error {g_error:e}");
    prop_assert!(h_error < 1e-6, "Hessian error {h_error:e}");
    prop_assert!((hess.clone() - hess.transpose()).amax() <= 1e-12 * hess.amax());
    Ok(())
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    /// Stretched (up to 1.8), compressed (down to 0.3, where the Hessian is indefinite) and
    /// sheared triangles, in any orientation.
    #[test]
    fn membrane_derivatives_match_central_differences(
        s1 in 0.3..1.8f64, s2 in 0.3..1.8f64, shear in -0.6..0.6f64, angle in -3.0..3.0f64,
    ) {
        membrane_check(deformed_triangle(s1, s2, shear, angle))?;
    }

    /// Hinges of two triangles at dihedral angles from flat to nearly folded (|theta| up to
    /// 3.1), with a rest angle of either sign.
    #[test]
    fn hinge_derivatives_match_central_differences(
        theta in -3.1..3.1f64, rest_angle in -1.0..1.0f64, stretch in 0.6..1.5f64,
        lean in -0.3..0.3f64, angle in -3.0..3.0f64,
    ) {
        hinge_check(theta, rest_angle, stretch, lean, angle)?;
    }
}

/// A hinge with its shared edge along x from 0 to `l`, the first wing at `x2`, and the second
/// wing rotated by `theta` about the edge (so the dihedral angle is `theta`).
fn hinge(theta: f64, l: f64, x2: Vector3<f64>, x3_flat: Vector3<f64>) -> [Vector3<f64>; 4] {
    let fold = Rotation3::from_axis_angle(&Vector3::x_axis(), theta);
    [
        Vector3::zeros(),
        Vector3::new(l, 0.0, 0.0),
        x2,
        fold * x3_flat,
    ]
}

fn hinge_check(
    theta: f64,
    rest_angle: f64,
    stretch: f64,
    lean: f64,
    angle: f64,
) -> Result<(), TestCaseError> {
    let fabric = fabric();
    let (x2, x3) = (
        Vector3::new(0.004, 0.008, 0.0),
        Vector3::new(0.006, -0.007, 0.0),
    );
    let rest = RestHinge::new(&fabric, &hinge(rest_angle, 0.01, x2, x3)).unwrap();
    prop_assert!((rest.rest_angle() - rest_angle).abs() < 1e-12);
    let rotation =
        Rotation3::from_axis_angle(&Unit::new_normalize(Vector3::new(0.3, -1.0, 2.0)), angle);
    let x = hinge(
        theta,
        0.01 * stretch,
        x2 + Vector3::new(lean * 0.01, 0.0, 0.0),
        x3,
    )
    .map(|p| rotation * p);
    let measured = dihedral_angle(&x).unwrap();
    prop_assert!(
        (measured - theta).abs() < 1e-10,
        "angle {measured} for {theta}"
    );
    let terms = rest.energy_gradient_hessian(&x).unwrap();
    let at = flatten(&x);
    let h = 1e-6 * 0.01;
    let energy = |y: &DVector<f64>| rest.energy_gradient_hessian(&points(y)).unwrap().energy;
    let gradient = |y: &DVector<f64>| {
        let g = rest.energy_gradient_hessian(&points(y)).unwrap().gradient;
        DVector::from_column_slice(g.as_slice())
    };
    let g = DVector::from_column_slice(terms.gradient.as_slice());
    // The natural scales: D / l per unit angle for the gradient, D / l^2 for the Hessian.
    let d = fabric.bending_stiffness();
    let g_error = fd::relative_error_vec(&g, &fd::gradient(energy, &at, h), 1e-3 * d / 0.01);
    let hess = DMatrix::from_column_slice(12, 12, terms.hessian.as_slice());
    let h_fd = fd::jacobian(gradient, &at, h);
    let h_error = fd::relative_error(&hess, &h_fd, 1e-3 * d / 1e-4);
    prop_assert!(
        g_error < 1e-6,
        "gradient error {g_error:e} at theta {theta}"
    );
    prop_assert!(h_error < 1e-5, "Hessian error {h_error:e} at theta {theta}");
    prop_assert!((hess.clone() - hess.transpose()).amax() <= 1e-12 * hess.amax());
    Ok(())
}

/// Under `F~ = diag(s1, s2)` in the sheet's plane, `S = 2 mu E + lambda_s tr(E) I` with
/// `E = diag((s1^2 - 1) / 2, (s2^2 - 1) / 2)`; under uniaxial stress (`S_22 = 0`) the lateral
/// stretch is `s2^2 = 1 - nu (s1^2 - 1)` and `S_11 = E (s1^2 - 1) / 2`. The nodal forces
/// equal the traction `h P n` integrated over the edges.
#[test]
fn membrane_stress_under_uniform_stretch_is_the_closed_form() {
    let (young, nu, thickness) = (5e6, 0.3, 5e-4);
    let fabric = Fabric::new(young, nu, thickness).unwrap();
    let rest = RestTriangle::new(&rest_triangle()).unwrap();
    for (s1, s2) in [(1.2, 1.0), (1.1, 0.9), (0.8, 1.3), (1.5, 1.5)] {
        let x = deformed_triangle(s1, s2, 0.0, 0.0);
        let f = reduced_deformation_gradient(&x, &rest);
        let s = second_piola_kirchhoff(&fabric, &f);
        let (e1, e2) = (0.5 * (s1 * s1 - 1.0), 0.5 * (s2 * s2 - 1.0));
        let mu = young / (2.0 * (1.0 + nu));
        let lambda_s = young * nu / (1.0 - nu * nu);
        // The rest frame of the triangle is rotated within the plane: compare invariants.
        let expected = Matrix2::new(
            2.0 * mu * e1 + lambda_s * (e1 + e2),
            0.0,
            0.0,
            2.0 * mu * e2 + lambda_s * (e1 + e2),
        );
        let (trace, det) = (s.trace(), s.determinant());
        assert!((trace - expected.trace()).abs() <= 1e-10 * expected.trace().abs().max(mu));
        assert!((det - expected.determinant()).abs() <= 1e-10 * (mu * mu));
    }
    let s1: f64 = 1.3;
    let s2 = (1.0 - nu * (s1 * s1 - 1.0)).sqrt();
    let x = deformed_triangle(s1, s2, 0.0, 0.0);
    let s = second_piola_kirchhoff(&fabric, &reduced_deformation_gradient(&x, &rest));
    let eigen = s.symmetric_eigenvalues();
    let (small, large) = (eigen.min(), eigen.max());
    assert!(small.abs() <= 1e-10 * young, "lateral stress {small}");
    let uniaxial = young * 0.5 * (s1 * s1 - 1.0);
    assert!(
        (large - uniaxial).abs() <= 1e-10 * uniaxial,
        "{large} vs {uniaxial}"
    );
}

/// A strip of width `w` and length `L` on a regular mesh of `n x 2` rectangles (each split by
/// one diagonal) bent around the y axis to a circular arc of radius `R`. The hinges along the
/// axis fold by the cells' angle `L / (n R)` exactly (the diagonal and lengthwise hinges stay
/// flat: their four vertices lie on one chord plane), so each carries the plate energy
/// `(D / 2) kappa^2` of its dual cell of area `w L / n`, and the sum is the continuum
/// `(D / 2) L w / R^2` but for the half cells at the two ends, which no hinge covers: exactly
/// `(n - 1) / n` of it, an error `1 / n` (first order, the boundary's).
#[test]
fn bent_strip_matches_the_plate_energy() {
    let fabric = fabric();
    let (length, width, radius) = (0.1, 0.02, 0.05);
    let exact = 0.5 * fabric.bending_stiffness() * length * width / (radius * radius);
    let mut errors = Vec::new();
    for n in [8usize, 16, 32, 64] {
        let energy = bent_strip_energy(&fabric, n, length, width, radius);
        let interior = exact * (n - 1) as f64 / n as f64;
        assert!(
            (energy - interior).abs() <= 1e-9 * exact,
            "n = {n}: {energy:e} vs {interior:e}"
        );
        errors.push((energy - exact) / exact);
    }
    let orders: Vec<f64> = errors.windows(2).map(|w| (w[0] / w[1]).log2()).collect();
    println!("bent strip: relative errors {errors:.3?}, observed orders {orders:.2?}");
    assert!(errors[3].abs() < 0.02, "error {:e} at n = 64", errors[3]);
}

/// Sum of hinge energies of the strip: `n` cells along x (bent), 2 across y.
fn bent_strip_energy(fabric: &Fabric, n: usize, length: f64, width: f64, radius: f64) -> f64 {
    let (rest, triangles) = grid(n, 2, length, width);
    let bent = |p: &Vec3| {
        let phi = p.x / radius;
        Vec3::new(radius * phi.sin(), p.y, radius * (1.0 - phi.cos()))
    };
    hinges(&triangles)
        .unwrap()
        .iter()
        .map(|h| {
            let hinge = RestHinge::new(fabric, &h.map(|v| rest[v])).unwrap();
            hinge
                .energy_gradient_hessian(&h.map(|v| bent(&rest[v])))
                .unwrap()
                .energy
        })
        .sum()
}

/// A sheet of `n x m` rectangles (each split by one diagonal) spanning `length x width` in the
/// plane z = 0.
fn grid(n: usize, m: usize, length: f64, width: f64) -> (Vec<Vec3>, Vec<[usize; 3]>) {
    let node = |i: usize, j: usize| i * (m + 1) + j;
    let nodes = (0..=n)
        .flat_map(|i| {
            (0..=m).map(move |j| {
                Vec3::new(
                    length * i as f64 / n as f64,
                    width * j as f64 / m as f64,
                    0.0,
                )
            })
        })
        .collect();
    let triangles = (0..n)
        .flat_map(|i| {
            (0..m).flat_map(move |j| {
                [
                    [node(i, j), node(i + 1, j), node(i + 1, j + 1)],
                    [node(i, j), node(i + 1, j + 1), node(i, j + 1)],
                ]
            })
        })
        .collect();
    (nodes, triangles)
}

/// The cloth term's energy, gradient and dense Hessian at `x`.
fn evaluate_term(term: &Cloth, x: &[Vec3]) -> (f64, DVector<f64>, DMatrix<f64>) {
    let (e, g, h) = evaluate_dense(term, x, &LoadLevel::FULL);
    (e, DVector::from_vec(g), h)
}

fn positions(y: &DVector<f64>) -> Vec<Vec3> {
    y.as_slice()
        .chunks_exact(3)
        .map(|p| Vec3::new(p[0], p[1], p[2]))
        .collect()
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(6))]

    /// The assembled term on a 2x2 sheet with `rest_scale` 0.9: its gradient against central
    /// differences of its energy at crumpled states; where every element is convex (the sheet
    /// stretched flat, each hinge at its rest angle) its Hessian against differences of the
    /// gradient, and everywhere symmetric and positive semidefinite (the projection); the
    /// exact Hessian (`project_hessian(false)`) against differences of the gradient everywhere.
    #[test]
    fn cloth_term_gradient_and_hessian_match_central_differences(
        stretch in 1.0..1.3f64,
        bumps in proptest::collection::vec(-1.0..1.0f64, 9 * 3),
    ) {
        let (rest, triangles) = grid(2, 2, 0.02, 0.02);
        let term = Cloth::new(&rest, triangles, fabric(), 0.9).unwrap();
        prop_assert_eq!(term.num_hinges(), 3 * 2 * 2 - 2 * 2);
        let h = 1e-6 * 0.01;
        let flat: Vec<Vec3> = rest.iter().map(|p| p * (0.9 * stretch)).collect();
        let crumpled: Vec<Vec3> = rest
            .iter()
            .zip(bumps.chunks_exact(3))
            .map(|(p, b)| p * stretch + Vec3::new(b[0], b[1], b[2]) * 0.002)
            .collect();
        for (x, convex) in [(&flat, true), (&crumpled, false)] {
            let (_, g, hess) = evaluate_term(&term, x);
            let at = DVector::from_iterator(3 * x.len(), x.iter().flat_map(|p| p.iter().copied()));
            let energy = |y: &DVector<f64>| evaluate_term(&term, &positions(y)).0;
            let scale = fabric().mu() * fabric().thickness() * 0.01;
            let g_error = fd::relative_error_vec(&g, &fd::gradient(energy, &at, h), scale * 1e-3);
            prop_assert!(g_error < 1e-6, "gradient error {g_error:e}");
            prop_assert!((hess.clone() - hess.transpose()).amax() <= 1e-12 * hess.amax());
            let smallest = hess.clone().symmetric_eigenvalues().min();
            prop_assert!(smallest >= -1e-9 * hess.amax(), "eigenvalue {smallest:e}");
            let gradient = |y: &DVector<f64>| evaluate_term(&term, &positions(y)).1;
            let differences = fd::jacobian(gradient, &at, h);
            if convex {
                let h_error = fd::relative_error(&hess, &differences, 1e-3 * hess.amax());
                prop_assert!(h_error < 1e-5, "Hessian error {h_error:e}");
            }
            // The exact Hessian (what Newton factorizes first) everywhere.
            term.project_hessian(false);
            let (_, _, exact) = evaluate_term(&term, x);
            term.project_hessian(true);
            let h_error = fd::relative_error(&exact, &differences, 1e-3 * exact.amax());
            prop_assert!(h_error < 1e-5, "exact Hessian error {h_error:e}");
        }
    }
}

/// Bad sheets are errors naming what is wrong: a non-positive `rest_scale`, a degenerate
/// triangle, an edge shared by three triangles.
#[test]
fn cloth_term_refuses_bad_sheets() {
    let (rest, triangles) = grid(1, 1, 0.01, 0.01);
    let message = |r: Result<Cloth, isochor_solvers::SolverError>| r.unwrap_err().to_string();
    assert!(message(Cloth::new(&rest, triangles.clone(), fabric(), 0.0)).contains("rest_scale"));
    let mut degenerate = rest.clone();
    degenerate[3] = degenerate[0];
    assert!(
        message(Cloth::new(&degenerate, triangles.clone(), fabric(), 1.0)).contains("degenerate")
    );
    let (mut fin_rest, mut fin) = (rest.clone(), triangles.clone());
    fin_rest.push(Vec3::new(0.005, 0.005, 0.005));
    fin.push([3, 0, 4]);
    let error = message(Cloth::new(&fin_rest, fin, fabric(), 1.0));
    assert!(error.contains("shared by 3"), "{error}");
}
