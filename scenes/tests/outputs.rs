//! Output folders against other runs and kills, through the `isochor` binary: the lock held
//! by another process, a kill between the two renames of the commit (the `ISOCHOR_FAULT`
//! hook of debug builds), and `--out` paths that cannot be written, refused before the solve.

use crate::common::{isochor, scratch, stderr};
use std::path::Path;
use std::process::{Command, Output};

fn names_in(dir: &Path) -> Vec<String> {
    let mut names: Vec<_> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    names.sort();
    names
}

fn run_into(out: &Path, extra: &[&str]) -> Output {
    let mut args = vec!["run", "two-tets", "--out", out.to_str().unwrap()];
    args.extend(extra);
    isochor(&args)
}

/// A second process is refused while another holds the folder's lock, and the output is
/// untouched. Before: both ran and the folder mixed their frames.
#[cfg(unix)]
#[test]
fn a_run_is_refused_while_another_process_holds_the_folder() {
    let dir = scratch("outputs-lock");
    let out = dir.join("out");
    assert!(run_into(&out, &[]).status.success());
    let lock = std::fs::File::create(dir.join(".out.lock")).unwrap();
    rustix::fs::flock(&lock, rustix::fs::FlockOperation::NonBlockingLockExclusive).unwrap();
    let o = run_into(&out, &[]);
    assert_eq!(o.status.code(), Some(1));
    let err = stderr(&o);
    assert!(
        err.contains("another isochor run") && err.contains("out"),
        "{err}"
    );
    assert!(out.join("summary.json").is_file());
    drop(lock);
    assert!(run_into(&out, &[]).status.success());
    assert_eq!(names_in(&dir), ["out"]);
    std::fs::remove_dir_all(&dir).unwrap();
}

/// Killed between the two renames of its commit (the process aborts there), a run leaves
/// both outputs beside the folder, its lock released by its death; a run failing on a bad key
/// leaves them so, and the next run completes the commit. Before: the folder vanished and the
/// next run, even a failing one, deleted both outputs.
#[cfg(debug_assertions)]
#[test]
fn a_kill_between_the_renames_loses_nothing() {
    let dir = scratch("outputs-window");
    let out = dir.join("out");
    assert!(run_into(&out, &[]).status.success());
    let o = Command::new(env!("CARGO_BIN_EXE_isochor"))
        .args(["run", "two-tets", "--set", "steps=2", "--out"])
        .arg(&out)
        .env("ISOCHOR_FAULT", "commit-between-renames")
        .output()
        .unwrap();
    assert!(!o.status.success(), "the fault point was not reached");
    assert!(!out.exists());
    assert_eq!(names_in(&dir), [".out.lock", ".out.new", ".out.old"]);
    let o = run_into(&out, &["--set", "no_such_key=1"]);
    assert_eq!(o.status.code(), Some(1));
    assert_eq!(names_in(&dir), [".out.lock", ".out.new", ".out.old"]);
    let o = isochor(&["check", "two-tets"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let o = run_into(&out, &["--set", "steps=3", "--json"]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert_eq!(names_in(&dir), ["out"]);
    let summary = std::fs::read_to_string(out.join("summary.json")).unwrap();
    assert!(summary.contains("\"steps\": 3"), "{summary}");
    std::fs::remove_dir_all(&dir).unwrap();
}

/// An `--out` that cannot be written is refused at once, naming it. Before: `/proc/x` named
/// `/proc/.x.tmp`, and a dangling link failed only after the whole solve.
#[cfg(unix)]
#[test]
fn unwritable_and_dangling_outputs_are_refused_before_the_run() {
    let o = isochor(&["run", "dynamic-cube", "--out", "/proc/x"]);
    assert_eq!(o.status.code(), Some(1));
    let err = stderr(&o);
    assert!(err.contains("/proc/x") && !err.contains(".x.tmp"), "{err}");
    let dir = scratch("outputs-dangling");
    let link = dir.join("link");
    std::os::unix::fs::symlink(dir.join("gone"), &link).unwrap();
    let o = isochor(&["run", "dynamic-cube", "--out", link.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(1));
    let err = stderr(&o);
    assert!(err.contains("link") && err.contains("gone"), "{err}");
    assert!(o.stdout.is_empty());
    assert_eq!(names_in(&dir), ["link"]);
    std::fs::remove_dir_all(&dir).unwrap();
}
