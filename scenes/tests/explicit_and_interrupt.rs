//! An explicit mesh of 10-node tets with named groups (the mesh `isochor.Problem` builds in
//! Python), and a run stopped between steps by its step hook.

use isochor_scenes::commands::run::StepHook;
use isochor_scenes::{load_scene, run_scene, Override, RunOptions, Scene, SceneError, SceneSource};
use std::ops::ControlFlow;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::Arc;

/// One 10-node tet (corners, then the mid-edge nodes in Gmsh's order: edges 01, 12, 20, 03,
/// 23, 13) with the groups `groups`, its base held and its apex pulled up.
fn one_tet(groups: &str) -> Result<Scene, SceneError> {
    let corners = [
        [0.0, 0.0, 0.0],
        [1.0, 0.0, 0.0],
        [0.0, 1.0, 0.0],
        [0.0, 0.0, 1.0],
    ];
    let edges = [(0, 1), (1, 2), (2, 0), (0, 3), (2, 3), (1, 3)];
    let mid = edges.map(|(a, b): (usize, usize)| {
        let (p, q) = (corners[a], corners[b]);
        [
            (p[0] + q[0]) / 2.0,
            (p[1] + q[1]) / 2.0,
            (p[2] + q[2]) / 2.0,
        ]
    });
    let positions: Vec<String> = corners
        .iter()
        .chain(&mid)
        .map(|p| format!("[{}, {}, {}]", p[0], p[1], p[2]))
        .collect();
    let text = format!(
        r#"name = "one-tet10"
method = "standard"
element = "tet10"

[mesh]
generator = "explicit"
positions = [{}]
tets = [[0, 1, 2, 3, 4, 5, 6, 7, 8, 9]]
{groups}

[material]
young = 1e3
nu = 0.3

[selections.base]
physical = "base"

[selections.apex]
vertices = [3]

[[dirichlet]]
selection = "base"

[[dirichlet]]
selection = "apex"
motion = {{ translate = [0.0, 0.0, 0.1] }}

[stepping]
mode = "quasi-static"
steps = 1
"#,
        positions.join(", ")
    );
    SceneSource {
        text,
        origin: "one-tet10".into(),
        base_dir: std::env::temp_dir(),
    }
    .load(None, &[])
}

#[test]
fn an_explicit_10_node_mesh_runs_on_its_groups() {
    let scene = one_tet("[mesh.groups.base]\nfaces = [[0, 2, 1]]").unwrap();
    let (result, _) = run_scene(&scene, &RunOptions::default()).unwrap();
    assert!(result.converged, "{:?}", result.error);
    assert_eq!((result.nodes, result.vertices, result.tets), (10, 4, 1));
    assert!(result.element == "tet10");
}

#[test]
fn explicit_groups_and_numbering_are_checked() {
    let error =
        |groups: &str| match one_tet(groups).and_then(|s| run_scene(&s, &RunOptions::default())) {
            Err(e) => e.to_string(),
            Ok(_) => panic!("{groups} was accepted"),
        };
    let both = error("[mesh.groups.base]\nfaces = [[0, 2, 1]]\ntets = [0]");
    assert!(
        both.contains("mesh.groups.base") && both.contains("exactly one"),
        "{both}"
    );
    let mid = error("[mesh.groups.base]\nfaces = [[0, 2, 4]]");
    assert!(
        mid.contains("mesh.groups.base.faces") && mid.contains("node 4 is not a tet's corner"),
        "{mid}"
    );
    let tet = error("[mesh.groups.base]\ntets = [1]");
    assert!(
        tet.contains("mesh.groups.base.tets") && tet.contains("tet 1 is out of range"),
        "{tet}"
    );
}

#[test]
fn a_step_hook_stops_the_run_after_its_step() {
    let sets = ["res=1", "steps=3"].map(|s| Override::parse(s).unwrap());
    let scene = load_scene("cantilever", None, &sets).unwrap();
    let calls = Arc::new(AtomicUsize::new(0));
    let seen = calls.clone();
    let mut options = RunOptions::in_memory(None, &sets, false);
    options.on_step = Some(StepHook(Arc::new(move |frame| {
        seen.fetch_add(1, Ordering::SeqCst);
        if frame.index == 1 {
            ControlFlow::Break(())
        } else {
            ControlFlow::Continue(())
        }
    })));
    let (result, _) = run_scene(&scene, &options).unwrap();
    assert_eq!(calls.load(Ordering::SeqCst), 1);
    assert!(!result.converged);
    assert_eq!(result.error.as_deref(), Some("interrupted after step 1"));
    assert_eq!((result.failed_step, result.steps), (None, 1));
    assert!(result.probes["tip_deflection"] > 0.0);
}
