//! Finite-difference property tests of lagged smoothed friction (Li et al. 2020, sec. 5):
//! the surface friction term on a point-triangle and an edge-edge pair, and the friction of
//! a vertex against a moving analytic obstacle (inside the obstacle contact term), and the
//! surface friction with a meshed obstacle's vertices in the pair (a triangle or an edge of
//! it, and a cube over a plate sliding under it): energy, gradient and Hessian against
//! central differences, at slips near 0, just below and just above `epsv`, and far beyond
//! it; every Hessian positive semidefinite.

use isochor_mesh::contact::{
    edge_edge_distance_kind, point_triangle_distance_kind, ContactSurface, DistanceKind,
};
use isochor_mesh::generate::box_grid;
use isochor_mesh::Vec3;
use isochor_solvers::contact::{plane_basis, FrictionPair, PairForce};
use isochor_solvers::terms::{
    Contact, EnergyTerm, FrictionLag, SurfaceContact, SurfaceContactSpec, SurfaceFriction,
};
use isochor_solvers::{LoadLevel, MeshObstacle, Obstacle, Shape, SurfaceFrictionSpec};
use isochor_validation::terms::evaluate_dense;
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
    evaluate_dense(term, x, &LoadLevel::quasi_static(0.6))
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
/// `x0` (the lagged and start state), of which the first `free` are a body's nodes (degrees
/// of freedom) and the others a meshed obstacle's vertices, evaluated with every node moved
/// by `base` scaled to a tangential slip of `slip epsv` (the obstacle's part prescribed over
/// the step, the body's the state).
fn check_pair(
    kind: DistanceKind,
    x0: [Vec3; 4],
    base: [Vec3; 4],
    free: usize,
    epsv: f64,
    slip: f64,
    lambda: f64,
) -> Result<(), TestCaseError> {
    let spec = SurfaceFrictionSpec {
        friction: 0.0,
        pairs: vec![([0, 1], 0.6)],
    };
    let term = SurfaceFriction::new(spec, epsv);
    // The same pair as the kernel sees it, for the slip's scale.
    let pair = FrictionPair::new(kind, &x0, 0.6 * lambda, epsv);
    let y = pair.tangential_motion(&base).norm();
    prop_assume!(y > 1e-6);
    let u: [Vec3; 4] = std::array::from_fn(|i| base[i] * (slip * epsv / y));
    let lag = FrictionLag {
        positions: x0.to_vec(),
        // Side one body 0, side two body 1 (the obstacle, or the other body).
        bodies: (0..4).map(|i| usize::from(i >= free.min(2))).collect(),
        obstacle_motion: u[free..].to_vec(),
        forces: vec![PairForce {
            nodes: [0, 1, 2, 3],
            kind,
            lambda,
        }],
    };
    term.lag(&x0[..free], &lag);
    prop_assert_eq!(term.num_pairs(), 1);
    let x: Vec<Vec3> = (0..free).map(|i| x0[i] + u[i]).collect();
    prop_assert!(
        term.hessian_pattern()
            .iter()
            .all(|&(r, c)| r < 3 * free && c < 3 * free),
        "no obstacle rows"
    );
    let (e, _, _) = evaluate(&term, &x);
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
        check_pair(kind, x0, [u, w * 0.5, u * 0.2 - w, w * 0.1], 4, epsv, s, lambda)?;
    }

    #[test]
    fn surface_friction_of_an_edge_edge_pair(a0 in vec3(), a1 in vec3(), b0 in vec3(), b1 in vec3(), u in vec3(), w in vec3(), epsv in 1e-4..1e-1f64, s in slip(), lambda in 0.1..10.0f64) {
        let x0 = [a0, a1, b0, b1];
        let kind = edge_edge_distance_kind(&a0, &a1, &b0, &b1);
        prop_assume!(kind.squared_distance(&x0) > 1e-4);
        prop_assume!((a1 - a0).cross(&(b1 - b0)).norm() > 1e-2);
        check_pair(kind, x0, [u, u * 0.3 + w, w * -0.7, u - w], 4, epsv, s, lambda)?;
    }

    /// A body's vertex against a meshed obstacle's triangle (its three vertices prescribed:
    /// they move by their own motion over the step, and their rows are dropped).
    #[test]
    fn surface_friction_of_a_vertex_against_an_obstacle_triangle(p in vec3(), a in vec3(), b in vec3(), c in vec3(), u in vec3(), w in vec3(), epsv in 1e-4..1e-1f64, s in slip(), lambda in 0.1..10.0f64) {
        let x0 = [p, a, b, c];
        let kind = point_triangle_distance_kind(&p, &a, &b, &c);
        prop_assume!(kind.squared_distance(&x0) > 1e-4);
        check_pair(kind, x0, [u, w, w * 0.8 - u * 0.1, w + u * 0.3], 1, epsv, s, lambda)?;
    }

    /// A body's edge against a meshed obstacle's edge.
    #[test]
    fn surface_friction_of_an_edge_against_an_obstacle_edge(a0 in vec3(), a1 in vec3(), b0 in vec3(), b1 in vec3(), u in vec3(), w in vec3(), epsv in 1e-4..1e-1f64, s in slip(), lambda in 0.1..10.0f64) {
        let x0 = [a0, a1, b0, b1];
        let kind = edge_edge_distance_kind(&a0, &a1, &b0, &b1);
        prop_assume!(kind.squared_distance(&x0) > 1e-4);
        prop_assume!((a1 - a0).cross(&(b1 - b0)).norm() > 1e-2);
        check_pair(kind, x0, [u, u * 0.3 + w, w * -0.7, w * -0.6 + u * 0.1], 2, epsv, s, lambda)?;
    }

    /// A vertex on a translating sphere at the step's start: the friction part of the
    /// obstacle term (with friction minus without) against central differences, the slip
    /// taken relative to the sphere's translation over the step. The vertex starts on the
    /// sphere so that the frictionless part's energy, `-lambda d + d^2 / 2` while in contact,
    /// stays of the friction's size: away from the sphere it is the constant
    /// `-lambda^2 / 2`, whose rounding in the difference swamps the friction's gradient at
    /// small slips (`mu lambda f1`, near `2 mu lambda s`).
    #[test]
    fn obstacle_friction_of_a_vertex(direction in vec3(), r in vec3(), epsv in 1e-4..1e-1f64, s in slip(), lambda in 0.1..10.0f64, mu in 0.05..1.5f64) {
        let sphere = Obstacle {
            translate: Vec3::new(0.3, -0.2, 0.1),
            ..Obstacle::fixed(Shape::Sphere { center: Vec3::zeros(), radius: 0.5 })
        };
        prop_assume!(direction.norm() > 0.2);
        let start = sphere.translate * 0.2 + direction.normalize() * 0.5;
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

/// A unit cube 1 mm above a plate of two triangles, a meshed obstacle translating along
/// `slide` (reached at the end of the run), in a surface-contact term with `dhat` 1 cm.
fn cube_over_a_sliding_plate(slide: Vec3) -> (Vec<Vec3>, SurfaceContact, MeshObstacle) {
    let cube = box_grid(
        Vec3::new(0.0, 0.0, 0.001),
        Vec3::new(1.0, 1.0, 1.001),
        [1, 1, 1],
    )
    .unwrap();
    let rest = cube.positions().to_vec();
    let plate = MeshObstacle {
        translate: slide,
        ..super::mesh_obstacle_term::square_plate()
    };
    let spec = SurfaceContactSpec {
        dhat: 0.01,
        self_contact: false,
        node_bodies: vec![0; rest.len()],
    };
    let surface = ContactSurface::from_boundary(&cube.boundary().unwrap());
    let term = SurfaceContact::new(spec, surface, rest.clone(), 1e5)
        .unwrap()
        .with_obstacles(vec![plate.clone()])
        .unwrap();
    (rest, term, plate)
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(8))]

    /// Friction of the cube against the plate sliding under it over a step from `t0` to `t1`:
    /// the lag carries the plate's motion over the step; a cube that stayed put is dragged
    /// along the plate's motion, one that moved with the plate feels no friction, and the
    /// term matches its central differences with the plate's rows dropped.
    #[test]
    fn friction_against_a_sliding_meshed_plate(t0 in 0.0..0.9f64, moves in proptest::collection::vec(-1.0..1.0f64, 24), epsv in 1e-4..1e-2f64) {
        let slide = Vec3::new(0.02, -0.01, 0.0);
        let (rest, contact, plate) = cube_over_a_sliding_plate(slide);
        let n = rest.len();
        let (from, to) = (LoadLevel::quasi_static(t0), LoadLevel::quasi_static(t0 + 0.1));
        contact.begin_attempt(&rest, &to).unwrap();
        let lag = contact.friction_lag(&rest, &from);
        let (then, now) = (plate.placed(&from), plate.placed(&to));
        prop_assert_eq!(lag.positions.len(), n + 4);
        for (i, m) in lag.obstacle_motion.iter().enumerate() {
            prop_assert!((m - (now[i] - then[i])).norm() <= 1e-15, "vertex {}: {}", i, m);
        }
        prop_assert!(lag.bodies[n..].iter().all(|&b| b == 1), "the plate is body 1");
        let friction = SurfaceFriction::new(SurfaceFrictionSpec { friction: 0.5, pairs: vec![] }, epsv);
        friction.lag(&rest, &lag);
        prop_assert!(friction.num_pairs() > 0, "the bottom face's pairs");
        let lambda = lag.forces.iter().map(|f| f.lambda).fold(0.0, f64::max);
        // Left behind: the plate drags the cube along its motion.
        let (_, g, _) = evaluate(&friction, &rest);
        let drag: Vec3 = (0..n).map(|v| -Vec3::new(g[3 * v], g[3 * v + 1], g[3 * v + 2])).sum();
        let step = slide * 0.1;
        prop_assert!(drag.dot(&step) > 0.9 * drag.norm() * step.norm(), "drag {} along {}", drag, step);
        // Carried along: no slip, no friction, but for the rounding of unit coordinates (a
        // slip of a few ulps, 1e-15 m, times f1(y)/y <= 2/epsv, times mu lambda).
        let carried: Vec<Vec3> = rest.iter().map(|p| p + step).collect();
        let (_, g, _) = evaluate(&friction, &carried);
        let rounding = 0.5 * lambda * 2.0 / epsv * 1e-15;
        prop_assert!(g.iter().all(|v| v.abs() <= rounding), "{:?} beyond {}", g, rounding);
        // Slipping by a few epsv in any direction.
        let x: Vec<Vec3> = carried
            .iter()
            .enumerate()
            .map(|(i, p)| p + Vec3::new(moves[3 * i], moves[3 * i + 1], moves[3 * i + 2]) * (2.0 * epsv))
            .collect();
        check_term(&friction, &x, STEP * epsv, 0.5 * lambda / epsv)?;
    }
}
