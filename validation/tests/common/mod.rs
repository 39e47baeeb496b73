//! Shared helpers of the scene-level studies: run a built-in scene (or one of its variants)
//! with `--set` overrides through the scenes library, time it, and cache results that
//! several tests of one binary need.

#![allow(dead_code)]

mod cantilever;
pub use cantilever::cantilever;

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

/// The outcome of a run that may fail: the result, or the error of a scene that could not
/// be built, or the message of a panic (which is always a bug).
pub enum Outcome {
    /// The run happened (converged or not).
    Ran(Box<RunResult>),
    /// The scene could not be loaded or built: a clear error.
    Error(String),
    /// The run panicked.
    Panic(String),
}

/// Like [`run`] but never panics: catches errors and panics.
pub fn try_run(scene: &str, variant: Option<&str>, sets: &[&str]) -> Outcome {
    let overrides: Result<Vec<Override>, String> = sets
        .iter()
        .map(|s| Override::parse(s).map_err(|e| e.to_string()))
        .collect();
    let attempt = std::panic::catch_unwind(|| {
        let scene = load_scene(scene, variant, &overrides?).map_err(|e| e.to_string())?;
        run_scene(&scene, &RunOptions::default())
            .map(|(r, _)| r)
            .map_err(|e| e.to_string())
    });
    match attempt {
        Ok(Ok(r)) => Outcome::Ran(Box::new(r)),
        Ok(Err(e)) => Outcome::Error(e),
        Err(p) => Outcome::Panic(
            p.downcast_ref::<String>()
                .cloned()
                .or_else(|| p.downcast_ref::<&str>().map(|s| s.to_string()))
                .unwrap_or_default(),
        ),
    }
}

/// Checks that an outcome is a converged state with finite output, a clear error, or a run
/// stopped by a named solver error whose last accepted state (the one its probes measure) is
/// finite, and returns a one-line description of it.
pub fn check_outcome(what: &str, outcome: &Outcome) -> Result<String, String> {
    match outcome {
        Outcome::Panic(m) => Err(format!("{what}: panicked: {m}")),
        Outcome::Error(e) if e.trim().is_empty() => Err(format!("{what}: empty error")),
        Outcome::Error(e) => Ok(format!("{what}: error: {e}")),
        Outcome::Ran(r) => {
            let last = r.history.last();
            let finite = r.volume_change.is_finite()
                && r.probes.values().all(|v| v.is_finite())
                && last.is_none_or(|s| {
                    s.kinetic_energy.is_finite()
                        && s.elastic_energy.is_finite()
                        && s.external_energy.is_finite()
                });
            if !finite {
                return Err(format!(
                    "{what}: non-finite {} state: volume change {:e}, probes {:?}, last step {:?}, error {:?}",
                    if r.converged {
                        "converged"
                    } else {
                        "last accepted"
                    },
                    r.volume_change,
                    r.probes,
                    last.map(|s| (s.kinetic_energy, s.elastic_energy, s.external_energy)),
                    r.error
                ));
            }
            if r.converged {
                return Ok(format!(
                    "{what}: converged, {} Newton iterations, volume change {:+.2e}, max inverted {}, probes {:?}",
                    r.newton_iterations, r.volume_change, r.max_inverted_tets, r.probes
                ));
            }
            match (&r.error, r.failed_step) {
                (Some(e), Some(step)) if !e.trim().is_empty() => Ok(format!(
                    "{what}: stopped at step {step}/{} ({} accepted, probes of the last one {:?}): {e}",
                    r.steps_requested, r.steps, r.probes
                )),
                _ => Err(format!(
                    "{what}: not converged without an error message and a failed step ({:?}, {:?})",
                    r.error, r.failed_step
                )),
            }
        }
    }
}

/// The largest `|V / V0 - 1|` a converged run may show when its volume constraints have zero
/// compliance (nu = 0.5, or the zonal method's zones) and their rows partition the body
/// (nodal P1 volumes, or one global zone). The saddle-point and dual solvers stop only when
/// every row meets `|phi_i - (C p)_i| <= tol V_i` (`Settings::constraint_tolerance`, 1e-10,
/// which no scene here overrides); with `C = 0` and `phi_i` the volume change the row
/// measures, `|V - V0| = |sum_i phi_i| <= tol sum_i V_i = tol V0`. To that the rounding of
/// summing `tets` tet volumes is added (a few machine epsilons per tet).
pub fn incompressible_volume_bound(tets: usize) -> f64 {
    isochor_solvers::Settings::default().constraint_tolerance + 16.0 * tets as f64 * f64::EPSILON
}

/// How far from 1 the volume ratio of a tet that no load reaches (its free vertices feel only
/// its own energy, at rest) may end in a converged run of a mesh with `vertices` vertices.
/// Newton accepts a force residual of `force_tolerance` (1e-9) times the force scale
/// (`Simulation::force_scale`: `mu h^2 sqrt(n)` without loads, the nodal force of a unit
/// strain over the mesh), i.e. the force of a strain of at most `force_tolerance sqrt(n)`;
/// a strain `s` changes a tet's volume ratio by at most `3 s`.
pub fn unloaded_volume_tolerance(vertices: usize) -> f64 {
    3.0 * isochor_solvers::Settings::default().force_tolerance * (vertices as f64).sqrt()
}
