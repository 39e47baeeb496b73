//! `isochor compare`: the same scene with several methods (or variants) side by side,
//! optionally swept over a parameter, as a table like Tables 1 and 2 of Francu et al. 2021:
//! the published values of the scene's `[paper]` section beside its own, the factor each
//! probe changes by over the sweep, and plots of both ([`plots`]).

mod comparison;
pub mod plots;
mod table;

pub use comparison::{CompareRow, Comparison, Factor, Variant};

use crate::commands::run::{run_scene, RunOptions};
use crate::error::SceneError;
use crate::format::overrides::{parse_sweep, Override};
use crate::format::SceneSource;
use crate::output::{write_file, OutputDir, OutputIdentity};
use isochor_solvers::Method;
use std::path::{Path, PathBuf};

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
    /// Output folder for `compare.csv`, `compare.md`, `compare.json` and the plots.
    pub out: Option<PathBuf>,
    /// Progress bars on stderr.
    pub progress: bool,
}

/// Parses a comma-separated method list, naming the valid methods on error.
pub fn parse_methods(list: &str) -> Result<Vec<Method>, SceneError> {
    list.split(',')
        .map(str::trim)
        .filter(|s| !s.is_empty())
        .map(|s| s.parse::<Method>().map_err(SceneError::from))
        .collect()
}

/// Runs every variant (for every sweep value). Runs that fail to converge are rows
/// with `converged = false`; a scene that cannot be built for one variant is a row
/// with its error. Bad keys, values and names fail the whole comparison before any run.
pub fn compare(request: &CompareRequest) -> Result<(Comparison, Option<PathBuf>), SceneError> {
    let source = SceneSource::resolve(&request.scene)?;
    let base = source.load(None, &request.overrides)?;
    let mut variants: Vec<Variant> = request
        .methods
        .iter()
        .map(|&m| Variant::Method(m))
        .collect();
    variants.extend(request.variants.iter().cloned().map(Variant::Named));
    if variants.is_empty() {
        if base.variants.is_empty() {
            return Err(SceneError::Usage(format!(
                "scene {} has no variants: give --methods (valid: {})",
                base.name,
                Method::ALL.map(Method::name).join(", ")
            )));
        }
        variants.extend(base.variants.keys().cloned().map(Variant::Named));
    }
    let (sweep_key, sweep_values) = match &request.sweep {
        Some(spec) => {
            let (k, v) = parse_sweep(spec)?;
            (Some(k), v.into_iter().map(Some).collect())
        }
        None => (None, vec![None]),
    };
    // Load every variant first, so that a bad key or value fails before any run.
    let mut plans = Vec::new();
    for value in &sweep_values {
        for variant in &variants {
            let mut overrides = request.overrides.clone();
            let named = match variant {
                Variant::Method(m) => {
                    overrides.push(Override::new(
                        "method",
                        toml::Value::String(m.name().into()),
                    ));
                    None
                }
                Variant::Named(v) => Some(v.as_str()),
            };
            if let (Some(k), Some(v)) = (&sweep_key, value) {
                overrides.push(Override::new(k.clone(), v.clone()));
            }
            let scene = source.load(named, &overrides)?;
            let shown = value
                .as_ref()
                .map(|v| Override::new("", v.clone()).display_value());
            plans.push((
                shown,
                variant.label(),
                named.map(str::to_string),
                overrides,
                scene,
            ));
        }
    }
    let out = request
        .out
        .as_deref()
        .map(|d| OutputDir::create(d, OutputIdentity::new("compare", &base.name)))
        .transpose()?;
    let mut rows = Vec::new();
    for (sweep_value, label, variant, overrides, scene) in plans {
        let mut options = RunOptions::in_memory(variant, &overrides, request.progress);
        options.preview = out
            .as_ref()
            .map(|d| d.path().join(preview_name(&label, sweep_value.as_deref())));
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
        paper: base.paper.clone(),
        units: base
            .probes
            .iter()
            .filter_map(|(name, p)| Some((name.clone(), p.unit()?)))
            .collect(),
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
            if comparison.plots_sweep() {
                plots::plot_sweep(&dir.path().join(SWEEP_PLOT), &comparison)?;
            }
            plots::plot_residuals(&dir.path().join(RESIDUALS_PLOT), &comparison)?;
            if comparison.is_dynamic() {
                plots::plot_energies(&dir.path().join(ENERGY_PLOT), &comparison)?;
            }
            Some(dir.commit()?)
        }
        None => None,
    };
    Ok((comparison, written))
}

/// The plot of every probe against the swept value.
pub const SWEEP_PLOT: &str = "compare.png";
/// The plot of the Newton residuals against the accumulated iterations.
pub const RESIDUALS_PLOT: &str = "compare-residuals.png";
/// The plot of the energies and the volume change against time (dynamic scenes).
pub const ENERGY_PLOT: &str = "compare-energy.png";

/// The file of a run's preview (its final state drawn, as `isochor run` draws
/// `preview.png`): `preview-LABEL.png`, or `preview-LABEL-VALUE.png` in a sweep, with every
/// character but letters, digits, `.`, `-` and `_` replaced by `_`.
pub fn preview_name(label: &str, sweep_value: Option<&str>) -> String {
    let stem = match sweep_value {
        Some(v) => format!("{label}-{v}"),
        None => label.to_string(),
    };
    let safe: String = stem
        .chars()
        .map(|c| match c {
            'a'..='z' | 'A'..='Z' | '0'..='9' | '.' | '-' | '_' => c,
            _ => '_',
        })
        .collect();
    format!("preview-{safe}.png")
}

/// Where a comparison wrote its tables and plots, for messages (the previews as a count).
pub fn describe_output(path: &Path) -> String {
    let mut files: Vec<String> = [
        "compare.csv",
        "compare.md",
        "compare.json",
        SWEEP_PLOT,
        RESIDUALS_PLOT,
        ENERGY_PLOT,
    ]
    .iter()
    .map(|f| path.join(f))
    .filter(|p| p.is_file())
    .map(|p| p.display().to_string())
    .collect();
    let previews = std::fs::read_dir(path).map_or(0, |entries| {
        entries
            .filter_map(Result::ok)
            .filter(|e| e.file_name().to_string_lossy().starts_with("preview-"))
            .count()
    });
    if previews > 0 {
        files.push(format!("{previews} previews (preview-*.png)"));
    }
    format!("wrote {}", files.join(", "))
}
