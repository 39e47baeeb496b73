//! `isochor study`: the speed/accuracy trade of several methods and elements over mesh
//! resolutions.
//!
//! Every method runs on every element (`--elements tet4,tet10`, default the scene's element)
//! at every resolution of the sweep (`--sweep res=1,2,4,8`, the mesh size taken as
//! `h = 1 / value`); each (method, element) pair is a series, labelled `METHOD/ELEMENT` when
//! the study has more than one element and `METHOD` otherwise. Each run records its wall time,
//! unknowns, Newton iterations and one probe. With `--max-unknowns N`, a run whose linear
//! system would have more than `N` unknowns (counted on the built problem before solving) is
//! skipped, and so are the finer runs of its series.
//!
//! Every series with three converged runs is extrapolated (Richardson): with
//! `f = f_inf + C h^p`, the observed order `p` solves
//! `(f1 - f2) / (f2 - f3) = (h1^p - h2^p) / (h2^p - h3^p)`. Its error estimate is the change
//! of the extrapolation when the finest run is added (the difference between the limits of
//! the last two triples), or, with only three runs, the conservative `|f_inf - f3|`. The
//! reference is a value known from elsewhere (`--reference-value`, with its relative
//! uncertainty `--reference-uncertainty`), or the extrapolation of the best-converging series
//! (the one whose extrapolation moves least from its finest value, unless
//! `--reference METHOD[/ELEMENT]` names it). The error of a run is
//! `|probe - reference| / |reference|`; for 10%, 5% and 1% the fastest run within them is
//! marked, with a warning when the reference is not known to better than the level. A series
//! whose own extrapolation lies farther from the reference than a level (beyond both
//! uncertainties) converges elsewhere: its runs within that level are crossings and do not
//! count as reaching it.
//! Outputs: `study.csv`, `study.md`, the log-log plot `study.png` of error against time and
//! `study-unknowns.png`, the probe against the unknowns (log scale) with the reference line.

mod plots;
mod reports;
mod request;
mod results;
mod richardson;

pub use plots::{plot_study, plot_unknowns};
pub use request::{parse_element, parse_elements, ReferenceSpec, StudyRequest};
pub use results::{Reference, Skipped, Study, StudyRun, LEVELS};
pub use richardson::{richardson, Richardson};

use crate::commands::run::{run_scene, RunOptions};
use crate::error::SceneError;
use crate::format::overrides::parse_sweep;
use crate::format::{Override, SceneSource};
use crate::output::{write_file, OutputDir, OutputIdentity};
use isochor_mesh::element::TetElement;
use isochor_solvers::{Method, Simulation};
use std::path::PathBuf;

/// Probes tried, in order, when `--probe` is not given.
const PREFERRED_PROBES: [&str; 5] = [
    "tip_deflection",
    "top_center_deflection",
    "end_deflection",
    "mean_radius_increase",
    "bulge_height",
];

/// Runs the study. Bad names or values fail before any run; runs that do not converge are
/// rows without an error value.
pub fn study(request: &StudyRequest) -> Result<(Study, Option<PathBuf>), SceneError> {
    if request.methods.is_empty() {
        return Err(SceneError::Usage(format!(
            "give --methods (valid: {})",
            Method::ALL.map(Method::name).join(", ")
        )));
    }
    let source = SceneSource::resolve(&request.scene)?;
    let base = source.load(None, &request.overrides)?;
    let probe = match &request.probe {
        Some(p) => {
            if !base.probes.contains_key(p) {
                return Err(SceneError::Usage(format!(
                    "scene {} has no probe {p} (probes: {})",
                    base.name,
                    base.probes.keys().cloned().collect::<Vec<_>>().join(", ")
                )));
            }
            p.clone()
        }
        None => PREFERRED_PROBES
            .iter()
            .find(|p| base.probes.contains_key(**p))
            .map(|p| p.to_string())
            .or_else(|| base.probes.keys().find(|k| *k != "volume_change").cloned())
            .ok_or_else(|| {
                SceneError::Usage(format!("scene {} has no probe to study", base.name))
            })?,
    };
    let mut methods: Vec<Method> = Vec::new();
    for m in &request.methods {
        if !methods.contains(m) {
            methods.push(*m);
        }
    }
    let mut elements: Vec<TetElement> = Vec::new();
    for e in &request.elements {
        if !elements.contains(e) {
            elements.push(*e);
        }
    }
    let explicit_elements = !elements.is_empty();
    if !explicit_elements {
        elements.push(base.element());
    }
    check_reference(&request.reference, &methods, &elements)?;
    let (key, values) = parse_sweep(request.sweep.as_deref().unwrap_or("res=1,2,4,8"))?;
    let mut levels = Vec::new();
    for v in &values {
        let r = v
            .as_float()
            .or_else(|| v.as_integer().map(|i| i as f64))
            .filter(|r| r.is_finite() && *r > 0.0)
            .ok_or_else(|| SceneError::Override {
                key: key.clone(),
                message: format!("study sweeps a resolution: {v} is not a positive number"),
            })?;
        levels.push((r, v.clone()));
    }
    levels.sort_by(|a, b| a.0.total_cmp(&b.0));
    let mut plans = Vec::new();
    let mut skipped = Vec::new();
    for method in &methods {
        for element in &elements {
            let mut over_limit = false;
            for (r, v) in &levels {
                let mut overrides = request.overrides.clone();
                overrides.push(Override::new(
                    "method",
                    toml::Value::String(method.name().into()),
                ));
                if explicit_elements {
                    overrides.push(Override::new(
                        "element",
                        toml::Value::String(element.name().into()),
                    ));
                }
                overrides.push(Override::new(key.clone(), v.clone()));
                let scene = source.load(None, &overrides)?;
                let label = Override::new("", v.clone()).display_value();
                if let Some(limit) = request.max_unknowns {
                    // Finer runs of a series only grow: count until one is over the limit.
                    let unknowns = if over_limit {
                        None
                    } else {
                        let built = crate::resolve::build(&scene)?;
                        Some(Simulation::new(built.problem, built.settings)?.num_dofs())
                    };
                    if over_limit || unknowns.is_some_and(|u| u > limit) {
                        over_limit = true;
                        skipped.push(Skipped {
                            method: method.name().to_string(),
                            element: element.name().to_string(),
                            label,
                            unknowns,
                        });
                        continue;
                    }
                }
                plans.push((
                    method.name().to_string(),
                    element.name().to_string(),
                    label,
                    *r,
                    overrides,
                    scene,
                ));
            }
        }
    }
    let out = request
        .out
        .as_deref()
        .map(|d| OutputDir::create(d, OutputIdentity::new("study", &base.name)))
        .transpose()?;
    let mut runs = Vec::new();
    for (method, element, label, resolution, overrides, scene) in plans {
        let options = RunOptions::in_memory(None, &overrides, request.progress);
        let result = run_scene(&scene, &options)
            .map(|(r, _)| r)
            .map_err(|e| e.to_string());
        let value = result
            .as_ref()
            .ok()
            .filter(|r| r.converged)
            .and_then(|r| r.probes.get(&probe).copied())
            .filter(|v| v.is_finite());
        runs.push(StudyRun {
            method,
            element,
            label,
            resolution,
            result,
            value,
            error: None,
        });
    }
    let mut study = Study::from_runs(base.name.clone(), key, probe, runs, request.reference)?;
    study.skipped = skipped;
    study.max_unknowns = request.max_unknowns;
    let written = match out {
        Some(dir) => {
            write_file(&dir.path().join("study.csv"), study.to_csv().as_bytes())?;
            write_file(&dir.path().join("study.md"), study.to_markdown().as_bytes())?;
            plot_study(&dir.path().join("study.png"), &study)?;
            plot_unknowns(&dir.path().join("study-unknowns.png"), &study)?;
            Some(dir.commit()?)
        }
        None => None,
    };
    Ok((study, written))
}

/// Checks a reference request against the study's methods and elements, before any run.
fn check_reference(
    reference: &ReferenceSpec,
    methods: &[Method],
    elements: &[TetElement],
) -> Result<(), SceneError> {
    match *reference {
        ReferenceSpec::Best => Ok(()),
        ReferenceSpec::Series { method, element } => {
            if !methods.contains(&method) {
                return Err(SceneError::Usage(format!(
                    "--reference {}: the study does not run that method (--methods {})",
                    method.name(),
                    methods
                        .iter()
                        .map(|m| m.name())
                        .collect::<Vec<_>>()
                        .join(",")
                )));
            }
            match element {
                Some(e) if !elements.contains(&e) => Err(SceneError::Usage(format!(
                    "--reference {}/{}: the study does not run that element (elements: {})",
                    method.name(),
                    e.name(),
                    elements
                        .iter()
                        .map(|e| e.name())
                        .collect::<Vec<_>>()
                        .join(",")
                ))),
                _ => Ok(()),
            }
        }
        ReferenceSpec::Value {
            value,
            relative_uncertainty,
        } => {
            if !(value.is_finite() && value != 0.0) {
                return Err(SceneError::Usage(format!(
                    "--reference-value {value}: errors are relative to it, so it must be finite and not zero"
                )));
            }
            if !(relative_uncertainty.is_finite() && relative_uncertainty >= 0.0) {
                return Err(SceneError::Usage(format!(
                    "--reference-uncertainty {relative_uncertainty}: a relative uncertainty is finite and not negative"
                )));
            }
            Ok(())
        }
    }
}
