//! Finite-difference property tests of lagged smoothed friction (Li et al. 2020, sec. 5):
//! the surface friction term on a point-triangle and an edge-edge pair, and the friction of
//! a vertex against a moving analytic obstacle (inside the obstacle contact term), energy,
//! gradient and Hessian against central differences, at slips near 0, just below and just
//! above `epsv`, and far beyond it; every Hessian positive semidefinite.

use isochor_mesh::contact::{edge_edge_distance_kind, point_triangle_distance_kind, DistanceKind};
use isochor_mesh::Vec3;
use isochor_solvers::contact::{plane_basis, FrictionPair, PairForce};
use isochor_solvers::terms::{Contact, EnergyTerm, SurfaceFriction};
use isochor_solvers::{LoadLevel, Obstacle, Shape, SurfaceFrictionSpec};
use nalgebra::DMatrix;
use proptest::prelude::*;
use proptest::test_runner::TestCaseError;

/// Central-difference step, relative to `epsv`.
const STEP: f64 = 1e-6;
/// Agreement required between a derivative and its central differences, relative to its
/// size (truncation `STEP^2` times the third derivative, rounding `1e-16 / STEP`).
const TOLERANCE: f64 = 1e-5;

fn vec3() -> impl Strategy<Value = Vec3> {
    (-1.0..1.0f64, -1.0..1.0f64, -1.0..1.0f64).prop_map(|(x, y, z)| Vec3::new(x, y, z))
}

/// Slips as fractions of `epsv`: near 0, just below and just above `epsv`, far beyond.
fn slip() -> impl Strategy<Value = f64> {
    prop_oneof![
        1e-3..0.05f64,
        0.95..0.9999f64,
        1.0001..1.05f64,
        1.5..10.0f64
    ]
}

/// The term's energy, gradient and dense Hessian at `x`.
fn evaluate(term: &dyn EnergyTerm, x: &[Vec3]) -> (f64, Vec<f64>, DMatrix<f64>) {
    let n = 3 * x.len();
    let pattern = term.hessian_pattern();
    let mut gradient = vec![0.0; n];
    let mut values = vec![0.0; pattern.len()];
    let level = LoadLevel::quasi_static(0.6);
    let e = term
        .evaluate(x, &level, Some(&mut gradient), Some(&mut values))
        .unwrap();
    let mut h = DMatrix::zeros(n, n);
    for (&(r, c), v) in pattern.iter().zip(&values) {
        h[(r, c)] += v;
    }
    (e, gradient, h)
}

fn moved(x: &[Vec3], k: usize, by: f64) -> Vec<Vec3> {
    let mut y = x.to_vec();
    y[k / 3][k % 3] += by;
    y
}

/// The gradient and Hessian of `term` at `x` against central differences with step `h`
/// (`floor`: the smallest Hessian scale, so that a vanishing one is not compared to noise).
fn check_term(term: &dyn EnergyTerm, x: &[Vec3], h: f64, floor: f64) -> Result<(), TestCaseError> {
    let (_, g, hess) = evaluate(term, x);
    let n = g.len();
    let level = LoadLevel::quasi_static(0.6);
    let energy = |y: &[Vec3]| term.evaluate(y, &level, None, None).unwrap();
    let g_scale = g.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    let h_scale = hess.amax().max(floor);
    for k in 0..n {
        let fd = (energy(&moved(x, k, h)) - energy(&moved(x, k, -h))) / (2.0 * h);
        prop_assert!(
            (fd - g[k]).abs() <= TOLERANCE * g_scale,
            "gradient {k}: {} against {fd}",
            g[k]
        );
        let (_, gp, _) = evaluate(term, &moved(x, k, h));
        let (_, gm, _) = evaluate(term, &moved(x, k, -h));
        for r in 0..n {
            let fd = (gp[r] - gm[r]) / (2.0 * h);
            prop_assert!(
                (fd - hess[(r, k)]).abs() <= TOLERANCE * h_scale,
                "hessian ({r}, {k}): {} against {fd}",
                hess[(r, k)]
            );
        }
    }
    let smallest = hess.clone().symmetric_eigenvalues().min();
    prop_assert!(smallest >= -1e-9 * h_scale, "not PSD: {smallest}");
    Ok(())
}

/// The surface friction term on one pair of closest features `kind` of the four nodes at
/// `x0` (the lagged and start state), evaluated at `x0` plus motions `base` scaled to a
/// tangential slip of `slip epsv`.
fn check_pair(
    kind: DistanceKind,
    x0: [Vec3; 4],
    base: [Vec3; 4],
    epsv: f64,
    slip: f64,
    lambda: f64,
) -> Result<(), TestCaseError> {
    let spec = SurfaceFrictionSpec {
        friction: 0.0,
        pairs: vec![([0, 1], 0.6)],
        node_bodies: vec![0, 0, 1, 1],
    };
    let term = SurfaceFriction::new(spec, epsv);
    let force = PairForce {
        nodes: [0, 1, 2, 3],
        kind,
        lambda,
    };
    term.lag(&x0, &x0, &[force]);
    prop_assert_eq!(term.num_pairs(), 1);
    // The same pair as the kernel sees it, for the slip's scale.
    let pair = FrictionPair::new(kind, &x0, 0.6 * lambda, epsv);
    let y = pair.tangential_motion(&base).norm();
    prop_assume!(y > 1e-6);
    let x: Vec<Vec3> = (0..4)
        .map(|i| x0[i] + base[i] * (slip * epsv / y))
        .collect();
    let (e, _, _) = evaluate(&term, &x);
    let u: [Vec3; 4] = std::array::from_fn(|i| x[i] - x0[i]);
    prop_assert!((e - pair.potential(&u)).abs() <= 1e-12 * e.abs().max(1e-300));
    check_term(&term, &x, STEP * epsv, 0.6 * lambda / epsv)
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    #[test]
    fn surface_friction_of_a_point_triangle_pair(p in vec3(), a in vec3(), b in vec3(), c in vec3(), u in vec3(), w in vec3(), epsv in 1e-4..1e-1f64, s in slip(), lambda in 0.1..10.0f64) {
        let x0 = [p, a, b, c];
        let kind = point_triangle_distance_kind(&p, &a, &b, &c);
        prop_assume!(kind.squared_distance(&x0) > 1e-4);
        check_pair(kind, x0, [u, w * 0.5, u * 0.2 - w, w * 0.1], epsv, s, lambda)?;
    }

    #[test]
    fn surface_friction_of_an_edge_edge_pair(a0 in vec3(), a1 in vec3(), b0 in vec3(), b1 in vec3(), u in vec3(), w in vec3(), epsv in 1e-4..1e-1f64, s in slip(), lambda in 0.1..10.0f64) {
        let x0 = [a0, a1, b0, b1];
        let kind = edge_edge_distance_kind(&a0, &a1, &b0, &b1);
        prop_assume!(kind.squared_distance(&x0) > 1e-4);
        prop_assume!((a1 - a0).cross(&(b1 - b0)).norm() > 1e-2);
        check_pair(kind, x0, [u, u * 0.3 + w, w * -0.7, u - w], epsv, s, lambda)?;
    }

    /// A vertex near a translating sphere: the friction part of the obstacle term (with
    /// friction minus without) against central differences, the slip taken relative to the
    /// sphere's translation over the step.
    #[test]
    fn obstacle_friction_of_a_vertex(start in vec3(), r in vec3(), epsv in 1e-4..1e-1f64, s in slip(), lambda in 0.1..10.0f64, mu in 0.05..1.5f64) {
        let sphere = Obstacle {
            translate: Vec3::new(0.3, -0.2, 0.1),
            ..Obstacle::fixed(Shape::Sphere { center: Vec3::zeros(), radius: 0.5 })
        };
        prop_assume!(start.norm() > 0.2);
        let (from, to) = (LoadLevel::quasi_static(0.2), LoadLevel::quasi_static(0.6));
        let contact = |mu: f64| {
            let mut c = Contact::new(vec![0], vec![sphere.clone()], vec![1.0]);
            c.set_friction(vec![mu], epsv).unwrap();
            c.set_multipliers(vec![lambda]).unwrap();
            c.begin_step(to);
            c.lag_friction(&[start], &[start], from);
            c
        };
        let (with, without) = (contact(mu), contact(0.0));
        // The tangential slip relative to the sphere's own motion over the step.
        let (_, n, _) = sphere.distance(&start, 0.6);
        let t = plane_basis(&n);
        let tangential = t * (t.transpose() * r);
        prop_assume!(tangential.norm() > 1e-3);
        let motion = sphere.translate * 0.4;
        let x = vec![start + motion + tangential * (s * epsv / tangential.norm()) + n * (0.1 * epsv)];
        let friction = Difference { with: &with, without: &without };
        let (e, _, _) = evaluate(&friction, &x);
        let expected = mu * lambda * isochor_solvers::contact::friction_f0(s * epsv, epsv);
        prop_assert!((e - expected).abs() <= 1e-9 * expected, "{} against {}", e, expected);
        check_term(&friction, &x, STEP * epsv, mu * lambda / epsv)?;
    }
}

/// The difference of two terms with the same pattern: the friction part of the obstacle
/// term.
#[derive(Debug)]
struct Difference<'a> {
    with: &'a Contact,
    without: &'a Contact,
}

impl EnergyTerm for Difference<'_> {
    fn name(&self) -> &'static str {
        "friction part"
    }

    fn hessian_pattern(&self) -> Vec<(usize, usize)> {
        self.with.hessian_pattern()
    }

    fn evaluate(
        &self,
        x: &[Vec3],
        level: &LoadLevel,
        gradient: Option<&mut [f64]>,
        hessian: Option<&mut [f64]>,
    ) -> Result<f64, isochor_solvers::SolverError> {
        let n = 3 * x.len();
        let len = self.hessian_pattern().len();
        let (mut g1, mut g0) = (vec![0.0; n], vec![0.0; n]);
        let (mut h1, mut h0) = (vec![0.0; len], vec![0.0; len]);
        let e = self.with.evaluate(x, level, Some(&mut g1), Some(&mut h1))?
            - self
                .without
                .evaluate(x, level, Some(&mut g0), Some(&mut h0))?;
        if let Some(g) = gradient {
            for (k, v) in g.iter_mut().enumerate() {
                *v += g1[k] - g0[k];
            }
        }
        if let Some(h) = hessian {
            for (k, v) in h.iter_mut().enumerate() {
                *v = h1[k] - h0[k];
            }
        }
        Ok(e)
    }
}

/// Bad friction values are refused: a negative coefficient, a NaN one, a zero slip length.
#[test]
fn bad_friction_values_are_errors() {
    let mut contact = Contact::new(
        vec![0],
        vec![Obstacle::fixed(Shape::HalfSpace {
            point: Vec3::zeros(),
            normal: Vec3::z(),
        })],
        vec![1.0],
    );
    assert!(
        contact.set_friction(vec![0.5, 0.5], 1e-3).is_err(),
        "one coefficient per obstacle"
    );
    contact.set_friction(vec![0.0], 1e-3).unwrap();
    assert!(
        !contact.has_friction(),
        "a zero coefficient is frictionless"
    );
    for bad in [-0.1, f64::NAN] {
        let spec = isochor_solvers::FrictionSpec {
            epsv: 1e-3,
            obstacles: vec![bad],
            surfaces: None,
        };
        assert!(spec.validate().is_err(), "coefficient {bad}");
    }
    let spec = isochor_solvers::FrictionSpec {
        epsv: 0.0,
        obstacles: vec![0.3],
        surfaces: None,
    };
    assert!(spec.validate().unwrap_err().to_string().contains("epsv"));
}
