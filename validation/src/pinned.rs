//! Pinned results: absolute values that the suite recomputes and compares, so that a change
//! that shifts an answer cannot pass unnoticed.
//!
//! Each group is one JSON file `validation/reference/<group>.json`, a map from a key (for
//! example `cantilever/mixed-p1/res=8/nu=0.4999/tip_deflection`) to a [`Pin`]: the value,
//! the tolerance it is compared with and where the value comes from. The tolerance of a
//! value computed by this code is derived from the solver's own tolerances (the test that
//! pins it says how), not from the spread of past runs.
//!
//! When a change moves a pinned value on purpose, rerun the test with `ISOCHOR_BLESS=1`:
//! values of kind [`Provenance::Code`] are rewritten with the current commit, new keys are
//! added with the tolerance the test passes, and values that come from analysis or from a
//! paper are never rewritten (a mismatch still fails). The commit that changes the file must
//! say why the values moved.

use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;
use std::path::PathBuf;
use std::sync::Mutex;

/// How close a recomputed value must be to its pin.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Tolerance {
    /// `|value - pin| <= tol * max(|pin|, floor)`; `floor` keeps values near zero meaningful.
    Relative {
        /// The relative tolerance.
        tol: f64,
        /// The scale below which the tolerance is absolute (`tol * floor`).
        floor: f64,
    },
    /// `|value - pin| <= tol`.
    Absolute {
        /// The absolute tolerance.
        tol: f64,
    },
}

impl Tolerance {
    /// A relative tolerance with the given floor.
    pub fn relative(tol: f64, floor: f64) -> Tolerance {
        Tolerance::Relative { tol, floor }
    }

    /// An absolute tolerance.
    pub fn absolute(tol: f64) -> Tolerance {
        Tolerance::Absolute { tol }
    }

    /// The largest allowed `|value - pin|`.
    pub fn bound(&self, pin: f64) -> f64 {
        match *self {
            Tolerance::Relative { tol, floor } => tol * pin.abs().max(floor),
            Tolerance::Absolute { tol } => tol,
        }
    }
}

/// Where a pinned value comes from.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case", tag = "kind", content = "detail")]
pub enum Provenance {
    /// Exact by analysis (the detail says which formula).
    Analytic(String),
    /// A number printed in a paper (the detail names the paper, table or figure).
    Paper(String),
    /// This code at a named commit.
    Code(String),
}

/// One pinned value.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Pin {
    /// The value.
    pub value: f64,
    /// How close a recomputed value must be.
    pub tolerance: Tolerance,
    /// Where the value comes from.
    pub provenance: Provenance,
}

type Group = BTreeMap<String, Pin>;

/// Serializes reads and writes of the reference files within one test process.
static FILES: Mutex<()> = Mutex::new(());

fn path(group: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("reference")
        .join(format!("{group}.json"))
}

fn read(group: &str) -> Result<Group, String> {
    let path = path(group);
    match std::fs::read_to_string(&path) {
        Ok(text) => serde_json::from_str(&text).map_err(|e| format!("{}: {e}", path.display())),
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => Ok(Group::new()),
        Err(e) => Err(format!("{}: {e}", path.display())),
    }
}

fn write(group: &str, pins: &Group) -> Result<(), String> {
    let path = path(group);
    let text = serde_json::to_string_pretty(pins).map_err(|e| e.to_string())? + "\n";
    std::fs::create_dir_all(path.parent().expect("reference folder"))
        .and_then(|_| std::fs::write(&path, text))
        .map_err(|e| format!("{}: {e}", path.display()))
}

fn blessing() -> bool {
    std::env::var("ISOCHOR_BLESS").is_ok_and(|v| v == "1")
}

fn current_commit() -> String {
    std::process::Command::new("git")
        .args(["rev-parse", "--short=12", "HEAD"])
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .output()
        .ok()
        .filter(|o| o.status.success())
        .map(|o| String::from_utf8_lossy(&o.stdout).trim().to_string())
        .map(|c| format!("isochor at commit {c}"))
        .unwrap_or_else(|| "isochor at an unknown commit".into())
}

/// Compares `value` with the pin `group`/`key`.
///
/// Returns a message naming the key, both values, the difference and the bound when they
/// differ by more than the pin's tolerance, or when the key is not pinned. With
/// `ISOCHOR_BLESS=1`, a pin of this code that moved (or changed its tolerance), or a missing
/// one, is written with `tolerance` and the current commit instead; analytic and paper pins
/// are only compared.
pub fn check(group: &str, key: &str, value: f64, tolerance: Tolerance) -> Result<(), String> {
    let _guard = FILES.lock().unwrap_or_else(|p| p.into_inner());
    let mut pins = read(group)?;
    let pinned = pins.get(key).cloned();
    let mismatch = |pin: &Pin| {
        let diff = (value - pin.value).abs();
        let bound = pin.tolerance.bound(pin.value);
        // A NaN on either side is a mismatch.
        let within = matches!(
            diff.partial_cmp(&bound),
            Some(std::cmp::Ordering::Less | std::cmp::Ordering::Equal)
        );
        (!within).then(|| {
            format!(
                "{group}/{key}: computed {value:.12e}, pinned {:.12e} ({:?}), difference {diff:.3e} > {bound:.3e}",
                pin.value, pin.provenance
            )
        })
    };
    match pinned {
        Some(pin) if !blessing() || !matches!(pin.provenance, Provenance::Code(_)) => {
            mismatch(&pin).map_or(Ok(()), Err)
        }
        Some(pin) if mismatch(&pin).is_none() && pin.tolerance == tolerance => Ok(()),
        None if !blessing() => Err(format!(
            "{group}/{key} = {value:.12e} is not pinned: run the test with ISOCHOR_BLESS=1 to add it to {}",
            path(group).display()
        )),
        _ => {
            let pin = Pin {
                value,
                tolerance,
                provenance: Provenance::Code(current_commit()),
            };
            pins.insert(key.to_string(), pin);
            write(group, &pins)
        }
    }
}

/// [`check`] that panics with its message: for tests.
#[track_caller]
pub fn assert_pinned(group: &str, key: &str, value: f64, tolerance: Tolerance) {
    if let Err(message) = check(group, key, value, tolerance) {
        panic!("{message}");
    }
}
