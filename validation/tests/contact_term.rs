//! Finite-difference validation of the contact term (augmented-Lagrangian frictionless
//! contact, sec. 8.2-8.3 of Francu et al. 2021): its gradient against central differences of
//! its energy and its Hessian against central differences of its gradient, for half-spaces,
//! spheres and cylinders, moved obstacles and positive multipliers, away from the kink
//! `lambda = rho d` where the energy is only C1.

use isochor_mesh::Vec3;
use isochor_solvers::terms::{Contact, EnergyTerm};
use isochor_solvers::{Obstacle, Shape};
use nalgebra::DMatrix;
use proptest::prelude::*;

/// Finite-difference agreement required (relative to the derivative's size, max norm).
const TOLERANCE: f64 = 1e-6;

/// Central-difference step (m); the kink is kept at least 100 steps away.
const STEP: f64 = 1e-6;

fn vec3() -> impl Strategy<Value = Vec3> {
    (-1.0..1.0f64, -1.0..1.0f64, -1.0..1.0f64).prop_map(|(x, y, z)| Vec3::new(x, y, z))
}

fn unit() -> impl Strategy<Value = Vec3> {
    vec3().prop_filter("non-zero", |v| v.norm() > 0.1)
}

fn shape() -> impl Strategy<Value = Shape> {
    prop_oneof![
        (vec3(), unit()).prop_map(|(point, normal)| Shape::HalfSpace { point, normal }),
        (vec3(), 0.2..1.0f64).prop_map(|(center, radius)| Shape::Sphere { center, radius }),
        (vec3(), unit(), 0.2..1.0f64).prop_map(|(point, axis, radius)| Shape::Cylinder {
            point,
            axis,
            radius
        }),
    ]
}

/// `(energy, gradient, dense Hessian)` of `term` at `x`.
fn evaluate(term: &Contact, x: &[Vec3]) -> (f64, Vec<f64>, DMatrix<f64>) {
    let n = 3 * x.len();
    let mut g = vec![0.0; n];
    let pattern = term.hessian_pattern();
    let mut values = vec![0.0; pattern.len()];
    let e = term
        .evaluate(x, 1.0, Some(&mut g), Some(&mut values))
        .unwrap();
    let mut h = DMatrix::zeros(n, n);
    for (&(r, c), v) in pattern.iter().zip(&values) {
        h[(r, c)] += v;
    }
    (e, g, h)
}

fn shifted(x: &[Vec3], dof: usize, by: f64) -> Vec<Vec3> {
    let mut y = x.to_vec();
    y[dof / 3][dof % 3] += by;
    y
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(256))]

    #[test]
    fn gradient_and_hessian_match_finite_differences(
        shapes in prop::collection::vec(shape(), 1..3),
        translate in vec3(),
        t in 0.0..1.0f64,
        rho in 0.5..50.0f64,
        before in prop::collection::vec(vec3(), 3),
        after in prop::collection::vec(vec3(), 3),
    ) {
        // Vertex 1 is not a candidate: its row must stay zero.
        let obstacles: Vec<Obstacle> = shapes
            .iter()
            .map(|&shape| Obstacle { shape, translate })
            .collect();
        let term = Contact::new(vec![0, 2], obstacles.clone(), vec![rho, 2.0 * rho]);
        term.set_time(t);
        // Multipliers from a projected update at another state: positive where that state
        // penetrated.
        term.update(&before, 0.0);
        let lambda = term.multipliers();
        prop_assert!(lambda.iter().all(|&l| l >= 0.0));
        for (a, &v) in [0usize, 2].iter().enumerate() {
            for (k, o) in obstacles.iter().enumerate() {
                let (d, _, _) = o.distance(&after[v], t);
                let r = [rho, 2.0 * rho][a];
                prop_assume!((lambda[a * obstacles.len() + k] - r * d).abs() > 100.0 * STEP * r);
                // Away from the centre of a sphere or the axis of a cylinder.
                prop_assume!(d > -0.15 + match o.shape {
                    Shape::HalfSpace { .. } => f64::NEG_INFINITY,
                    Shape::Sphere { radius, .. } | Shape::Cylinder { radius, .. } => -radius,
                });
            }
        }
        let (_, g, h) = evaluate(&term, &after);
        prop_assert!(g[3..6].iter().all(|&v| v == 0.0));
        let n = g.len();
        let scale_g = g.iter().fold(1e-3 * rho, |m, v| m.max(v.abs()));
        let scale_h = h.iter().fold(rho, |m: f64, v| m.max(v.abs()));
        let mut fd_h = DMatrix::zeros(n, n);
        for dof in 0..n {
            let (ep, gp, _) = evaluate(&term, &shifted(&after, dof, STEP));
            let (em, gm, _) = evaluate(&term, &shifted(&after, dof, -STEP));
            let fd = (ep - em) / (2.0 * STEP);
            prop_assert!(
                (fd - g[dof]).abs() <= TOLERANCE * scale_g,
                "gradient {dof}: {} against {fd}", g[dof]
            );
            for r in 0..n {
                fd_h[(r, dof)] = (gp[r] - gm[r]) / (2.0 * STEP);
            }
        }
        let error = (&h - &fd_h).abs().max();
        prop_assert!(error <= TOLERANCE * scale_h, "Hessian error {error:e}\n{h}\n{fd_h}");
        prop_assert!((&h - h.transpose()).abs().max() <= 1e-12 * scale_h);
    }

    #[test]
    fn projected_update_releases_and_converges(
        rho in 0.5..50.0f64,
        heights in prop::collection::vec(-0.01..0.01f64, 4),
    ) {
        // Ground z = 0: a vertex below gets a positive multiplier, one above none; an update
        // at a state with every gap within the tolerance and unchanged multipliers converges.
        let x: Vec<Vec3> = heights.iter().map(|&z| Vec3::new(0.0, 0.0, z)).collect();
        let ground = Obstacle::fixed(Shape::HalfSpace { point: Vec3::zeros(), normal: Vec3::z() });
        let term = Contact::new((0..4).collect(), vec![ground], vec![rho; 4]);
        term.update(&x, 1e-9);
        for (l, z) in term.multipliers().iter().zip(&heights) {
            prop_assert!(*l >= 0.0);
            prop_assert_eq!(*l > 0.0, *z < 0.0);
        }
        // Resting exactly on the ground with these forces: no multiplier moves.
        let flat = vec![Vec3::zeros(); 4];
        prop_assert!(term.update(&flat, 1e-9));
        // Lifted off: everything is released.
        let lifted = vec![Vec3::new(0.0, 0.0, 1.0); 4];
        term.update(&lifted, 1e-9);
        prop_assert!(term.multipliers().iter().all(|&l| l == 0.0));
        prop_assert_eq!(term.summary(&lifted).active_vertices, 0);
    }
}
