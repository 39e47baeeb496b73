//! The built-in contact scenes of issue 30, reduced: two balls colliding in free space keep
//! their total linear momentum (and pass through each other without `[contact]`); a tube squashed flat between two plates keeps its volume and
//! a positive gap between its inner walls while they touch; two pads lift a cylinder by
//! friction. On every accepted state of each, no two surface triangles intersect.

use isochor_mesh::contact::{intersecting_triangles, ContactSurface};
use isochor_mesh::{ElementMesh, Vec3};
use isochor_scenes::resolve::{build, SceneBodies, Selections};
use isochor_scenes::{builtin, load_scene, Override, Scene};
use isochor_solvers::{Frame, Settings, Simulation};
use std::time::Instant;

/// A built-in scene reduced, with more `--set` overrides after the reduced ones.
fn reduced(name: &str, sets: &[&str]) -> Scene {
    let overrides: Vec<Override> = builtin::reduced(name)
        .unwrap()
        .iter()
        .chain(sets)
        .map(|s| Override::parse(s).unwrap())
        .collect();
    load_scene(name, None, &overrides).unwrap()
}

/// What a run leaves beside its states: the joined mesh, the bodies, the selections, the settings and the
/// force scale of the residual tolerance.
struct Ran {
    mesh: ElementMesh,
    bodies: SceneBodies,
    selections: Selections,
    settings: Settings,
    force_scale: f64,
    intersecting_steps: Vec<usize>,
}

/// Runs `scene` as `isochor run` does (initial velocities, barrier contact, friction),
/// calling `observe` with the joined mesh on every accepted step and checking it for
/// intersecting surface triangles. Prints the wall time per step.
fn run_checked(scene: &Scene, mut observe: impl FnMut(&ElementMesh, &Frame<'_>)) -> Ran {
    let resolved = build(scene).unwrap();
    let mesh = resolved.problem.mesh.clone();
    let mut sim = Simulation::new(resolved.problem, resolved.settings).unwrap();
    if let Some(v) = resolved.bodies.initial_velocities(mesh.num_nodes()) {
        sim.set_velocities(v).unwrap();
    }
    if let Some(spec) = resolved.surface_contact {
        sim.set_surface_contact(spec).unwrap();
    }
    if let Some(spec) = resolved.friction {
        sim.set_friction(spec).unwrap();
    }
    let force_scale = sim.force_scale().unwrap();
    let surface = ContactSurface::from_element_surface(&mesh.boundary().unwrap());
    let (start, mut steps, mut intersecting_steps) = (Instant::now(), 0, Vec::new());
    sim.run(resolved.stepping, |frame| {
        if !intersecting_triangles(&surface, &frame.state.positions).is_empty() {
            intersecting_steps.push(frame.index);
        }
        observe(&mesh, frame);
        steps += 1;
    })
    .unwrap_or_else(|e| panic!("{}: step {}: {}", scene.name, e.failed_step, e.error));
    eprintln!(
        "{} ({:?}, {:?}): {} tets, {steps} steps, {:.3} s per step",
        scene.name,
        scene.method,
        scene.element,
        mesh.num_elements(),
        start.elapsed().as_secs_f64() / steps as f64
    );
    Ran {
        mesh,
        bodies: resolved.bodies,
        selections: resolved.selections,
        settings: resolved.settings,
        force_scale,
        intersecting_steps,
    }
}

/// The linear momentum of `nodes` at velocities `v`.
fn momentum(masses: &[f64], v: &[Vec3], nodes: impl Iterator<Item = usize>) -> Vec3 {
    nodes.fold(Vec3::zeros(), |p, n| p + masses[n] * v[n])
}

/// Implicit Euler changes the momentum by `dt` times the sum of the step's forces. The
/// elastic, pressure and barrier forces are gradients of energies that a translation does
/// not change, so they sum to zero, and a converged step moves the total momentum by `dt`
/// times the sum of the residual's nodal vectors: at most `dt sqrt(n) tau F` in norm (`n`
/// nodes, `tau F` the bound on the residual's 2-norm). Over the run to time `t`: `t sqrt(n)
/// tau F`. The struck ball leaves with more than 30% of the momentum.
#[test]
fn colliding_balls_keep_their_momentum_and_bounce_apart() {
    for (method, element) in [
        ("mixed-p1", "tet4"),
        ("standard", "tet4"),
        ("standard", "tet10"),
    ] {
        let (m, e) = (format!("method={method}"), format!("element={element}"));
        let scene = reduced("colliding-balls", &[&m, &e]);
        let mut frames = Vec::new();
        let ran = run_checked(&scene, |_, frame| {
            let contact = frame.surface_contact.as_ref().unwrap();
            frames.push((
                frame.state.t,
                frame.state.velocities.clone(),
                contact.min_distance,
            ));
        });
        assert!(
            ran.intersecting_steps.is_empty(),
            "{method} {element}: intersecting triangles on steps {:?}",
            ran.intersecting_steps
        );
        let masses = ran
            .mesh
            .lumped_masses(&vec![scene.material.rho; ran.mesh.num_elements()]);
        let n = ran.mesh.num_nodes();
        let [a, b] = [0, 1].map(|i| ran.bodies.parts[i].clone());
        let v0 = ran.bodies.initial_velocities(n).unwrap();
        let start = momentum(&masses, &v0, 0..n);
        let per_time = (n as f64).sqrt() * ran.settings.force_tolerance * ran.force_scale;
        let mut worst: f64 = 0.0;
        for (t, v, distance) in &frames {
            let drift = (momentum(&masses, v, 0..n) - start).norm();
            assert!(
                drift <= t * per_time,
                "{method} {element}: t = {t}: momentum moved by {drift:e}, bound {:e}",
                t * per_time
            );
            assert!(*distance > 0.0, "{method} {element}: t = {t}: touching");
            worst = worst.max(drift / (t * per_time));
        }
        let (_, v, _) = frames.last().unwrap();
        let [pa, pb] = [&a, &b].map(|part| momentum(&masses, v, part.nodes()).x);
        let closest = frames.iter().map(|f| f.2).fold(f64::INFINITY, f64::min);
        eprintln!(
            "colliding-balls {method} {element}: momentum {:.6e}, drift at most {worst:.2e} of its bound, end a {pa:.6e} b {pb:.6e}, closest {closest:.3e} m",
            start.x
        );
        assert!(
            pb > 0.3 * start.x && pa < 0.7 * start.x,
            "{method} {element}: the struck ball leaves: a {pa}, b {pb}"
        );
    }
}

/// Without `[contact]` nothing pushes the struck ball: the balls pass through each other.
#[test]
fn without_contact_the_balls_pass_through_each_other() {
    let mut scene = reduced("colliding-balls", &["method=standard"]);
    scene.contact = None;
    let mut last = Vec::new();
    let ran = run_checked(&scene, |_, frame| last = frame.state.velocities.clone());
    assert!(
        !ran.intersecting_steps.is_empty(),
        "the balls overlap in flight"
    );
    let b = ran.bodies.parts[1].clone();
    assert!(
        b.nodes().all(|n| last[n].norm() < 1e-12),
        "nothing pushes b"
    );
}

/// A bad `contact.dhat` is refused, naming the key.
#[test]
fn a_bad_reach_is_refused_by_key() {
    let overrides: Vec<Override> = ["contact.dhat=-1.0"]
        .iter()
        .map(|s| Override::parse(s).unwrap())
        .collect();
    let e = load_scene("colliding-balls", None, &overrides)
        .unwrap_err()
        .to_string();
    assert!(e.contains("contact.dhat"), "{e}");
}

/// The tube squashed until its inner walls touch: on every accepted step the volume is the
/// rest volume to the constraint tolerance (`nu = 0.5`, mixed-p1: each nodal row holds its
/// volume to `tau_c` of its rest volume, and the rows sum to the whole volume) and every pair
/// of primitives within `dhat` is apart; at the end the inner wall touches itself: its two
/// sides in the symmetry plane x = 0 are closer than `dhat` and apart, and pairs are
/// within `dhat`.
#[test]
fn the_squashed_tube_keeps_its_volume_and_its_walls_apart() {
    let scene = reduced("squashed-tube", &[]);
    let dhat = scene.contact.as_ref().unwrap().dhat.unwrap();
    let mut steps = Vec::new();
    let ran = run_checked(&scene, |mesh, frame| {
        let volume: f64 = mesh.volumes_at(&frame.state.positions).iter().sum();
        let contact = frame.surface_contact.as_ref().unwrap();
        steps.push((
            volume,
            contact.min_distance,
            contact.pairs_within_dhat,
            frame.state.positions.clone(),
        ));
    });
    assert!(
        ran.intersecting_steps.is_empty(),
        "intersecting triangles on steps {:?}",
        ran.intersecting_steps
    );
    let rest: f64 = ran.mesh.volumes_at(ran.mesh.nodes()).iter().sum();
    let tolerance = ran.settings.constraint_tolerance;
    for (k, (volume, distance, _, _)) in steps.iter().enumerate() {
        let change = volume / rest - 1.0;
        assert!(
            change.abs() <= tolerance,
            "step {k}: volume change {change:e}"
        );
        assert!(*distance > 0.0, "step {k}: the walls touch");
    }
    // The inner wall's gap in the symmetry plane x = 0, where it closes.
    let inner = ran.selections.nodes("inner_top").unwrap();
    let inner_bottom = ran.selections.nodes("inner_bottom").unwrap();
    let (_, distance, pairs, x) = steps.last().unwrap();
    let gap = inner.iter().map(|&n| x[n].y).fold(f64::INFINITY, f64::min)
        - inner_bottom
            .iter()
            .map(|&n| x[n].y)
            .fold(f64::NEG_INFINITY, f64::max);
    eprintln!(
        "squashed-tube: {} steps, largest volume change {:.2e}, the inner walls {gap:.3e} m apart at x = 0, {pairs} pairs within dhat, closest {distance:.3e} m",
        steps.len(),
        steps
            .iter()
            .map(|s| (s.0 / rest - 1.0).abs())
            .fold(0.0, f64::max)
    );
    assert!(*pairs > 0, "pairs within dhat at the end");
    assert!(
        gap > 0.0 && gap < dhat && *distance < dhat,
        "the inner walls touch at the end: {gap:e} m apart, dhat {dhat:e}"
    );
}

/// The pads squeeze the cylinder, then lift it by `L` = 10 mm (their backs are driven). Held
/// by friction (none against the ground), the cylinder rises with them, less what the pads'
/// shear and the smoothed static friction let it lag (a creep below `epsv` per step); with
/// no friction between pads and cylinder it stays on the ground (the pads' barrier, normal to
/// their faces as they tilt, lifts it by less than 5% of their rise).
#[test]
fn the_pads_lift_the_cylinder_by_friction() {
    for friction in [0.8, 0.0] {
        let f = format!("contact.friction={friction}");
        let scene = reduced("grasp", &[&f]);
        let mut path = Vec::new();
        let ran = run_checked(&scene, |_, frame| {
            path.push((frame.state.t, frame.state.positions.clone()));
        });
        assert!(
            ran.intersecting_steps.is_empty(),
            "friction {friction}: intersecting triangles on steps {:?}",
            ran.intersecting_steps
        );
        let mean_z = |name: &str, x: &[Vec3]| {
            let nodes = ran.selections.nodes(name).unwrap();
            nodes
                .iter()
                .map(|&n| x[n].z - ran.mesh.nodes()[n].z)
                .sum::<f64>()
                / nodes.len() as f64
        };
        let (_, x) = path.last().unwrap();
        let (pads, object) = (mean_z("left_back", x), mean_z("object", x));
        eprintln!(
            "grasp friction {friction}: the pads rose {pads:.4e} m, the cylinder {object:.4e} m"
        );
        assert!(
            (pads - 0.01).abs() < 1e-12,
            "the pads' backs are driven: {pads}"
        );
        if friction > 0.0 {
            assert!(
                (object - pads).abs() < 0.05 * pads,
                "friction {friction}: {object} against {pads}"
            );
        } else {
            assert!(
                object < 0.05 * pads,
                "without friction the cylinder stays down: {object}"
            );
        }
    }
}
