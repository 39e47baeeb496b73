//! Finite-difference validation of the contact term (augmented-Lagrangian frictionless
//! contact, sec. 8.2-8.3 of Francu et al. 2021): its gradient against central differences of
//! its energy and its Hessian against central differences of its gradient, for half-spaces,
//! spheres, cylinders and rings, moved obstacles, positive multipliers and raised penalties,
//! away from the kink `lambda = rho d` where the energy is only C1; the ring's signed
//! distance, gradient and Hessian against differences of each other, near its axis and its
//! tube's centre circle too; and the projected multiplier update, its convergence flag, the
//! penalties' growth and the contact summary against their formulas.

use isochor_mesh::Vec3;
use isochor_solvers::terms::Contact;
use isochor_solvers::{LoadLevel, Obstacle, Shape};
use isochor_validation::terms::evaluate_dense;
use nalgebra::DMatrix;
use proptest::prelude::*;

/// Finite-difference agreement required (relative to the derivative's size, max norm).
const TOLERANCE: f64 = 1e-6;

/// Central-difference step (m); the kink is kept at least 100 steps away.
const STEP: f64 = 1e-6;

/// Smallest distance `|r|` of a vertex from a sphere's centre or a cylinder's axis (m), where
/// `d = |r| - R` is singular. The Hessian of `d` is `(I - u u^T) / |r|`, so the central
/// differences of the gradient `-f grad d` err by about `STEP^2 f / |r|^3`. Against a sphere
/// or cylinder `d >= -R`, so `lambda <= rho_a R` and `f = lambda - rho_a d <= 2 rho_a R <= 4 rho`:
/// at `|r| = 0.15` the error is about `1e-9 rho`, far inside `TOLERANCE` times the Hessian
/// scale (at least `rho`); at `|r| ~ STEP` the stencil straddles the centre and means nothing.
const MIN_RADIAL: f64 = 0.15;

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
        (vec3(), unit(), 0.4..1.0f64, 0.1..0.3f64).prop_map(|(center, axis, radius, tube)| {
            Shape::Ring {
                center,
                axis,
                radius,
                tube,
            }
        }),
    ]
}

/// Distance from the axis of a ring at parameter `t`, and from its tube's centre circle.
fn ring_radii(o: &Obstacle, x: &Vec3, t: f64) -> Option<(f64, f64)> {
    let Shape::Ring {
        center,
        axis,
        radius,
        ..
    } = o.shape
    else {
        return None;
    };
    let a = axis.normalize();
    let r = x - center - t * o.translate;
    let rho = (r - a * a.dot(&r)).norm();
    let big = radius + t * o.radius_change;
    Some((rho, (rho - big).hypot(a.dot(&r))))
}

/// `(energy, gradient, dense Hessian)` of `term` at `x`.
fn evaluate(term: &Contact, x: &[Vec3]) -> (f64, Vec<f64>, DMatrix<f64>) {
    evaluate_dense(term, x, &LoadLevel::FULL)
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
        radius_change in -0.1..0.1f64,
        t in 0.0..1.0f64,
        rho in 0.5..50.0f64,
        before in prop::collection::vec(vec3(), 3),
        after in prop::collection::vec(vec3(), 3),
        updates in 1..4usize,
    ) {
        // Vertex 1 is not a candidate: its row must stay zero.
        // A half-space has no radius to change.
        let radius_change = if shapes.iter().any(|s| matches!(s, Shape::HalfSpace { .. })) {
            0.0
        } else {
            radius_change
        };
        let obstacles: Vec<Obstacle> = shapes
            .iter()
            .map(|&shape| Obstacle { shape, translate, radius_change, curve: None })
            .collect();
        let term = Contact::new(vec![0, 2], obstacles.clone(), vec![rho, 2.0 * rho]);
        term.begin_step(LoadLevel::quasi_static(t));
        // Multipliers from projected updates at another state: positive where that state
        // penetrated. Repeated at the same state a violation does not fall, so from the
        // second update on the penalties grow: the derivatives hold at any penalty scale.
        for _ in 0..updates {
            term.update(&before, 0.0);
        }
        let rho = rho * term.penalty_scale();
        let lambda = term.multipliers();
        prop_assert!(lambda.iter().all(|&l| l >= 0.0));
        for (a, &v) in [0usize, 2].iter().enumerate() {
            for (k, o) in obstacles.iter().enumerate() {
                let (d, _, _) = o.distance(&after[v], t);
                let r = [rho, 2.0 * rho][a];
                prop_assume!((lambda[a * obstacles.len() + k] - r * d).abs() > 100.0 * STEP * r);
                // At least MIN_RADIAL from the centre of a sphere or the axis of a cylinder,
                // where `d = |r| - R` is singular.
                if let Shape::Sphere { radius, .. } | Shape::Cylinder { radius, .. } = o.shape {
                    prop_assume!(d + radius + t * radius_change >= MIN_RADIAL);
                }
                // A ring's Hessian has the same `1 / |q|` and a `R / (rho |q|)` term: the same
                // bound away from its axis and its tube's centre circle.
                if let Some((rho, q)) = ring_radii(o, &after[v], t) {
                    prop_assume!(rho >= MIN_RADIAL && q >= MIN_RADIAL);
                }
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

    /// The ring's `d`, `grad d` and `Hess d` (moved and with its major radius changed) against
    /// central differences of `d` and of `grad d`, at points anywhere, at `10^-3` to `10^-1`
    /// of `R` from its axis (where the `R / rho` curvature is large), and at `10^-3` to
    /// `10^-1` of `r` from its tube's centre circle (where `1 / |q|` is). The step is `1e-4`
    /// of the nearer of those distances, so that the truncation error, about
    /// `(step / distance)^2` of the Hessian, is `1e-8` of it; rounding adds about
    /// `eps / step` (below `1e-7` of the unit gradient).
    #[test]
    fn ring_distance_matches_finite_differences(
        center in vec3(),
        axis in unit(),
        radius in 0.4..1.0f64,
        tube_fraction in 0.1..0.9f64,
        translate in vec3(),
        radius_change in -0.1..0.1f64,
        t in 0.0..1.0f64,
        place in 0..3usize,
        log_near in -3.0..-1.0f64,
        angle in 0.0..std::f64::consts::TAU,
        around in 0.0..std::f64::consts::TAU,
        far in (0.0..2.0f64, -1.0..1.0f64),
    ) {
        let tube = tube_fraction * (radius - 0.1);
        let obstacle = Obstacle {
            shape: Shape::Ring { center, axis, radius, tube },
            translate,
            radius_change,
            curve: None,
        };
        let big = radius + t * radius_change;
        let a = axis.normalize();
        let e1 = a.cross(&Vec3::new(0.3, -0.5, 0.8)).normalize();
        let e2 = a.cross(&e1);
        let (rho, height) = match place {
            0 => (far.0, far.1),
            1 => (10f64.powf(log_near) * big, far.1),
            _ => {
                let s = 10f64.powf(log_near) * tube;
                (big + s * around.cos(), s * around.sin())
            }
        };
        let x = center + t * translate + rho * (angle.cos() * e1 + angle.sin() * e2) + height * a;
        let (rho, q) = ring_radii(&obstacle, &x, t).unwrap();
        prop_assume!(rho > 1e-6 && q > 1e-6);
        let step = 1e-4 * rho.min(q).min(1.0);
        let (d, n, h) = obstacle.distance(&x, t);
        prop_assert!((d - (q - tube)).abs() <= 1e-12);
        let scale_h = h.abs().max().max(1.0);
        for c in 0..3 {
            let mut plus = x;
            let mut minus = x;
            plus[c] += step;
            minus[c] -= step;
            let (dp, np, _) = obstacle.distance(&plus, t);
            let (dm, nm, _) = obstacle.distance(&minus, t);
            let fd = (dp - dm) / (2.0 * step);
            prop_assert!((fd - n[c]).abs() <= TOLERANCE, "gradient {c}: {} against {fd}", n[c]);
            let column = (np - nm) / (2.0 * step);
            for r in 0..3 {
                prop_assert!(
                    (column[r] - h[(r, c)]).abs() <= TOLERANCE * scale_h,
                    "Hessian ({r}, {c}): {} against {}\n{h}", h[(r, c)], column[r]
                );
            }
        }
        prop_assert!((h - h.transpose()).abs().max() <= 1e-12 * scale_h);
    }

    /// The projected update `lambda <- max(0, lambda - rho d)` and its convergence flag (every
    /// multiplier moved by at most `rho * tolerance`), applied twice from zero, against the
    /// formula with distances known by hand: a floor `z >= 0` (`d = z`) and a ceiling
    /// `z <= 0.02` (`d = 0.02 - z`), a penalty per candidate, candidates out of vertex order.
    /// Every candidate starts below the floor, so every floor multiplier is positive after the
    /// first update and moves in the second (by `rho z`, or to zero when the vertex has lifted
    /// off by more than `lambda / rho`); vertices above the ceiling push down. The summary
    /// reports the multipliers' total force and the candidates with a positive one.
    #[test]
    fn projected_update_follows_the_formula(
        rho in prop::collection::vec(0.5..50.0f64, 3),
        below in prop::collection::vec(-0.01..-1e-4f64, 4),
        after in prop::collection::vec(-0.01..0.03f64, 4),
        log_tolerance in -9.0..-2.0f64,
    ) {
        const CEILING: f64 = 0.02;
        let floor = Obstacle::fixed(Shape::HalfSpace { point: Vec3::zeros(), normal: Vec3::z() });
        let ceiling = Obstacle::fixed(Shape::HalfSpace {
            point: Vec3::new(0.0, 0.0, CEILING),
            normal: -Vec3::z(),
        });
        // Vertex 1 is not a candidate.
        let candidates = [3usize, 0, 2];
        let term = Contact::new(candidates.to_vec(), vec![floor, ceiling], rho.clone());
        let tolerance = 10f64.powf(log_tolerance);
        let mut expected = vec![0.0; 6];
        for heights in [&below, &after] {
            let x: Vec<Vec3> = heights.iter().map(|&z| Vec3::new(0.3, -0.2, z)).collect();
            let previous = expected.clone();
            for (a, &v) in candidates.iter().enumerate() {
                for (k, d) in [heights[v], CEILING - heights[v]].into_iter().enumerate() {
                    expected[2 * a + k] = (previous[2 * a + k] - rho[a] * d).max(0.0);
                }
            }
            let converged = (0..6).all(|i| (expected[i] - previous[i]).abs() <= rho[i / 2] * tolerance);
            prop_assert_eq!(term.update(&x, tolerance), converged);
            let lambda = term.multipliers();
            for i in 0..6 {
                // One multiply and one subtraction: a few units of rounding.
                let scale = previous[i] + rho[i / 2] * 0.03;
                prop_assert!(
                    (lambda[i] - expected[i]).abs() <= 4.0 * f64::EPSILON * scale,
                    "multiplier {i}: {} against {}", lambda[i], expected[i]
                );
            }
            let summary = term.summary(&x);
            let force: f64 = (0..3).map(|a| lambda[2 * a] - lambda[2 * a + 1]).sum();
            let size: f64 = lambda.iter().sum();
            prop_assert!((summary.force.z - force).abs() <= 8.0 * f64::EPSILON * size);
            prop_assert_eq!(summary.force.x, 0.0);
            let active = (0..3).filter(|a| lambda[2 * a] + lambda[2 * a + 1] > 0.0).count();
            prop_assert_eq!(summary.active_vertices, active);
            let penetration = candidates
                .iter()
                .map(|&v| (-heights[v]).max(heights[v] - CEILING))
                .fold(0.0, f64::max);
            prop_assert!((summary.max_penetration - penetration).abs() <= f64::EPSILON * CEILING);
        }
    }
}

/// The penalty adaptation: a vertex held 1 cm inside a floor leaves the violation at 1 cm
/// after every update, so each update from the second on multiplies the penalty by 10, up
/// to 1000; the energy's force uses the raised penalty, and a new step starts from the
/// base penalty again.
#[test]
fn penalties_grow_while_the_violation_stalls_and_reset_each_step() {
    let floor = Obstacle::fixed(Shape::HalfSpace {
        point: Vec3::zeros(),
        normal: Vec3::z(),
    });
    let rho = 2.0;
    let term = Contact::new(vec![0], vec![floor], vec![rho]);
    term.begin_step(LoadLevel::quasi_static(0.0));
    let x = [Vec3::new(0.0, 0.0, -0.01)];
    let mut lambda = 0.0;
    for expected_scale in [1.0, 1.0, 10.0, 100.0, 1000.0] {
        assert_eq!(term.penalty_scale(), expected_scale);
        // The update uses the penalty in force before it.
        lambda += expected_scale * rho * 0.01;
        assert!(!term.update(&x, 1e-3));
        assert!((term.multipliers()[0] - lambda).abs() <= 1e-12 * lambda);
    }
    let (_, gradient, _) = evaluate(&term, &x);
    let force = lambda + 1000.0 * rho * 0.01;
    assert!(
        (gradient[2] + force).abs() <= 1e-12 * force,
        "{} against {force}",
        -gradient[2]
    );
    term.begin_step(LoadLevel::quasi_static(1.0));
    assert_eq!(term.penalty_scale(), 1.0);
    // Progress (the violation falls from 1 cm to 1 mm, below a quarter) keeps the penalty.
    assert!(!term.update(&x, 1e-4));
    assert!(!term.update(&[Vec3::new(0.0, 0.0, -0.001)], 1e-4));
    assert_eq!(term.penalty_scale(), 1.0);
}
