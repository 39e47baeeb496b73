//! Several bodies in one scene (`[[bodies]]`): each body of a joined scene behaves exactly as
//! it does alone, placements move the mesh before anything else, selections restrict to a
//! body, frames carry the `body` field, and what cannot be meant is refused by key.

use isochor_mesh::io::{read_vtu_file, FieldValues};
use isochor_scenes::resolve::build;
use isochor_scenes::{run_scene, RunOptions, Scene, SceneError};
use std::path::PathBuf;

/// A cantilever bar `0.1 x 0.02 x 0.02` m clamped at `x = 0`, sagging under gravity; `young`
/// its stiffness. `mesh` is the scene's `[mesh]` table body (or empty), `bodies` more TOML.
fn scene(method: &str, element: &str, mesh: &str, bodies: &str, extra: &str) -> String {
    format!(
        r#"name = "bars"
method = "{method}"
element = "{element}"
{mesh}

[material]
young = 1e5
nu = 0.45
rho = 1000.0

{bodies}

[loads]
gravity = [0.0, 0.0, -9.8]

[stepping]
mode = "quasi-static"
steps = 2

{extra}
"#
    )
}

const BAR: &str = r#"generator = "box"
min = [0.0, 0.0, 0.0]
max = [0.1, 0.02, 0.02]
res = 1
cells = [5, 1, 1]"#;

/// The clamp and tip of the bar at `y0` (restricted to `body` if given), its sag probe.
fn bar_conditions(tag: &str, y0: f64, body: Option<&str>) -> String {
    let body = body.map_or(String::new(), |b| format!("body = \"{b}\"\n"));
    format!(
        r#"
[selections.clamp_{tag}]
plane = {{ point = [0.0, 0.0, 0.0], normal = [1.0, 0.0, 0.0] }}
box = {{ min = [-1.0, {y0}, -1.0], max = [1.0, {y1}, 1.0] }}
{body}
[selections.tip_{tag}]
plane = {{ point = [0.1, 0.0, 0.0], normal = [1.0, 0.0, 0.0] }}
box = {{ min = [-1.0, {y0}, -1.0], max = [1.0, {y1}, 1.0] }}
{body}
[[dirichlet]]
selection = "clamp_{tag}"

[probes.sag_{tag}]
kind = "displacement"
selection = "tip_{tag}"
component = "z"
scale = -1.0
"#,
        y1 = y0 + 0.02
    )
}

fn parse(text: &str) -> Result<Scene, SceneError> {
    Scene::from_toml_str(text, "test scene")
}

fn run(scene: &Scene) -> std::collections::BTreeMap<String, f64> {
    let (result, _) = run_scene(scene, &RunOptions::default()).unwrap();
    assert!(result.converged, "{:?}", result.error);
    result.probes
}

fn close(a: f64, b: f64) -> bool {
    (a - b).abs() <= 1e-9 * a.abs().max(b.abs())
}

/// A bar placed at `y = 0.05` with twice the stiffness, as a `[[bodies]]` entry.
fn second_bar(name: &str) -> String {
    format!(
        r#"[[bodies]]
name = "{name}"
mesh = {{ {} }}
material = {{ young = 2e5 }}
place = {{ translate = [0.0, 0.05, 0.0] }}
"#,
        BAR.replace('\n', ", ")
    )
}

#[test]
fn each_body_of_a_joined_scene_sags_as_it_does_alone() {
    for (method, element) in [("mixed-p1", "tet4"), ("standard", "tet10")] {
        let own = format!("[mesh]\n{BAR}");
        let stiff_alone = BAR
            .replace("[0.0, 0.0, 0.0]", "[0.0, 0.05, 0.0]")
            .replace("[0.1, 0.02, 0.02]", "[0.1, 0.07, 0.02]");
        let alone_a = parse(&scene(
            method,
            element,
            &own,
            "",
            &bar_conditions("a", 0.0, None),
        ))
        .unwrap();
        let alone_b = parse(
            &scene(
                method,
                element,
                &format!("[mesh]\n{stiff_alone}"),
                "",
                &bar_conditions("b", 0.05, None),
            )
            .replace("young = 1e5", "young = 2e5"),
        )
        .unwrap();
        let joined = parse(&scene(
            method,
            element,
            &own,
            &second_bar("stiff"),
            &(bar_conditions("a", 0.0, Some("body")) + &bar_conditions("b", 0.05, Some("stiff"))),
        ))
        .unwrap();
        let (a, b, both) = (run(&alone_a), run(&alone_b), run(&joined));
        assert!(a["sag_a"] > 1e-5, "the bar sags: {}", a["sag_a"]);
        assert!(
            close(both["sag_a"], a["sag_a"]),
            "{method} {element}: {} vs {}",
            both["sag_a"],
            a["sag_a"]
        );
        assert!(
            close(both["sag_b"], b["sag_b"]),
            "{method} {element}: {} vs {}",
            both["sag_b"],
            b["sag_b"]
        );
        assert!(b["sag_b"] < 0.6 * a["sag_a"], "the stiffer bar sags less");
    }
}

#[test]
fn a_scene_of_bodies_alone_equals_the_scene_with_mesh() {
    let with_mesh = parse(&scene(
        "mixed-p1",
        "tet4",
        &format!("[mesh]\n{BAR}"),
        "",
        &bar_conditions("a", 0.0, None),
    ))
    .unwrap();
    let body = format!(
        "[[bodies]]\nname = \"bar\"\nmesh = {{ {} }}\n",
        BAR.replace('\n', ", ")
    );
    let bodies_only = parse(&scene(
        "mixed-p1",
        "tet4",
        "",
        &body,
        &bar_conditions("a", 0.0, Some("bar")),
    ))
    .unwrap();
    assert_eq!(run(&with_mesh)["sag_a"], run(&bodies_only)["sag_a"]);
}

#[test]
fn a_placement_rotates_then_translates_the_rest_mesh() {
    let body = format!(
        r#"[[bodies]]
name = "turned"
mesh = {{ {} }}
place = {{ rotate = {{ axis = [0.0, 0.0, 1.0], degrees = 90.0 }}, translate = [1.0, 0.0, 0.0] }}
"#,
        BAR.replace('\n', ", ")
    );
    let extra = r#"
[selections.all]
all = true
[[dirichlet]]
selection = "all"
"#;
    let plain = parse(&scene(
        "standard",
        "tet4",
        &format!("[mesh]\n{BAR}"),
        "",
        extra,
    ))
    .unwrap();
    let placed = parse(&scene("standard", "tet4", "", &body, extra)).unwrap();
    let (plain, placed) = (build(&plain).unwrap(), build(&placed).unwrap());
    let (x, y) = (plain.problem.mesh.nodes(), placed.problem.mesh.nodes());
    assert_eq!(x.len(), y.len());
    for (p, q) in x.iter().zip(y) {
        // (x, y, z) turned a quarter about z is (-y, x, z); then moved by 1 along x.
        assert!((q.x - (1.0 - p.y)).abs() < 1e-15 && (q.y - p.x).abs() < 1e-15 && q.z == p.z);
    }
    assert!((placed.problem.mesh.rest_volume() - 0.1 * 0.02 * 0.02).abs() < 1e-15);
}

#[test]
fn frames_carry_the_body_of_each_tet() {
    let text = scene(
        "mixed-p1",
        "tet4",
        &format!("[mesh]\n{BAR}"),
        &second_bar("stiff"),
        &(bar_conditions("a", 0.0, Some("body")) + &bar_conditions("b", 0.05, Some("stiff"))),
    );
    let scene = parse(&text).unwrap();
    let out = std::env::temp_dir().join(format!("isochor-bodies-frames-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&out);
    let options = RunOptions {
        out: Some(out.clone()),
        ..RunOptions::default()
    };
    let (result, _) = run_scene(&scene, &options).unwrap();
    assert!(result.converged);
    let frame = read_vtu_file(PathBuf::from(&out).join("frame_00002.vtu")).unwrap();
    let body = frame
        .cell_data
        .iter()
        .find(|f| f.name == "body")
        .expect("a body field");
    let FieldValues::Int(ids) = &body.values else {
        panic!("body is {:?}", body.values)
    };
    let tets = ids.len() / 2;
    assert!(ids[..tets].iter().all(|&b| b == 0) && ids[tets..].iter().all(|&b| b == 1));
    let region = frame
        .cell_data
        .iter()
        .find(|f| f.name == "region")
        .expect("a region field");
    assert!(matches!(&region.values, FieldValues::Int(r) if r[tets..].iter().all(|&r| r == 1)));
    let _ = std::fs::remove_dir_all(&out);
}

/// The error of a scene text, at resolution if it parses.
fn refused(text: &str) -> String {
    match parse(text) {
        Err(e) => e.to_string(),
        Ok(scene) => build(&scene).map(|_| ()).unwrap_err().to_string(),
    }
}

#[test]
fn what_cannot_be_meant_is_refused_by_key() {
    let own = format!("[mesh]\n{BAR}");
    let conditions =
        bar_conditions("a", 0.0, Some("body")) + &bar_conditions("b", 0.05, Some("stiff"));
    // Overlapping bodies: the second bar in the first.
    let overlap = second_bar("stiff").replace("[0.0, 0.05, 0.0]", "[0.03, 0.005, 0.005]");
    let e = refused(&scene("mixed-p1", "tet4", &own, &overlap, &conditions));
    assert!(
        e.contains("bodies 'body' and 'stiff' overlap") && e.contains("surface nodes"),
        "{e}"
    );
    // Two bodies of one name.
    let e = refused(&scene(
        "mixed-p1",
        "tet4",
        &own,
        &second_bar("body"),
        &conditions,
    ));
    assert!(
        e.contains("bodies.0.name") && e.contains("names two bodies"),
        "{e}"
    );
    // A selection of a body that does not exist.
    let e = refused(&scene(
        "mixed-p1",
        "tet4",
        &own,
        &second_bar("other"),
        &conditions,
    ));
    assert!(
        e.contains("selections.clamp_b.body") && e.contains("no body named 'stiff'"),
        "{e}"
    );
    // A body free in quasi-static stepping.
    let e = refused(&scene(
        "mixed-p1",
        "tet4",
        &own,
        &second_bar("stiff"),
        &bar_conditions("a", 0.0, Some("body")),
    ));
    assert!(
        e.contains("body 'stiff'") && e.contains("rigid motions"),
        "{e}"
    );
    // A velocity without dynamics; no body at all.
    let moving = second_bar("stiff") + "velocity = [1.0, 0.0, 0.0]\n";
    let e = refused(&scene("mixed-p1", "tet4", &own, &moving, &conditions));
    assert!(e.contains("bodies.0.velocity"), "{e}");
    let e = refused(&scene("mixed-p1", "tet4", "", "", ""));
    assert!(e.contains("[[bodies]]"), "{e}");
    // A bad mesh key of a body names the body.
    let coarse = second_bar("stiff").replace("res = 1", "res = 0");
    let e = refused(&scene("mixed-p1", "tet4", &own, &coarse, &conditions));
    assert!(e.contains("bodies.0.mesh.res"), "{e}");
}

#[test]
fn a_free_body_keeps_its_initial_velocity() {
    let body = format!(
        "[[bodies]]\nname = \"flying\"\nmesh = {{ {} }}\nvelocity = [0.5, 0.0, -0.25]\n",
        BAR.replace('\n', ", ")
    );
    let text = scene("mixed-p1", "tet4", "", &body, "")
        .replace("gravity = [0.0, 0.0, -9.8]", "")
        .replace(
            "mode = \"quasi-static\"\nsteps = 2",
            "mode = \"dynamic\"\nframes = 4\ndt = 0.01",
        )
        + r#"
[selections.all]
all = true

[probes.dx]
kind = "displacement"
selection = "all"
component = "x"

[probes.dz]
kind = "displacement"
selection = "all"
component = "z"
"#;
    let p = run(&parse(&text).unwrap());
    assert!(close(p["dx"], 0.5 * 0.04), "dx = {}", p["dx"]);
    assert!(close(p["dz"], -0.25 * 0.04), "dz = {}", p["dz"]);
}
