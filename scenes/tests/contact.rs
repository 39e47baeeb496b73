//! The contact scenes: the resting block carries its weight, the coarse ball lands (and the
//! zonal method keeps its volume through the impact), run in reduced versions.

use isochor_scenes::{load_scene, run_scene, Override, RunOptions};

fn run(name: &str, variant: Option<&str>, sets: &[&str]) -> isochor_scenes::RunResult {
    let sets: Vec<Override> = sets.iter().map(|s| Override::parse(s).unwrap()).collect();
    let scene = load_scene(name, variant, &sets).unwrap();
    let (result, _) = run_scene(&scene, &RunOptions::default()).unwrap();
    assert!(result.converged, "{name} {variant:?}: {:?}", result.error);
    result
}

#[test]
fn resting_block_carries_its_weight() {
    for variant in ["standard", "mixed-p1", "zonal"] {
        let result = run("resting-block", Some(variant), &[]);
        let weight = 1000.0 * 9.8 * 0.1f64.powi(3);
        let force = result.probes["contact_force"];
        assert!((force - weight).abs() < 1e-6 * weight, "{variant}: {force}");
        assert!(result.probes["max_penetration"] <= 1e-6 * 0.1 * 3f64.sqrt());
        assert_eq!(result.probes["first_contact_step"], 1.0);
        let last = result.history.last().unwrap();
        assert_eq!(
            last.contact.active_vertices, 16,
            "{variant}: the bottom face"
        );
    }
}

#[test]
fn coarse_ball_lands_and_zonal_keeps_its_volume() {
    let sets = ["res=2", "frames=30", "mesh.center=[0.0, 0.0, 0.101]"];
    let zonal = run("ball-drop-coarse", Some("zonal"), &sets);
    let first = zonal.probes["first_contact_frame"];
    assert!(
        first > 1.0 && first < 30.0,
        "first contact at frame {first}"
    );
    assert!(zonal.probes["max_penetration"] <= 1e-6 * 0.2 * 3f64.sqrt());
    assert!(zonal.probes["max_contact_force"] > 0.0);
    for probe in ["min_volume_ratio", "max_volume_ratio"] {
        let ratio = zonal.probes[probe];
        assert!((ratio - 1.0).abs() <= 1e-8, "zonal {probe} = {ratio}");
    }
    let standard = run("ball-drop-coarse", Some("standard-0.45"), &sets);
    assert_eq!(standard.probes["first_contact_frame"], first);
    assert!(standard.probes["min_volume_ratio"] < 1.0 - 1e-6);
}

/// The fine ball of Fig. 10 of Sheen et al. (63,888 tets, 400 frames of 1 ms) with the zonal
/// method: long (`cargo test --release -p isochor-scenes --test scenes -- --ignored contact::`).
/// Prints the figures of Table 1 (time and Newton iterations per frame) and the volume
/// extremes.
#[test]
#[ignore]
fn fine_ball_drop_keeps_its_volume() {
    let result = run("ball-drop", Some("zonal"), &[]);
    let frames = result.steps as f64;
    eprintln!(
        "ball-drop zonal: {} tets, {:.2} s and {:.2} Newton iterations per frame, volume ratio {} to {}, first contact at frame {}, max penetration {:e} m",
        result.tets,
        result.wall_time_s / frames,
        result.newton_iterations as f64 / frames,
        result.probes["min_volume_ratio"],
        result.probes["max_volume_ratio"],
        result.probes["first_contact_frame"],
        result.probes["max_penetration"],
    );
    assert_eq!(result.tets, 63_888);
    for probe in ["min_volume_ratio", "max_volume_ratio"] {
        assert!((result.probes[probe] - 1.0).abs() <= 1e-8, "{probe}");
    }
    assert!(result.probes["max_penetration"] <= 1e-6 * 0.2 * 3f64.sqrt());
}
