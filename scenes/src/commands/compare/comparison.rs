//! A comparison's rows, the published values beside them and what the tables and plots read.

use crate::format::overrides::dotted;
use crate::format::{LengthUnit, PaperSpec};
use crate::record::RunResult;
use isochor_solvers::Method;
use std::collections::{BTreeMap, BTreeSet};

/// One column of the comparison, a variant of the scene: a method (the scene with
/// `method = NAME`) or one of the scene's named variants.
#[derive(Debug, Clone, PartialEq)]
pub enum Variant {
    /// The scene with `method = NAME`.
    Method(Method),
    /// One of the scene's named variants.
    Named(String),
}

impl Variant {
    /// The variant's label in tables: the method's or the variant's name.
    pub fn label(&self) -> String {
        match self {
            Variant::Method(m) => m.name().to_string(),
            Variant::Named(v) => v.clone(),
        }
    }
}

/// One row of the table.
#[derive(Debug, Clone)]
pub struct CompareRow {
    /// The swept parameter's value, if sweeping.
    pub sweep_value: Option<String>,
    /// Method or variant label.
    pub label: String,
    /// The run (or why it could not start).
    pub result: Result<RunResult, String>,
}

impl CompareRow {
    /// The swept value as a number, if it is one.
    pub fn sweep_number(&self) -> Option<f64> {
        self.sweep_value.as_deref()?.parse().ok()
    }

    /// The value of a probe, if the run converged.
    pub(super) fn converged_probe(&self, probe: &str) -> Option<f64> {
        let r = self.result.as_ref().ok().filter(|r| r.converged)?;
        r.probes.get(probe).copied().filter(|v| v.is_finite())
    }
}

/// The result of a comparison.
#[derive(Debug, Clone)]
pub struct Comparison {
    /// The scene's name.
    pub scene: String,
    /// The swept key.
    pub sweep_key: Option<String>,
    /// Rows in sweep-major order.
    pub rows: Vec<CompareRow>,
    /// The scene's published values, if it has any.
    pub paper: Option<PaperSpec>,
    /// The units the scene shows its length probes in (the rest are shown as measured).
    pub units: BTreeMap<String, LengthUnit>,
}

/// How much a probe changes over the sweep for one method or variant: its value at the first
/// swept value over its value at the last.
#[derive(Debug, Clone, PartialEq)]
pub struct Factor {
    /// Method or variant label.
    pub label: String,
    /// The probe.
    pub probe: String,
    /// Ours (if both runs converged and the last value is not zero).
    pub ours: Option<f64>,
    /// The published one (if the paper gives both values).
    pub paper: Option<f64>,
}

impl Comparison {
    /// Whether any run stepped in time (implicit Euler): then the energies are plotted.
    pub fn is_dynamic(&self) -> bool {
        self.rows
            .iter()
            .any(|row| row.result.as_ref().is_ok_and(|r| r.dynamic))
    }

    /// The probes of the table (every probe but `volume_change`, which has its own column).
    pub fn probe_names(&self) -> Vec<String> {
        let names: BTreeSet<String> = self
            .rows
            .iter()
            .filter_map(|r| r.result.as_ref().ok())
            .flat_map(|r| r.probes.keys().cloned())
            .filter(|k| k != "volume_change")
            .collect();
        names.into_iter().collect()
    }

    /// The method and variant labels, in the order of the rows.
    pub fn labels(&self) -> Vec<String> {
        let mut labels: Vec<String> = Vec::new();
        for row in &self.rows {
            if !labels.contains(&row.label) {
                labels.push(row.label.clone());
            }
        }
        labels
    }

    /// The swept values, in the order of the rows.
    fn sweep_values(&self) -> Vec<&CompareRow> {
        let mut firsts: Vec<&CompareRow> = Vec::new();
        for row in &self.rows {
            if !firsts.iter().any(|r| r.sweep_value == row.sweep_value) {
                firsts.push(row);
            }
        }
        firsts
    }

    /// Whether the sweep has two or more values, all numbers (then `compare.png` plots it).
    pub fn plots_sweep(&self) -> bool {
        let values = self.sweep_values();
        self.sweep_key.is_some()
            && values.len() >= 2
            && values.iter().all(|r| r.sweep_number().is_some())
    }

    /// Whether the run sweeps the key the paper's values are published over.
    fn sweeps_paper_key(&self) -> Option<&PaperSpec> {
        let paper = self.paper.as_ref()?;
        let key = self.sweep_key.as_deref()?;
        (dotted(key) == dotted(&paper.sweep)).then_some(paper)
    }

    /// The published value of `probe` for a row, when the run sweeps the paper's key and the
    /// row's value is one the paper gives.
    pub fn paper_value(&self, row: &CompareRow, probe: &str) -> Option<f64> {
        self.sweeps_paper_key()?
            .value(probe, &row.label, row.sweep_number()?)
    }

    /// The probes with a published value beside at least one row.
    pub fn paper_probes(&self) -> Vec<String> {
        self.probe_names()
            .into_iter()
            .filter(|p| self.rows.iter().any(|r| self.paper_value(r, p).is_some()))
            .collect()
    }

    /// What the paper section contributes, or why it cannot be shown beside these runs.
    pub fn paper_notes(&self) -> Vec<String> {
        let Some(paper) = &self.paper else {
            return Vec::new();
        };
        let given = format!(
            "{} = {}",
            paper.sweep,
            paper
                .values
                .iter()
                .map(f64::to_string)
                .collect::<Vec<_>>()
                .join(", ")
        );
        let source = &paper.source;
        let key = match &self.sweep_key {
            None => {
                return vec![format!(
                "{source}: published for {given}; sweep {} to see those values beside these runs",
                paper.sweep
            )]
            }
            Some(k) if self.sweeps_paper_key().is_none() => {
                return vec![format!(
                "{source}: published for {given}, not over {k}: cannot match this sweep, not shown"
            )]
            }
            Some(k) => k,
        };
        let values = self.sweep_values();
        let missing: Vec<&str> = values
            .iter()
            .filter(|r| r.sweep_number().and_then(|x| paper.position(x)).is_none())
            .filter_map(|r| r.sweep_value.as_deref())
            .collect();
        if missing.len() == values.len() {
            return vec![format!(
                "{source}: published for {given}; this sweep has none of those values: cannot match, not shown"
            )];
        }
        let mut notes = vec![format!(
            "{source}: the published values are the columns \"paper\""
        )];
        if !missing.is_empty() {
            notes.push(format!(
                "{source}: no values at {key} = {} (published for {given})",
                missing.join(", ")
            ));
        }
        let absent: Vec<String> = self
            .labels()
            .into_iter()
            .filter(|l| !paper.probes.values().any(|c| c.contains_key(l)))
            .collect();
        if !absent.is_empty() {
            notes.push(format!("{source}: no values for {}", absent.join(", ")));
        }
        notes
    }

    /// The factor every probe changes by over the sweep, per method or variant (none without
    /// a sweep of two or more values).
    pub fn factors(&self) -> Vec<Factor> {
        let values = self.sweep_values();
        let (Some(first), Some(last)) = (values.first(), values.last()) else {
            return Vec::new();
        };
        if values.len() < 2 {
            return Vec::new();
        }
        let row = |label: &str, at: &CompareRow| {
            self.rows
                .iter()
                .find(|r| r.label == label && r.sweep_value == at.sweep_value)
        };
        let ratio = |a: Option<f64>, b: Option<f64>| Some(a? / b?).filter(|f| f.is_finite());
        let mut factors = Vec::new();
        for label in self.labels() {
            let (Some(a), Some(b)) = (row(&label, first), row(&label, last)) else {
                continue;
            };
            for probe in self.probe_names() {
                factors.push(Factor {
                    label: label.clone(),
                    ours: ratio(a.converged_probe(&probe), b.converged_probe(&probe)),
                    paper: ratio(self.paper_value(a, &probe), self.paper_value(b, &probe)),
                    probe,
                });
            }
        }
        factors
    }

    /// A probe's value in its display unit.
    pub fn shown(&self, probe: &str, value: f64) -> f64 {
        self.units
            .get(probe)
            .map_or(value, |u| u.from_metres(value))
    }

    /// A probe's name with its display unit, e.g. `tip_deflection (cm)`.
    pub fn probe_title(&self, probe: &str) -> String {
        match self.units.get(probe) {
            Some(u) => format!("{probe} ({})", u.symbol()),
            None => probe.to_string(),
        }
    }

    /// Every run as JSON (SI units), with the published values beside each run (`paper`),
    /// the scene's paper section and notes, the factors and the display units.
    pub fn to_json(&self) -> serde_json::Value {
        let runs: Vec<serde_json::Value> = self
            .rows
            .iter()
            .map(|row| {
                let mut v = match &row.result {
                    Ok(r) => r.to_json(),
                    Err(e) => serde_json::json!({ "error": e, "converged": false }),
                };
                if let serde_json::Value::Object(map) = &mut v {
                    map.insert("config".into(), row.label.clone().into());
                    if let (Some(k), Some(val)) = (&self.sweep_key, &row.sweep_value) {
                        map.insert(
                            "sweep".into(),
                            serde_json::json!({ "key": k, "value": val }),
                        );
                    }
                    let published: serde_json::Map<String, serde_json::Value> = self
                        .probe_names()
                        .into_iter()
                        .filter_map(|p| Some((p.clone(), self.paper_value(row, &p)?.into())))
                        .collect();
                    if !published.is_empty() {
                        map.insert("paper".into(), published.into());
                    }
                }
                v
            })
            .collect();
        let factors: Vec<serde_json::Value> = self
            .factors()
            .into_iter()
            .map(|f| {
                serde_json::json!({
                    "config": f.label, "probe": f.probe, "ours": f.ours, "paper": f.paper
                })
            })
            .collect();
        let units: BTreeMap<&String, &str> =
            self.units.iter().map(|(p, u)| (p, u.symbol())).collect();
        serde_json::json!({
            "scene": self.scene,
            "sweep": self.sweep_key,
            "runs": runs,
            "factors": factors,
            "units": units,
            "paper": self.paper,
            "paper_notes": self.paper_notes(),
        })
    }
}
