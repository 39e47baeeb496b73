//! Hostile inputs to the `isochor` binary: sizes beyond the machine, non-finite numbers,
//! conflicting keys, bodies the supports do not hold, obstacles inside the body at the
//! start, stale temporary outputs, and paths, tokens and bytes that must be reported
//! clearly. Each is refused with exit status 1 and a message naming the key or file, without
//! a panic and (where it could) without allocating first.

use crate::common::{isochor, scratch, stderr};
use std::path::{Path, PathBuf};
use std::process::{Command, Output};

/// Runs the binary in 64 MiB of address space (itself included): a refusal that allocated
/// the mesh, or a vector of steps, first would abort instead.
fn isochor_in_64_mib(args: &[&str]) -> Output {
    Command::new("sh")
        .arg("-c")
        .arg("ulimit -v 65536 && exec \"$0\" \"$@\"")
        .arg(env!("CARGO_BIN_EXE_isochor"))
        .args(args)
        .output()
        .expect("sh runs")
}

/// Asserts a clean refusal (status 1, no panic, nothing on stdout) whose message holds every
/// needle; returns the message.
fn refused(o: &Output, needles: &[&str]) -> String {
    let err = stderr(o);
    assert_eq!(o.status.code(), Some(1), "stderr: {err}");
    assert!(!err.contains("panicked"), "{err}");
    assert!(
        o.stdout.is_empty(),
        "{}",
        String::from_utf8_lossy(&o.stdout)
    );
    for n in needles {
        assert!(err.contains(n), "stderr lacks {n:?}: {err}");
    }
    err
}

#[test]
fn sizes_beyond_the_machine_are_refused_before_allocating() {
    let o = isochor_in_64_mib(&["run", "cantilever", "--set", "res=1000000"]);
    refused(
        &o,
        &["key 'mesh.res'", "res = 1000000", "tets", "unknowns", "GiB"],
    );
    let o = isochor_in_64_mib(&["run", "cantilever", "--set", "cells=[100000,100000,100000]"]);
    refused(
        &o,
        &["key 'mesh.cells'", "[100000, 100000, 100000]", "tets"],
    );
    // i64::MAX (the largest TOML integer): the estimate is in floating point and cannot wrap.
    let o = isochor_in_64_mib(&["run", "ball-drop", "--set", "res=9223372036854775807"]);
    refused(&o, &["key 'mesh.res'", "bytes"]);
    let o = isochor_in_64_mib(&[
        "run",
        "cantilever",
        "--set",
        "element=tet10",
        "--set",
        "res=400",
    ]);
    refused(&o, &["key 'mesh.res'", "tet10"]);
    for (scene, set, key) in [
        ("cantilever", "steps=1000000000000", "stepping.steps"),
        ("cantilever", "steps=10000000", "stepping.steps"),
        ("dynamic-cube", "frames=1000000000000", "stepping.frames"),
        ("cantilever", "every=10000000", "output.every"),
    ] {
        let o = isochor_in_64_mib(&["run", scene, "--set", set]);
        refused(&o, &[key, "limit of 1000000"]);
    }
    // A float where a count is expected is a type error, not a huge count.
    let o = isochor(&["run", "dynamic-cube", "--set", "frames=1e12"]);
    refused(&o, &["stepping", "floating point"]);
    let o = isochor(&["show", "cantilever", "--set", "res=1000000"]);
    refused(&o, &["key 'mesh.res'"]);
}

#[test]
fn a_mesh_file_is_sized_by_its_header() {
    let dir = scratch("bounds-header");
    let mesh = dir.join("huge.msh");
    std::fs::write(
        &mesh,
        "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n100000000000\n1 0 0 0\n$EndNodes\n\
         $Elements\n600000000000\n",
    )
    .unwrap();
    let o = isochor_in_64_mib(&[
        "run",
        "cantilever",
        "--set",
        &format!("mesh={}", mesh.display()),
    ]);
    refused(&o, &["key 'mesh.path'", "huge.msh", "tets"]);
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn non_finite_numbers_are_refused_naming_the_key() {
    for (set, key, what) in [
        ("gravity=[0,nan,0]", "loads.gravity[1]", "NaN"),
        ("gravity=[0, -inf, 0]", "loads.gravity[1]", "-inf"),
        ("mesh.max=[0.2, inf, 0.05]", "mesh.max[1]", "inf"),
        ("nu=nan", "material.nu", "NaN"),
    ] {
        let o = isochor(&["run", "cantilever", "--set", set]);
        refused(&o, &[&format!("key '{key}'"), what]);
    }
    let dir = scratch("bounds-nan");
    let scene = dir.join("nan.toml");
    let text = isochor(&["show", "resting-block"]).stdout;
    let text = String::from_utf8(text).unwrap()
        + "\n[selections.probe]\nsphere = { center = [0.0, nan, 0.0], radius = 1.0 }\n";
    std::fs::write(&scene, text).unwrap();
    let o = isochor(&["run", scene.to_str().unwrap()]);
    refused(&o, &["key 'selections.probe.sphere.center[1]'", "NaN"]);
    let o = isochor(&[
        "run",
        "resting-block",
        "--set",
        "obstacles.0.normal=[0, 0, inf]",
    ]);
    refused(&o, &["key 'obstacles[0].normal[2]'"]);
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn alternative_and_repeated_keys_conflict() {
    for sets in [
        ["mu=1e4", "E=3e4"],
        ["E=3e4", "young=3e4"],
        ["rho=1000", "density=1000"],
        ["nu=0.3", "material.nu=0.4"],
    ] {
        let mut args = vec!["run", "cantilever"];
        for s in &sets {
            args.extend(["--set", s]);
        }
        refused(
            &isochor(&args),
            &["conflicts with --set", "give each parameter once"],
        );
    }
    let o = isochor(&["run", "cantilever", "--set", "mu=1e4", "--set", "E=3e4"]);
    refused(&o, &["--set E", "--set mu", "alternatives"]);
    // In a scene file, too.
    let o = isochor(&["show", "cantilever", "--set", "material.mu=1e4"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let dir = scratch("bounds-both");
    let scene = dir.join("both.toml");
    let text = String::from_utf8(isochor(&["show", "cantilever"]).stdout).unwrap();
    std::fs::write(&scene, text.replace("young = ", "mu = 1e4\nyoung = ")).unwrap();
    refused(
        &isochor(&["run", scene.to_str().unwrap()]),
        &["material", "not both"],
    );
    std::fs::remove_dir_all(&dir).unwrap();
}

/// A cube under gravity with the given Dirichlet conditions (TOML) and stepping.
fn unsupported_cube(dir: &Path, dirichlet: &str, stepping: &str) -> PathBuf {
    let path = dir.join("cube.toml");
    std::fs::write(
        &path,
        format!(
            r#"name = "cube"
method = "standard"
[mesh]
generator = "box"
min = [0.0, 0.0, 0.0]
max = [1.0, 1.0, 1.0]
res = 2
[material]
young = 1e5
nu = 0.3
[selections.corner]
vertices = [0]
[selections.bottom]
plane = {{ point = [0.0, 0.0, 0.0], normal = [0.0, 0.0, 1.0] }}
{dirichlet}
[loads]
gravity = [0.0, 0.0, -9.8]
[stepping]
{stepping}
"#
        ),
    )
    .unwrap();
    path
}

#[test]
fn a_quasi_static_body_must_be_held() {
    let dir = scratch("bounds-supports");
    let quasi = "mode = \"quasi-static\"\nsteps = 1";
    for (dirichlet, free) in [
        ("", "6 of its 6"),
        ("[[dirichlet]]\nselection = \"corner\"", "3 of its 6"),
        (
            "[[dirichlet]]\nselection = \"bottom\"\naxes = \"z\"",
            "3 of its 6",
        ),
    ] {
        let scene = unsupported_cube(&dir, dirichlet, quasi);
        let o = isochor(&["run", scene.to_str().unwrap()]);
        refused(
            &o,
            &["key 'dirichlet'", free, "rigid motions", "dynamic stepping"],
        );
    }
    let scene = unsupported_cube(&dir, "[[dirichlet]]\nselection = \"bottom\"", quasi);
    let o = isochor(&["run", scene.to_str().unwrap(), "--json"]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    // Dynamics need no support: the body falls.
    let scene = unsupported_cube(&dir, "", "mode = \"dynamic\"\ndt = 0.01\nframes = 2");
    let o = isochor(&["run", scene.to_str().unwrap(), "--json"]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn an_obstacle_inside_the_body_at_the_start_is_refused() {
    // The ground through the middle of the resting block.
    let o = isochor(&[
        "run",
        "resting-block",
        "--set",
        "obstacles.0.point=[0.0, 0.0, 0.05]",
    ]);
    refused(
        &o,
        &["key 'obstacles[0]'", "half-space", "nodes lie inside it"],
    );
    // A sphere wholly inside the cantilever, which the boundary vertices would never meet.
    let dir = scratch("bounds-obstacle");
    let scene = dir.join("inside.toml");
    let text = String::from_utf8(isochor(&["show", "cantilever"]).stdout).unwrap();
    let text = text
        + "\n[[obstacles]]\nshape = \"half-space\"\npoint = [0.0, -1.0, 0.0]\nnormal = [0.0, 1.0, 0.0]\n\
           \n[[obstacles]]\nshape = \"sphere\"\ncenter = [0.1, 0.025, 0.025]\nradius = 0.02\n";
    std::fs::write(&scene, text).unwrap();
    let o = isochor(&["run", scene.to_str().unwrap()]);
    refused(&o, &["key 'obstacles[1]'", "sphere", "1 of its 81 nodes"]);
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn the_builtin_scenes_with_obstacles_start_clear_of_them() {
    let names = String::from_utf8(isochor(&["list"]).stdout).unwrap();
    let mut with_obstacles = 0;
    for name in names.lines() {
        let shown = String::from_utf8(isochor(&["show", name]).stdout).unwrap();
        if !shown.contains("[[obstacles]]") {
            continue;
        }
        with_obstacles += 1;
        let mut args = vec!["run", name, "--json"];
        let reduced = isochor_scenes::builtin::reduced(name).unwrap();
        for s in reduced {
            args.extend(["--set", s]);
        }
        let o = isochor(&args);
        assert_eq!(o.status.code(), Some(0), "{name}: {}", stderr(&o));
    }
    assert!(with_obstacles >= 3, "{names}");
}

#[test]
fn a_killed_runs_temporary_folder_is_removed_by_the_next_run() {
    let dir = scratch("bounds-stale");
    let out = dir.join("out");
    let temp = dir.join(".out.tmp");
    let mut child = Command::new(env!("CARGO_BIN_EXE_isochor"))
        .args(["run", "dynamic-cube", "--set", "res=4", "--out"])
        .arg(&out)
        .stdout(std::process::Stdio::null())
        .stderr(std::process::Stdio::null())
        .spawn()
        .unwrap();
    let start = std::time::Instant::now();
    while !temp.join("frame_00000.vtu").exists() {
        assert!(
            start.elapsed().as_secs() < 60,
            "no temporary output appeared"
        );
        std::thread::sleep(std::time::Duration::from_millis(20));
    }
    child.kill().unwrap();
    child.wait().unwrap();
    assert!(temp.exists() && !out.exists());
    let o = isochor(&["run", "two-tets", "--out", out.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    assert!(out.join("summary.json").is_file());
    let names: Vec<_> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().file_name())
        .collect();
    assert_eq!(names, ["out"]);
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn paths_that_do_not_exist_or_are_folders_say_so() {
    let dir = scratch("bounds-paths");
    let missing = dir.join("no-such.toml");
    let o = isochor(&["run", missing.to_str().unwrap()]);
    let err = refused(&o, &["no-such.toml", "no such scene file"]);
    assert!(!err.contains("not a built-in scene"), "{err}");
    let o = isochor(&["run", "sub/scene"]);
    refused(&o, &["sub/scene", "no such scene file"]);
    let o = isochor(&["run", "cantilevr"]);
    refused(&o, &["not a built-in scene", "cantilever"]);
    let o = isochor(&["run", dir.to_str().unwrap()]);
    refused(&o, &["is a directory, not a scene file"]);
    let folder = dir.join("mesh.msh");
    std::fs::create_dir(&folder).unwrap();
    for mesh in [&folder, &dir] {
        let o = isochor(&[
            "run",
            "cantilever",
            "--set",
            &format!("mesh={}", mesh.display()),
        ]);
        refused(&o, &["is a directory, not a mesh file"]);
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn long_tokens_and_binary_bytes_are_not_echoed_raw() {
    let dir = scratch("bounds-tokens");
    let long = "x".repeat(300);
    let o = isochor(&["run", &long]);
    let err = refused(&o, &["... (300 characters)"]);
    assert!(err.len() < 1000, "{err}");
    let mesh = dir.join("long.msh");
    std::fs::write(
        &mesh,
        format!("$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n1\n1 0 {long} 0\n$EndNodes\n"),
    )
    .unwrap();
    let o = isochor(&[
        "run",
        "cantilever",
        "--set",
        &format!("mesh={}", mesh.display()),
    ]);
    let err = refused(&o, &["long.msh:6", "y coordinate", "... (300 characters)"]);
    assert!(err.len() < 400, "{err}");
    let garbage = dir.join("garbage.msh");
    let bytes: Vec<u8> = (0..2000u32).map(|i| (i * 7919 % 256) as u8).collect();
    std::fs::write(&garbage, bytes).unwrap();
    let o = isochor(&[
        "run",
        "cantilever",
        "--set",
        &format!("mesh={}", garbage.display()),
    ]);
    refused(&o, &["garbage.msh:1", "\\u{"]);
    assert!(
        o.stderr
            .iter()
            .all(|&b| b == b'\n' || (b' '..=b'~').contains(&b) || b >= 0x80),
        "control bytes echoed: {:?}",
        stderr(&o)
    );
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn mesh_errors_name_the_files_own_tags() {
    let dir = scratch("bounds-tags");
    let mesh = dir.join("flat.msh");
    // Runs the cantilever on a Gmsh 2.2 file of nodes 10, 20, 30, 40 and element 42.
    let run_on = |nodes: &str, element: &str| {
        std::fs::write(
            &mesh,
            format!(
                "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n4\n{nodes}$EndNodes\n$Elements\n1\n{element}\n$EndElements\n"
            ),
        )
        .unwrap();
        isochor(&[
            "run",
            "cantilever",
            "--set",
            &format!("mesh={}", mesh.display()),
        ])
    };
    // The last node in the plane of the others.
    let o = run_on(
        "10 0 0 0\n20 1 0 0\n30 0 1 0\n40 1 1 0\n",
        "42 4 2 1 1 10 20 30 40",
    );
    refused(
        &o,
        &[
            "flat.msh:13",
            "tet 42 is degenerate",
            "numbered as in the file",
        ],
    );
    let o = run_on(
        "10 0 0 0\n20 1 0 0\n30 0 1 0\n40 0 0 1\n",
        "42 4 2 1 1 10 20 30 30",
    );
    refused(
        &o,
        &["tet 42: vertex 30 appears more than once in [10, 20, 30, 30]"],
    );
    std::fs::remove_dir_all(&dir).unwrap();
}

/// A dotted key of 30,000 levels, on the command line or in a scene's variant, is refused.
/// Before: the nested tables it built overflowed the stack (exit status 134).
#[test]
fn keys_nested_beyond_any_scene_key_are_refused() {
    let deep = vec!["a"; 30_000].join(".");
    let o = isochor(&["run", "two-tets", "--set", &format!("{deep}=1")]);
    refused(&o, &["--set a.a.a", "30000 dotted segments", "at most 32"]);
    let dir = scratch("bounds-deep-variant");
    let shown = isochor(&["show", "two-tets"]);
    let scene = format!(
        "{}\n[variants.deep]\n\"{deep}\" = 1\n",
        String::from_utf8_lossy(&shown.stdout)
    );
    let path = dir.join("deep.toml");
    std::fs::write(&path, scene).unwrap();
    let o = isochor(&["run", path.to_str().unwrap(), "--variant", "deep"]);
    refused(&o, &["30000 dotted segments"]);
    std::fs::remove_dir_all(&dir).unwrap();
}

/// Scene and mesh paths that are devices or FIFOs (or links to them) are refused before
/// they are read. Before: `/dev/zero` aborted on an 8 GiB allocation, `/dev/urandom` was
/// read for ever and a FIFO blocked without a word.
#[cfg(unix)]
#[test]
fn devices_and_fifos_are_refused_before_reading() {
    let dir = scratch("bounds-devices");
    let zero = dir.join("zero.msh");
    std::os::unix::fs::symlink("/dev/zero", &zero).unwrap();
    let o = isochor_in_64_mib(&[
        "run",
        "two-tets",
        "--set",
        &format!("mesh={}", zero.display()),
    ]);
    refused(&o, &["zero.msh", "is a device, not a regular file"]);
    let random = dir.join("random.toml");
    std::os::unix::fs::symlink("/dev/urandom", &random).unwrap();
    let o = isochor(&["run", random.to_str().unwrap()]);
    refused(&o, &["random.toml", "is a device"]);
    let fifo = dir.join("pipe.node");
    let made = Command::new("mkfifo").arg(&fifo).status().unwrap();
    assert!(made.success());
    std::fs::write(dir.join("pipe.ele"), "1 4 0\n1 1 2 3 4\n").unwrap();
    let o = isochor(&[
        "run",
        "two-tets",
        "--set",
        &format!("mesh={}", fifo.display()),
    ]);
    refused(&o, &["pipe.node", "FIFO"]);
    std::fs::remove_dir_all(&dir).unwrap();
}

/// `min_increment` below the floor of 30 halvings of the run is refused. Before: 1e-300 was
/// accepted and a failing step halved its increment for ever.
#[test]
fn a_min_increment_below_the_floor_is_refused() {
    let o = isochor(&["run", "two-tets", "--set", "min_increment=1e-300"]);
    refused(&o, &["stepping.min_increment", "1e-300", "1e-9"]);
    let o = isochor(&["check", "two-tets", "--set", "min_increment=1e-9"]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
}

/// A load curve of more than 10,000 points is refused before any solve, naming it. Before:
/// 100,001 corners made 100,001 solves, and the step limit did not count them.
#[test]
fn load_curves_with_too_many_corners_are_refused() {
    let n = 100_001;
    let points: Vec<String> = (0..n)
        .map(|k| {
            let s = k as f64 / (n - 1) as f64;
            format!("[{s}, {}]", (k % 2) as f64)
        })
        .collect();
    let shown = isochor(&["show", "two-tets"]);
    let scene = String::from_utf8_lossy(&shown.stdout).replacen(
        "[[dirichlet]]\n",
        &format!("[[dirichlet]]\ncurve = [{}]\n", points.join(", ")),
        1,
    );
    let dir = scratch("bounds-corners");
    let path = dir.join("corners.toml");
    std::fs::write(&path, scene).unwrap();
    let o = isochor(&["run", path.to_str().unwrap()]);
    refused(&o, &["dirichlet.0.curve", "100001 points", "at most 10000"]);
    std::fs::remove_dir_all(&dir).unwrap();
}

/// What a scene cannot mean is refused naming its key. Before, each was accepted and the
/// run reported converged: a curve wholly beyond the run's end (its corners never reached),
/// `gravity_curve` without gravity, a curve on a fixed support, `first_increment` with fixed
/// stepping (all silently ignored).
#[test]
fn keys_that_change_nothing_are_refused() {
    for (scene, sets, key) in [
        (
            "two-tets",
            &["dirichlet.0.curve=[[2, 0], [3, 1]]"][..],
            "dirichlet.0.curve",
        ),
        (
            "two-tets",
            &["loads.gravity_curve=[[0, 0], [1, 1]]"],
            "loads.gravity_curve",
        ),
        (
            "pressure-cube",
            &["dirichlet.0.curve=[[0, 0], [1, 1]]"],
            "dirichlet.0.curve",
        ),
        (
            "two-tets",
            &["increments=fixed", "first_increment=0.5"],
            "stepping.first_increment",
        ),
        (
            "two-tets",
            &["increments=fixed", "min_increment=0.01"],
            "stepping.min_increment",
        ),
    ] {
        let mut args = vec!["check", scene];
        for s in sets {
            args.extend(["--set", s]);
        }
        refused(&isochor(&args), &[key]);
    }
}

/// What a user may mean is run, with a warning on stderr and in the summary: a massless
/// body whose only load is gravity, an obstacle that touches nothing. Before: nothing said
/// that the run computed all zeros, or that the obstacle never acted.
#[test]
fn questionable_runs_warn_on_stderr_and_in_the_summary() {
    let o = isochor(&[
        "run",
        "cantilever",
        "--set",
        "rho=0",
        "--set",
        "res=2",
        "--json",
    ]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let summary: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    let warning = "material.rho = 0 and gravity is the only load";
    assert!(
        summary["warnings"][0].as_str().unwrap().contains(warning),
        "{summary}"
    );
    assert!(stderr(&o).contains(warning), "{}", stderr(&o));
    let dir = scratch("bounds-far-obstacle");
    let shown = isochor(&["show", "two-tets"]);
    let scene = format!(
        "{}\n[[obstacles]]\nshape = \"half-space\"\npoint = [0.0, 0.0, -10.0]\n",
        String::from_utf8_lossy(&shown.stdout)
    );
    let path = dir.join("far.toml");
    std::fs::write(&path, scene).unwrap();
    let o = isochor(&["run", path.to_str().unwrap(), "--json"]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let summary: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    let warning = "obstacles.0 touched nothing";
    assert!(
        summary["warnings"][0].as_str().unwrap().contains(warning),
        "{summary}"
    );
    assert!(stderr(&o).contains(warning));
    std::fs::remove_dir_all(&dir).unwrap();
}

/// An invalid obstacle is named by its index. Before: "obstacle: a sphere needs ...", with
/// no index.
#[test]
fn obstacle_errors_name_the_obstacle() {
    let dir = scratch("bounds-obstacle-index");
    let shown = isochor(&["show", "two-tets"]);
    let scene = format!(
        "{}\n[[obstacles]]\nshape = \"half-space\"\npoint = [0.0, 0.0, -10.0]\n\n\
         [[obstacles]]\nshape = \"sphere\"\ncenter = [0.0, 0.0, -10.0]\nradius = -1.0\n",
        String::from_utf8_lossy(&shown.stdout)
    );
    let path = dir.join("obstacles.toml");
    std::fs::write(&path, scene).unwrap();
    refused(
        &isochor(&["run", path.to_str().unwrap()]),
        &["obstacle 1", "sphere"],
    );
    std::fs::remove_dir_all(&dir).unwrap();
}
