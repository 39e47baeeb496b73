//! Meshed rigid obstacles (`[[obstacles]] shape = "mesh"`): a plate given as an OBJ square of
//! two triangles holds a pressed block where the analytic half-space holds it (to within the
//! barrier's reach), and a plate moving into a block never leaves an intersection between
//! the block's surface and the plate's triangles on any accepted state; a scene file's run
//! writes the contact columns, the `min-distance` probe and the plate's surface per frame.

use crate::common::scratch;
use isochor_mesh::contact::{intersecting_triangles, ContactSurface};
use isochor_scenes::resolve::build;
use isochor_scenes::Scene;
use isochor_solvers::Simulation;
use std::path::Path;

/// The barrier's reach of these tests (m).
const DHAT: f64 = 2e-5;

/// A 1 cm cube of soft rubber, its bottom `gap` above `z = 0` and its top clamped and moved
/// down by `press`, above `obstacle` (an `[[obstacles]]` table).
fn block(press: f64, gap: f64, obstacle: &str) -> Scene {
    let text = format!(
        r#"name = "block"
method = "mixed-p0"

[mesh]
generator = "box"
min = [0.0, 0.0, {gap}]
max = [0.01, 0.01, {top}]
res = 2

[material]
young = 1e5
nu = 0.45

[selections.top]
plane = {{ point = [0.0, 0.0, {top}], normal = [0.0, 0.0, 1.0] }}

[[dirichlet]]
selection = "top"
motion = {{ translate = [0.0, 0.0, {down}] }}

{obstacle}

[stepping]
mode = "quasi-static"
steps = 4
"#,
        top = gap + 0.01,
        down = -press,
    );
    Scene::from_toml_str(&text, "block").unwrap()
}

/// A square plate `[-0.01, 0.02]^2` at `z = 0` as one quad of an OBJ file.
fn plate_file(dir: &Path) -> String {
    let path = dir.join("plate.obj");
    std::fs::write(
        &path,
        "v -0.01 -0.01 0\nv 0.02 -0.01 0\nv 0.02 0.02 0\nv -0.01 0.02 0\nf 1 2 3 4\n",
    )
    .unwrap();
    path.display().to_string()
}

/// Runs `scene`; the final block centroid's z and the intersecting pairs (block surface
/// against itself and the obstacles' triangles) summed over the accepted states.
fn run(scene: &Scene) -> (f64, usize, usize) {
    let resolved = build(scene).unwrap();
    let mesh = resolved.problem.mesh.clone();
    let n = mesh.num_nodes();
    let obstacles = resolved.mesh_obstacles.clone();
    let mut sim = Simulation::new(resolved.problem, resolved.settings).unwrap();
    if let Some(spec) = resolved.surface_contact {
        sim.set_surface_contact(spec).unwrap();
    }
    if !obstacles.is_empty() {
        sim.set_mesh_obstacles(obstacles.clone()).unwrap();
    }
    // The block's triangles and the obstacles' after them, as the contact term numbers them.
    let mut triangles = ContactSurface::from_element_surface(&mesh.boundary().unwrap())
        .triangles()
        .to_vec();
    let mut offset = n;
    for o in &obstacles {
        triangles.extend(o.triangles.iter().map(|t| t.map(|v| v + offset)));
        offset += o.vertices.len();
    }
    let surface = ContactSurface::from_triangles(triangles);
    let (mut intersections, mut frames) = (0, 0);
    let summary = sim
        .run(resolved.stepping, |frame| {
            let mut x = frame.state.positions.clone();
            assert_eq!(frame.mesh_obstacles.len(), obstacles.len());
            for placed in &frame.mesh_obstacles {
                x.extend(placed);
            }
            intersections += intersecting_triangles(&surface, &x).len();
            frames += 1;
        })
        .unwrap();
    let x = &summary.final_state.positions;
    let z = x.iter().map(|p| p.z).sum::<f64>() / n as f64;
    (z, intersections, frames)
}

#[test]
fn a_meshed_plate_holds_the_block_where_the_half_space_does() {
    let dir = scratch("mesh-obstacle-rest");
    let plate = plate_file(&dir);
    let (press, gap) = (1e-3, 2e-4);
    let (half_space, _, _) = run(&block(press, gap, "[[obstacles]]\nshape = \"half-space\""));
    let meshed =
        format!("[contact]\ndhat = {DHAT}\n\n[[obstacles]]\nshape = \"mesh\"\npath = '{plate}'");
    let (mesh, intersections, _) = run(&block(press, gap, &meshed));
    eprintln!("centroid z: half-space {half_space:.6e}, meshed plate {mesh:.6e}, dhat {DHAT:e}");
    assert_eq!(intersections, 0);
    assert!(
        (mesh - half_space).abs() <= DHAT,
        "centroid z {mesh} against the half-space's {half_space} (dhat {DHAT})"
    );
    // The barrier keeps a positive gap: the plate holds the block slightly higher.
    assert!(mesh > half_space, "{mesh} above {half_space}");
}

#[test]
fn a_moving_plate_presses_the_block_without_crossing_it() {
    let dir = scratch("mesh-obstacle-moving");
    let plate = plate_file(&dir);
    let gap = 2e-4;
    let obstacle = format!(
        "[contact]\ndhat = {DHAT}\n\n[[obstacles]]\nshape = \"mesh\"\npath = '{plate}'\ntranslate = [0.0, 0.0, {}]",
        gap + 3e-4
    );
    let (z, intersections, frames) = run(&block(0.0, gap, &obstacle));
    assert_eq!(intersections, 0, "no triangle pair intersects");
    // Once the plate touches, a step may move it by less than the block's gap to it: the
    // adaptive stepping cuts the four steps into more.
    eprintln!("moving plate: {frames} accepted steps for 4 asked");
    assert!(frames > 4, "{frames} accepted steps");
    // The plate pushed the bottom up by about 0.3 mm against the clamped top.
    let rest = gap + 0.005;
    assert!(z > rest + 1e-4, "centroid z {z} rose from {rest}");
}

#[test]
fn a_plate_through_the_block_at_the_start_is_refused() {
    let dir = scratch("mesh-obstacle-inside");
    let plate = plate_file(&dir);
    let obstacle = format!(
        "[[obstacles]]\nshape = \"mesh\"\npath = '{plate}'\nplace = {{ translate = [0.0, 0.0, 0.005] }}"
    );
    let resolved = build(&block(0.0, 2e-4, &obstacle)).unwrap();
    let mut sim = Simulation::new(resolved.problem, resolved.settings).unwrap();
    sim.set_surface_contact(resolved.surface_contact.unwrap())
        .unwrap();
    let e = sim
        .set_mesh_obstacles(resolved.mesh_obstacles)
        .unwrap_err()
        .to_string();
    assert!(e.contains("obstacle0") && e.contains("intersects"), "{e}");
}

#[test]
fn a_scene_file_runs_with_its_plate_and_writes_the_contact_columns() {
    let dir = scratch("mesh-obstacle-cli");
    plate_file(&dir);
    let obstacle = format!(
        "[contact]\ndhat = {DHAT}\n\n[[obstacles]]\nshape = \"mesh\"\nname = \"plate\"\npath = \"plate.obj\"\n\n[probes.gap]\nkind = \"min-distance\""
    );
    let text = toml::to_string(&block(1e-3, 2e-4, &obstacle)).unwrap();
    let scene = dir.join("block.toml");
    std::fs::write(&scene, text).unwrap();
    let out = dir.join("out");
    let o = crate::common::isochor(&[
        "run",
        scene.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", crate::common::stderr(&o));
    let steps = std::fs::read_to_string(out.join("steps.csv")).unwrap();
    let header: Vec<&str> = steps.lines().next().unwrap().split(',').collect();
    let last: Vec<&str> = steps.lines().last().unwrap().split(',').collect();
    let column = |name: &str| -> f64 {
        let i = header
            .iter()
            .position(|h| *h == name)
            .unwrap_or_else(|| panic!("{name}"));
        last[i].parse().unwrap()
    };
    assert!(column("contact_pairs") > 0.0);
    // The plate carries the whole load: its force is the total, pointing up.
    let (plate, total) = (column("contact_force_plate_z"), column("contact_force_z"));
    assert!(
        plate > 0.0 && plate == total,
        "plate {plate}, total {total}"
    );
    let summary: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap()).unwrap();
    let gap = summary["probes"]["gap"].as_f64().unwrap();
    assert!(gap > 0.0 && gap < DHAT, "min-distance {gap}");
    // The plate's surface beside every frame, as part 1 of the frame's time.
    let pvd = std::fs::read_to_string(out.join("frame.pvd")).unwrap();
    assert!(
        pvd.contains(r#"part="1" file="frame_00000_plate.vtp""#),
        "{pvd}"
    );
    let rest = std::fs::read_to_string(out.join("frame_00000_plate.vtp")).unwrap();
    assert!(
        rest.contains(r#"NumberOfPoints="4" NumberOfPolys="2""#),
        "{rest}"
    );
}

#[test]
fn obstacle_names_are_plain_and_unique() {
    let with = |names: [&str; 2]| {
        let obstacles: String = names
            .iter()
            .map(|n| {
                format!("[[obstacles]]\nshape = \"mesh\"\npath = \"plate.obj\"\nname = \"{n}\"\n\n")
            })
            .collect();
        let text = toml::to_string(&block(0.0, 2e-4, "")).unwrap() + &obstacles;
        Scene::from_toml_str(&text, "block")
            .map(|_| ())
            .unwrap_err()
            .to_string()
    };
    let e = with(["a,b", "c"]);
    assert!(e.contains("obstacles.0.name") && e.contains("a,b"), "{e}");
    let e = with(["plate", "plate"]);
    assert!(
        e.contains("obstacles.1.name") && e.contains("earlier"),
        "{e}"
    );
}
