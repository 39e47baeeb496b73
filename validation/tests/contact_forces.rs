//! The contact forces reported per obstacle (the `contact_force_<name>_*` columns of
//! `steps.csv`) are whole forces, normal and tangential: the 20 x 20 x 10 mm block of the
//! built-in incline (4 g) under gravity tilted by 30 degrees, on the ground (an analytic
//! half-space) or on a meshed plate, implicit Euler. Sticking (mu = 0.7) the force on the
//! block balances its weight and its momentum's change over each step (the lumped masses
//! times the velocity change over `dt`: the block comes to rest); sliding (mu = 0.3) the
//! tangential force is `mu` times the normal one.
//!
//! The tolerances are the solver's: the balance of the whole body holds to the sum of the
//! force residual over its nodes (at most `sqrt(nodes)` times its norm, which Newton drove
//! below its tolerance); and friction's normal forces are those of its last lag, which
//! settled to within 1% of the largest (`FRICTION_SETTLED` of the solvers), so a force
//! computed with them matches the solve's to that fraction of the friction force.

use super::incline::G;
use super::mesh_obstacle_friction::{block_scene, plate_file, DHAT, DT};
use isochor_mesh::Vec3;
use isochor_scenes::resolve;
use isochor_scenes::Scene;

/// How far the lagged friction forces may move and still count as settled.
const FRICTION_SETTLED: f64 = 1e-2;
/// The block's mass (kg): 1000 kg/m^3 times 4e-6 m^3 (its lumped masses add up to it).
const MASS: f64 = 4e-3;

/// The ground the block stands on.
#[derive(Clone, Copy, Debug)]
enum Ground {
    HalfSpace,
    MeshedPlate,
}

/// The block on `ground` at slope `theta` (degrees) with friction `mu`, over `frames` implicit
/// Euler steps of [`DT`].
fn block(ground: Ground, theta: f64, mu: f64, frames: usize) -> Scene {
    let friction = format!("friction = {mu}");
    match ground {
        Ground::HalfSpace => block_scene(
            theta,
            "[[obstacles]]\nshape = \"half-space\"\n",
            0.0,
            &friction,
            frames,
        ),
        Ground::MeshedPlate => block_scene(
            theta,
            &format!(
                "[[obstacles]]\nshape = \"mesh\"\npath = '{}'\n",
                plate_file()
            ),
            DHAT / 2.0,
            &friction,
            frames,
        ),
    }
}

/// What a step of the block shows: the force the ground exerts on it, the rate of change of
/// its momentum over the step, its node count and the step's final force residual.
struct Balance {
    force: Vec3,
    momentum_rate: Vec3,
    nodes: usize,
    residual: f64,
}

/// The [`Balance`] of every accepted step of `scene` (implicit Euler with step [`DT`]).
fn balances(ground: Ground, scene: &Scene) -> Vec<Balance> {
    let resolved = resolve::build(scene).unwrap();
    let mesh = resolved.problem.mesh.clone();
    let masses = mesh.lumped_masses(&vec![1000.0; mesh.num_elements()]);
    let (mut sim, stepping) = crate::incline::simulation(resolved);
    let mut velocities = vec![Vec3::zeros(); masses.len()];
    let mut steps = Vec::new();
    sim.run(stepping, |frame| {
        let force = match ground {
            Ground::HalfSpace => frame.report.contact.obstacle_forces[0],
            Ground::MeshedPlate => frame.surface_contact.as_ref().unwrap().obstacle_forces[0],
        };
        let v = &frame.state.velocities;
        let momentum_rate = (0..masses.len())
            .map(|i| (v[i] - velocities[i]) * (masses[i] / DT))
            .sum();
        velocities.clone_from(v);
        steps.push(Balance {
            force,
            momentum_rate,
            nodes: masses.len(),
            residual: frame.report.force_residual,
        });
    })
    .unwrap();
    steps
}

#[test]
fn the_contact_force_on_a_sticking_block_balances_its_weight() {
    let t = 30.0f64.to_radians();
    let weight = Vec3::new(G * t.sin(), 0.0, -G * t.cos()) * MASS;
    for ground in [Ground::HalfSpace, Ground::MeshedPlate] {
        let scene = block(ground, 30.0, 0.7, 6);
        for (step, b) in balances(ground, &scene).iter().enumerate() {
            let tangential = b.force.xy().norm();
            let bound = (b.nodes as f64).sqrt() * b.residual + FRICTION_SETTLED * tangential;
            let imbalance = (b.force + weight - b.momentum_rate).norm();
            eprintln!(
                "{ground:?} step {}: force {:?}, weight {weight:?}, momentum rate {:?}: \
                 imbalance {imbalance:.2e} (bound {bound:.2e}: residual {:.1e} on {} nodes)",
                step + 1,
                b.force,
                b.momentum_rate,
                b.residual,
                b.nodes
            );
            assert!(
                tangential > 0.5 * weight.xy().norm(),
                "{ground:?}: no tangential force in {:?}",
                b.force
            );
            assert!(imbalance <= bound, "{ground:?}: {imbalance} beyond {bound}");
        }
    }
}

#[test]
fn the_tangential_force_on_a_sliding_block_is_mu_times_the_normal_one() {
    let mu = 0.3;
    for ground in [Ground::HalfSpace, Ground::MeshedPlate] {
        let scene = block(ground, 30.0, mu, 6);
        let force = balances(ground, &scene).last().unwrap().force;
        let ratio = force.xy().norm() / force.z;
        eprintln!("{ground:?}: force {force:?}, tangential over normal {ratio:.5} against {mu}");
        assert!(
            force.x < 0.0,
            "{ground:?}: friction must point up the slope: {force:?}"
        );
        assert!(
            (ratio - mu).abs() <= FRICTION_SETTLED * mu,
            "{ground:?}: {ratio} against {mu}"
        );
    }
}
