//! The reference files' TOML: one `[[run]]` record per run, with the tolerance and the
//! provenance most of its values share stated once and the others listed per probe.
//!
//! [`render`] writes a canonical text (records sorted by run, probes by name, the shared
//! tolerance and provenance chosen from the values alone), so reading a file and writing it
//! back changes nothing, and a blessing that moves one value changes its line only.

use super::{Group, Pin, Provenance, Run, Tolerance};
use serde::Deserialize;
use std::collections::BTreeMap;
use std::fmt::Write;

/// A reference file as stored.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct File {
    #[serde(default)]
    run: Vec<Record>,
}

/// One run's record as stored.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct Record {
    name: String,
    variant: Option<String>,
    element: Option<String>,
    #[serde(default)]
    overrides: Vec<String>,
    provenance: Provenance,
    tolerance: StoredTolerance,
    values: BTreeMap<String, f64>,
    /// The probes whose tolerance is not the record's.
    #[serde(default)]
    tolerances: BTreeMap<String, StoredTolerance>,
    /// The probes whose provenance is not the record's.
    #[serde(default)]
    provenances: BTreeMap<String, Provenance>,
}

/// `{ relative = tol, floor = f }` (floor 0 when absent) or `{ absolute = tol }`.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct StoredTolerance {
    relative: Option<f64>,
    floor: Option<f64>,
    absolute: Option<f64>,
}

impl StoredTolerance {
    fn tolerance(&self) -> Result<Tolerance, String> {
        match (self.relative, self.floor, self.absolute) {
            (Some(tol), floor, None) => Ok(Tolerance::relative(tol, floor.unwrap_or(0.0))),
            (None, None, Some(tol)) => Ok(Tolerance::absolute(tol)),
            _ => Err("a tolerance is { relative, floor } or { absolute }".into()),
        }
    }
}

/// Reads a reference file.
pub(super) fn parse(text: &str) -> Result<Group, String> {
    let file: File = toml::from_str(text).map_err(|e| e.to_string())?;
    let mut group = Group::new();
    for record in file.run {
        let run = Run {
            name: record.name,
            variant: record.variant,
            element: record.element,
            overrides: record.overrides,
        };
        let tolerance = record.tolerance.tolerance()?;
        let unknown = record
            .tolerances
            .keys()
            .chain(record.provenances.keys())
            .find(|probe| !record.values.contains_key(*probe));
        if let Some(probe) = unknown {
            return Err(format!("{}: {probe} has no value", run));
        }
        let mut probes = BTreeMap::new();
        for (probe, value) in record.values {
            let tolerance = match record.tolerances.get(&probe) {
                Some(t) => t
                    .tolerance()
                    .map_err(|e| format!("{}: {probe}: {e}", run))?,
                None => tolerance,
            };
            let provenance = record
                .provenances
                .get(&probe)
                .unwrap_or(&record.provenance)
                .clone();
            let pin = Pin {
                value,
                tolerance,
                provenance,
            };
            probes.insert(probe, pin);
        }
        if group.insert(run.clone(), probes).is_some() {
            return Err(format!("{}: two records", run));
        }
    }
    Ok(group)
}

/// Writes a reference file.
pub(super) fn render(group: &Group) -> String {
    let mut out = String::from(
        "# Pinned values: one record per run (see isochor_validation::pinned and\n\
         # docs/testing.md). Written by the pin tests under ISOCHOR_BLESS=1.\n",
    );
    for (run, probes) in group.iter().filter(|(_, probes)| !probes.is_empty()) {
        let tolerance = most_common(probes.values().map(|p| tolerance(&p.tolerance)));
        let provenance = most_common(probes.values().map(|p| provenance(&p.provenance)));
        out += "\n[[run]]\n";
        writeln!(out, "name = {}", string(&run.name)).unwrap();
        for (key, value) in [("variant", &run.variant), ("element", &run.element)] {
            if let Some(value) = value {
                writeln!(out, "{key} = {}", string(value)).unwrap();
            }
        }
        if !run.overrides.is_empty() {
            let overrides: Vec<String> = run.overrides.iter().map(|s| string(s)).collect();
            writeln!(out, "overrides = [{}]", overrides.join(", ")).unwrap();
        }
        writeln!(out, "provenance = {provenance}").unwrap();
        writeln!(out, "tolerance = {tolerance}").unwrap();
        out += "[run.values]\n";
        for (probe, pin) in probes {
            writeln!(out, "{} = {}", key(probe), float(pin.value)).unwrap();
        }
        let exceptions = |title: &str, shared: &str, of: &dyn Fn(&Pin) -> String| {
            let lines: String = probes
                .iter()
                .map(|(probe, pin)| (probe, of(pin)))
                .filter(|(_, text)| text != shared)
                .map(|(probe, text)| format!("{} = {text}\n", key(probe)))
                .collect();
            if lines.is_empty() {
                lines
            } else {
                format!("[run.{title}]\n{lines}")
            }
        };
        out += &exceptions("tolerances", &tolerance, &|p| self::tolerance(&p.tolerance));
        out += &exceptions("provenances", &provenance, &|p| {
            self::provenance(&p.provenance)
        });
    }
    out
}

/// The text shared by the most values; on a tie, the first in order of the probes.
fn most_common(texts: impl Iterator<Item = String>) -> String {
    let texts: Vec<String> = texts.collect();
    let count = |t: &String| texts.iter().filter(|u| *u == t).count();
    let mut best = &texts[0];
    for text in &texts {
        if count(text) > count(best) {
            best = text;
        }
    }
    best.clone()
}

fn tolerance(tolerance: &Tolerance) -> String {
    match *tolerance {
        Tolerance::Relative { tol, floor } if floor == 0.0 && floor.is_sign_positive() => {
            format!("{{ relative = {} }}", float(tol))
        }
        Tolerance::Relative { tol, floor } => {
            format!("{{ relative = {}, floor = {} }}", float(tol), float(floor))
        }
        Tolerance::Absolute { tol } => format!("{{ absolute = {} }}", float(tol)),
    }
}

fn provenance(provenance: &Provenance) -> String {
    let (kind, detail) = match provenance {
        Provenance::Analytic(detail) => ("analytic", detail),
        Provenance::Paper(detail) => ("paper", detail),
        Provenance::Code(detail) => ("code", detail),
    };
    format!("{{ {kind} = {} }}", string(detail))
}

/// The shortest decimal that reads back to `value` bit for bit (Rust's `{:?}`), in TOML.
fn float(value: f64) -> String {
    if value.is_nan() {
        "nan".into()
    } else if value.is_infinite() {
        if value > 0.0 { "inf" } else { "-inf" }.into()
    } else {
        format!("{value:?}")
    }
}

/// A TOML basic string.
fn string(text: &str) -> String {
    toml::Value::String(text.to_string()).to_string()
}

/// A TOML key: bare when it can be, quoted otherwise.
fn key(text: &str) -> String {
    let bare = !text.is_empty()
        && text
            .chars()
            .all(|c| c.is_ascii_alphanumeric() || c == '_' || c == '-');
    if bare {
        text.to_string()
    } else {
        string(text)
    }
}
