//! What the integration tests share: a fresh scratch folder per test, and the `isochor`
//! binary with its output as text.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

/// A fresh, empty scratch folder for one test (`name` unique in the test binary).
pub fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("isochor-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// Runs the `isochor` binary with `args`.
pub fn isochor(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_isochor"))
        .args(args)
        .output()
        .expect("the isochor binary runs")
}

/// Runs the `isochor` binary with `args` in the working directory `dir`.
pub fn isochor_in(args: &[&str], dir: &Path) -> Output {
    Command::new(env!("CARGO_BIN_EXE_isochor"))
        .args(args)
        .current_dir(dir)
        .output()
        .expect("the isochor binary runs")
}

/// What a run printed on stderr.
pub fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

/// What a run printed on stdout.
pub fn stdout(o: &Output) -> String {
    String::from_utf8_lossy(&o.stdout).into_owned()
}
