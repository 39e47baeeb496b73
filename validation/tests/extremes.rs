//! Stability at the extremes: every input here must end in a converged state with finite
//! output or in a clear error, never a panic or a NaN in a converged result. The outcomes
//! are printed (`-- --nocapture`); only panics, silent failures and non-finite converged
//! output fail the tests, plus the few physical checks stated at each test.

mod common;

use common::{check_outcome, try_run, Outcome};
use std::time::Instant;

/// Checks every outcome, prints them, and fails listing the bad ones.
fn check_all(title: &str, cases: Vec<(String, Outcome)>) -> Vec<(String, Outcome)> {
    eprintln!("{title}:");
    let mut bad = Vec::new();
    for (what, outcome) in &cases {
        match check_outcome(what, outcome) {
            Ok(line) => eprintln!("  ok   {line}"),
            Err(line) => {
                eprintln!("  BAD  {line}");
                bad.push(line);
            }
        }
    }
    assert!(bad.is_empty(), "{bad:#?}");
    cases
}

fn converged(o: &Outcome) -> Option<&isochor_scenes::RunResult> {
    match o {
        Outcome::Ran(r) if r.converged => Some(r),
        _ => None,
    }
}

/// nu = 0.5 and 0.49999 with every method on the coarse cantilever. `condensed` refuses
/// nu = 0.5 with an error (it needs `C^-1`); the constrained methods converge at both.
#[test]
fn poisson_ratio_at_and_next_to_one_half() {
    let start = Instant::now();
    let methods = [
        "standard",
        "mixed-p1",
        "mixed-p0",
        "mixed-p1-log",
        "mixed-p0-log",
        "condensed",
        "dual",
        "zonal",
    ];
    let mut cases = Vec::new();
    for nu in ["0.5", "0.49999"] {
        for m in methods {
            let sets = [
                format!("method={m}"),
                format!("nu={nu}"),
                "res=2".into(),
                "steps=2".into(),
            ];
            let sets: Vec<&str> = sets.iter().map(String::as_str).collect();
            cases.push((
                format!("cantilever {m} nu={nu}"),
                try_run("cantilever", None, &sets),
            ));
        }
    }
    let cases = check_all("nu at and next to 0.5", cases);
    for (what, o) in &cases {
        if what.contains("mixed-p1 ") || what.contains("zonal ") {
            let r = converged(o).unwrap_or_else(|| panic!("{what} did not converge"));
            assert!(
                r.volume_change.abs() < 1e-4,
                "{what}: {:e}",
                r.volume_change
            );
        }
    }
    eprintln!("{:.1} s", start.elapsed().as_secs_f64());
}

/// Young's modulus from 100 Pa (the beam collapses under its own weight) to 1 GPa.
#[test]
fn young_modulus_from_1e2_to_1e9() {
    let start = Instant::now();
    let mut cases = Vec::new();
    for e in ["1e2", "1e4", "1e6", "1e9"] {
        for m in ["standard", "mixed-p1", "zonal"] {
            let sets = [format!("method={m}"), format!("E={e}"), "res=2".into()];
            let sets: Vec<&str> = sets.iter().map(String::as_str).collect();
            cases.push((
                format!("cantilever {m} E={e}"),
                try_run("cantilever", None, &sets),
            ));
        }
    }
    let cases = check_all("Young's modulus 1e2..1e9 Pa", cases);
    // The stiff end must converge: a 1 GPa beam barely moves.
    for (what, o) in &cases {
        if what.contains("E=1e9") || what.contains("E=1e6") {
            assert!(converged(o).is_some(), "{what} did not converge");
        }
    }
    eprintln!("{:.1} s", start.elapsed().as_secs_f64());
}

/// The left of the two tets pressed to J = 1e-3, exactly flat (J = 0) and through itself
/// (J = -0.1). The zonal method's energy (F-bar neo-Hookean with `lambda U(J; beta)`) is
/// defined for J <= 0; standard neo-Hookean's log J is not, so it must say so.
#[test]
fn compression_to_zero_volume_and_through_it() {
    let start = Instant::now();
    let mut cases = Vec::new();
    for factor in ["1e-3", "0.0", "-0.1"] {
        let motion = format!("dirichlet.0.motion.scale.factors=[{factor}, 1.0, 1.0]");
        for (label, sets) in [
            ("standard", vec!["method=standard".to_string()]),
            (
                "zonal (standard energy)",
                vec!["method=zonal".into(), "zonal_energy=standard".into()],
            ),
            (
                "zonal (F-bar, lambda, beta = 9)",
                vec![
                    "method=zonal".into(),
                    "zonal_energy=constrained".into(),
                    "lambda=10e3".into(),
                    "beta=9".into(),
                ],
            ),
        ] {
            let mut all = sets.clone();
            all.push(motion.clone());
            let all: Vec<&str> = all.iter().map(String::as_str).collect();
            cases.push((
                format!("two-tets {label}, left tet scaled by {factor}"),
                try_run("two-tets", None, &all),
            ));
        }
    }
    // A block under ten times its traction (150 kPa on E = 66 kPa).
    for m in ["standard", "mixed-p1", "zonal"] {
        let sets = [
            format!("method={m}"),
            "res=4".into(),
            "loads.traction.0.traction=[0.0, 0.0, -150e3]".into(),
        ];
        let sets: Vec<&str> = sets.iter().map(String::as_str).collect();
        cases.push((
            format!("compressed-block {m} at 10x traction"),
            try_run("compressed-block", None, &sets),
        ));
    }
    check_all("compression to J near 0", cases);
    eprintln!("{:.1} s", start.elapsed().as_secs_f64());
}

/// A mesh given with a negatively oriented tet is re-oriented on input (the mesh crate's
/// documented `Orientation::Reorient`), so it runs exactly like the original; a degenerate
/// tet (zero rest volume) is a clear error.
#[test]
fn inverted_and_degenerate_rest_meshes() {
    let original = try_run("two-tets", Some("constrained"), &["steps=2"]);
    let reversed = try_run(
        "two-tets",
        Some("constrained"),
        &["steps=2", "mesh.tets=[[0, 1, 2, 3], [0, 1, 2, 4]]"],
    );
    let degenerate = try_run(
        "two-tets",
        Some("constrained"),
        &[
            "steps=2",
            "mesh.positions=[[0.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0], [-1.0, 0.3, 0.3], [0.0, 0.3, 0.3]]",
        ],
    );
    let cases = check_all(
        "inverted and degenerate rest meshes",
        vec![
            ("two-tets".into(), original),
            ("two-tets, first tet reversed".into(), reversed),
            ("two-tets, right tet flat".into(), degenerate),
        ],
    );
    let (a, b) = (converged(&cases[0].1), converged(&cases[1].1));
    let (a, b) = (
        a.expect("original converges"),
        b.expect("reversed converges"),
    );
    assert_eq!(a.probes, b.probes);
    assert!(
        matches!(&cases[2].1, Outcome::Error(_)),
        "a degenerate rest tet was accepted"
    );
}

/// The dynamic cube at dt = 33 ms (four times the paper's 8 ms): implicit Euler dissipates,
/// so the total energy never rises above its first frame's by more than rounding, and the
/// cube settles.
#[test]
fn dynamic_cube_large_time_step_energy_stays_bounded() {
    let start = Instant::now();
    let mut cases = Vec::new();
    for v in ["zonal", "one-ring", "standard"] {
        cases.push((
            format!("dynamic-cube {v} dt = 33 ms"),
            try_run("dynamic-cube", Some(v), &["res=4", "dt=0.033", "frames=60"]),
        ));
    }
    let cases = check_all("dynamic cube at dt = 33 ms", cases);
    for (what, o) in &cases {
        let r = converged(o).unwrap_or_else(|| panic!("{what} did not converge"));
        let total: Vec<f64> = r
            .history
            .iter()
            .map(|s| s.kinetic_energy + s.elastic_energy + s.external_energy)
            .collect();
        assert!(total.iter().all(|e| e.is_finite()));
        let scale = r
            .history
            .iter()
            .map(|s| s.external_energy.abs())
            .fold(0.0, f64::max);
        let max_rise = total
            .windows(2)
            .map(|w| w[1] - w[0])
            .fold(f64::NEG_INFINITY, f64::max);
        let kinetic = r.history.last().unwrap().kinetic_energy;
        eprintln!(
            "  {what}: total energy {:.3} -> {:.3} (largest rise between frames {:.3e}), final kinetic {:.3e}",
            total[0],
            total[total.len() - 1],
            max_rise,
            kinetic
        );
        let first = total[0];
        assert!(
            total.iter().all(|e| *e <= first + 1e-6 * scale),
            "{what}: total energy rises above its first frame: {total:?}"
        );
        assert!(kinetic < 1e-6 * scale, "{what}: still moving ({kinetic})");
    }
    eprintln!("{:.1} s", start.elapsed().as_secs_f64());
}
