//! Barrier contact between bodies (`[contact]`): two soft balls collide in free space under
//! implicit Euler. On every accepted state no two surface triangles intersect, the balls
//! never touch, linear momentum is conserved through the impact, and the struck ball leaves.

use isochor_mesh::contact::{intersecting_triangles, ContactSurface};
use isochor_mesh::Vec3;
use isochor_scenes::resolve::build;
use isochor_scenes::Scene;
use isochor_solvers::Simulation;

/// Ball `a` (radius 0.05 m) flying at 0.5 m/s along x into ball `b` at rest, 1 cm apart.
fn balls(method: &str, element: &str, contact: &str) -> Scene {
    Scene::from_toml_str(&balls_text(method, element, contact), "balls").unwrap()
}

fn balls_text(method: &str, element: &str, contact: &str) -> String {
    format!(
        r#"name = "balls"
method = "{method}"
element = "{element}"

[material]
young = 1e6
nu = 0.45
rho = 1000.0

[[bodies]]
name = "a"
mesh = {{ generator = "ball", radius = 0.05, res = 1, center = [-0.055, 0.0, 0.0] }}
velocity = [0.5, 0.0, 0.0]

[[bodies]]
name = "b"
mesh = {{ generator = "ball", radius = 0.05, res = 1, center = [0.055, 0.0, 0.0] }}

{contact}

[stepping]
mode = "dynamic"
dt = 0.002
frames = 30
"#
    )
}

/// Runs the scene; returns the x momentum of each body at every frame and the number of
/// intersecting triangle pairs seen on any accepted state.
fn collide(scene: &Scene) -> (Vec<[f64; 2]>, usize) {
    let resolved = build(scene).unwrap();
    let mesh = resolved.problem.mesh.clone();
    let masses = mesh.lumped_masses(&vec![1000.0; mesh.num_elements()]);
    let parts = resolved.bodies.parts.clone();
    let mut sim = Simulation::new(resolved.problem, resolved.settings).unwrap();
    sim.set_velocities(
        resolved
            .bodies
            .initial_velocities(mesh.num_nodes())
            .unwrap(),
    )
    .unwrap();
    if let Some(spec) = resolved.surface_contact {
        sim.set_surface_contact(spec).unwrap();
    }
    let surface = ContactSurface::from_element_surface(&mesh.boundary().unwrap());
    let (mut momenta, mut intersections) = (Vec::new(), 0);
    sim.run(resolved.stepping, |frame| {
        let x: &[Vec3] = &frame.state.positions;
        intersections += intersecting_triangles(&surface, x).len();
        let v = &frame.state.velocities;
        momenta.push([0, 1].map(|b| parts[b].nodes().map(|n| masses[n] * v[n].x).sum::<f64>()));
    })
    .unwrap();
    (momenta, intersections)
}

#[test]
fn two_balls_collide_without_touching_and_keep_their_momentum() {
    for (method, element) in [
        ("standard", "tet4"),
        ("mixed-p1", "tet4"),
        ("standard", "tet10"),
    ] {
        let (momenta, intersections) = collide(&balls(method, element, "[contact]"));
        assert_eq!(
            intersections, 0,
            "{method} {element}: no triangles intersect"
        );
        let start = momenta[0][0] + momenta[0][1];
        for (frame, [a, b]) in momenta.iter().enumerate() {
            assert!(
                (a + b - start).abs() <= 1e-6 * start.abs(),
                "{method} {element}: frame {frame}: momentum {} against {start}",
                a + b
            );
        }
        let [a, b] = momenta[momenta.len() - 1];
        eprintln!("{method} {element}: start {start:.6e}, end a {a:.6e} b {b:.6e}");
        assert!(
            b > 0.3 * start && a < 0.7 * start,
            "{method} {element}: the struck ball leaves: a {a}, b {b}"
        );
    }
}

#[test]
fn without_contact_the_balls_pass_through_each_other() {
    let (momenta, intersections) = collide(&balls("standard", "tet4", ""));
    assert!(intersections > 0, "the balls overlap in flight");
    let [a, b] = momenta[momenta.len() - 1];
    assert!(b.abs() < 1e-12 && a > 0.0, "nothing pushes b: a {a}, b {b}");
}

#[test]
fn a_bad_reach_is_refused_by_key() {
    let text = balls_text("standard", "tet4", "[contact]\ndhat = -1.0");
    let e = Scene::from_toml_str(&text, "balls")
        .unwrap_err()
        .to_string();
    assert!(e.contains("contact.dhat"), "{e}");
}

/// Two equal cubes (1 cm) stacked with a 0.5 mm gap: the lower one clamped at its base, the
/// upper one's top pushed down 1 mm. Mirror images of each other across the frictionless
/// interface, the two cubes share the 0.5 mm left once the gap closes: the lower cube's top
/// sinks by 0.25 mm where they touch (more where its face bulges away from the other).
fn stack(method: &str) -> Scene {
    let cube = |z0: f64| {
        format!(
            "{{ generator = \"box\", min = [0.0, 0.0, {z0}], max = [0.01, 0.01, {}], res = 1 }}",
            z0 + 0.01
        )
    };
    let text = format!(
        r#"name = "stack"
method = "{method}"

[material]
young = 1e5
nu = 0.3

[[bodies]]
name = "lower"
mesh = {lower}

[[bodies]]
name = "upper"
mesh = {upper}

[contact]
dhat = 1e-6

[selections.base]
plane = {{ point = [0.0, 0.0, 0.0], normal = [0.0, 0.0, 1.0] }}

[selections.top]
plane = {{ point = [0.0, 0.0, 0.0205], normal = [0.0, 0.0, 1.0] }}

[selections.interface]
plane = {{ point = [0.0, 0.0, 0.01], normal = [0.0, 0.0, 1.0] }}
body = "lower"

[[dirichlet]]
selection = "base"

[[dirichlet]]
selection = "top"
motion = {{ translate = [0.0, 0.0, -1e-3] }}

[stepping]
mode = "quasi-static"
steps = 4
"#,
        lower = cube(0.0),
        upper = cube(0.0105)
    );
    Scene::from_toml_str(&text, "stack").unwrap()
}

#[test]
fn stacked_cubes_share_the_compression() {
    for method in ["standard", "mixed-p1"] {
        let resolved = build(&stack(method)).unwrap();
        let mesh = resolved.problem.mesh.clone();
        let interface = resolved.selections.nodes("interface").unwrap().to_vec();
        let mut sim = Simulation::new(resolved.problem, resolved.settings).unwrap();
        sim.set_surface_contact(resolved.surface_contact.unwrap())
            .unwrap();
        let surface = ContactSurface::from_element_surface(&mesh.boundary().unwrap());
        let mut intersections = 0;
        sim.run(resolved.stepping, |frame| {
            intersections += intersecting_triangles(&surface, &frame.state.positions).len();
        })
        .unwrap();
        assert_eq!(intersections, 0, "{method}: the cubes never overlap");
        let x = &sim.state().positions;
        let sink = interface
            .iter()
            .map(|&n| mesh.nodes()[n].z - x[n].z)
            .sum::<f64>()
            / interface.len() as f64;
        eprintln!(
            "{method}: the lower cube's top sinks {sink:.6e} m on average (0.25 mm by symmetry)"
        );
        // The meshes are not mirror images of each other (the same Kuhn split), so their
        // faces are not either; on average each cube still gives half of the 0.5 mm.
        assert!((sink - 2.5e-4).abs() < 0.01 * 2.5e-4, "{method}: {sink}");
    }
}
