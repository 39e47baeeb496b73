//! Pinned results: absolute values that the suite recomputes and compares, so that a change
//! that shifts an answer cannot pass unnoticed.
//!
//! Each group is one TOML file `validation/reference/<group>.toml` of records, one per
//! [`Run`] (a scene with its variant, element and overrides, or one evaluation of a kernel).
//! Every value carries a [`Pin`]: the value, the tolerance it is compared with and where the
//! value comes from. A record states the run, the provenance and the tolerance that most of
//! its values share, then a table `probe = value`, then the probes whose tolerance or
//! provenance differ (tables `tolerances` and `provenances`):
//!
//! ```toml
//! [[run]]
//! name = "cantilever"
//! variant = "mixed-p1"
//! element = "tet4"
//! overrides = ["nu=0.4999", "res=1", "steps=1"]
//! provenance = { code = "isochor at commit 35918fc7133c" }
//! tolerance = { relative = 1.0000000000000002e-6, floor = 0.001 }
//! [run.values]
//! end_deflection = 0.005910900558686521
//! tip_deflection = 0.005896654529186376
//! ```
//!
//! A tolerance is `{ relative = tol, floor = f }` (`floor` 0 when absent) or
//! `{ absolute = tol }`; a provenance `{ code = ... }`, `{ analytic = ... }` or
//! `{ paper = ... }`. Floats are written in their shortest form that reads back bit for bit.
//! The tolerance of a value computed by this code is derived from the solver's own tolerances
//! (the test that pins it says how), not from the spread of past runs.
//!
//! When a change moves a pinned value on purpose, rerun the test with `ISOCHOR_BLESS=1`:
//! values of kind [`Provenance::Code`] that moved are rewritten with the current commit (and
//! nothing else, so the diff of the file lists the probes that changed), new values are
//! added with the tolerance the test passes, and values that come from analysis or from a
//! paper are never rewritten (a mismatch still fails). The commit that changes the file must
//! say why the values moved.

mod stored;

use serde::Deserialize;
use std::collections::BTreeMap;
use std::fmt;
use std::path::PathBuf;
use std::sync::Mutex;

/// How close a recomputed value must be to its pin.
#[derive(Debug, Clone, Copy, PartialEq)]
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
#[derive(Debug, Clone, PartialEq, Eq, PartialOrd, Ord, Deserialize)]
#[serde(rename_all = "snake_case", deny_unknown_fields)]
pub enum Provenance {
    /// Exact by analysis (the detail says which formula).
    Analytic(String),
    /// A number printed in a paper (the detail names the paper, table or figure).
    Paper(String),
    /// This code at a named commit.
    Code(String),
}

/// One pinned value.
#[derive(Debug, Clone, PartialEq)]
pub struct Pin {
    /// The value.
    pub value: f64,
    /// How close a recomputed value must be.
    pub tolerance: Tolerance,
    /// Where the value comes from.
    pub provenance: Provenance,
}

/// What one record pins: a scene run (name, variant, element, `--set` overrides in the
/// order they apply), or one evaluation of a kernel (a name alone).
#[derive(Debug, Clone, PartialEq, Eq, PartialOrd, Ord, Default)]
pub struct Run {
    /// The scene, or the kernel and the quantity.
    pub name: String,
    /// The scene's variant, if any.
    pub variant: Option<String>,
    /// The element (`tet4` or `tet10`), for a scene run.
    pub element: Option<String>,
    /// The `KEY=VALUE` overrides of the run.
    pub overrides: Vec<String>,
}

impl Run {
    /// A record with a name alone.
    pub fn named(name: impl Into<String>) -> Run {
        Run {
            name: name.into(),
            ..Run::default()
        }
    }

    /// A scene run.
    pub fn scene(name: &str, variant: Option<&str>, element: &str, overrides: &[String]) -> Run {
        Run {
            name: name.into(),
            variant: variant.map(Into::into),
            element: Some(element.into()),
            overrides: overrides.to_vec(),
        }
    }
}

impl fmt::Display for Run {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}", self.name)?;
        if let Some(variant) = &self.variant {
            write!(f, "/{variant}")?;
        }
        if let Some(element) = &self.element {
            write!(f, " ({element})")?;
        }
        if !self.overrides.is_empty() {
            write!(f, " [{}]", self.overrides.join(" "))?;
        }
        Ok(())
    }
}

/// The pins of one group: every run's probes.
pub type Group = BTreeMap<Run, BTreeMap<String, Pin>>;

/// Serializes reads and writes of the reference files within one test process.
static FILES: Mutex<()> = Mutex::new(());

fn path(group: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("reference")
        .join(format!("{group}.toml"))
}

fn read(group: &str) -> Result<Group, String> {
    let path = path(group);
    match std::fs::read_to_string(&path) {
        Ok(text) => stored::parse(&text).map_err(|e| format!("{}: {e}", path.display())),
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => Ok(Group::new()),
        Err(e) => Err(format!("{}: {e}", path.display())),
    }
}

fn write(group: &str, pins: &Group) -> Result<(), String> {
    let path = path(group);
    std::fs::create_dir_all(path.parent().expect("reference folder"))
        .and_then(|_| std::fs::write(&path, stored::render(pins)))
        .map_err(|e| format!("{}: {e}", path.display()))
}

/// Every pin of `group` (for a test that fails on pins no run recomputes any more).
pub fn pins(group: &str) -> Result<Group, String> {
    let _guard = FILES.lock().unwrap_or_else(|p| p.into_inner());
    read(group)
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

/// Compares `value` with the pin of `probe` in `run`'s record of `group`.
///
/// Returns a message naming the run and the probe, both values, the difference and the bound
/// when they differ by more than the pin's tolerance, or when the probe is not pinned. With
/// `ISOCHOR_BLESS=1`, a pin of this code that moved (or changed its tolerance), or a missing
/// one, is written with `tolerance` and the current commit instead; analytic and paper pins
/// are only compared.
pub fn check(
    group: &str,
    run: &Run,
    probe: &str,
    value: f64,
    tolerance: Tolerance,
) -> Result<(), String> {
    let _guard = FILES.lock().unwrap_or_else(|p| p.into_inner());
    let mut pins = read(group)?;
    let pinned = pins.get(run).and_then(|probes| probes.get(probe)).cloned();
    let mismatch = |pin: &Pin| {
        let diff = (value - pin.value).abs();
        let bound = pin.tolerance.bound(pin.value);
        // A NaN value is a mismatch too.
        (diff.is_nan() || diff > bound).then(|| {
            format!(
                "{group}: {run}: {probe}: computed {value:.12e}, pinned {:.12e} ({:?}), difference {diff:.3e} > {bound:.3e}",
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
            "{group}: {run}: {probe} = {value:.12e} is not pinned: run the test with ISOCHOR_BLESS=1 to add it to {}",
            path(group).display()
        )),
        _ => {
            let pin = Pin {
                value,
                tolerance,
                provenance: Provenance::Code(current_commit()),
            };
            pins.entry(run.clone())
                .or_default()
                .insert(probe.to_string(), pin);
            write(group, &pins)
        }
    }
}

/// [`check`] that panics with its message: for tests.
#[track_caller]
pub fn assert_pinned(group: &str, run: &Run, probe: &str, value: f64, tolerance: Tolerance) {
    if let Err(message) = check(group, run, probe, value, tolerance) {
        panic!("{message}");
    }
}
