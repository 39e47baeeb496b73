//! The pneumatic actuators of Francu et al. 2021, Fig. 6 and Table 1 (`cushion`, `bubble`,
//! `finger`; shapes ours), in their reduced versions ([`builtin::reduced`]) at the paper's
//! nu = 0.499: each inflates (its chamber's volume grows, the bubble's membrane rises, the
//! finger bends towards its strain-limiting base), and `mixed-p1` inflates more than
//! `standard`, whose nearly incompressible linear tets lock. The pressure is a follower load
//! on the chamber's walls, which point into the cavity: a sign error would shrink the
//! chambers and fail every assertion here (the absolute values are pinned in
//! `validation/tests/reference.rs`).

use isochor_mesh::element::TetElement;
use isochor_mesh::generate;
use isochor_scenes::format::SelectionSpec;
use isochor_scenes::resolve::mesh_with_groups;
use isochor_scenes::resolve::Selections;
use isochor_scenes::{builtin, load_scene, run_scene, Override, RunOptions, RunResult};

/// Runs a variant of a built-in actuator in its reduced version and checks it converged.
fn run(name: &str, variant: &str) -> RunResult {
    let sets: Vec<Override> = builtin::reduced(name)
        .unwrap_or_else(|| panic!("no reduced version of {name}"))
        .iter()
        .map(|s| Override::parse(s).unwrap())
        .collect();
    let scene = load_scene(name, Some(variant), &sets).unwrap_or_else(|e| panic!("{name}: {e}"));
    let (r, _) =
        run_scene(&scene, &RunOptions::default()).unwrap_or_else(|e| panic!("{name}: {e}"));
    assert!(
        r.converged,
        "{name} [{variant}] failed at step {:?}: {:?}",
        r.failed_step, r.error
    );
    r
}

/// The two methods' runs of actuator `name`, with its chamber volume ratio and its
/// `displacement` probe for each, printed as a table row.
fn inflate(name: &str, displacement: &str) -> [(f64, f64); 2] {
    ["standard", "mixed-p1"].map(|variant| {
        let r = run(name, variant);
        let (ratio, u) = (r.probes["chamber_volume_ratio"], r.probes[displacement]);
        eprintln!(
            "{name} [{variant}] {} tets: chamber volume ratio {ratio:.4}, {displacement} {:.2} mm, {} Newton iterations, {:.2} s",
            r.tets,
            1e3 * u,
            r.newton_iterations,
            r.wall_time_s
        );
        (ratio, u)
    })
}

/// Asserts that both methods inflate the chamber and move the probe the right way, and
/// that the mixed method does both more than the locking standard one.
fn assert_inflates(name: &str, displacement: &str) {
    let [(ratio_standard, u_standard), (ratio_mixed, u_mixed)] = inflate(name, displacement);
    assert!(ratio_standard > 1.0 && u_standard > 0.0, "{name} standard");
    assert!(
        ratio_mixed > ratio_standard,
        "{name}: {ratio_mixed} vs {ratio_standard}"
    );
    assert!(u_mixed > u_standard, "{name}: {u_mixed} vs {u_standard}");
}

/// The cushion's chamber grows and its top rises, more with `mixed-p1`.
#[test]
fn cushion_inflates_and_mixed_inflates_more() {
    assert_inflates("cushion", "top_rise");
}

/// The bubble's chamber grows and its membrane's apex rises, more with `mixed-p1`.
#[test]
fn bubble_bulges_and_mixed_bulges_more() {
    assert_inflates("bubble", "apex_rise");
}

/// The finger's chambers grow and its tip moves towards the strain-limiting base (-z), more
/// with `mixed-p1`.
#[test]
fn finger_bends_towards_its_base_and_mixed_bends_more() {
    assert_inflates("finger", "tip_deflection");
}

/// A `physical` selection resolves against a generator's groups as against a Gmsh file's:
/// the cushion's `chamber` selects exactly the generator's chamber faces, the spine arm's
/// `clamped` group the faces and vertices its plane x = 0 selects; a group the generator
/// does not name is an error listing those it does.
#[test]
fn generated_groups_resolve_like_a_files() {
    let scene = load_scene("cushion", None, &[]).unwrap();
    let mesh = mesh_with_groups(scene.mesh.as_ref().unwrap(), TetElement::Tet4, true).unwrap();
    let s = Selections::new(&mesh, &scene.selections).unwrap();
    let (_, groups) = generate::cushion(2).unwrap();
    assert_eq!(
        s.faces("chamber").unwrap(),
        groups.get("chamber").unwrap().faces
    );

    let spine = load_scene("spine-arm", None, &[]).unwrap();
    let mut specs = spine.selections.clone();
    let named = |key: &str| SelectionSpec {
        physical: Some(key.to_string()),
        ..Default::default()
    };
    specs.insert("named".into(), named("clamped"));
    specs.insert("unknown".into(), named("chamber"));
    let mesh = mesh_with_groups(spine.mesh.as_ref().unwrap(), TetElement::Tet10, true).unwrap();
    let s = Selections::new(&mesh, &specs).unwrap();
    let sorted = |f: &[[usize; 3]]| {
        let mut f = f.to_vec();
        f.sort_unstable();
        f
    };
    assert_eq!(
        sorted(s.faces("named").unwrap()),
        sorted(s.faces("clamped").unwrap())
    );
    assert_eq!(s.nodes("named").unwrap(), s.nodes("clamped").unwrap());
    let e = s.faces("unknown").unwrap_err().to_string();
    assert!(e.contains("groups: clamped, free_end"), "{e}");
}
