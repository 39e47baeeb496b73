//! Frictionless contact against rigid obstacles (augmented Lagrangian with projected
//! multiplier updates, sec. 8.3 of Francu et al. 2021): a block resting on the ground, a
//! ball bouncing off it, a block squeezed between cylinders, a cylinder squeezed by a
//! shrinking ring.

use crate::common;

use common::plane;
use isochor_mesh::generate::{ball, box_grid, cylinder};
use isochor_mesh::{BoundarySurface, TetMesh, Vec3};
use isochor_solvers::{
    Dirichlet, Load, Material, Method, Motion, Obstacle, Problem, Settings, Shape, Simulation,
    Stepping,
};

const G: f64 = 9.8;

/// The ground `z >= z0`.
fn ground(z0: f64) -> Obstacle {
    Obstacle::fixed(Shape::HalfSpace {
        point: Vec3::new(0.0, 0.0, z0),
        normal: Vec3::z(),
    })
}

/// Penetration tolerance of the default settings for `mesh`.
fn tolerance(mesh: &TetMesh) -> f64 {
    let (lo, hi) = mesh.bounding_box();
    Settings::default().contact_tolerance * (hi - lo).norm()
}

/// Checks complementarity pair by pair, `(vertex, obstacle, lambda, d)`, and returns the
/// pairs in contact: every multiplier `lambda >= 0`, every gap `d >= -tol`, and
/// `|lambda d| <= lambda tol` (a positive multiplier only where the gap is within `tol`). The
/// bound is the stopping rule's: the last update moved no multiplier by more than `rho tol`,
/// so a positive `lambda = lambda_old - rho d` has `|d| <= tol` and a zero one has
/// `d >= lambda_old / rho >= 0`.
fn assert_complementarity(
    pairs: impl Iterator<Item = (usize, usize, f64, f64)>,
    tol: f64,
    what: &str,
) -> usize {
    let (mut active, mut widest) = (0, 0.0f64);
    for (v, k, l, d) in pairs {
        assert!(
            l >= 0.0 && d >= -tol && (l * d).abs() <= l * tol,
            "{what}: vertex {v}, obstacle {k}: lambda {l:e} at gap {d:e} (tolerance {tol:e})"
        );
        if l > 0.0 {
            active += 1;
            widest = widest.max(d.abs());
        }
    }
    eprintln!("{what}: {active} pairs in contact, largest |d| among them {widest:.1e} m (tolerance {tol:.1e} m)");
    active
}

/// The `(vertex, obstacle, lambda, d)` pairs of a finished quasi-static run: the multipliers
/// (boundary-vertex-major over the obstacles) and the gaps at the final state `x`, with the
/// obstacles at the end of their motion.
fn final_pairs(
    sim: &Simulation,
    obstacles: &[Obstacle],
    x: &[Vec3],
) -> Vec<(usize, usize, f64, f64)> {
    let candidates = BoundarySurface::new(sim.mesh().corners())
        .unwrap()
        .vertices()
        .to_vec();
    let lambda = sim.contact_multipliers();
    assert_eq!(lambda.len(), candidates.len() * obstacles.len());
    let m = obstacles.len();
    candidates
        .iter()
        .enumerate()
        .flat_map(|(a, &v)| {
            obstacles
                .iter()
                .enumerate()
                .map(move |(k, o)| (v, k, a * m + k, o.distance(&x[v], 1.0).0))
        })
        .map(|(v, k, i, d)| (v, k, lambda[i], d))
        .collect()
}

fn volume(mesh: &TetMesh, x: &[Vec3]) -> f64 {
    (0..mesh.num_tets()).map(|e| mesh.volume_at(e, x)).sum()
}

/// A 0.1 m cube of 3^3 cells standing on the ground under gravity, its bottom face held
/// sideways only (so the stiffness is regular in x and y), loaded in two steps.
fn resting_block(method: Method, nu: f64) -> Problem {
    resting_block_at(method, nu, 0.0)
}

/// The same with the ground (and the block's bottom) at height `z0`.
fn resting_block_at(method: Method, nu: f64, z0: f64) -> Problem {
    let base = Vec3::new(0.0, 0.0, z0);
    let mesh = box_grid(base, base + Vec3::repeat(0.1), [3, 3, 3]).unwrap();
    let bottom = plane(&mesh, 2, z0);
    Problem {
        mesh: mesh.into(),
        method,
        material: Material::from_young_poisson(100e3, nu, 1000.0).unwrap(),
        regions: Vec::new(),
        zones: None,
        dirichlet: vec![Dirichlet {
            nodes: bottom,
            axes: [true, true, false],
            motion: Motion::Fixed,
            curve: None,
        }],
        loads: vec![Load::Gravity(Vec3::new(0.0, 0.0, -G)).into()],
        obstacles: vec![ground(z0)],
        cloths: Vec::new(),
    }
}

/// A block on the ground carries its weight through the contact forces, with every method
/// (and zero compliance), without penetrating, and with complementarity at every boundary
/// vertex: the 16 bottom vertices carry positive multipliers at zero gap (to the contact
/// tolerance), every other vertex none.
#[test]
fn resting_block_carries_its_weight_without_penetrating() {
    // Every method, and zero-compliance volume constraints (nu = 0.5) too. (Not mixed-p0 at
    // nu = 0.5: six element constraints per cell against three DOFs per vertex lock it.)
    let cases = Method::ALL
        .into_iter()
        .map(|m| (m, 0.45))
        .chain([(Method::MixedP1, 0.5), (Method::MixedP1Log, 0.5)]);
    for (method, nu) in cases {
        let problem = resting_block(method, nu);
        let obstacles = problem.obstacles.clone();
        let weight = G * 1000.0 * problem.mesh.rest_volume();
        let tol = tolerance(problem.mesh.corners());
        let mut sim = Simulation::new(problem, Settings::default()).unwrap();
        let scale = sim.force_scale().unwrap();
        let summary = sim
            .run(Stepping::quasi_static(2), |_| {})
            .unwrap_or_else(|e| panic!("{method}: {e}"));
        let last = summary.reports.last().unwrap();
        let force = last.contact.force;
        let residual = last.force_residual;
        assert!(
            (force.z - weight).abs() <= 10.0 * residual.max(1e-9 * scale),
            "{method}: contact force {force} against weight {weight} (residual {residual:e})"
        );
        assert!(force.x.abs() + force.y.abs() < 1e-12 * weight);
        assert!(last.contact.max_penetration <= tol, "{method}");
        assert_eq!(
            last.contact.active_vertices, 16,
            "{method}: the bottom face"
        );
        let x = &summary.final_state.positions;
        let pairs = assert_complementarity(
            final_pairs(&sim, &obstacles, x).into_iter(),
            tol,
            &format!("{method} at nu = {nu}"),
        );
        assert_eq!(pairs, 16, "{method}: the bottom face");
        let lowest = summary
            .final_state
            .positions
            .iter()
            .map(|p| p.z)
            .fold(f64::INFINITY, f64::min);
        assert!(lowest >= -tol, "{method}: lowest vertex at {lowest}");
    }
}

/// Moving the origin changes nothing: the block whose centre sits at the origin (so that the
/// potential of gravity is near zero and no longer dominates the energy's size) converges in
/// the same iterations to the same state. (The line search once judged rounding noise by
/// the energy's size alone, and `condensed` failed here.)
#[test]
fn resting_block_does_not_depend_on_the_origin() {
    for method in Method::ALL {
        let solve = |z0: f64| {
            let mut sim =
                Simulation::new(resting_block_at(method, 0.45, z0), Settings::default()).unwrap();
            sim.run(Stepping::quasi_static(2), |_| {})
                .unwrap_or_else(|e| panic!("{method} with the ground at z = {z0}: {e}"))
        };
        let (high, low) = (solve(0.0), solve(-0.05));
        let iterations = |s: &isochor_solvers::RunSummary| -> Vec<usize> {
            s.reports.iter().map(|r| r.newton_iterations()).collect()
        };
        assert_eq!(iterations(&high), iterations(&low), "{method}");
        let shift = Vec3::new(0.0, 0.0, 0.05);
        let gap = high
            .final_state
            .positions
            .iter()
            .zip(&low.final_state.positions)
            .map(|(a, b)| (a - (b + shift)).norm())
            .fold(0.0, f64::max);
        assert!(gap < 1e-9, "{method}: states differ by {gap:e} m");
    }
}

/// A 0.1 m cube hanging from its top face under gravity (ramped with the load), its bottom
/// on a ground that starts at the rest height and recedes by 4 mm over 4 steps. At the first
/// step the ground carries part of the weight (the free sag, about `rho g L^2 / (2 E)` = 0.1
/// mm at a quarter of the load, exceeds the ground's 0 mm drop); from the second on the gap
/// is open (the ground 1 mm down against a sag near 0.25 mm). At every step complementarity
/// holds at every boundary vertex: in contact at the first, every multiplier released after.
#[test]
fn receding_ground_releases_every_contact() {
    let mesh = box_grid(Vec3::zeros(), Vec3::repeat(0.1), [3, 3, 3]).unwrap();
    let tol = tolerance(&mesh);
    let boundary = BoundarySurface::new(&mesh).unwrap().vertices().to_vec();
    let ground = Obstacle {
        shape: Shape::HalfSpace {
            point: Vec3::new(0.0, 0.0, 1e-3),
            normal: Vec3::z(),
        },
        translate: Vec3::new(0.0, 0.0, -4e-3),
        radius_change: 0.0,
        curve: None,
    };
    let top = plane(&mesh, 2, 0.1);
    let problem = Problem {
        mesh: mesh.into(),
        method: Method::Standard,
        material: Material::from_young_poisson(100e3, 0.45, 1000.0).unwrap(),
        regions: Vec::new(),
        zones: None,
        dirichlet: vec![Dirichlet {
            nodes: top,
            axes: [true; 3],
            motion: Motion::Fixed,
            curve: None,
        }],
        loads: vec![Load::Gravity(Vec3::new(0.0, 0.0, -G)).into()],
        obstacles: vec![ground.clone()],
        cloths: Vec::new(),
    };
    let steps = 4;
    let mut sim = Simulation::new(problem, Settings::default()).unwrap();
    let mut active = Vec::new();
    sim.run(Stepping::quasi_static(steps), |frame| {
        // One obstacle with normal +z: each vertex's contact force is (0, 0, lambda).
        let t = frame.index as f64 / steps as f64;
        let x = &frame.state.positions;
        let pairs = boundary
            .iter()
            .map(|&v| (v, 0, frame.contact_forces[v].z, ground.distance(&x[v], t).0));
        active.push(assert_complementarity(
            pairs,
            tol,
            &format!("step {}", frame.index),
        ));
    })
    .unwrap();
    assert!(active[0] > 0, "{active:?}");
    assert!(active[1..].iter().all(|&a| a == 0), "{active:?}");
}

/// A ball of radius 0.1 m (`48 res^3` tets) with shear modulus `mu`, `gap` above the ground.
fn dropped_ball(res: usize, method: Method, mu: f64, nu: f64, gap: f64) -> Problem {
    let mut mesh = ball(0.1, res).unwrap();
    mesh = TetMesh::new(
        mesh.positions()
            .iter()
            .map(|p| p + Vec3::new(0.0, 0.0, 0.1 + gap))
            .collect(),
        mesh.tets().to_vec(),
    )
    .unwrap();
    let young = 2.0 * mu * (1.0 + nu);
    Problem {
        mesh: mesh.into(),
        method,
        material: Material::from_young_poisson(young, nu, 1000.0).unwrap(),
        regions: Vec::new(),
        zones: None,
        dirichlet: Vec::new(),
        loads: vec![Load::Gravity(Vec3::new(0.0, 0.0, -G)).into()],
        obstacles: vec![ground(0.0)],
        cloths: Vec::new(),
    }
}

#[test]
fn dropped_ball_bounces_and_releases_every_contact() {
    // Stiffer than the scene's 16 kPa so that the coarse ball lets go within 120 frames.
    let problem = dropped_ball(2, Method::Standard, 160e3, 0.45, 0.01);
    let tol = tolerance(problem.mesh.corners());
    let masses = 1000.0 * problem.mesh.rest_volume();
    let mut sim = Simulation::new(problem, Settings::default()).unwrap();
    let mut first_contact = None;
    let mut released = None;
    let mut upward = false;
    let mut max_penetration: f64 = 0.0;
    let mut negative = false;
    sim.run(
        Stepping::ImplicitEuler {
            dt: 1e-3,
            frames: 120,
        },
        |frame| {
            let c = &frame.report.contact;
            max_penetration = max_penetration.max(c.max_penetration);
            negative |= frame.contact_forces.iter().any(|f| f.z < 0.0);
            if c.active_vertices > 0 && first_contact.is_none() {
                first_contact = Some(frame.index);
            }
            if first_contact.is_some() && c.active_vertices == 0 && released.is_none() {
                released = Some(frame.index);
                let momentum: f64 = frame.state.velocities.iter().map(|v| v.z).sum();
                upward = momentum > 0.0;
            }
        },
    )
    .unwrap();
    let first = first_contact.expect("the ball reaches the ground");
    let released = released.expect("the ball leaves the ground");
    assert!(released > first);
    assert!(upward, "the ball moves up when it lets go ({masses} kg)");
    assert!(max_penetration <= tol, "penetration {max_penetration:e}");
    assert!(!negative, "a contact force pulled");
    assert!(sim.contact_multipliers().iter().all(|&l| l == 0.0));
}

#[test]
fn zonal_keeps_the_volume_through_the_impact() {
    let problem = dropped_ball(2, Method::Zonal, 16e3, 0.45, 0.001);
    let mesh = problem.mesh.corners().clone();
    let rest = mesh.rest_volume();
    let mut sim = Simulation::new(problem, Settings::default()).unwrap();
    let mut worst: f64 = 0.0;
    let mut touched = false;
    sim.run(
        Stepping::ImplicitEuler {
            dt: 1e-3,
            frames: 40,
        },
        |frame| {
            touched |= frame.report.contact.active_vertices > 0;
            worst = worst.max((volume(&mesh, &frame.state.positions) / rest - 1.0).abs());
        },
    )
    .unwrap();
    assert!(touched);
    assert!(worst <= 1e-8, "volume drift {worst:e}");
}

/// An incompressible block squeezed by two moving cylinders: no penetration, complementarity
/// at every boundary vertex and both cylinders, vertical forces that cancel, and the thickness
/// under the cylinders' lines that their motion prescribes.
#[test]
fn incompressible_block_squeezed_between_moving_cylinders() {
    // Two cylinders along y press the bottom and top of a cube at nu = 0.5 (C = 0) by 10 mm
    // each; the planes x = 0.05 and y = 0 are held in x and y only.
    let mesh = box_grid(Vec3::zeros(), Vec3::repeat(0.1), [4, 4, 4]).unwrap();
    let tol = tolerance(&mesh);
    let hold = |axis: usize, value: f64| Dirichlet {
        nodes: plane(&mesh, axis, value),
        axes: [axis == 0, axis == 1, false],
        motion: Motion::Fixed,
        curve: None,
    };
    let dirichlet = vec![hold(0, 0.05), hold(1, 0.0)];
    let cylinder = |z: f64, dz: f64| Obstacle {
        shape: Shape::Cylinder {
            point: Vec3::new(0.05, 0.0, z),
            axis: Vec3::y(),
            radius: 0.05,
        },
        translate: Vec3::new(0.0, 0.0, dz),
        radius_change: 0.0,
        curve: None,
    };
    let obstacles = vec![cylinder(-0.05, 0.01), cylinder(0.15, -0.01)];
    let problem = Problem {
        mesh: mesh.into(),
        method: Method::MixedP1,
        material: Material::from_young_poisson(100e3, 0.5, 1000.0).unwrap(),
        regions: Vec::new(),
        zones: None,
        dirichlet,
        loads: Vec::new(),
        obstacles: obstacles.clone(),
        cloths: Vec::new(),
    };
    let mut sim = Simulation::new(problem, Settings::default()).unwrap();
    let summary = sim.run(Stepping::quasi_static(2), |_| {}).unwrap();
    let last = summary.reports.last().unwrap();
    let x = &summary.final_state.positions;
    assert!(last.contact.max_penetration <= tol);
    assert!(last.contact.active_vertices >= 2);
    let pairs = assert_complementarity(
        final_pairs(&sim, &obstacles, x).into_iter(),
        tol,
        "squeezed block",
    );
    assert!(pairs >= 2, "{pairs} pairs in contact");
    let squeeze: f64 = sim.contact_multipliers().iter().sum();
    assert!(squeeze > 0.0);
    // The holds react in x and y only: the cylinders' vertical forces cancel.
    assert!(
        last.contact.force.z.abs() <= 1e-6 * squeeze,
        "{}",
        last.contact.force
    );
    // Under the cylinders' lowest and highest lines, the cube is 80 mm thick.
    let rest = sim.mesh().nodes();
    let middle: Vec<f64> = (0..x.len())
        .filter(|&v| (rest[v].x - 0.05).abs() < 1e-9)
        .map(|v| x[v].z)
        .collect();
    let top = middle.iter().copied().fold(f64::MIN, f64::max);
    let bottom = middle.iter().copied().fold(f64::MAX, f64::min);
    assert!(
        (top - 0.09).abs() <= tol && (bottom - 0.01).abs() <= tol,
        "{bottom} to {top}"
    );
}

/// A cylinder (radius 50 mm, 100 mm tall, its base clamped) through a ring (tube 10 mm)
/// whose hole shrinks from 52 to 45 mm at mid-height, in 4 steps: no vertex ends inside the
/// ring by more than the contact tolerance, complementarity holds at every boundary vertex,
/// at least as many vertex-ring pairs touch as the ring's plane has surface vertices, and
/// every one of those has been pushed inwards (the contact is frictionless, so they also slide
/// along the tube, out of the plane, and need not end at the hole's radius: measured, the
/// farthest ends at 46.1 mm).
#[test]
fn shrinking_ring_squeezes_a_cylinder_without_penetrating() {
    let mesh = cylinder(0.05, 0.1, 2).unwrap();
    let tol = tolerance(&mesh);
    let ring = Obstacle {
        shape: Shape::Ring {
            center: Vec3::new(0.0, 0.0, 0.05),
            axis: Vec3::z(),
            radius: 0.062,
            tube: 0.01,
        },
        translate: Vec3::zeros(),
        radius_change: -0.007,
        curve: None,
    };
    let waist: Vec<usize> = BoundarySurface::new(&mesh)
        .unwrap()
        .vertices()
        .iter()
        .copied()
        .filter(|&v| (mesh.positions()[v].z - 0.05).abs() < 1e-12)
        .collect();
    let problem = Problem {
        mesh: mesh.clone().into(),
        method: Method::Standard,
        material: Material::from_young_poisson(100e3, 0.45, 1000.0).unwrap(),
        regions: Vec::new(),
        zones: None,
        dirichlet: vec![Dirichlet {
            nodes: plane(&mesh, 2, 0.0),
            axes: [true; 3],
            motion: Motion::Fixed,
            curve: None,
        }],
        loads: Vec::new(),
        obstacles: vec![ring.clone()],
        cloths: Vec::new(),
    };
    let mut sim = Simulation::new(problem, Settings::default()).unwrap();
    let summary = sim.run(Stepping::quasi_static(4), |_| {}).unwrap();
    let last = summary.reports.last().unwrap();
    assert!(last.contact.max_penetration <= tol);
    let x = &summary.final_state.positions;
    let pairs = assert_complementarity(final_pairs(&sim, &[ring], x).into_iter(), tol, "ring");
    assert!(pairs >= waist.len(), "{pairs} pairs in contact");
    assert!(!waist.is_empty());
    for &v in &waist {
        let radius = x[v].xy().norm();
        assert!(radius < 0.05, "vertex {v} at radius {radius}");
    }
}

#[test]
fn bad_obstacles_and_unconverged_contact_are_errors() {
    let mut problem = resting_block(Method::Standard, 0.45);
    problem.obstacles.push(Obstacle::fixed(Shape::Sphere {
        center: Vec3::zeros(),
        radius: -1.0,
    }));
    assert!(Simulation::new(problem, Settings::default()).is_err());
    // A ring whose hole would close, and a half-space asked to change its radius.
    let ring = Shape::Ring {
        center: Vec3::zeros(),
        axis: Vec3::z(),
        radius: 0.2,
        tube: 0.05,
    };
    for (shape, change) in [(ring, -0.16), (ring, -0.2), (ground(0.0).shape, 0.01)] {
        let mut problem = resting_block(Method::Standard, 0.45);
        problem.obstacles.push(Obstacle {
            radius_change: change,
            ..Obstacle::fixed(shape)
        });
        assert!(Simulation::new(problem, Settings::default()).is_err());
    }

    // A block pushed 10 mm into the ground with a single multiplier update.
    let mut problem = resting_block(Method::Standard, 0.45);
    problem.obstacles = vec![Obstacle {
        shape: Shape::HalfSpace {
            point: Vec3::zeros(),
            normal: Vec3::z(),
        },
        translate: Vec3::new(0.0, 0.0, 0.01),
        radius_change: 0.0,
        curve: None,
    }];
    let settings = Settings {
        max_contact_iterations: 1,
        ..Settings::default()
    };
    let mut sim = Simulation::new(problem, settings).unwrap();
    let failure = sim.run(Stepping::quasi_static(1), |_| {}).unwrap_err();
    assert!(matches!(
        failure.error,
        isochor_solvers::SolverError::ContactNotConverged { iterations: 1, .. }
    ));
    // The failed step is rolled back: the rest state, and the multipliers it started with.
    assert_eq!(failure.last_state.positions, sim.state().positions);
    assert!(sim.contact_multipliers().iter().all(|&l| l == 0.0));
}
