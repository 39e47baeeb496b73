//! Volume preservation: nu = 0.5 exactly, the stretched cylinder of Fig. 13 of Francu et al.
//! 2021, the two tets of Fig. 2 and the indented puck of Fig. 9 of Sheen et al. 2021; and the
//! per-tet pressure of the cube of Fig. 7 of Sheen et al.
//!
//! Run with `-- --nocapture` to see every run's numbers and wall time.

use crate::common;

use common::{
    assert_converged, incompressible_volume_bound, probe, run, unloaded_volume_tolerance,
};
use isochor_scenes::RunResult;
use std::time::Instant;

/// `mixed-p1` and `zonal` at nu = 0.5 exactly keep the volume to the constraint tolerance
/// (`incompressible_volume_bound`: 1e-10 plus rounding).
fn incompressible(scene: &str, method: &str, sets: &[&str]) {
    let mut all = vec![format!("method={method}"), "nu=0.5".to_string()];
    all.extend(sets.iter().map(|s| s.to_string()));
    let r = run(
        scene,
        None,
        &all.iter().map(String::as_str).collect::<Vec<_>>(),
    );
    assert_converged(&r, &format!("{scene} {method} nu = 0.5"));
    let bound = incompressible_volume_bound(r.tets);
    assert!(
        r.volume_change.abs() <= bound,
        "{scene} {method} nu = 0.5: volume change {:e} > {bound:e}",
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

/// Sec. 9 of Francu et al.: the block compressed by a fixed displacement at nu = 0.4999
/// (variant `platen`: its top face glued to a platen pushed down by 10% of the height, its
/// bottom sliding), reduced (384 tets). `mixed-p1` changes its volume only as its pressures
/// say, to the constraint tolerance (the whole-body sum of its rows, see
/// `incompressible_volume_bound`): that is the material's own compressibility. `standard`
/// locks (the glued face keeps the block from barrelling freely) and loses more (the paper:
/// 0.14% against virtually none).
#[test]
fn platen_compressed_block_standard_loses_more_volume_than_mixed_p1() {
    let mixed = run(
        "compressed-block",
        Some("platen"),
        &[
            "res=4",
            "steps=2",
            "method=mixed-p1",
            "probes.volume_law.kind=pressure-volume-mismatch",
        ],
    );
    assert_converged(&mixed, "compressed-block platen mixed-p1");
    let standard = run(
        "compressed-block",
        Some("platen"),
        &["res=4", "steps=2", "method=standard"],
    );
    assert_converged(&standard, "compressed-block platen standard");
    eprintln!(
        "platen, nu = 0.4999, res 4: volume change standard {:+.4}%, mixed-p1 {:+.4}%",
        100.0 * standard.volume_change,
        100.0 * mixed.volume_change
    );
    let law = probe(&mixed, "volume_law");
    let bound = incompressible_volume_bound(mixed.tets);
    assert!(law.abs() <= bound, "mixed-p1 volume law off by {law:e}");
    assert!(
        mixed.volume_change.abs() < standard.volume_change.abs(),
        "mixed-p1 {:e}, standard {:e}",
        mixed.volume_change,
        standard.volume_change
    );
}

/// Fig. 2 of Sheen et al.: the left tet is pressed to 5% of its width (its volume ratio is
/// prescribed: 0.05). Without a constraint the free tet's apex feels only its own tet, so it
/// stays at rest and the total ratio is (0.05 + 1) / 2 = 0.525 exactly (the paper, pressing
/// it flat: 46.6% of the total remains), to `unloaded_volume_tolerance`. With one global zone
/// the total is kept to the constraint tolerance (`incompressible_volume_bound`) and the free
/// tet takes what the pressed one lost: 2 - 0.05 = 1.95, to twice that.
#[test]
fn two_tets_lose_or_keep_the_volume() {
    let pressed = 0.05;
    let free = run("two-tets", Some("unconstrained"), &[]);
    assert_converged(&free, "two-tets unconstrained");
    let total = probe(&free, "total_volume_ratio");
    let right = probe(&free, "free_tet_volume_ratio");
    eprintln!("unconstrained: total {total:.16}, free tet {right:.16}");
    let tol = unloaded_volume_tolerance(free.vertices);
    assert!((right - 1.0).abs() <= tol, "free tet volume ratio {right}");
    assert!(
        (total - (1.0 + pressed) / 2.0).abs() <= tol / 2.0,
        "total volume ratio {total}"
    );

    let kept = run("two-tets", Some("constrained"), &[]);
    assert_converged(&kept, "two-tets constrained");
    let total = probe(&kept, "total_volume_ratio");
    let right = probe(&kept, "free_tet_volume_ratio");
    eprintln!("constrained: total {total:.16}, free tet {right:.16}");
    let bound = incompressible_volume_bound(kept.tets);
    assert!((total - 1.0).abs() <= bound, "total volume ratio {total}");
    assert!(
        (right - (2.0 - pressed)).abs() <= 2.0 * bound,
        "free tet volume ratio {right}"
    );
}

/// Fig. 9 of Sheen et al.: the puck indented to 50% of its height in 50 steps, zonal with
/// lambda = 100 kPa and beta = 9 (the scene) and beta = 0. Both converge, keep the volume to
/// the constraint tolerance and never invert a tet (the paper: "completely free of inverted
/// tets", and beta = 0 "does not converge to an infeasible state").
///
/// The paper finds beta = 9 faster (14.84% in runtime, from slow convergence of beta = 0
/// past 25% indentation); what that claim reduces to here is that beta = 9 needs no more
/// Newton iterations than beta = 0. The speed-up is not reproduced: both take 3 iterations
/// per step at res 3 and at res 6 (150 in all). Here no tet comes near inversion (the
/// smallest volume ratio at 50% is 0.41 with beta = 0 and 0.51 with beta = 9 at res 6),
/// while on the paper's mesh the moving boundary starts to invert elements past 25%, where
/// it saw beta = 0 slow down.
fn bulge_puck(res: &str) -> [RunResult; 2] {
    let start = Instant::now();
    // The paper's 50 steps (the scene's default is one adaptive step).
    let nine = run("bulge-puck", Some("zonal"), &[res, "steps=50"]);
    let zero = run("bulge-puck", Some("zonal"), &[res, "steps=50", "beta=0"]);
    for (beta, r) in [("9", &nine), ("0", &zero)] {
        let what = format!("bulge-puck {res} zonal beta = {beta}");
        assert_converged(r, &what);
        let bound = incompressible_volume_bound(r.tets);
        assert!(
            r.volume_change.abs() <= bound,
            "{what}: volume change {:e} > {bound:e}",
            r.volume_change
        );
        assert_eq!(r.max_inverted_tets, 0, "{what}: inverted tets");
    }
    eprintln!(
        "bulge-puck {res}: beta = 9: {} Newton iterations, {:.2} s; beta = 0: {} Newton iterations, {:.2} s ({:.1} s)",
        nine.newton_iterations,
        nine.wall_time_s,
        zero.newton_iterations,
        zero.wall_time_s,
        start.elapsed().as_secs_f64()
    );
    assert!(
        nine.newton_iterations <= zero.newton_iterations,
        "beta = 9 takes {} Newton iterations, beta = 0 {}",
        nine.newton_iterations,
        zero.newton_iterations
    );
    [nine, zero]
}

/// The coarse puck (648 tets). Its `bulge_height` (the highest rise of the top surface at
/// rest radius >= 30 mm) is not asserted: the puck's lattice has rings at 16.7 mm (the
/// indenter's edge), 33.3 mm and 50 mm only, so one element spans the drop from the indenter
/// to the rim, and the whole top surface goes down (-0.89 mm at its highest rim vertex; the
/// side wall's top edge moves out by 10 mm, twice as much as at res 6). The bulge appears
/// from res 6 on (+0.52 mm; +0.64 mm at res 9), see the paper-mesh test.
#[test]
fn bulge_puck_zonal_keeps_the_volume_coarse() {
    bulge_puck("res=3");
}

/// The paper-size puck (5184 tets), where the bulge is resolved: with the zone the top
/// surface rises beyond 30 mm (+0.52 mm), more than with standard neo-Hookean at nu = 0.4545,
/// which loses volume (4.0% here, 5.1% in the paper), and at nu = 0.495, which locks (no
/// visible bulging in the paper's Fig. 9; here its rim goes down, -0.15 mm).
#[test]
#[ignore = "long: the paper-size puck (5184 tets, 50 steps), four runs, about 90 s in the dev profile"]
fn bulge_puck_zonal_keeps_the_volume_paper_mesh() {
    let [nine, _] = bulge_puck("res=6");
    let bulge = probe(&nine, "bulge_height");
    assert!(bulge > 0.0, "no bulge: {bulge}");
    for variant in ["standard-0.4545", "standard-0.495"] {
        let r = run("bulge-puck", Some(variant), &["res=6"]);
        assert_converged(&r, variant);
        let standard = probe(&r, "bulge_height");
        eprintln!(
            "{variant}: bulge {:.3} mm (zonal {:.3} mm), volume change {:+.2}%",
            1e3 * standard,
            1e3 * bulge,
            100.0 * r.volume_change
        );
        assert!(
            standard < bulge,
            "{variant} bulges {standard} >= zonal {bulge}"
        );
    }
}

/// Fig. 7 of Sheen et al.: the per-tet pressure of the cube standing under gravity (res 5,
/// 750 tets) is irregular for standard neo-Hookean at nu = 0.495 (locking) and smooth with
/// one global zone and a local penalty. `pressure_checkerboard` is the mean jump across
/// interior faces over the standard deviation: `2 / sqrt(pi)` (1.128) for uncorrelated
/// noise, 2 for a perfect checkerboard, near 0 for a smooth field. Standard's pressure is the
/// roughest (0.71 against 0.55 for zonal and 0.46 for mixed-p1 at nu = 0.5); none
/// checkerboards: every index is below that of uncorrelated noise. (The tet pressure of
/// mixed-p1 is the average of its four nodal pressures, which filters nodal oscillations:
/// Sheen et al.'s one-ring checkerboard does not show in it.)
#[test]
fn pressure_cube_standard_pressure_is_the_roughest() {
    let index = |variant: &str| {
        let r = run("pressure-cube", Some(variant), &["res=5"]);
        assert_converged(&r, variant);
        probe(&r, "pressure_checkerboard")
    };
    let standard = index("standard");
    let one_ring = index("one-ring");
    let zonal = index("zonal");
    eprintln!(
        "checkerboard index: standard {standard:.3}, one-ring {one_ring:.3}, zonal {zonal:.3}"
    );
    let noise = 2.0 / std::f64::consts::PI.sqrt();
    for (what, c) in [
        ("standard", standard),
        ("one-ring", one_ring),
        ("zonal", zonal),
    ] {
        assert!(c > 0.0 && c < noise, "{what}: index {c}");
    }
    assert!(
        standard > zonal && standard > one_ring,
        "standard {standard}, one-ring {one_ring}, zonal {zonal}"
    );
}
