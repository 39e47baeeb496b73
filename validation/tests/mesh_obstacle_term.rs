//! The surface-contact term with a meshed rigid obstacle against finite differences and the
//! barrier potential it wraps: a unit cube 1 mm above a plate of two triangles, within the
//! barrier's reach, perturbed at random (the plate placed by a rotation and a translation at
//! a random load level). The plate's vertices are positions, not degrees of freedom: the
//! term's gradient is the central difference of its energy in the cube's coordinates, its
//! Hessian the potential's over all positions restricted to the cube's rows and columns, and
//! the plate's force on the cube the opposite of the cube's gradient summed.

use isochor_mesh::contact::{contact_candidates, ContactSurface, PairFilter};
use isochor_mesh::generate::box_grid;
use isochor_mesh::Vec3;
use isochor_solvers::contact::BarrierPotential;
use isochor_solvers::terms::{EnergyTerm, SurfaceContact, SurfaceContactSpec};
use isochor_solvers::{AxisRotation, LoadLevel, MeshObstacle};
use nalgebra::DMatrix;
use proptest::prelude::*;

const DHAT: f64 = 0.01;

/// The plate `[-1, 2]^2` at `z = 0`, rotated a little about x and lifted, both reached at the
/// end of the run.
fn plate() -> MeshObstacle {
    MeshObstacle {
        translate: Vec3::new(0.0, 0.0, 5e-4),
        rotate: Some(AxisRotation {
            center: Vec3::new(0.5, 0.5, 0.0),
            axis: Vec3::x(),
            angle: 1e-4,
        }),
        ..square_plate()
    }
}

/// The fixed plate `[-1, 2]^2` at `z = 0`, two triangles.
pub fn square_plate() -> MeshObstacle {
    MeshObstacle {
        name: "plate".into(),
        vertices: vec![
            Vec3::new(-1.0, -1.0, 0.0),
            Vec3::new(2.0, -1.0, 0.0),
            Vec3::new(2.0, 2.0, 0.0),
            Vec3::new(-1.0, 2.0, 0.0),
        ],
        triangles: vec![[0, 1, 2], [0, 2, 3]],
        translate: Vec3::zeros(),
        rotate: None,
        curve: None,
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(16))]

    #[test]
    fn the_term_drops_the_plates_rows_and_matches_its_derivatives(
        moves in proptest::collection::vec(-2e-4..2e-4f64, 24),
        t in 0.0..1.0f64,
    ) {
        let cube = box_grid(Vec3::new(0.0, 0.0, 0.001), Vec3::new(1.0, 1.0, 1.001), [1, 1, 1]).unwrap();
        let rest = cube.positions().to_vec();
        let n = rest.len();
        let surface = ContactSurface::from_boundary(&cube.boundary().unwrap());
        let spec = SurfaceContactSpec { dhat: DHAT, self_contact: true, node_bodies: vec![0; n] };
        let obstacle = plate();
        let term = SurfaceContact::new(spec, surface.clone(), rest.clone(), 1e5)
            .unwrap()
            .with_obstacles(vec![obstacle.clone()])
            .unwrap();
        let x: Vec<Vec3> = rest
            .iter()
            .enumerate()
            .map(|(i, p)| p + Vec3::new(moves[3 * i], moves[3 * i + 1], moves[3 * i + 2]))
            .collect();
        let level = LoadLevel::quasi_static(t);
        term.begin_attempt(&rest, &level).unwrap();
        prop_assert!(term.update(&x), "the pairs appear");
        let dofs = 3 * n;
        let pattern = term.hessian_pattern();
        prop_assert!(pattern.iter().all(|&(r, c)| r < dofs && c < dofs), "no plate rows");
        let mut values = vec![0.0; pattern.len()];
        let mut gradient = vec![0.0; dofs];
        let e = term.evaluate(&x, &level, Some(&mut gradient), Some(&mut values)).unwrap();
        prop_assert!(e > 0.0 && e.is_finite());
        let energy = |y: &[Vec3]| term.evaluate(y, &level, None, None).unwrap();
        let scale = gradient.iter().fold(0.0f64, |m, g| m.max(g.abs()));
        let h = 1e-8;
        for dof in 0..dofs {
            let (mut plus, mut minus) = (x.clone(), x.clone());
            plus[dof / 3][dof % 3] += h;
            minus[dof / 3][dof % 3] -= h;
            let fd = (energy(&plus) - energy(&minus)) / (2.0 * h);
            prop_assert!((fd - gradient[dof]).abs() <= 1e-5 * scale, "dof {dof}: {fd} against {}", gradient[dof]);
        }
        // The potential over all positions (the cube's nodes, then the placed plate's).
        let placed = obstacle.placed(&level);
        let all: Vec<Vec3> = x.iter().chain(&placed).copied().collect();
        let all_rest: Vec<Vec3> = rest.iter().chain(&obstacle.vertices).copied().collect();
        let mut triangles = surface.triangles().to_vec();
        triangles.extend(obstacle.triangles.iter().map(|t| t.map(|v| v + n)));
        let joined = ContactSurface::from_triangles(triangles);
        let mut bodies = vec![0; n];
        bodies.extend([1; 4]);
        let candidates = contact_candidates(&joined, &all, None, DHAT, PairFilter::BetweenBodies(&bodies));
        let unit = BarrierPotential { dhat: DHAT, kappa: 1.0 };
        let mut unit_gradient = vec![0.0; 3 * all.len()];
        unit.add_gradient(&joined, &candidates, &all_rest, &all, &mut unit_gradient);
        let dot = |a: &[f64], b: &[f64]| a.iter().zip(b).map(|(p, q)| p * q).sum::<f64>();
        let body_gradient = &unit_gradient[..dofs];
        let kappa = dot(&gradient, body_gradient) / dot(body_gradient, body_gradient);
        for (ours, theirs) in gradient.iter().zip(body_gradient) {
            prop_assert!((ours - kappa * theirs).abs() <= 1e-10 * scale);
        }
        let mut ours = DMatrix::<f64>::zeros(dofs, dofs);
        for (&(r, c), v) in pattern.iter().zip(&values) {
            ours[(r, c)] += v;
        }
        let mut theirs = DMatrix::<f64>::zeros(dofs, dofs);
        for (r, c, v) in unit.hessian_triplets(&joined, &candidates, &all_rest, &all) {
            if r < dofs && c < dofs {
                theirs[(r, c)] += kappa * v;
            }
        }
        prop_assert!((&ours - &theirs).norm() <= 1e-10 * theirs.norm(), "{} against {}", ours.norm(), theirs.norm());
        // The plate's force on the cube: minus the cube's gradient, summed.
        let force = term.obstacle_forces(&x)[0];
        let pushed: Vec3 = (0..n).map(|i| -Vec3::new(gradient[3 * i], gradient[3 * i + 1], gradient[3 * i + 2])).sum();
        prop_assert!((force - pushed).norm() <= 1e-9 * pushed.norm(), "{force} against {pushed}");
        prop_assert!(force.z > 0.0, "the plate pushes the cube up");
    }
}

#[test]
fn a_plate_moving_through_the_cube_in_one_step_is_refused() {
    let cube = box_grid(
        Vec3::new(0.0, 0.0, 0.001),
        Vec3::new(1.0, 1.0, 1.001),
        [1, 1, 1],
    )
    .unwrap();
    let rest = cube.positions().to_vec();
    let surface = ContactSurface::from_boundary(&cube.boundary().unwrap());
    let spec = SurfaceContactSpec {
        dhat: DHAT,
        self_contact: true,
        node_bodies: vec![0; rest.len()],
    };
    let through = MeshObstacle {
        translate: Vec3::new(0.0, 0.0, 0.5),
        rotate: None,
        ..plate()
    };
    let term = SurfaceContact::new(spec, surface, rest.clone(), 1e5)
        .unwrap()
        .with_obstacles(vec![through])
        .unwrap();
    // A small step stays clear of the cube (1 mm above the plate); the whole run's does not.
    term.begin_attempt(&rest, &LoadLevel::quasi_static(1e-3))
        .unwrap();
    let e = term
        .begin_attempt(&rest, &LoadLevel::FULL)
        .unwrap_err()
        .to_string();
    assert!(e.contains("plate") && e.contains("cross"), "{e}");
}

/// Two unit cubes 1 mm apart: the force the upper exerts on the lower is minus the barrier's
/// gradient over the lower cube's nodes, and pushes it down.
#[test]
fn the_force_between_two_bodies_is_minus_the_gradient_on_one() {
    let lower = box_grid(Vec3::zeros(), Vec3::repeat(1.0), [1, 1, 1]).unwrap();
    let upper = box_grid(
        Vec3::new(0.0, 0.0, 1.001),
        Vec3::new(1.0, 1.0, 2.001),
        [1, 1, 1],
    )
    .unwrap();
    let offset = lower.positions().len();
    let mut rest = lower.positions().to_vec();
    rest.extend(upper.positions());
    let mut triangles = ContactSurface::from_boundary(&lower.boundary().unwrap())
        .triangles()
        .to_vec();
    triangles.extend(
        ContactSurface::from_boundary(&upper.boundary().unwrap())
            .triangles()
            .iter()
            .map(|t| t.map(|v| v + offset)),
    );
    let bodies: Vec<usize> = (0..rest.len()).map(|v| usize::from(v >= offset)).collect();
    let spec = SurfaceContactSpec {
        dhat: DHAT,
        self_contact: false,
        node_bodies: bodies,
    };
    let term = SurfaceContact::new(
        spec,
        ContactSurface::from_triangles(triangles),
        rest.clone(),
        1e5,
    )
    .unwrap();
    let mut gradient = vec![0.0; 3 * rest.len()];
    term.evaluate(&rest, &LoadLevel::FULL, Some(&mut gradient), None)
        .unwrap();
    let on_lower: Vec3 = (0..offset)
        .map(|v| -Vec3::new(gradient[3 * v], gradient[3 * v + 1], gradient[3 * v + 2]))
        .sum();
    let forces = term.body_pair_forces(&rest);
    assert_eq!(forces.len(), 1);
    assert!(
        (forces[0] - on_lower).norm() <= 1e-12 * on_lower.norm(),
        "{} against {on_lower}",
        forces[0]
    );
    assert!(forces[0].z < 0.0 && forces[0].xy().norm() <= 1e-9 * forces[0].z.abs());
}
