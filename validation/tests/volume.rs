//! Volume preservation: nu = 0.5 exactly, the stretched cylinder of Fig. 13 of Francu et al.
//! 2021, the two tets of Fig. 2 and the indented puck of Fig. 9 of Sheen et al. 2021.
//!
//! Run with `-- --nocapture` to see every run's numbers and wall time.

mod common;

use common::{assert_converged, probe, run};
use std::time::Instant;

/// `|volume change| < 1e-8` with `mixed-p1` and `zonal` at nu = 0.5 exactly.
fn incompressible(scene: &str, method: &str, sets: &[&str]) {
    let mut all = vec![format!("method={method}"), "nu=0.5".to_string()];
    all.extend(sets.iter().map(|s| s.to_string()));
    let r = run(
        scene,
        None,
        &all.iter().map(String::as_str).collect::<Vec<_>>(),
    );
    assert_converged(&r, &format!("{scene} {method} nu = 0.5"));
    assert!(
        r.volume_change.abs() < 1e-8,
        "{scene} {method} nu = 0.5: volume change {:e}",
        r.volume_change
    );
}

#[test]
fn nu_one_half_keeps_the_volume_cantilever() {
    for method in ["mixed-p1", "zonal"] {
        incompressible("cantilever", method, &["res=2"]);
    }
}

#[test]
fn nu_one_half_keeps_the_volume_compressed_block() {
    for method in ["mixed-p1", "zonal"] {
        incompressible("compressed-block", method, &["res=4"]);
    }
}

#[test]
fn nu_one_half_keeps_the_volume_stretched_cylinder_zonal() {
    incompressible("stretched-cylinder", "zonal", &["res=3"]);
}

/// mixed-p1 at nu = 0.5 (C = 0, a singular KKT matrix: spurious pressure modes) on the
/// cylinder stretched to twice its length. Converges at res 3 and 4 (61 Newton iterations
/// over 20 steps). The coarser cylinders (res 1: 120 tets, res 2: 960 tets) do not, at
/// nu = 0.4999 either: the reduced stiffness turns indefinite along the path and the shifted
/// Newton steps stall (see the solvers' docs).
#[test]
fn nu_one_half_keeps_the_volume_stretched_cylinder_mixed_p1() {
    incompressible("stretched-cylinder", "mixed-p1", &["res=3"]);
}

/// Fig. 13 of Francu et al.: stretched to twice its length, mixed-p1 at nu = 0.4999 keeps the
/// volume to 0.015% (we ask for 0.05%). A coarser cylinder than the paper's (res 3, 3240
/// tets); `stretched_cylinder_paper_mesh` runs the paper's 7680 tets.
#[test]
fn stretched_cylinder_mixed_p1_keeps_the_volume() {
    let r = run("stretched-cylinder", Some("mixed-p1"), &["res=3"]);
    assert_converged(&r, "stretched-cylinder mixed-p1 res 3");
    eprintln!(
        "mixed-p1, nu = 0.4999, res 3: volume change {:+.4}%",
        100.0 * r.volume_change
    );
    assert!(r.volume_change.abs() < 5e-4, "{:e}", r.volume_change);
}

/// The same and standard at nu = 0.49 (the paper: -1.8%) on the paper's mesh (7680 tets).
#[test]
#[ignore = "long: the paper's 7680-tet cylinder, about a minute in the dev profile"]
fn stretched_cylinder_paper_mesh() {
    let r = run("stretched-cylinder", Some("mixed-p1"), &[]);
    assert_converged(&r, "stretched-cylinder mixed-p1");
    eprintln!(
        "mixed-p1, nu = 0.4999, res 4: volume change {:+.4}%",
        100.0 * r.volume_change
    );
    assert!(r.volume_change.abs() < 5e-4, "{:e}", r.volume_change);
    let s = run("stretched-cylinder", Some("standard"), &[]);
    assert_converged(&s, "stretched-cylinder standard");
    eprintln!(
        "standard, nu = 0.49, res 4: volume change {:+.4}%",
        100.0 * s.volume_change
    );
    standard_changes_volume(s.volume_change);
}

/// Standard neo-Hookean at nu = 0.49 changes the volume by the order the paper reports
/// (1.8%, unsigned in the paper): between a third of it and three times it. Stretching a
/// compressible solid increases its volume, and so it does here (+1.8% on the paper's mesh).
fn standard_changes_volume(change: f64) {
    assert!(
        (0.006..=0.054).contains(&change.abs()),
        "standard at nu = 0.49 changes the volume by {:+.3}% (paper: 1.8%)",
        100.0 * change
    );
}

#[test]
fn stretched_cylinder_standard_changes_volume() {
    let r = run("stretched-cylinder", Some("standard"), &["res=3"]);
    assert_converged(&r, "stretched-cylinder standard res 3");
    eprintln!(
        "standard, nu = 0.49, res 3: volume change {:+.4}%",
        100.0 * r.volume_change
    );
    standard_changes_volume(r.volume_change);
}

/// Fig. 2 of Sheen et al.: the left tet is pressed to 5% of its width. Without a constraint
/// its volume is lost (the paper, pressing it flat: 46.6% of the total remains; here about
/// (1 + 0.05) / 2); with one global zone the total is kept and the free tet doubles (to
/// 2 - 0.05 of its volume).
#[test]
fn two_tets_lose_or_keep_the_volume() {
    let free = run("two-tets", Some("unconstrained"), &[]);
    assert_converged(&free, "two-tets unconstrained");
    let total = probe(&free, "total_volume_ratio");
    let right = probe(&free, "free_tet_volume_ratio");
    eprintln!("unconstrained: total {total:.4}, free tet {right:.4}");
    assert!((0.45..0.55).contains(&total), "total volume ratio {total}");

    let kept = run("two-tets", Some("constrained"), &[]);
    assert_converged(&kept, "two-tets constrained");
    let total = probe(&kept, "total_volume_ratio");
    let right = probe(&kept, "free_tet_volume_ratio");
    eprintln!("constrained: total {total:.10}, free tet {right:.6}");
    assert!((total - 1.0).abs() < 1e-8, "total volume ratio {total}");
    assert!((right - 1.95).abs() < 1e-6, "free tet volume ratio {right}");
}

/// Fig. 9 of Sheen et al.: the puck indented to 50% of its height. Zonal (lambda = 100 kPa,
/// beta = 9) keeps the volume to 1e-8 and ends with no inverted tet. beta = 0 versus 9:
/// the paper finds beta = 9 converges faster; the iterations are printed, not asserted.
fn bulge_puck(res: &str) {
    let start = Instant::now();
    let nine = run("bulge-puck", Some("zonal"), &[res]);
    assert_converged(&nine, "bulge-puck zonal beta = 9");
    assert!(nine.volume_change.abs() < 1e-8, "{:e}", nine.volume_change);
    assert_eq!(
        probe(&nine, "inverted_tets"),
        0.0,
        "inverted tets at the end"
    );
    let zero = run("bulge-puck", Some("zonal"), &[res, "beta=0"]);
    eprintln!(
        "bulge-puck {res}: beta = 9: {} Newton iterations, {:.2} s, max inverted {}, final inverted {}; \
         beta = 0: {} Newton iterations, {:.2} s, converged {}, max inverted {}, final inverted {}  ({:.1} s)",
        nine.newton_iterations,
        nine.wall_time_s,
        nine.max_inverted_tets,
        probe(&nine, "inverted_tets"),
        zero.newton_iterations,
        zero.wall_time_s,
        zero.converged,
        zero.max_inverted_tets,
        zero.probes["inverted_tets"],
        start.elapsed().as_secs_f64()
    );
}

#[test]
fn bulge_puck_zonal_keeps_the_volume_coarse() {
    bulge_puck("res=3");
}

#[test]
#[ignore = "long: the paper-size puck (5184 tets, 50 steps)"]
fn bulge_puck_zonal_keeps_the_volume_paper_mesh() {
    bulge_puck("res=6");
}
