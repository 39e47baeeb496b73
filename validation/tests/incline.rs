//! Friction in motion (implicit Euler), on the built-in scene `incline` reduced: a block on
//! the ground under gravity tilted by `theta` sticks when `tan(theta) < mu` and slides with
//! the acceleration `g (sin(theta) - mu cos(theta))` when `tan(theta) > mu`; and a block
//! resting on a clamped plate body (friction between surfaces) sticks with a high
//! coefficient between the two bodies and slides without friction. No accepted state of any
//! of these runs has two surface triangles intersect.
//!
//! Sticking is smoothed: under a tangential force `F` below `mu lambda` a step slips by the
//! `u` with `f1(u) = F / (mu lambda)`, less than `epsv`, so over `N` steps the block creeps by
//! less than `N epsv` (plus its elastic shear, `rho g sin(theta) H^2 / (2 G)` at the top of a
//! block of height `H`, which the centroid sees half of).

use isochor_mesh::contact::{intersecting_triangles, ContactSurface};
use isochor_mesh::Vec3;
use isochor_scenes::resolve::{self, ResolvedScene};
use isochor_scenes::{builtin, load_scene, Override, Scene};
use isochor_solvers::{Simulation, Stepping};

/// The gravity's magnitude (m/s^2).
pub const G: f64 = 9.81;

/// The simulation of `resolved` with its barrier contact, meshed obstacles and friction
/// attached, and its stepping.
pub fn simulation(resolved: ResolvedScene) -> (Simulation, Stepping) {
    let mut sim = Simulation::new(resolved.problem, resolved.settings).unwrap();
    if let Some(spec) = resolved.surface_contact {
        sim.set_surface_contact(spec).unwrap();
    }
    if !resolved.mesh_obstacles.is_empty() {
        sim.set_mesh_obstacles(resolved.mesh_obstacles).unwrap();
    }
    if let Some(spec) = resolved.friction {
        sim.set_friction(spec).unwrap();
    }
    (sim, resolved.stepping)
}

/// The centroid's x at every frame `(t, x)` (the rest state first) and the lags of the
/// friction's normal forces per step; asserts that no accepted state has two triangles of the
/// bodies' surfaces and the meshed obstacles' intersect.
pub fn slide(resolved: ResolvedScene, nodes: Option<Vec<usize>>) -> (Vec<(f64, f64)>, Vec<usize>) {
    let nodes = nodes.unwrap_or_else(|| (0..resolved.problem.mesh.num_nodes()).collect());
    let centroid = |x: &[Vec3]| nodes.iter().map(|&n| x[n].x).sum::<f64>() / nodes.len() as f64;
    let mut path = vec![(0.0, centroid(resolved.problem.mesh.nodes()))];
    let mut lags = Vec::new();
    let surface = surface_with_obstacles(&resolved);
    let (mut sim, stepping) = simulation(resolved);
    sim.run(stepping, |frame| {
        path.push((frame.state.t, centroid(&frame.state.positions)));
        lags.push(frame.report.friction_lags);
        let mut x = frame.state.positions.clone();
        x.extend(frame.mesh_obstacles.iter().flatten());
        let crossing = intersecting_triangles(&surface, &x);
        assert!(
            crossing.is_empty(),
            "t {}: triangles {crossing:?} intersect",
            frame.state.t
        );
    })
    .unwrap();
    (path, lags)
}

/// The bodies' boundary triangles and the meshed obstacles' after them, numbered as the
/// surface-contact term numbers them (obstacle vertices after the bodies' nodes).
fn surface_with_obstacles(resolved: &ResolvedScene) -> ContactSurface {
    let mesh = &resolved.problem.mesh;
    let mut triangles = ContactSurface::from_element_surface(&mesh.boundary().unwrap())
        .triangles()
        .to_vec();
    let mut offset = mesh.num_nodes();
    for o in &resolved.mesh_obstacles {
        triangles.extend(o.triangles.iter().map(|t| t.map(|v| v + offset)));
        offset += o.vertices.len();
    }
    ContactSurface::from_triangles(triangles)
}

/// The incline reduced at slope `theta` (degrees) and friction `mu`.
fn incline(theta: f64, mu: f64) -> ResolvedScene {
    let t = theta.to_radians();
    let sets: Vec<String> = builtin::reduced("incline")
        .unwrap()
        .iter()
        .map(|s| s.to_string())
        .chain([
            format!("gravity=[{}, 0.0, {}]", G * t.sin(), -G * t.cos()),
            format!("contact.friction={mu}"),
            "frames=20".to_string(),
        ])
        .collect();
    let overrides: Vec<Override> = sets.iter().map(|s| Override::parse(s).unwrap()).collect();
    resolve::build(&load_scene("incline", None, &overrides).unwrap()).unwrap()
}

/// The least-squares acceleration `2 c2` of `x = c0 + c1 t + c2 t^2` through the points.
pub fn fitted_acceleration(path: &[(f64, f64)]) -> f64 {
    let mut a = nalgebra::Matrix3::zeros();
    let mut b = nalgebra::Vector3::zeros();
    for &(t, x) in path {
        let row = nalgebra::Vector3::new(1.0, t, t * t);
        a += row * row.transpose();
        b += row * x;
    }
    2.0 * a.lu().solve(&b).unwrap()[2]
}

#[test]
fn the_block_slides_down_the_incline_with_the_kinetic_acceleration() {
    assert_kinetic_acceleration("incline", incline);
}

#[test]
fn the_block_sticks_on_the_incline_below_the_friction_angle() {
    assert_sticks("incline", incline);
}

/// The block of `ground(theta, mu)` slides down at `g (sin theta - mu cos theta)` within 2%
/// at 30 degrees with mu 0.3 and 0.5 and at 20 degrees with mu 0.2.
pub fn assert_kinetic_acceleration(ground: &str, scene: impl Fn(f64, f64) -> ResolvedScene) {
    for (theta, mu) in [(30.0f64, 0.3), (30.0, 0.5), (20.0, 0.2)] {
        let (path, lags) = slide(scene(theta, mu), None);
        let t = theta.to_radians();
        let expected = G * (t.sin() - mu * t.cos());
        let measured = fitted_acceleration(&path);
        eprintln!(
            "{ground} theta {theta} mu {mu}: acceleration {measured:.5} against {expected:.5} ({:+.3}%), lags per step {lags:?}",
            100.0 * (measured / expected - 1.0)
        );
        assert!(
            (measured - expected).abs() <= 0.02 * expected,
            "{ground}, theta {theta}, mu {mu}: {measured} against {expected}"
        );
    }
}

/// The block of `ground(theta, mu)` sticks at 30 degrees with mu 0.7 and at 20 degrees with
/// mu 0.5: over the run it creeps by less than the smoothed static friction's slip `epsv` a
/// step plus the block's elastic shear.
pub fn assert_sticks(ground: &str, scene: impl Fn(f64, f64) -> ResolvedScene) {
    for (theta, mu) in [(30.0f64, 0.7), (20.0, 0.5)] {
        let resolved = scene(theta, mu);
        let epsv = resolved.friction.as_ref().unwrap().epsv;
        let (path, lags) = slide(resolved, None);
        let t = theta.to_radians();
        let steps = (path.len() - 1) as f64;
        // Block 10 mm high, E = 1 MPa, nu = 0.3, rho = 1000.
        let shear = 1000.0 * G * t.sin() * 0.01f64.powi(2) / (2.0 * 1e6 / 2.6);
        let bound = steps * epsv + shear;
        let creep = path.last().unwrap().1 - path[0].1;
        let predicted = steps * epsv * (1.0 - (1.0 - t.tan() / mu).sqrt());
        eprintln!(
            "{ground} theta {theta} mu {mu}: displacement {creep:.3e} (creep predicted {predicted:.3e}, bound {bound:.3e}, epsv {epsv:.1e}), lags per step {lags:?}"
        );
        assert!(
            creep.abs() <= bound,
            "{ground}, theta {theta}, mu {mu}: {creep} beyond {bound}"
        );
    }
}

/// A block body resting on a clamped plate body, `dhat` 0.1 mm, under gravity tilted by 30
/// degrees; `contact` is the `[contact]` section's friction keys.
fn block_on_plate(contact: &str) -> ResolvedScene {
    resolve::build(&Scene::from_toml_str(&block_on_plate_text(contact), "block-on-plate").unwrap())
        .unwrap()
}

fn block_on_plate_text(contact: &str) -> String {
    let t = 30.0f64.to_radians();
    format!(
        r#"name = "block-on-plate"
method = "standard"

[material]
young = 1e6
nu = 0.3
rho = 1000.0

[[bodies]]
name = "plate"
mesh = {{ generator = "box", min = [0.0, 0.0, -0.01], max = [0.04, 0.04, 0.0], cells = [4, 4, 1], res = 1 }}

[[bodies]]
name = "block"
mesh = {{ generator = "box", min = [0.01, 0.01, 0.00005], max = [0.03, 0.03, 0.01005], cells = [2, 2, 1], res = 1 }}

[selections.base]
body = "plate"
plane = {{ point = [0.0, 0.0, -0.01], normal = [0.0, 0.0, 1.0] }}

[[dirichlet]]
selection = "base"
axes = "xyz"

[loads]
gravity = [{}, 0.0, {}]

[contact]
dhat = 1e-4
self = false
{contact}

[stepping]
mode = "dynamic"
dt = 0.005
frames = 10
"#,
        G * t.sin(),
        -G * t.cos()
    )
}

#[test]
fn bad_friction_keys_are_refused_by_key() {
    for (keys, key) in [
        ("friction = -0.1", "contact.friction"),
        ("friction = nan", "contact.friction"),
        ("epsv = 0.0", "contact.epsv"),
        (
            "[[contact.pairs]]\nbodies = [\"block\", \"ball\"]\nfriction = 0.5",
            "contact.pairs[0].bodies",
        ),
        (
            "[[contact.pairs]]\nbodies = [\"block\", \"plate\"]\nfriction = -1.0",
            "contact.pairs[0].friction",
        ),
        (
            "[[contact.obstacles]]\nobstacle = 0\nfriction = 0.5",
            "contact.obstacles[0].obstacle",
        ),
    ] {
        let e = Scene::from_toml_str(&block_on_plate_text(keys), "block-on-plate")
            .unwrap_err()
            .to_string();
        assert!(e.contains(key), "{keys}: {e}");
    }
}

#[test]
fn a_block_on_a_plate_body_sticks_by_friction_and_slides_without() {
    let block = |r: &ResolvedScene| r.bodies.parts[1].nodes().collect::<Vec<_>>();
    let t = 30.0f64.to_radians();
    // The pair's coefficient overrides the scene's 0 (names in either order).
    let sticking = block_on_plate(
        "friction = 0.0\n[[contact.pairs]]\nbodies = [\"block\", \"plate\"]\nfriction = 0.9",
    );
    let epsv = sticking.friction.as_ref().unwrap().epsv;
    let nodes = block(&sticking);
    let (path, lags) = slide(sticking, Some(nodes));
    let creep = path.last().unwrap().1 - path[0].1;
    let steps = (path.len() - 1) as f64;
    let shear = 1000.0 * G * t.sin() * 0.01f64.powi(2) / (2.0 * 1e6 / 2.6);
    eprintln!(
        "block on plate, mu 0.9: displacement {creep:.3e} (bound {:.3e}), lags per step {lags:?}",
        steps * epsv + 2.0 * shear
    );
    // The plate shears too (its top by as much as the block's, under the same stress).
    assert!(creep.abs() <= steps * epsv + 2.0 * shear, "{creep}");
    // Without friction the block slides at g sin(theta).
    let sliding = block_on_plate("friction = 0.0");
    assert!(sliding.friction.is_none(), "no coefficient: frictionless");
    let nodes = block(&sliding);
    let (path, _) = slide(sliding, Some(nodes));
    let measured = fitted_acceleration(&path);
    let expected = G * t.sin();
    eprintln!("block on plate, mu 0: acceleration {measured:.4} against {expected:.4}");
    assert!(
        (measured - expected).abs() <= 0.02 * expected,
        "{measured} against {expected}"
    );
}
