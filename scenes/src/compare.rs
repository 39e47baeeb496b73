//! `isochor compare`: the same scene with several methods (or variants) side by side,
//! optionally swept over a parameter, as a table like Tables 1 and 2 of Francu et al. 2021.

use crate::output::{write_file, OutputDir};
use crate::overrides::{parse_sweep, Override};
use crate::result::RunResult;
use crate::run::{run_scene, RunOptions};
use crate::{SceneError, SceneSource};
use isochor_solvers::Method;
use std::collections::BTreeSet;
use std::fmt::Write;
use std::path::{Path, PathBuf};

/// One column of the comparison: a method or a variant.
#[derive(Debug, Clone, PartialEq)]
pub enum Config {
    /// The scene with `method = NAME`.
    Method(Method),
    /// One of the scene's named variants.
    Variant(String),
}

impl Config {
    fn label(&self) -> String {
        match self {
            Config::Method(m) => m.name().to_string(),
            Config::Variant(v) => v.clone(),
        }
    }
}

/// A comparison request.
#[derive(Debug, Clone, Default)]
pub struct CompareRequest {
    /// Built-in name or scene path.
    pub scene: String,
    /// Methods to compare (`--methods`).
    pub methods: Vec<Method>,
    /// Variants to compare (`--variants`); with neither, all the scene's variants.
    pub variants: Vec<String>,
    /// `--set` overrides applied to every run.
    pub overrides: Vec<Override>,
    /// `--sweep KEY=V1,V2,...`.
    pub sweep: Option<String>,
    /// Output folder for `compare.csv`, `compare.md` and `compare.json`.
    pub out: Option<PathBuf>,
    /// Progress bars on stderr.
    pub progress: bool,
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

/// The result of a comparison.
#[derive(Debug, Clone)]
pub struct Comparison {
    /// The scene's name.
    pub scene: String,
    /// The swept key.
    pub sweep_key: Option<String>,
    /// Rows in sweep-major order.
    pub rows: Vec<CompareRow>,
}

/// Parses a comma-separated method list, naming the valid methods on error.
pub fn parse_methods(list: &str) -> Result<Vec<Method>, SceneError> {
    list.split(',')
        .map(str::trim)
        .filter(|s| !s.is_empty())
        .map(|s| s.parse::<Method>().map_err(SceneError::from))
        .collect()
}

/// Runs every configuration (for every sweep value). Runs that fail to converge are rows
/// with `converged = false`; a scene that cannot be built for one configuration is a row
/// with its error. Bad keys, values and names fail the whole comparison before any run.
pub fn compare(request: &CompareRequest) -> Result<(Comparison, Option<PathBuf>), SceneError> {
    let source = SceneSource::resolve(&request.scene)?;
    let base = source.load(None, &request.overrides)?;
    let mut configs: Vec<Config> = request.methods.iter().map(|&m| Config::Method(m)).collect();
    configs.extend(request.variants.iter().cloned().map(Config::Variant));
    if configs.is_empty() {
        if base.variants.is_empty() {
            return Err(SceneError::Usage(format!(
                "scene {} has no variants: give --methods (valid: {})",
                base.name,
                Method::ALL.map(Method::name).join(", ")
            )));
        }
        configs.extend(base.variants.keys().cloned().map(Config::Variant));
    }
    let (sweep_key, sweep_values) = match &request.sweep {
        Some(spec) => {
            let (k, v) = parse_sweep(spec)?;
            (Some(k), v.into_iter().map(Some).collect())
        }
        None => (None, vec![None]),
    };
    // Load every configuration first, so that a bad key or value fails before any run.
    let mut plans = Vec::new();
    for value in &sweep_values {
        for config in &configs {
            let mut overrides = request.overrides.clone();
            let variant = match config {
                Config::Method(m) => {
                    overrides.push(Override::new(
                        "method",
                        toml::Value::String(m.name().into()),
                    ));
                    None
                }
                Config::Variant(v) => Some(v.as_str()),
            };
            if let (Some(k), Some(v)) = (&sweep_key, value) {
                overrides.push(Override::new(k.clone(), v.clone()));
            }
            let scene = source.load(variant, &overrides)?;
            let shown = value
                .as_ref()
                .map(|v| Override::new("", v.clone()).display_value());
            plans.push((
                shown,
                config.label(),
                variant.map(str::to_string),
                overrides,
                scene,
            ));
        }
    }
    let out = request.out.as_deref().map(OutputDir::create).transpose()?;
    let mut rows = Vec::new();
    for (sweep_value, label, variant, overrides, scene) in plans {
        let options = RunOptions {
            out: None,
            progress: request.progress,
            variant,
            overrides: overrides
                .iter()
                .map(|o| format!("{}={}", o.key, o.display_value()))
                .collect(),
            checkpoint_every: None,
        };
        let result = run_scene(&scene, &options)
            .map(|(r, _)| r)
            .map_err(|e| e.to_string());
        rows.push(CompareRow {
            sweep_value,
            label,
            result,
        });
    }
    let comparison = Comparison {
        scene: base.name.clone(),
        sweep_key,
        rows,
    };
    let written = match out {
        Some(dir) => {
            write_file(
                &dir.path().join("compare.csv"),
                comparison.to_csv().as_bytes(),
            )?;
            write_file(
                &dir.path().join("compare.md"),
                comparison.to_markdown().as_bytes(),
            )?;
            let json = serde_json::to_string_pretty(&comparison.to_json())
                .map_err(|e| SceneError::Output(e.to_string()))?;
            write_file(&dir.path().join("compare.json"), json.as_bytes())?;
            Some(dir.commit()?)
        }
        None => None,
    };
    Ok((comparison, written))
}

impl Comparison {
    fn probe_names(&self) -> Vec<String> {
        let names: BTreeSet<String> = self
            .rows
            .iter()
            .filter_map(|r| r.result.as_ref().ok())
            .flat_map(|r| r.probes.keys().cloned())
            .filter(|k| k != "volume_change")
            .collect();
        names.into_iter().collect()
    }

    /// Header and cells of the table.
    fn table(&self) -> (Vec<String>, Vec<Vec<String>>) {
        let probes = self.probe_names();
        let mut header = Vec::new();
        if let Some(k) = &self.sweep_key {
            header.push(k.clone());
        }
        header.extend(
            [
                "config",
                "method",
                "nu",
                "tets",
                "dofs",
                "steps",
                "newton_iterations",
                "converged",
            ]
            .map(String::from),
        );
        header.extend(probes.iter().cloned());
        header.extend(
            ["volume_change_percent", "max_inverted_tets", "wall_time_s"].map(String::from),
        );
        let rows = self
            .rows
            .iter()
            .map(|row| {
                let mut cells = Vec::new();
                if self.sweep_key.is_some() {
                    cells.push(row.sweep_value.clone().unwrap_or_default());
                }
                cells.push(row.label.clone());
                match &row.result {
                    Ok(r) => {
                        cells.push(r.method.clone());
                        cells.push(format!("{}", r.nu));
                        cells.push(r.tets.to_string());
                        cells.push(r.dofs.to_string());
                        cells.push(if r.converged {
                            r.steps.to_string()
                        } else {
                            format!("{}/{}", r.steps, r.steps_requested)
                        });
                        cells.push(r.newton_iterations.to_string());
                        cells.push(if r.converged {
                            "yes".into()
                        } else {
                            "no".into()
                        });
                        for p in &probes {
                            cells.push(
                                r.probes
                                    .get(p)
                                    .map_or(String::new(), |v| format!("{v:.6e}")),
                            );
                        }
                        cells.push(format!("{:.4e}", 100.0 * r.volume_change));
                        cells.push(r.max_inverted_tets.to_string());
                        cells.push(format!("{:.3}", r.wall_time_s));
                    }
                    Err(e) => {
                        cells.push(format!("error: {e}"));
                        cells.resize(header.len(), String::new());
                    }
                }
                cells
            })
            .collect();
        (header, rows)
    }

    /// The table as aligned text.
    pub fn to_text(&self) -> String {
        let (header, rows) = self.table();
        let mut widths: Vec<usize> = header.iter().map(String::len).collect();
        for row in &rows {
            for (w, c) in widths.iter_mut().zip(row) {
                *w = (*w).max(c.len());
            }
        }
        let mut out = format!("scene: {}\n", self.scene);
        let line = |cells: &[String]| {
            cells
                .iter()
                .zip(&widths)
                .map(|(c, w)| format!("{c:<w$}"))
                .collect::<Vec<_>>()
                .join("  ")
                .trim_end()
                .to_string()
        };
        let _ = writeln!(out, "{}", line(&header));
        for row in &rows {
            let _ = writeln!(out, "{}", line(row));
        }
        for row in &self.rows {
            if let Ok(r) = &row.result {
                if let Some(e) = &r.error {
                    let _ = writeln!(
                        out,
                        "{}: stopped at step {}: {e}",
                        row.label,
                        r.failed_step.unwrap_or(0)
                    );
                }
            }
        }
        out
    }

    /// The table as CSV.
    pub fn to_csv(&self) -> String {
        let (header, rows) = self.table();
        let quote = |c: &String| {
            if c.contains([',', '"', '\n']) {
                format!("\"{}\"", c.replace('"', "\"\""))
            } else {
                c.clone()
            }
        };
        let mut out = String::new();
        for row in std::iter::once(&header).chain(&rows) {
            let _ = writeln!(
                out,
                "{}",
                row.iter().map(quote).collect::<Vec<_>>().join(",")
            );
        }
        out
    }

    /// The table as Markdown.
    pub fn to_markdown(&self) -> String {
        let (header, rows) = self.table();
        let mut out = format!("# {}\n\n", self.scene);
        let cell = |c: &String| c.replace('|', "\\|");
        let _ = writeln!(
            out,
            "| {} |",
            header.iter().map(cell).collect::<Vec<_>>().join(" | ")
        );
        let _ = writeln!(out, "|{}|", vec!["---"; header.len()].join("|"));
        for row in &rows {
            let _ = writeln!(
                out,
                "| {} |",
                row.iter().map(cell).collect::<Vec<_>>().join(" | ")
            );
        }
        out
    }

    /// Every run as JSON.
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
                }
                v
            })
            .collect();
        serde_json::json!({ "scene": self.scene, "sweep": self.sweep_key, "runs": runs })
    }
}

/// Where a comparison wrote its tables, for messages.
pub fn describe_output(path: &Path) -> String {
    format!(
        "wrote {}, {} and {}",
        path.join("compare.csv").display(),
        path.join("compare.md").display(),
        path.join("compare.json").display()
    )
}
