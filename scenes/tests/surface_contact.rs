//! Barrier contact between bodies (`[contact]`) in quasi-static stepping: two stacked cubes
//! pressed together share the compression, and no two surface triangles intersect on any
//! accepted state. The colliding balls are the built-in scene `colliding-balls`
//! (`contact_scenes.rs`).

use isochor_mesh::contact::{intersecting_triangles, ContactSurface};
use isochor_scenes::resolve::build;
use isochor_scenes::Scene;
use isochor_solvers::Simulation;

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
        let (mut intersections, mut iterations, mut projected) = (0, 0, 0);
        sim.run(resolved.stepping, |frame| {
            intersections += intersecting_triangles(&surface, &frame.state.positions).len();
            iterations += frame.report.iterations.len();
            projected += frame
                .report
                .iterations
                .iter()
                .filter(|i| i.hessian_projected)
                .count();
        })
        .unwrap();
        assert_eq!(intersections, 0, "{method}: the cubes never overlap");
        eprintln!(
            "{method}: {projected} of {iterations} iterations projected the barrier's Hessian"
        );
        // Both paths run here: the exact barrier Hessian where the matrix factorizes with it,
        // the projected one (14 of 44 and 18 of 49 iterations, measured) where it does not.
        assert!(0 < projected && projected < iterations, "{method}");
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
