//! Shared helpers of the scene-level studies: run a built-in scene (or one of its variants)
//! with `--set` overrides through the scenes library, time it, and cache results that
//! several tests of one binary need.

#![allow(dead_code)]

use isochor_scenes::{load_scene, run_scene, Override, RunOptions, RunResult};
use std::collections::HashMap;
use std::sync::{Arc, Mutex, OnceLock};
use std::time::Instant;

/// Runs `scene` (a built-in name) with an optional variant and `KEY=VALUE` overrides, and
/// prints one line with the outcome and the wall time. Panics only on a scene that cannot
/// be loaded or built (a bug of the test, not of the solver).
pub fn run(scene: &str, variant: Option<&str>, sets: &[&str]) -> RunResult {
    let overrides: Vec<Override> = sets
        .iter()
        .map(|s| Override::parse(s).unwrap_or_else(|e| panic!("{s}: {e}")))
        .collect();
    let loaded = load_scene(scene, variant, &overrides)
        .unwrap_or_else(|e| panic!("{scene} {variant:?} {sets:?}: {e}"));
    let start = Instant::now();
    let (result, _) = run_scene(&loaded, &RunOptions::default())
        .unwrap_or_else(|e| panic!("{scene} {variant:?} {sets:?}: {e}"));
    eprintln!(
        "[{:7.2} s] {scene} {} {sets:?}: {} tets, {} dofs, {} Newton iterations, converged {}, volume change {:+.3e}, probes {:?}{}",
        start.elapsed().as_secs_f64(),
        variant.unwrap_or(""),
        result.tets,
        result.dofs,
        result.newton_iterations,
        result.converged,
        result.volume_change,
        result.probes,
        result
            .error
            .as_ref()
            .map(|e| format!(", error at step {:?}: {e}", result.failed_step))
            .unwrap_or_default()
    );
    result
}

type Cell = Arc<OnceLock<RunResult>>;

/// [`run`], computed once per process for the same arguments: tests of one binary that
/// need the same (expensive) run share it; a second caller waits for the first.
pub fn run_cached(scene: &str, variant: Option<&str>, sets: &[&str]) -> RunResult {
    static CACHE: OnceLock<Mutex<HashMap<String, Cell>>> = OnceLock::new();
    let key = format!("{scene}|{variant:?}|{sets:?}");
    let cell: Cell = CACHE
        .get_or_init(Default::default)
        .lock()
        .unwrap()
        .entry(key)
        .or_default()
        .clone();
    cell.get_or_init(|| run(scene, variant, sets)).clone()
}

/// Asserts that a run converged, naming the run and its error otherwise.
pub fn assert_converged(r: &RunResult, what: &str) {
    assert!(
        r.converged,
        "{what}: did not converge (step {:?}): {:?}",
        r.failed_step, r.error
    );
}

/// A probe value, which must be present and finite.
pub fn probe(r: &RunResult, name: &str) -> f64 {
    let v = *r
        .probes
        .get(name)
        .unwrap_or_else(|| panic!("no probe {name} in {:?}", r.probes));
    assert!(v.is_finite(), "probe {name} is {v}");
    v
}

/// `max / min - 1` of a set of positive values.
pub fn variation(values: &[f64]) -> f64 {
    let max = values.iter().copied().fold(f64::NEG_INFINITY, f64::max);
    let min = values.iter().copied().fold(f64::INFINITY, f64::min);
    max / min - 1.0
}
