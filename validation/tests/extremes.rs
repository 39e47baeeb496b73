//! Stability at the extremes: every input here ends as its test says, case by case: a
//! converged state with finite output, a refusal before the run naming the cause, or a run
//! stopped by a solver error naming the cause that keeps its last accepted state (finite,
//! and measured by the probes). Never a panic, never a NaN. The outcomes are printed
//! (`-- --nocapture`).

use crate::common;

use common::{
    check_outcome, incompressible_volume_bound, probe, try_run, unloaded_volume_tolerance, Outcome,
};
use isochor_scenes::{RunResult, StepRecord};
use std::ops::RangeInclusive;
use std::time::Instant;

/// The message of `SolverError::NotConverged`: the iteration limit, with both residuals.
const NOT_CONVERGED: &str = "did not converge in";

/// How a case must end.
#[derive(Debug, Clone)]
enum Expect {
    /// Every step converged.
    Converged,
    /// Refused before the run, with an error containing this text.
    Refused(&'static str),
    /// Stopped at a step in `steps` by a solver error containing every text of `cause`,
    /// keeping the state of the step before (the one its probes measure).
    Stopped {
        steps: RangeInclusive<usize>,
        cause: &'static [&'static str],
    },
}

fn meets(outcome: &Outcome, expect: &Expect) -> Result<(), String> {
    match (expect, outcome) {
        (Expect::Converged, Outcome::Ran(r)) if r.converged => Ok(()),
        (Expect::Refused(text), Outcome::Error(e)) if e.contains(text) => Ok(()),
        (Expect::Stopped { steps, cause }, Outcome::Ran(r)) if !r.converged => {
            let step = r.failed_step.unwrap_or(0);
            let error = r.error.as_deref().unwrap_or_default();
            if !steps.contains(&step) {
                Err(format!("stopped at step {step}, expected {steps:?}"))
            } else if let Some(missing) = cause.iter().find(|c| !error.contains(**c)) {
                Err(format!("the error does not say \"{missing}\": {error}"))
            } else if r.steps + 1 != step {
                Err(format!(
                    "{} accepted steps kept before the failed step {step}",
                    r.steps
                ))
            } else {
                Ok(())
            }
        }
        _ => Err(format!("expected {expect:?}")),
    }
}

/// Checks every outcome (`check_outcome`) and its expectation, prints them, and fails listing
/// the bad ones; returns the outcomes for the physical checks of each test.
fn check_cases(title: &str, cases: Vec<(String, Outcome, Expect)>) -> Vec<(String, Outcome)> {
    eprintln!("{title}:");
    let mut bad = Vec::new();
    for (what, outcome, expect) in &cases {
        let checked = check_outcome(what, outcome).and_then(|line| match meets(outcome, expect) {
            Ok(()) => Ok(line),
            Err(e) => Err(format!("{line}\n       {e}")),
        });
        match checked {
            Ok(line) => eprintln!("  ok   {line}"),
            Err(line) => {
                eprintln!("  BAD  {line}");
                bad.push(line);
            }
        }
    }
    assert!(bad.is_empty(), "{bad:#?}");
    cases.into_iter().map(|(w, o, _)| (w, o)).collect()
}

fn ran(o: &Outcome) -> &RunResult {
    match o {
        Outcome::Ran(r) => r,
        _ => unreachable!("checked by check_cases"),
    }
}

/// nu = 0.5 and 0.49999 with every method on the coarse cantilever. At nu = 0.5 standard
/// refuses (lambda is infinite), P0 refuses (zero-compliance element constraints lock linear
/// tets), `condensed` refuses (it needs `C^-1`); the other methods converge at both ratios.
/// With zero compliance the volume is kept to the constraint tolerance
/// (`incompressible_volume_bound`): `mixed-p1`, `dual` and `zonal` at 0.5, `zonal` (whose
/// zones never have compliance) at 0.49999 too. `mixed-p1-log` keeps `sum_e V_e log J_e`
/// instead, so by Jensen's inequality its volume can only grow (by about half the mean
/// square of `log J`).
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
            let expect = match (m, nu) {
                ("standard", "0.5") => Expect::Refused("nu = 0.5 makes lambda infinite"),
                ("mixed-p0" | "mixed-p0-log", "0.5") => {
                    Expect::Refused("cannot run at nu = 0.5: element (P0) constraints")
                }
                ("condensed", "0.5") => {
                    Expect::Refused("cannot run at nu = 0.5: static condensation needs C^-1")
                }
                _ => Expect::Converged,
            };
            cases.push((
                format!("cantilever {m} nu={nu}"),
                try_run("cantilever", None, &sets),
                expect,
            ));
        }
    }
    let cases = check_cases("nu at and next to 0.5", cases);
    for (what, o) in &cases {
        let Outcome::Ran(r) = o else { continue };
        let bound = incompressible_volume_bound(r.tets);
        let hard = what.contains("zonal ")
            || (what.ends_with("nu=0.5") && (what.contains("mixed-p1 ") || what.contains("dual ")));
        if hard {
            assert!(
                r.volume_change.abs() <= bound,
                "{what}: volume change {:e} > {bound:e}",
                r.volume_change
            );
        }
        if what.contains("mixed-p1-log") && what.ends_with("nu=0.5") {
            assert!(
                r.volume_change > bound,
                "{what}: the log measure should gain volume (Jensen), got {:e}",
                r.volume_change
            );
        }
    }
    eprintln!("{:.1} s", start.elapsed().as_secs_f64());
}

/// Young's modulus from 100 Pa to 1 GPa, every run converged or stopped by a named solver
/// error keeping a finite last state:
/// - E = 1e2: every method stops at the first step with `NotConverged`, keeping the rest
///   state. The beam cannot carry its own weight: at 10% of gravity the stress at the root,
///   0.1 rho g L = 210 Pa, is six times mu = 33 Pa (a uniaxial neo-Hookean stretch of about
///   7); the equilibrium is a hanging, stretched rope that 50 Newton iterations from the
///   straight beam do not reach.
/// - E = 1e4: `mixed-p1` and `zonal` converge (the tip sags 0.21 m, more than the beam is
///   long); `standard` stops with `NotConverged` after some accepted steps (at step 6 of 10
///   today): its locked nu = 0.4999 energy under large rotations makes the Newton matrix
///   indefinite (shifts) and the iterations wander.
/// - E = 1e6 and 1e9: every method converges.
#[test]
fn young_modulus_from_1e2_to_1e9() {
    let start = Instant::now();
    let mut cases = Vec::new();
    for e in ["1e2", "1e4", "1e6", "1e9"] {
        for m in ["standard", "mixed-p1", "zonal"] {
            // Fixed increments: the cases pin where one solve per step stops (adaptive
            // stepping is tested in stepping.rs).
            let sets = [
                format!("method={m}"),
                format!("E={e}"),
                "res=2".into(),
                "steps=10".into(),
                "increments=fixed".into(),
            ];
            let sets: Vec<&str> = sets.iter().map(String::as_str).collect();
            let expect = match (e, m) {
                ("1e2", _) => Expect::Stopped {
                    steps: 1..=1,
                    cause: &[NOT_CONVERGED],
                },
                ("1e4", "standard") => Expect::Stopped {
                    steps: 2..=10,
                    cause: &[NOT_CONVERGED],
                },
                _ => Expect::Converged,
            };
            cases.push((
                format!("cantilever {m} E={e}"),
                try_run("cantilever", None, &sets),
                expect,
            ));
        }
    }
    let cases = check_cases("Young's modulus 1e2..1e9 Pa", cases);
    // A run stopped at the first step keeps the rest state.
    for (what, o) in cases.iter().filter(|(w, _)| w.ends_with("E=1e2")) {
        let r = ran(o);
        assert_eq!(probe(r, "tip_deflection"), 0.0, "{what}");
        assert_eq!(r.volume_change, 0.0, "{what}");
    }
    eprintln!("{:.1} s", start.elapsed().as_secs_f64());
}

/// The left of the two tets pressed to J = 1e-3, exactly flat (J = 0) and through itself
/// (J = -0.1) in ten steps, with three energies:
/// - the zonal method's constrained energy (F-bar neo-Hookean with `lambda U(J; beta)`,
///   Sheen et al. 2021 eq. 12-13) is defined for every J: it converges in every case, the
///   global zone keeps the total volume and the free tet takes the rest, `2 - J`;
/// - standard neo-Hookean (no constraint) and the zonal method with the standard energy have
///   `log J`: they converge at J = 1e-3 and refuse J <= 0 with a typed error, keeping the
///   state of step 9. At J = 0 the target itself is outside the domain: every full step lands
///   on it and is halved, the gap halves per iteration, and after 50 iterations the error is
///   `BoundaryUnreachable` ("the energy's domain"). At J = -0.1 the target lies past J = 0:
///   the distance to J = 0 halves per iteration until no step of at least 2^-30 stays
///   valid, and the error is a line search that found no valid state.
///
/// The block under ten times its traction (150 kPa on E = 66 kPa) does not approach J = 0
/// (the smallest tet volume ratio of its last accepted state is about 0.8 to 1): every method
/// stops with `NotConverged` at a load past the scene's own 15 kPa (step 1), where the
/// tangent stiffness turns indefinite (the failed step's Newton matrices needed a shift) and
/// the shifted iterations stall, with no inverted tet in any accepted state.
#[test]
fn compression_to_zero_volume_and_through_it() {
    let start = Instant::now();
    let mut cases = Vec::new();
    let refused_at_zero = Expect::Stopped {
        steps: 10..=10,
        cause: &["the prescribed motion was not reached", "energy's domain"],
    };
    let refused_through_zero = Expect::Stopped {
        steps: 10..=10,
        cause: &["line search failed", "valid state"],
    };
    for factor in ["1e-3", "0.0", "-0.1"] {
        let motion = format!("dirichlet.0.motion.scale.factors=[{factor}, 1.0, 1.0]");
        let log_j = match factor {
            "1e-3" => Expect::Converged,
            "0.0" => refused_at_zero.clone(),
            _ => refused_through_zero.clone(),
        };
        for (label, sets, expect) in [
            (
                "standard",
                vec!["method=standard".to_string()],
                log_j.clone(),
            ),
            (
                "zonal (standard energy)",
                vec!["method=zonal".into(), "zonal_energy=standard".into()],
                log_j,
            ),
            (
                "zonal (F-bar, lambda, beta = 9)",
                vec![
                    "method=zonal".into(),
                    "zonal_energy=constrained".into(),
                    "lambda=10e3".into(),
                    "beta=9".into(),
                ],
                Expect::Converged,
            ),
        ] {
            let mut all = sets.clone();
            all.push(motion.clone());
            all.push("increments=fixed".into());
            let all: Vec<&str> = all.iter().map(String::as_str).collect();
            cases.push((
                format!("two-tets {label}, left tet scaled by {factor}"),
                try_run("two-tets", None, &all),
                expect,
            ));
        }
    }
    for m in ["standard", "mixed-p1", "zonal"] {
        let sets = [
            format!("method={m}"),
            "res=4".into(),
            "loads.traction.0.traction=[0.0, 0.0, -150e3]".into(),
            "probes.min_volume_ratio.kind=min-volume-ratio".into(),
            "steps=10".into(),
            "increments=fixed".into(),
        ];
        let sets: Vec<&str> = sets.iter().map(String::as_str).collect();
        cases.push((
            format!("compressed-block {m} at 10x traction"),
            try_run("compressed-block", None, &sets),
            Expect::Stopped {
                steps: 2..=10,
                cause: &[NOT_CONVERGED],
            },
        ));
    }
    let cases = check_cases("compression to J near 0", cases);

    for (what, o) in &cases {
        let r = ran(o);
        if what.starts_with("compressed-block") {
            let failed = r
                .failed
                .as_ref()
                .expect("a stopped run records its failed step");
            assert!(
                failed.iterations.shifts.iter().any(|s| *s > 0.0),
                "{what}: the failed step never shifted its Newton matrix: {:?}",
                failed.iterations.shifts
            );
            assert!(probe(r, "min_volume_ratio") > 0.0, "{what}: {:?}", r.probes);
            assert_eq!(r.max_inverted_tets, 0, "{what}");
            continue;
        }
        // The kept state: the left tet scaled by f_k = 1 + (f - 1) k / 10 after k steps.
        let f: f64 = what.rsplit(' ').next().unwrap().parse().unwrap();
        let k = r.steps as f64;
        let left = 1.0 + (f - 1.0) * k / 10.0;
        let total = probe(r, "total_volume_ratio");
        let free = probe(r, "free_tet_volume_ratio");
        let (want_total, want_free, tol) = if what.contains("two-tets standard") {
            // No constraint: the free apex feels only its own tet, at rest.
            let tol = unloaded_volume_tolerance(r.vertices);
            ((1.0 + left) / 2.0, 1.0, tol)
        } else {
            // One global zone: the total within the constraint tolerance; the left tet's
            // volume is prescribed, so the free tet's ratio is 2 total - left.
            let tol = 2.0 * incompressible_volume_bound(r.tets);
            (1.0, 2.0 - left, tol)
        };
        assert!(
            (total - want_total).abs() <= tol && (free - want_free).abs() <= tol,
            "{what}: total {total} (want {want_total}), free tet {free} (want {want_free}), after {k} steps"
        );
        let inverted = usize::from(what.contains("F-bar") && f <= 0.0);
        assert_eq!(r.max_inverted_tets, inverted, "{what}: inverted tets");
    }
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
    let cases = check_cases(
        "inverted and degenerate rest meshes",
        vec![
            ("two-tets".into(), original, Expect::Converged),
            (
                "two-tets, first tet reversed".into(),
                reversed,
                Expect::Converged,
            ),
            (
                "two-tets, right tet flat".into(),
                degenerate,
                Expect::Refused("tet 1 is degenerate"),
            ),
        ],
    );
    assert_eq!(ran(&cases[0].1).probes, ran(&cases[1].1).probes);
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
            Expect::Converged,
        ));
    }
    let cases = check_cases("dynamic cube at dt = 33 ms", cases);
    for (what, o) in &cases {
        let r = ran(o);
        let total: Vec<f64> = r.history.iter().map(StepRecord::total_energy).collect();
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
