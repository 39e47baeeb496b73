//! The `isochor` binary end to end: the command-line contract of docs/contracts.md.

use crate::common::{isochor, scratch, stderr, stdout};
use isochor_mesh::io::read_vtu_file;
use std::path::Path;
use std::process::{Command, Output};

fn assert_failed_cleanly(o: &Output, out: &Path, needles: &[&str]) {
    assert_eq!(o.status.code(), Some(1), "stderr: {}", stderr(o));
    assert!(
        stdout(o).is_empty(),
        "stdout must stay empty: {}",
        stdout(o)
    );
    let err = stderr(o);
    for n in needles {
        assert!(err.contains(n), "stderr lacks {n:?}: {err}");
    }
    assert!(
        !out.exists(),
        "{} must not exist after an error",
        out.display()
    );
    let leftovers: Vec<_> = std::fs::read_dir(out.parent().unwrap()).unwrap().collect();
    assert!(leftovers.is_empty(), "partial output left: {leftovers:?}");
}

#[test]
fn list_prints_every_builtin_scene_one_per_line() {
    let o = isochor(&["list"]);
    assert!(o.status.success());
    let lines: Vec<String> = stdout(&o).lines().map(str::to_string).collect();
    let names: Vec<String> = isochor_scenes::builtin::names()
        .map(str::to_string)
        .collect();
    assert_eq!(lines, names);
    for expected in [
        "cantilever",
        "compressed-block",
        "inflated-tube",
        "two-tets",
        "zoning-beam",
    ] {
        assert!(lines.iter().any(|l| l == expected), "{expected}");
    }
}

#[test]
fn a_bad_key_is_named_with_the_valid_ones_and_writes_nothing() {
    let dir = scratch("cli-bad-key");
    let out = dir.join("out");
    let o = isochor(&[
        "run",
        "cantilever",
        "--set",
        "nuu=0.3",
        "--out",
        out.to_str().unwrap(),
        "--json",
    ]);
    assert_failed_cleanly(&o, &out, &["nuu", "valid:", "nu,", "res", "method"]);
    // A dotted key into a table that does not have it: serde names the valid fields.
    let o = isochor(&[
        "run",
        "cantilever",
        "--set",
        "material.poisson=0.3",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert_failed_cleanly(&o, &out, &["poisson", "expected one of", "`nu`"]);
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn a_bad_value_is_named_and_writes_nothing() {
    let dir = scratch("cli-bad-value");
    let out = dir.join("out");
    let o = isochor(&[
        "run",
        "cantilever",
        "--set",
        "nu=abc",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert_failed_cleanly(&o, &out, &["material.nu", "expected f64"]);
    let o = isochor(&[
        "run",
        "cantilever",
        "--set",
        "method=mixed",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert_failed_cleanly(&o, &out, &["method", "mixed-p1", "standard", "zonal"]);
    let o = isochor(&[
        "run",
        "compressed-block",
        "--set",
        "res=6",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert_failed_cleanly(&o, &out, &["mesh.res", "multiple of 4"]);
    let o = isochor(&[
        "run",
        "cantilever",
        "--set",
        "nu=0.7",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert_failed_cleanly(&o, &out, &["nu"]);
    let o = isochor(&["compare", "cantilever", "--methods", "standard,bogus"]);
    assert_eq!(o.status.code(), Some(1));
    assert!(
        stderr(&o).contains("bogus") && stderr(&o).contains("mixed-p1"),
        "{}",
        stderr(&o)
    );
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn a_missing_file_is_named_and_writes_nothing() {
    let dir = scratch("cli-missing");
    let out = dir.join("out");
    let scene = dir.join("no-such-scene.toml");
    let o = isochor(&[
        "run",
        scene.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
    ]);
    assert_failed_cleanly(&o, &out, &["no-such-scene.toml", "cantilever"]);
    let mesh = dir.join("no-such-mesh.msh");
    let o = isochor(&[
        "run",
        "cantilever",
        "--set",
        &format!("mesh={}", mesh.display()),
        "--out",
        out.to_str().unwrap(),
    ]);
    assert_failed_cleanly(&o, &out, &["no-such-mesh.msh", "not found"]);
    let o = isochor(&[
        "run",
        "cantilever",
        "--set",
        "mesh=shape.stl",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert_failed_cleanly(&o, &out, &[".stl", ".msh", ".vtu"]);
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn a_copied_scene_file_with_a_typo_is_rejected() {
    let dir = scratch("cli-typo");
    let out = dir.join("out");
    let shown = isochor(&["show", "cantilever"]);
    assert!(shown.status.success());
    let text = stdout(&shown).replace("[material]\n", "[material]\nyoungs_modulus = 1.0\n");
    let path = dir.join("my.toml");
    std::fs::write(&path, text).unwrap();
    let o = isochor(&[
        "run",
        path.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
    ]);
    std::fs::remove_file(&path).unwrap();
    assert_failed_cleanly(&o, &out, &["my.toml", "youngs_modulus", "expected one of"]);
    std::fs::remove_dir_all(&dir).unwrap();
}

const CONTRACT_KEYS: [&str; 13] = [
    "scene",
    "method",
    "nu",
    "vertices",
    "tets",
    "dofs",
    "steps",
    "newton_iterations",
    "converged",
    "wall_time_s",
    "volume_change",
    "probes",
    "max_inverted_tets",
];

#[test]
fn run_json_is_one_object_with_every_contract_key_and_out_writes_everything() {
    let dir = scratch("cli-json");
    let out = dir.join("out");
    let o = isochor(&[
        "run",
        "cantilever",
        "--set",
        "res=1",
        "--set",
        "steps=2",
        "--set",
        "method=mixed-p1",
        "--json",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let text = stdout(&o);
    assert_eq!(
        text.trim().lines().count(),
        1,
        "exactly one JSON line: {text}"
    );
    let v: serde_json::Value = serde_json::from_str(&text).unwrap();
    for key in CONTRACT_KEYS {
        assert!(v.get(key).is_some(), "missing key {key}: {v}");
    }
    assert_eq!(v["scene"], "cantilever");
    assert_eq!(v["method"], "mixed-p1");
    assert_eq!(v["nu"], 0.4999);
    assert_eq!(v["tets"], 6 * 4);
    assert_eq!(v["steps"], 2);
    assert!(v["converged"].is_boolean());
    assert!(v["max_inverted_tets"].is_u64());
    let probes = v["probes"].as_object().unwrap();
    assert!(
        probes["tip_deflection"].as_f64().unwrap() > 0.0,
        "the tip bends down: {v}"
    );
    assert!(probes.contains_key("end_deflection"));
    for f in [
        "summary.json",
        "iterations.csv",
        "steps.csv",
        "residuals.png",
        "frame.pvd",
        "frame_00000.vtu",
        "frame_00002.vtu",
    ] {
        assert!(out.join(f).is_file(), "{f} missing");
    }
    let summary: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap()).unwrap();
    for key in CONTRACT_KEYS {
        assert!(summary.get(key).is_some(), "summary.json lacks {key}");
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

/// `vtu_encoding` chooses the frames' format (flat or dotted key); `auto` keeps small meshes
/// in ASCII, and both formats hold the same data.
#[test]
fn vtu_encoding_chooses_ascii_or_binary_frames_with_the_same_data() {
    let dir = scratch("cli-encoding");
    let frame = |name: &str, set: Option<&str>| {
        let out = dir.join(name);
        let mut args = vec!["run", "cantilever", "--set", "res=1", "--set", "steps=1"];
        if let Some(s) = set {
            args.extend(["--set", s]);
        }
        args.extend(["--out", out.to_str().unwrap()]);
        let o = isochor(&args);
        assert!(o.status.success(), "{}", stderr(&o));
        let path = out.join("frame_00001.vtu");
        let text = String::from_utf8_lossy(&std::fs::read(&path).unwrap()).into_owned();
        (read_vtu_file(&path).unwrap(), text)
    };
    let (auto, auto_text) = frame("auto", None);
    let (ascii, ascii_text) = frame("ascii", Some("output.vtu_encoding=ascii"));
    let (binary, binary_text) = frame("binary", Some("vtu_encoding=binary"));
    assert!(auto_text.contains(r#"format="ascii""#));
    assert!(!auto_text.contains(r#"format="appended""#));
    assert!(ascii_text.contains(r#"format="ascii""#));
    assert!(binary_text.contains(r#"compressor="vtkZLibDataCompressor""#));
    assert!(!binary_text.contains(r#"format="ascii""#));
    assert_eq!(auto, ascii);
    assert_eq!(ascii, binary);
    let o = isochor(&["show", "cantilever", "--set", "vtu_encoding=zip"]);
    assert!(!o.status.success());
    assert!(stderr(&o).contains("output.vtu_encoding"), "{}", stderr(&o));
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn compare_prints_a_table_and_writes_csv_and_markdown() {
    let dir = scratch("cli-compare");
    let out = dir.join("out");
    let o = isochor(&[
        "compare",
        "cantilever",
        "--methods",
        "standard,mixed-p1",
        "--set",
        "res=1",
        "--set",
        "steps=1",
        "--sweep",
        "nu=0.49,0.4999",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let table = stdout(&o);
    assert!(
        table.contains("tip_deflection") && table.contains("mixed-p1") && table.contains("0.4999"),
        "{table}"
    );
    let csv = std::fs::read_to_string(out.join("compare.csv")).unwrap();
    assert_eq!(csv.lines().count(), 1 + 4, "{csv}");
    assert!(std::fs::read_to_string(out.join("compare.md"))
        .unwrap()
        .contains("| nu |"));
    std::fs::remove_dir_all(&dir).unwrap();
}

/// A run that fails says so in its exit code and JSON, keeps the accepted steps' outputs, and
/// logs the failed step's iterations last in `iterations.csv` (with the stiffness shift).
#[test]
fn a_failed_run_logs_the_failed_step() {
    let dir = scratch("cli-failed");
    let out = dir.join("out");
    let o = isochor(&[
        "run",
        "cantilever",
        "--set",
        "res=1",
        "--set",
        "steps=2",
        "--set",
        "increments=fixed",
        "--set",
        "solver.max_iterations=2",
        "--json",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(3), "{}", stderr(&o));
    let v: serde_json::Value = serde_json::from_str(&stdout(&o)).unwrap();
    assert_eq!(v["converged"], false);
    assert_eq!(v["failed_step"], 1);
    let log = std::fs::read_to_string(out.join("iterations.csv")).unwrap();
    let mut lines = log.lines();
    assert_eq!(
        lines.next(),
        Some("step,t,iteration,force_residual,constraint_residual,volume_error,step_length,backtracks,shift,attempt,hessian_projected")
    );
    let rows: Vec<Vec<&str>> = lines.map(|l| l.split(',').collect()).collect();
    // Two iterations of step 1, then its final residuals (no step length, no shift).
    assert_eq!(rows.len(), 3, "{log}");
    assert!(rows.iter().all(|r| r[0] == "1" && r.len() == 11), "{log}");
    assert!(
        rows[..2].iter().all(|r| r[8].parse::<f64>().is_ok()),
        "{log}"
    );
    assert_eq!(rows[2][8], "", "{log}");
    // No barrier contact here: no iteration projected its Hessian.
    assert!(rows[..2].iter().all(|r| r[10] == "0"), "{log}");
    assert_eq!(rows[2][10], "", "{log}");
    std::fs::remove_dir_all(&dir).unwrap();
}

/// A run with `--checkpoint-every` killed part way leaves its unfinished folder with a
/// checkpoint; `isochor resume DIR` finishes it with the uninterrupted run's results, bit for
/// bit (the final states of the two checkpoints are equal), and refuses to resume it twice.
#[test]
fn a_killed_run_resumes_to_the_uninterrupted_result() {
    let dir = scratch("cli-resume");
    let run_args = |out: &Path| -> Vec<String> {
        [
            "run",
            "dynamic-cube",
            "--set",
            "res=5",
            "--set",
            "frames=120",
            "--checkpoint-every",
            "3",
            "--json",
            "--out",
        ]
        .iter()
        .map(|s| s.to_string())
        .chain([out.to_str().unwrap().to_string()])
        .collect()
    };
    let whole = dir.join("whole");
    let args = run_args(&whole);
    let o = isochor(&args.iter().map(String::as_str).collect::<Vec<_>>());
    assert!(o.status.success(), "{}", stderr(&o));
    let uninterrupted: serde_json::Value = serde_json::from_str(&stdout(&o)).unwrap();

    let cut = dir.join("cut");
    let mut child = Command::new(env!("CARGO_BIN_EXE_isochor"))
        .args(run_args(&cut))
        .stdout(std::process::Stdio::null())
        .stderr(std::process::Stdio::null())
        .spawn()
        .unwrap();
    let checkpoint = dir.join(".cut.tmp").join("checkpoint.toml");
    let start = std::time::Instant::now();
    while !checkpoint.exists() && start.elapsed().as_secs() < 120 {
        std::thread::sleep(std::time::Duration::from_millis(5));
    }
    child.kill().unwrap();
    child.wait().unwrap();
    assert!(
        !cut.exists(),
        "the run finished before it could be killed: make it longer"
    );
    let o = isochor(&["resume", cut.to_str().unwrap(), "--json"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let resumed: serde_json::Value = serde_json::from_str(&stdout(&o)).unwrap();
    for key in [
        "steps",
        "newton_iterations",
        "volume_change",
        "probes",
        "converged",
    ] {
        assert_eq!(resumed[key], uninterrupted[key], "{key}");
    }
    let solver = |d: &Path| {
        let text = std::fs::read_to_string(d.join("checkpoint.toml")).unwrap();
        text.parse::<toml::Table>().unwrap()["solver"].clone()
    };
    assert!(solver(&cut) == solver(&whole), "the final states differ");
    assert!(!dir.join(".cut.tmp").exists());

    let again = isochor(&["resume", cut.to_str().unwrap()]);
    assert_eq!(again.status.code(), Some(1));
    assert!(
        stderr(&again).contains("already finished"),
        "{}",
        stderr(&again)
    );
    let none = isochor(&["resume", dir.join("nothing").to_str().unwrap()]);
    assert!(
        stderr(&none).contains("no interrupted run"),
        "{}",
        stderr(&none)
    );
    std::fs::remove_dir_all(&dir).unwrap();
}

/// Frames carry the von Mises stress (every scene) and the velocity (dynamic scenes): the
/// velocity of the last frame is its displacement increment over `dt`.
#[test]
fn frames_carry_von_mises_stress_and_velocity() {
    use isochor_mesh::io::{read_vtu_file, FieldValues};
    let dir = scratch("cli-fields");
    let out = dir.join("out");
    let o = isochor(&[
        "run",
        "dynamic-cube",
        "--set",
        "res=2",
        "--set",
        "frames=2",
        "--set",
        "every=1",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let frame = |k: usize| read_vtu_file(out.join(format!("frame_{k:05}.vtu"))).unwrap();
    let (one, two) = (frame(1), frame(2));
    let vector = |f: &isochor_mesh::io::VtuFile, name: &str| match &f
        .point_data
        .iter()
        .find(|d| d.name == name)
        .unwrap()
        .values
    {
        FieldValues::Vector(v) => v.clone(),
        _ => panic!("{name} is not a vector field"),
    };
    let (u1, u2, v2) = (
        vector(&one, "displacement"),
        vector(&two, "displacement"),
        vector(&two, "velocity"),
    );
    for ((a, b), v) in u1.iter().zip(&u2).zip(&v2) {
        assert!((v - (b - a) / 0.008).norm() <= 1e-9 * (1.0 + v.norm()));
    }
    let Some(FieldValues::Scalar(vm)) = two
        .cell_data
        .iter()
        .find(|d| d.name == "von_mises")
        .map(|d| &d.values)
    else {
        panic!("no von_mises cell data");
    };
    assert!(vm.iter().all(|s| s.is_finite() && *s >= 0.0) && vm.iter().any(|s| *s > 0.0));
    std::fs::remove_dir_all(&dir).unwrap();
}

/// `isochor penalties --out DIR` writes penalties.csv and penalties.png (Fig. 3 of Sheen et
/// al. 2021), and every CSV value is the penalty function's own at that `J` (written in the
/// shortest form that reads back exactly, so compared exactly), over `J` in `(0, 3]`.
#[test]
fn penalties_writes_the_csv_and_png_of_fig_3() {
    use isochor_energies::{
        LogPenalty, QuadraticPenalty, SheenPenalty, Snh2Penalty, StvkPenalty, VolumetricPenalty,
    };
    let dir = scratch("cli-penalties");
    let out = dir.join("fig3");
    let o = isochor(&["penalties", "--out", out.to_str().unwrap()]);
    assert!(o.status.success(), "stderr: {}", stderr(&o));
    let png = std::fs::read(out.join("penalties.png")).unwrap();
    assert_eq!(&png[1..4], b"PNG");
    let csv = std::fs::read_to_string(out.join("penalties.csv")).unwrap();
    let mut lines = csv.lines();
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    let penalties: [(&str, Box<dyn VolumetricPenalty>); 6] = [
        ("neo_hookean", Box::new(LogPenalty)),
        ("stable_neo_hookean", Box::new(QuadraticPenalty)),
        ("snh2", Box::new(Snh2Penalty)),
        ("kikuuwe_stvk", Box::new(StvkPenalty)),
        ("ours_beta_1", Box::new(SheenPenalty::new(1.0).unwrap())),
        ("ours_beta_6", Box::new(SheenPenalty::new(6.0).unwrap())),
    ];
    let mut expected_header = vec!["J".to_string()];
    for (name, _) in &penalties {
        expected_header.extend([format!("U_{name}"), format!("dU_{name}")]);
    }
    assert_eq!(header, expected_header);
    let rows: Vec<Vec<f64>> = lines
        .map(|l| l.split(',').map(|v| v.parse().unwrap()).collect())
        .collect();
    assert!(rows.len() >= 100, "{} samples", rows.len());
    let (first, last) = (rows[0][0], rows[rows.len() - 1][0]);
    assert!(
        first > 0.0 && first <= 0.01 && last == 3.0,
        "J from {first} to {last}"
    );
    for row in &rows {
        let j = row[0];
        for (k, (name, u)) in penalties.iter().enumerate() {
            assert_eq!(row[1 + 2 * k], u.value(j).unwrap(), "U_{name}({j})");
            assert_eq!(
                row[2 + 2 * k],
                u.first_derivative(j).unwrap(),
                "dU_{name}({j})"
            );
        }
    }
    std::fs::remove_dir_all(&dir).unwrap();
}
