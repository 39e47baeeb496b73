//! Load stepping that adapts and runs that survive: adaptive quasi-static increments, time
//! steps retried in substeps, load curves, and checkpoints that resume a run bit for bit.
//! Iteration counts are printed (`-- --nocapture`).

use crate::common;

use common::{assert_converged, probe, run};
use isochor_scenes::resolve::{self, ResolvedScene};
use isochor_scenes::{load_scene, Override};
use isochor_solvers::{Checkpoint, Method, Simulation, State};

fn built(scene: &str, sets: &[&str]) -> ResolvedScene {
    let overrides: Vec<Override> = sets.iter().map(|s| Override::parse(s).unwrap()).collect();
    resolve::build(&load_scene(scene, None, &overrides).unwrap()).unwrap()
}

/// The cantilever at its default settings takes the full load in one step with every method,
/// and gives the deflection of ten fixed steps to the solver's tolerance.
#[test]
fn the_cantilever_takes_its_load_in_one_step_with_every_method() {
    for method in Method::ALL {
        let m = format!("method={method}");
        let one = run("cantilever", None, &[&m, "res=2"]);
        assert_converged(&one, &format!("cantilever {method}, adaptive"));
        let ten = run(
            "cantilever",
            None,
            &[&m, "res=2", "steps=10", "increments=fixed"],
        );
        assert_converged(&ten, &format!("cantilever {method}, 10 fixed steps"));
        let (a, b) = (probe(&one, "tip_deflection"), probe(&ten, "tip_deflection"));
        eprintln!(
            "{method:<13} one step: {} Newton iterations, {} cuts, tip {a:.9e}; ten steps: {} iterations, tip {b:.9e}",
            one.newton_iterations, one.cuts, ten.newton_iterations
        );
        assert_eq!((one.steps, one.cuts), (1, 0), "{method}");
        assert!((a - b).abs() <= 1e-6 * b.abs(), "{method}: {a} vs {b}");
    }
}

/// A soft cantilever (E = 1 kPa) that no Newton iteration reaches from the straight beam in
/// one step: fixed stepping stops at step 1, adaptive stepping cuts the increment, converges,
/// and records its cuts.
#[test]
fn a_load_too_large_for_one_step_is_cut_until_it_converges() {
    let fixed = run("cantilever", None, &["E=1e3", "res=2", "increments=fixed"]);
    assert!(
        !fixed.converged && fixed.failed_step == Some(1),
        "{fixed:?}"
    );
    let r = run("cantilever", None, &["E=1e3", "res=2"]);
    assert_converged(&r, "soft cantilever, adaptive");
    let levels: Vec<(f64, f64, usize)> = r
        .history
        .iter()
        .map(|s| (s.t, s.increment, s.cuts.len()))
        .collect();
    eprintln!(
        "soft cantilever: {} steps, {} cuts, {} Newton iterations; (t, increment, cuts) {levels:?}",
        r.steps, r.cuts, r.newton_iterations
    );
    assert!(r.cuts >= 1 && r.cuts == levels.iter().map(|l| l.2).sum::<usize>());
    assert_eq!(r.history.last().unwrap().t, 1.0);
    assert!(levels.windows(2).all(|w| w[1].0 > w[0].0));
    assert!(r.history[0].cuts.iter().all(|c| !c.error.is_empty()));
    assert!(probe(&r, "tip_deflection") > 0.1);
}

/// A prescribed motion that flattens a tet to zero volume cannot be reached by the standard
/// energy with any increment: the run ends with the typed error after the smallest increment
/// and keeps its last converged state.
#[test]
fn an_unreachable_load_ends_with_a_typed_error_keeping_the_last_state() {
    let r = run(
        "two-tets",
        None,
        &[
            "method=standard",
            "steps=1",
            "dirichlet.0.motion.scale.factors=[0.0, 1.0, 1.0]",
        ],
    );
    let error = r.error.clone().unwrap_or_default();
    eprintln!("{} steps, {} cuts: {error}", r.steps, r.cuts);
    assert!(
        !r.converged && error.contains("even with an increment"),
        "{error}"
    );
    assert!(r.steps >= 1 && r.failed_step == Some(r.steps + 1));
    assert!(r.cuts >= 9);
    let ratio = probe(&r, "total_volume_ratio");
    assert!(ratio.is_finite() && ratio > 0.5 && ratio < 0.51, "{ratio}");
}

/// A chamber inflated to the full pressure at half the run and deflated by its end: at half
/// the run it has the volume of the plain inflation, at the end it is back at rest (the
/// volume to a few times the constraint tolerance, 1e-10 per node).
#[test]
fn a_chamber_inflated_and_deflated_returns_to_rest() {
    let plain = run("inflated-tube", None, &["res=1"]);
    assert_converged(&plain, "inflated tube");
    let r = run(
        "inflated-tube",
        None,
        &[
            "res=1",
            "steps=2",
            "loads.pressure.0.curve=[[0.0, 0.0], [0.5, 1.0], [1.0, 0.0]]",
        ],
    );
    assert_converged(&r, "inflated and deflated tube");
    let half = r
        .history
        .iter()
        .find(|s| s.t == 0.5)
        .expect("a frame at 0.5");
    eprintln!(
        "volume change: plain {:e}, at half {:e}, at the end {:e}; radius increase at the end {:e}",
        plain.volume_change,
        half.volume_change,
        r.volume_change,
        probe(&r, "mean_radius_increase")
    );
    assert!((half.volume_change - plain.volume_change).abs() <= 1e-6 * plain.volume_change);
    assert!(r.volume_change.abs() <= 1e-9, "{}", r.volume_change);
    assert!(
        probe(&r, "mean_radius_increase").abs() <= 1e-9 * probe(&plain, "mean_radius_increase")
    );
}

/// Time steps too large for a three-iteration Newton limit are retried in substeps; the
/// frames stay at multiples of `dt`.
#[test]
fn failed_time_steps_are_retried_in_substeps_keeping_the_frames() {
    let r = run(
        "dynamic-cube",
        None,
        &["res=3", "frames=4", "dt=0.2", "max_iterations=3"],
    );
    assert_converged(&r, "dynamic cube with substeps");
    let times: Vec<f64> = r.history.iter().map(|s| s.t).collect();
    eprintln!("{} steps, {} cuts: times {times:?}", r.steps, r.cuts);
    assert!(r.cuts >= 1 && r.steps > 4);
    for k in 1..=4 {
        assert!(
            times.contains(&(k as f64 * 0.2)),
            "no frame at {}",
            k as f64 * 0.2
        );
    }
    let total: f64 = r.history.iter().map(|s| s.increment).sum();
    assert!((total - 0.8).abs() < 1e-12, "{total}");
}

/// Runs `built` to the end, taking a checkpoint after accepted step `at`; returns the final
/// state and the checkpoint.
fn run_with_checkpoint(built: ResolvedScene, at: usize) -> (State, Checkpoint) {
    let mut sim = Simulation::new(built.problem, built.settings).unwrap();
    let mut taken = None;
    let summary = sim
        .run(built.stepping, |frame| {
            if frame.index == at {
                taken = Some(frame.checkpoint());
            }
        })
        .unwrap();
    (
        summary.final_state,
        taken.expect("the checkpoint step was reached"),
    )
}

/// A run resumed from a checkpoint ends in the uninterrupted run's state, bit for bit: quasi-
/// statically with contact (multipliers restored) and adaptive cuts, and in dynamics.
#[test]
fn a_resumed_run_equals_the_uninterrupted_one_bit_for_bit() {
    for (scene, sets, at) in [
        ("resting-block", vec!["res=2", "steps=4"], 2),
        ("cantilever", vec!["E=1e3", "res=1"], 2),
        ("dynamic-cube", vec!["res=3", "frames=6"], 3),
    ] {
        let (uninterrupted, checkpoint) = run_with_checkpoint(built(scene, &sets), at);
        let b = built(scene, &sets);
        let mut sim = Simulation::new(b.problem, b.settings).unwrap();
        sim.restore(checkpoint).unwrap();
        let resumed = sim.run(b.stepping, |_| {}).unwrap();
        assert!(
            resumed.final_state == uninterrupted,
            "{scene}: the resumed run differs"
        );
        eprintln!("{scene}: resumed after step {at}, equal bit for bit");
    }
    // A checkpoint that is not a run's (a zero increment would never advance) is refused.
    let (_, mut bad) = run_with_checkpoint(built("cantilever", &["res=1", "steps=2"]), 1);
    bad.progress.increment = 0.0;
    let b = built("cantilever", &["res=1", "steps=2"]);
    let mut sim = Simulation::new(b.problem, b.settings).unwrap();
    let e = sim.restore(bad).unwrap_err().to_string();
    assert!(e.contains("increment = 0"), "{e}");
}

/// An indenter (a prescribed motion) that squeezes the puck by half the run and releases it
/// by its end: at half the run the puck stores the plain indentation's energy, at the end it
/// is back at rest.
#[test]
fn an_indenter_squeezes_and_releases() {
    let plain = run("bulge-puck", Some("zonal"), &["res=2"]);
    assert_converged(&plain, "bulge puck");
    let r = run(
        "bulge-puck",
        Some("zonal"),
        &[
            "res=2",
            "steps=2",
            "dirichlet.1.curve=[[0.0, 0.0], [0.5, 1.0], [1.0, 0.0]]",
        ],
    );
    assert_converged(&r, "bulge puck squeezed and released");
    let half = r
        .history
        .iter()
        .find(|s| s.t == 0.5)
        .expect("a frame at 0.5");
    let plain_energy = plain.history.last().unwrap().elastic_energy;
    let end = r.history.last().unwrap();
    eprintln!(
        "elastic energy: plain {plain_energy:e}, at half {:e}, at the end {:e}; bulge at the end {:e} (plain {:e})",
        half.elastic_energy,
        end.elastic_energy,
        probe(&r, "bulge_height"),
        probe(&plain, "bulge_height")
    );
    assert!((half.elastic_energy - plain_energy).abs() <= 1e-6 * plain_energy);
    assert!(end.elastic_energy.abs() <= 1e-9 * plain_energy);
    assert!(probe(&r, "bulge_height").abs() <= 1e-9 * probe(&plain, "bulge_height").abs());
}

/// The ground (an obstacle) raised 1 cm by half the run and lowered back, under full gravity
/// throughout (a constant gravity curve): at half the run the block rests 1 cm higher in the
/// plain resting shape, at the end it is back in it (both to the contact tolerance).
#[test]
fn an_obstacle_moves_out_and_back() {
    let positions_at = |sets: &[&str]| {
        let b = built("resting-block", sets);
        let mut sim = Simulation::new(b.problem, b.settings).unwrap();
        let mut frames = Vec::new();
        sim.run(b.stepping, |frame| {
            if frame.frame.is_some() {
                frames.push(frame.state.positions.clone());
            }
        })
        .unwrap();
        frames
    };
    let gravity = "loads.gravity_curve=[[0.0, 1.0]]";
    let plain = positions_at(&["steps=1", gravity]).pop().unwrap();
    let moved = positions_at(&[
        "steps=2",
        gravity,
        "obstacles.0.translate=[0.0, 0.0, 0.01]",
        "obstacles.0.curve=[[0.0, 0.0], [0.5, 1.0], [1.0, 0.0]]",
    ]);
    let lift = isochor_mesh::Vec3::new(0.0, 0.0, 0.01);
    let off = |a: &[isochor_mesh::Vec3], shift: isochor_mesh::Vec3| {
        a.iter()
            .zip(&plain)
            .map(|(x, p)| (x - p - shift).norm())
            .fold(0.0, f64::max)
    };
    let (half, end) = (off(&moved[0], lift), off(&moved[1], lift * 0.0));
    eprintln!("largest distance from the plain resting shape: at half (lifted) {half:e} m, at the end {end:e} m");
    // The contact tolerance: 1e-6 of the bounding-box diagonal (0.17 m).
    assert!(half <= 2e-7 && end <= 2e-7, "{half} {end}");
}
