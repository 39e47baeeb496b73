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

use crate::commands::run::{run_scene, RunOptions};
use crate::error::SceneError;
use crate::format::overrides::{parse_sweep, Override};
use crate::format::{ElementName, SceneSource};
use crate::output::{finish_plot, plot_error, range, tick, write_file, OutputDir};
use crate::record::RunResult;
use isochor_mesh::element::TetElement;
use isochor_solvers::{Method, Simulation};
use plotters::prelude::*;
use std::fmt::Write;
use std::path::{Path, PathBuf};

/// Error levels at which the fastest run is marked, coarse to fine.
pub const LEVELS: [f64; 3] = [0.10, 0.05, 0.01];

/// Probes tried, in order, when `--probe` is not given.
const PREFERRED_PROBES: [&str; 5] = [
    "tip_deflection",
    "top_center_deflection",
    "end_deflection",
    "mean_radius_increase",
    "bulge_height",
];

/// A study request.
#[derive(Debug, Clone, Default)]
pub struct StudyRequest {
    /// Built-in name or scene path.
    pub scene: String,
    /// Methods to compare.
    pub methods: Vec<Method>,
    /// Elements to run every method on (empty: the scene's element).
    pub elements: Vec<TetElement>,
    /// `KEY=V1,V2,...` over mesh resolutions (default `res=1,2,4,8`).
    pub sweep: Option<String>,
    /// The probe to measure (default: the scene's deflection probe).
    pub probe: Option<String>,
    /// Where the reference comes from (default: the best-converging series).
    pub reference: ReferenceSpec,
    /// Skip runs with more unknowns than this (and the finer runs of their series).
    pub max_unknowns: Option<usize>,
    /// `--set` overrides applied to every run.
    pub overrides: Vec<Override>,
    /// Output folder for `study.csv`, `study.md`, `study.png` and `study-unknowns.png`.
    pub out: Option<PathBuf>,
    /// Progress bars on stderr.
    pub progress: bool,
}

/// Where the reference of a study comes from.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub enum ReferenceSpec {
    /// The extrapolation of the best-converging series.
    #[default]
    Best,
    /// The extrapolation of one method's series: on `element`, or, when `None`, the
    /// best-converging of that method's series.
    Series {
        /// The method.
        method: Method,
        /// The element, if the method runs on several.
        element: Option<TetElement>,
    },
    /// A value known from elsewhere (an independent, finer computation).
    Value {
        /// The reference value of the probe (finite, not zero: errors are relative to it).
        value: f64,
        /// Its relative uncertainty (0 when taken as exact): levels finer than this are not
        /// resolved.
        relative_uncertainty: f64,
    },
}

impl ReferenceSpec {
    /// Parses `--reference METHOD[/ELEMENT]`.
    pub fn parse_series(text: &str) -> Result<ReferenceSpec, SceneError> {
        let (method, element) = match text.trim().split_once('/') {
            Some((m, e)) => (m.trim(), Some(parse_element(e.trim())?)),
            None => (text.trim(), None),
        };
        Ok(ReferenceSpec::Series {
            method: method.parse()?,
            element,
        })
    }
}

/// Parses one element name (`tet4`, `tet10`).
pub fn parse_element(name: &str) -> Result<TetElement, SceneError> {
    name.parse::<ElementName>()
        .map(|e| e.0)
        .map_err(SceneError::Usage)
}

/// Parses a comma-separated element list (`--elements tet4,tet10`).
pub fn parse_elements(list: &str) -> Result<Vec<TetElement>, SceneError> {
    list.split(',')
        .map(str::trim)
        .filter(|s| !s.is_empty())
        .map(parse_element)
        .collect()
}

/// The label of a series: `METHOD/ELEMENT`, or `METHOD` alone when the study has one element.
fn series_label(method: &str, element: &str, several_elements: bool) -> String {
    if several_elements {
        format!("{method}/{element}")
    } else {
        method.to_string()
    }
}

/// One run of the study.
#[derive(Debug, Clone)]
pub struct StudyRun {
    /// Method name.
    pub method: String,
    /// Element name (`tet4`, `tet10`).
    pub element: String,
    /// The swept value as given.
    pub label: String,
    /// The swept value as a number (the resolution; `h = 1 / resolution`).
    pub resolution: f64,
    /// The run, or why it could not start.
    pub result: Result<RunResult, String>,
    /// The probe's value, if the run converged.
    pub value: Option<f64>,
    /// `|value - reference| / |reference|`.
    pub error: Option<f64>,
}

impl StudyRun {
    fn converged(&self) -> Option<&RunResult> {
        self.result.as_ref().ok().filter(|r| r.converged)
    }

    fn wall_time(&self) -> Option<f64> {
        self.converged().map(|r| r.wall_time_s)
    }
}

/// A Richardson extrapolation from three runs of one series.
#[derive(Debug, Clone, PartialEq)]
pub struct Richardson {
    /// The method.
    pub method: String,
    /// The element.
    pub element: String,
    /// Resolutions of the three runs, coarse to fine.
    pub resolutions: [f64; 3],
    /// Their probe values.
    pub values: [f64; 3],
    /// Observed order of convergence in `h`.
    pub order: f64,
    /// The extrapolated limit.
    pub limit: f64,
    /// `|limit - finest value|`.
    pub finest_gap: f64,
    /// `|limit - limit of the previous triple|`, with four or more runs.
    pub previous_gap: Option<f64>,
}

impl Richardson {
    /// The estimated error of the limit: the previous gap, or the finest gap without one.
    pub fn estimate(&self) -> f64 {
        self.previous_gap.unwrap_or(self.finest_gap)
    }

    /// [`Richardson::estimate`] relative to the limit.
    pub fn relative_estimate(&self) -> f64 {
        self.estimate() / self.limit.abs()
    }
}

/// Extrapolates `f(h) = f_inf + C h^p` through three (resolution, value) pairs, coarse to
/// fine. `None` if the values do not converge monotonically (oscillate or diverge) or the
/// order is outside (0.05, 20).
pub fn richardson(points: [(f64, f64); 3]) -> Option<(f64, f64)> {
    let h = points.map(|(r, _)| 1.0 / r);
    let f = points.map(|(_, v)| v);
    let (d1, d2) = (f[0] - f[1], f[1] - f[2]);
    let ordered = h[0] > h[1] && h[1] > h[2] && h[2] > 0.0;
    let ratio = d1 / d2;
    // Monotone: differences of one sign (a zero d2 gives inf or NaN); whether they shrink
    // fast enough for a positive order is decided by the bracket below.
    if !ordered || !ratio.is_finite() || ratio <= 0.0 {
        return None;
    }
    let g = |p: f64| (h[0].powf(p) - h[1].powf(p)) / (h[1].powf(p) - h[2].powf(p)) - ratio;
    let (mut lo, mut hi) = (0.05, 20.0);
    if g(lo) > 0.0 || g(hi) < 0.0 {
        return None;
    }
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if g(mid) < 0.0 {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    let p = 0.5 * (lo + hi);
    let c = d2 / (h[1].powf(p) - h[2].powf(p));
    Some((p, f[2] - c * h[2].powf(p)))
}

/// The reference a study measures errors against.
#[derive(Debug, Clone, PartialEq)]
pub enum Reference {
    /// The extrapolation of one series.
    Extrapolated(Richardson),
    /// A value given with the study (`--reference-value`).
    Given {
        /// The value.
        value: f64,
        /// Its relative uncertainty.
        relative_uncertainty: f64,
    },
}

impl Reference {
    /// The reference value of the probe.
    pub fn value(&self) -> f64 {
        match self {
            Reference::Extrapolated(r) => r.limit,
            Reference::Given { value, .. } => *value,
        }
    }

    /// Its relative uncertainty: the extrapolation's relative estimate, or the given one.
    pub fn relative_uncertainty(&self) -> f64 {
        match self {
            Reference::Extrapolated(r) => r.relative_estimate(),
            Reference::Given {
                relative_uncertainty,
                ..
            } => *relative_uncertainty,
        }
    }

    /// The extrapolation, if the reference is one.
    pub fn extrapolation(&self) -> Option<&Richardson> {
        match self {
            Reference::Extrapolated(r) => Some(r),
            Reference::Given { .. } => None,
        }
    }
}

/// A run left out by `--max-unknowns`.
#[derive(Debug, Clone, PartialEq)]
pub struct Skipped {
    /// Method name.
    pub method: String,
    /// Element name.
    pub element: String,
    /// The swept value as given.
    pub label: String,
    /// Its unknowns, if counted (a finer run of a series already over the limit is not).
    pub unknowns: Option<usize>,
}

/// The result of a study.
#[derive(Debug, Clone)]
pub struct Study {
    /// Scene name.
    pub scene: String,
    /// The swept key.
    pub sweep_key: String,
    /// The probe measured.
    pub probe: String,
    /// Every run, series by series (method-major, then element), coarse to fine.
    pub runs: Vec<StudyRun>,
    /// The extrapolation of every series that allowed one.
    pub extrapolations: Vec<Richardson>,
    /// The reference: given, or one of `extrapolations`.
    pub reference: Option<Reference>,
    /// Runs left out by `--max-unknowns`, with the limit.
    pub skipped: Vec<Skipped>,
    /// The `--max-unknowns` limit, if any.
    pub max_unknowns: Option<usize>,
}

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
    let out = request.out.as_deref().map(OutputDir::create).transpose()?;
    let mut runs = Vec::new();
    for (method, element, label, resolution, overrides, scene) in plans {
        let options = RunOptions {
            out: None,
            progress: request.progress,
            variant: None,
            overrides: overrides
                .iter()
                .map(|o| format!("{}={}", o.key, o.display_value()))
                .collect(),
            checkpoint_every: None,
        };
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

/// Seconds to three significant digits (`0.0183 s`, `1.15 s`, `36.2 s`, `341 s`).
fn seconds(t: f64) -> String {
    if !t.is_finite() || t <= 0.0 {
        return format!("{t} s");
    }
    let digits = (2 - t.log10().floor() as i32).max(0) as usize;
    format!("{t:.digits$} s")
}

/// A relative error as a percentage with two decimals, or three significant digits below
/// 0.1% (`12.34%`, `0.0512%`).
fn percent(e: f64) -> String {
    let p = 100.0 * e;
    if p > 0.0 && p < 0.1 {
        let digits = (2 - p.log10().floor() as i32).max(0) as usize;
        format!("{p:.digits$}%")
    } else {
        format!("{p:.2}%")
    }
}

impl Study {
    /// The study of finished runs (series by series, coarse to fine): extrapolates every
    /// series with three converged runs, takes the reference `wanted` asks for and measures
    /// every run's error against it.
    pub fn from_runs(
        scene: String,
        sweep_key: String,
        probe: String,
        runs: Vec<StudyRun>,
        wanted: ReferenceSpec,
    ) -> Result<Study, SceneError> {
        let mut study = Study {
            scene,
            sweep_key,
            probe,
            runs,
            extrapolations: Vec::new(),
            reference: None,
            skipped: Vec::new(),
            max_unknowns: None,
        };
        study.extrapolate(wanted)?;
        Ok(study)
    }

    /// Whether the study runs more than one element (series are then labelled
    /// `METHOD/ELEMENT`).
    pub fn several_elements(&self) -> bool {
        self.runs
            .iter()
            .map(|r| &r.element)
            .chain(self.skipped.iter().map(|s| &s.element))
            .any(|e| self.runs.first().is_some_and(|f| f.element != *e))
    }

    /// The label of the series of `method` on `element`.
    pub fn label(&self, method: &str, element: &str) -> String {
        series_label(method, element, self.several_elements())
    }

    /// The label of a run's series.
    pub fn run_label(&self, run: &StudyRun) -> String {
        self.label(&run.method, &run.element)
    }

    /// Converged (resolution, value) pairs of one series, coarse to fine.
    fn series(&self, method: &str, element: &str) -> Vec<(f64, f64)> {
        self.runs
            .iter()
            .filter(|r| r.method == method && r.element == element)
            .filter_map(|r| r.value.map(|v| (r.resolution, v)))
            .collect()
    }

    /// The (method, element) pairs, in the order of the runs.
    pub fn series_keys(&self) -> Vec<(String, String)> {
        let mut keys: Vec<(String, String)> = Vec::new();
        for r in &self.runs {
            if !keys.iter().any(|(m, e)| *m == r.method && *e == r.element) {
                keys.push((r.method.clone(), r.element.clone()));
            }
        }
        keys
    }

    /// The series labels, in the order of the runs.
    pub fn series_labels(&self) -> Vec<String> {
        self.series_keys()
            .iter()
            .map(|(m, e)| self.label(m, e))
            .collect()
    }

    fn extrapolate(&mut self, wanted: ReferenceSpec) -> Result<(), SceneError> {
        for (method, element) in self.series_keys() {
            let s = self.series(&method, &element);
            if s.len() < 3 {
                continue;
            }
            let n = s.len();
            let Some((order, limit)) = richardson([s[n - 3], s[n - 2], s[n - 1]]) else {
                continue;
            };
            let previous_gap = (n >= 4)
                .then(|| richardson([s[n - 4], s[n - 3], s[n - 2]]))
                .flatten()
                .map(|(_, l)| (limit - l).abs());
            self.extrapolations.push(Richardson {
                method: method.clone(),
                element: element.clone(),
                resolutions: [s[n - 3].0, s[n - 2].0, s[n - 1].0],
                values: [s[n - 3].1, s[n - 2].1, s[n - 1].1],
                order,
                limit,
                finest_gap: (limit - s[n - 1].1).abs(),
                previous_gap,
            });
        }
        let best = |candidates: Vec<&Richardson>| {
            candidates
                .into_iter()
                .min_by(|a, b| a.relative_estimate().total_cmp(&b.relative_estimate()))
                .cloned()
                .map(Reference::Extrapolated)
        };
        self.reference = match wanted {
            ReferenceSpec::Best => best(self.extrapolations.iter().collect()),
            ReferenceSpec::Series { method, element } => {
                let candidates: Vec<&Richardson> = self
                    .extrapolations
                    .iter()
                    .filter(|e| e.method == method.name())
                    .filter(|e| element.is_none_or(|el| e.element == el.name()))
                    .collect();
                let name = match element {
                    Some(e) => format!("{}/{}", method.name(), e.name()),
                    None => method.name().to_string(),
                };
                Some(best(candidates).ok_or_else(|| {
                    SceneError::Usage(format!(
                        "{name} cannot be extrapolated: it needs three converged runs whose values converge monotonically"
                    ))
                })?)
            }
            ReferenceSpec::Value {
                value,
                relative_uncertainty,
            } => Some(Reference::Given {
                value,
                relative_uncertainty,
            }),
        };
        if let Some(reference) = &self.reference {
            let value = reference.value();
            for run in &mut self.runs {
                run.error = run.value.map(|v| (v - value).abs() / value.abs());
            }
        }
        Ok(())
    }

    /// Whether the reference is known to within `level` (relative), so that errors at that
    /// level mean something.
    pub fn resolves(&self, level: f64) -> bool {
        self.reference
            .as_ref()
            .is_some_and(|r| r.relative_uncertainty() <= level)
    }

    /// The relative distance of the series labelled `series`' own extrapolated limit from the
    /// reference, if the series converges elsewhere at `level`: when even the nearest reading
    /// of both (the distance minus the extrapolation's estimate and the reference's
    /// uncertainty) is farther than `level`. Its runs within `level` are then crossings on the
    /// way to another limit (a method that solves a different model, such as `zonal` with its
    /// own penalty), which no resolution can be chosen in advance to hit, and are not counted
    /// as reaching the level.
    pub fn converges_elsewhere(&self, level: f64, series: &str) -> Option<f64> {
        let reference = self.reference.as_ref()?;
        let value = reference.value();
        let e = self
            .extrapolations
            .iter()
            .find(|e| self.label(&e.method, &e.element) == series)?;
        let distance = (e.limit - value).abs() / value.abs();
        (distance - e.relative_estimate() - reference.relative_uncertainty() > level)
            .then_some(distance)
    }

    /// Index of the fastest converged run with error at most `level`, of the series labelled
    /// `series` if given (see [`Study::label`]), leaving out series that converge elsewhere
    /// (see [`Study::converges_elsewhere`]).
    pub fn fastest(&self, level: f64, series: Option<&str>) -> Option<usize> {
        self.runs
            .iter()
            .enumerate()
            .filter(|(_, r)| series.is_none_or(|s| self.run_label(r) == s))
            .filter(|(_, r)| r.error.is_some_and(|e| e <= level))
            .filter(|(_, r)| {
                self.converges_elsewhere(level, &self.run_label(r))
                    .is_none()
            })
            .filter_map(|(i, r)| r.wall_time().map(|t| (i, t)))
            .min_by(|a, b| a.1.total_cmp(&b.1))
            .map(|(i, _)| i)
    }

    fn header(&self) -> Vec<String> {
        [
            "method",
            "element",
            self.sweep_key.as_str(),
            "tets",
            "dofs",
            "steps",
            "newton_iterations",
            "converged",
            "wall_time_s",
            self.probe.as_str(),
            "error",
        ]
        .map(String::from)
        .to_vec()
    }

    /// Column of the probe in [`Study::header`].
    const PROBE_COLUMN: usize = 9;

    fn rows(&self) -> Vec<Vec<String>> {
        let width = self.header().len();
        self.runs
            .iter()
            .map(|run| {
                let mut c = vec![run.method.clone(), run.element.clone(), run.label.clone()];
                match &run.result {
                    Ok(r) => {
                        c.push(r.tets.to_string());
                        c.push(r.dofs.to_string());
                        c.push(format!("{}/{}", r.steps, r.steps_requested));
                        c.push(r.newton_iterations.to_string());
                        c.push(if r.converged { "yes" } else { "no" }.into());
                        c.push(format!("{:.3}", r.wall_time_s));
                        c.push(run.value.map_or(String::new(), |v| format!("{v:.6e}")));
                        c.push(run.error.map_or(String::new(), |e| format!("{e:.3e}")));
                    }
                    Err(e) => {
                        c.push(format!("error: {e}"));
                        c.resize(width, String::new());
                    }
                }
                c
            })
            .collect()
    }

    /// One line per run left out by `--max-unknowns`.
    fn skipped_lines(&self) -> String {
        let mut s = String::new();
        for k in &self.skipped {
            let _ = writeln!(
                s,
                "skipped {} at {} = {}: {} (--max-unknowns {})",
                self.label(&k.method, &k.element),
                self.sweep_key,
                k.label,
                match k.unknowns {
                    Some(u) => format!("{u} unknowns"),
                    None => "a coarser run of the series is already over the limit".into(),
                },
                self.max_unknowns.map_or("?".into(), |m| m.to_string())
            );
        }
        s
    }

    /// The reference and the fastest runs per error level, for people.
    pub fn summary(&self) -> String {
        let mut s = String::new();
        let given = self
            .reference
            .as_ref()
            .filter(|r| r.extrapolation().is_none())
            .map(Reference::value);
        for e in &self.extrapolations {
            let _ = writeln!(
                s,
                "extrapolation of {} from {} = {:?}: {:?} -> {:.6e} (observed order {:.2}; |limit - finest| = {:.2e} ({:.3}%){}{})",
                self.label(&e.method, &e.element),
                self.sweep_key,
                e.resolutions,
                e.values,
                e.limit,
                e.order,
                e.finest_gap,
                100.0 * e.finest_gap / e.limit.abs(),
                e.previous_gap
                    .map(|g| format!(", |limit - previous limit| = {g:.2e} ({:.3}%)", 100.0 * g / e.limit.abs()))
                    .unwrap_or_default(),
                given
                    .map(|v| format!("; {:.3}% from the reference", 100.0 * (e.limit - v).abs() / v.abs()))
                    .unwrap_or_default()
            );
        }
        match &self.reference {
            Some(Reference::Extrapolated(r)) => {
                let _ = writeln!(
                    s,
                    "reference {} = {:.6e} (Richardson extrapolation of {}), estimated error {:.2e} ({:.3}%)",
                    self.probe,
                    r.limit,
                    self.label(&r.method, &r.element),
                    r.estimate(),
                    100.0 * r.relative_estimate()
                );
            }
            Some(Reference::Given {
                value,
                relative_uncertainty,
            }) => {
                let _ = writeln!(
                    s,
                    "reference {} = {value:.6e} (given), relative uncertainty {:.3}%",
                    self.probe,
                    100.0 * relative_uncertainty
                );
            }
            None => {
                let _ = writeln!(
                    s,
                    "no reference: no series has three converged runs that converge monotonically"
                );
                return s;
            }
        }
        for level in LEVELS {
            if let Some(r) = self.reference.as_ref().filter(|_| !self.resolves(level)) {
                let _ = writeln!(
                    s,
                    "error <= {:.0}%: not resolved (the reference is uncertain by {:.2}%)",
                    100.0 * level,
                    100.0 * r.relative_uncertainty()
                );
                continue;
            }
            let Some(best) = self.fastest(level, None) else {
                let _ = writeln!(s, "error <= {:.0}%: no run", 100.0 * level);
                continue;
            };
            let b = &self.runs[best];
            let best_label = self.run_label(b);
            let t = b.wall_time().unwrap_or(f64::NAN);
            let mut line = format!(
                "error <= {:.0}%: fastest {} at {} = {} ({:.3} s, error {:.2}%)",
                100.0 * level,
                best_label,
                self.sweep_key,
                b.label,
                t,
                100.0 * b.error.unwrap_or(f64::NAN)
            );
            let others: Vec<String> = self
                .series_labels()
                .into_iter()
                .filter(|m| *m != best_label)
                .map(|m| match (self.fastest(level, Some(&m)), self.converges_elsewhere(level, &m)) {
                    (None, Some(d)) => format!(
                        "{m} converges elsewhere (its extrapolated limit is {:.2}% from the reference)",
                        100.0 * d
                    ),
                    (Some(i), _) => {
                        let o = &self.runs[i];
                        let ot = o.wall_time().unwrap_or(f64::NAN);
                        format!(
                            "{m} needs {} = {} ({:.3} s, {:.1}x slower)",
                            self.sweep_key,
                            o.label,
                            ot,
                            ot / t
                        )
                    }
                    (None, None) => format!("{m} does not reach it"),
                })
                .collect();
            if !others.is_empty() {
                line += &format!("; {}", others.join("; "));
            }
            let _ = writeln!(s, "{line}");
        }
        s
    }

    /// The table and summary as aligned text.
    pub fn to_text(&self) -> String {
        let header = self.header();
        let rows = self.rows();
        let mut widths: Vec<usize> = header.iter().map(String::len).collect();
        for row in &rows {
            for (w, c) in widths.iter_mut().zip(row) {
                *w = (*w).max(c.len());
            }
        }
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
        let mut out = format!("scene: {}, probe: {}\n", self.scene, self.probe);
        let _ = writeln!(out, "{}", line(&header));
        for row in &rows {
            let _ = writeln!(out, "{}", line(row));
        }
        for run in &self.runs {
            if let Ok(r) = &run.result {
                if let Some(e) = &r.error {
                    let _ = writeln!(
                        out,
                        "{} at {} = {}: stopped at step {}: {e}",
                        self.run_label(run),
                        self.sweep_key,
                        run.label,
                        r.failed_step.unwrap_or(0)
                    );
                }
            }
        }
        out += &self.skipped_lines();
        out + &self.summary()
    }

    /// Every run as CSV, with the reference in the last columns.
    pub fn to_csv(&self) -> String {
        let mut header = self.header();
        header[Self::PROBE_COLUMN] = format!("probe:{}", self.probe);
        header.push("reference".into());
        let reference = self
            .reference
            .as_ref()
            .map_or(String::new(), |r| format!("{:.9e}", r.value()));
        let mut out = String::new();
        let _ = writeln!(out, "{}", header.join(","));
        for mut row in self.rows() {
            row.push(reference.clone());
            let quoted: Vec<String> = row
                .iter()
                .map(|c| {
                    if c.contains([',', '"', '\n']) {
                        format!("\"{}\"", c.replace('"', "\"\""))
                    } else {
                        c.clone()
                    }
                })
                .collect();
            let _ = writeln!(out, "{}", quoted.join(","));
        }
        out
    }

    /// Error against wall time as a Markdown table: one row per swept value, one column per
    /// series, each cell `error, time (unknowns)`; runs that did not converge say so, skipped
    /// and missing runs are blank.
    pub fn error_table(&self) -> String {
        let keys = self.series_keys();
        let mut values: Vec<(f64, String)> = Vec::new();
        for r in &self.runs {
            if !values.iter().any(|(_, l)| *l == r.label) {
                values.push((r.resolution, r.label.clone()));
            }
        }
        values.sort_by(|a, b| a.0.total_cmp(&b.0));
        let mut out = format!("| {} |", self.sweep_key);
        for (m, e) in &keys {
            out += &format!(" {} |", self.label(m, e));
        }
        out += "\n|---|";
        out += &"---|".repeat(keys.len());
        out += "\n";
        for (_, label) in &values {
            out += &format!("| {label} |");
            for (m, e) in &keys {
                let run = self
                    .runs
                    .iter()
                    .find(|r| r.method == *m && r.element == *e && r.label == *label);
                let cell = match run.map(|r| (r, &r.result)) {
                    None => String::new(),
                    Some((_, Err(_))) => "error".into(),
                    Some((_, Ok(res))) if !res.converged => {
                        format!("not converged, {}", seconds(res.wall_time_s))
                    }
                    Some((r, Ok(res))) => format!(
                        "{}, {} ({} unknowns)",
                        r.error.map_or("-".into(), percent),
                        seconds(res.wall_time_s),
                        res.dofs
                    ),
                };
                out += &format!(" {cell} |");
            }
            out += "\n";
        }
        out
    }

    /// The fastest run of every series within each error level, as a Markdown table: one row
    /// per level, the overall fastest first, then each series' own fastest run.
    pub fn fastest_table(&self) -> String {
        let labels = self.series_labels();
        let mut out = "| error | fastest |".to_string();
        for l in &labels {
            out += &format!(" {l} |");
        }
        out += "\n|---|---|";
        out += &"---|".repeat(labels.len());
        out += "\n";
        let cell = |i: usize| {
            let r = &self.runs[i];
            format!(
                "{} {}: {} ({})",
                self.sweep_key,
                r.label,
                seconds(r.wall_time().unwrap_or(f64::NAN)),
                r.error.map_or("-".into(), percent)
            )
        };
        for level in LEVELS {
            out += &format!("| {:.0}% |", 100.0 * level);
            if !self.resolves(level) {
                out += " not resolved |";
                out += &" |".repeat(labels.len());
                out += "\n";
                continue;
            }
            match self.fastest(level, None) {
                Some(i) => {
                    out += &format!(" **{}** at {} |", self.run_label(&self.runs[i]), cell(i))
                }
                None => out += " no run |",
            }
            for l in &labels {
                match (
                    self.fastest(level, Some(l)),
                    self.converges_elsewhere(level, l),
                ) {
                    (Some(i), _) => out += &format!(" {} |", cell(i)),
                    (None, Some(d)) => {
                        out += &format!(" converges elsewhere (limit {} off) |", percent(d))
                    }
                    (None, None) => out += " not reached |",
                }
            }
            out += "\n";
        }
        out
    }

    /// The tables and summary as Markdown.
    pub fn to_markdown(&self) -> String {
        let header = self.header();
        let mut out = format!("# Study: {} ({})\n\n", self.scene, self.probe);
        let _ = writeln!(out, "| {} |", header.join(" | "));
        let _ = writeln!(out, "|{}|", vec!["---"; header.len()].join("|"));
        for row in self.rows() {
            let cells: Vec<String> = row.iter().map(|c| c.replace('|', "\\|")).collect();
            let _ = writeln!(out, "| {} |", cells.join(" | "));
        }
        out += "\n## Error against wall time\n\n";
        out += &self.error_table();
        out += "\n## Fastest run within each error level\n\n";
        out += &self.fastest_table();
        out += "\n```text\n";
        out += &self.skipped_lines();
        out += &self.summary();
        out += "```\n";
        out
    }
}

/// Log-log plot of error (percent) against wall time, one curve per series (a color per
/// method, dashed for the second element), with the error
/// levels as dashed lines and the fastest run for each level circled.
pub fn plot_study(path: &Path, study: &Study) -> Result<(), SceneError> {
    crate::output::register_font();
    let points: Vec<(usize, f64, f64)> = study
        .runs
        .iter()
        .enumerate()
        .filter_map(|(i, r)| Some((i, r.wall_time()?, 100.0 * r.error?)))
        .collect();
    let floor = points
        .iter()
        .map(|p| p.2)
        .filter(|e| *e > 0.0)
        .fold(f64::INFINITY, f64::min)
        .min(0.5)
        / 2.0;
    let floor = if floor.is_finite() { floor } else { 1e-3 };
    let err = |e: f64| e.max(floor);
    let (t_lo, t_hi) = points
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), p| {
            (lo.min(p.1), hi.max(p.1))
        });
    let (t_lo, t_hi) = if t_lo <= t_hi {
        (t_lo.max(1e-4) / 1.5, t_hi * 1.5)
    } else {
        (1e-3, 1.0)
    };
    let e_hi = points.iter().map(|p| p.2).fold(10.0f64, f64::max) * 1.5;
    let e_lo = floor / 1.5;
    let root = BitMapBackend::new(path, (1000, 650)).into_drawing_area();
    root.fill(&WHITE).map_err(|e| plot_error(path, e))?;
    let title = match &study.reference {
        Some(Reference::Extrapolated(r)) => format!(
            "{}: error of {} against time (reference {:.4e} from {}, est. error {:.2}%)",
            study.scene,
            study.probe,
            r.limit,
            study.label(&r.method, &r.element),
            100.0 * r.relative_estimate()
        ),
        Some(Reference::Given {
            value,
            relative_uncertainty,
        }) => format!(
            "{}: error of {} against time (reference {value:.4e} given, uncertain by {:.2}%)",
            study.scene,
            study.probe,
            100.0 * relative_uncertainty
        ),
        None => format!("{}: no reference", study.scene),
    };
    let mut chart = ChartBuilder::on(&root)
        .caption(title, ("sans-serif", 17))
        .margin(15)
        .x_label_area_size(45)
        .y_label_area_size(70)
        .build_cartesian_2d((t_lo..t_hi).log_scale(), (e_lo..e_hi).log_scale())
        .map_err(|e| plot_error(path, e))?;
    chart
        .configure_mesh()
        .x_desc("wall time (s)")
        .y_desc("relative error (%)")
        .x_label_formatter(&|v| tick(*v))
        .y_label_formatter(&|v| tick(*v))
        .draw()
        .map_err(|e| plot_error(path, e))?;
    for (level, color) in LEVELS.iter().zip([
        RGBColor(90, 90, 90),
        RGBColor(130, 130, 130),
        RGBColor(170, 170, 170),
    ]) {
        let y = 100.0 * level;
        chart
            .draw_series(DashedLineSeries::new(
                [(t_lo, y), (t_hi, y)],
                8,
                6,
                color.stroke_width(1),
            ))
            .map_err(|e| plot_error(path, e))?;
    }
    for style in series_styles(study) {
        let series: Vec<(f64, f64, String)> = points
            .iter()
            .filter(|p| style.has(&study.runs[p.0]))
            .map(|p| (p.1, err(p.2), study.runs[p.0].label.clone()))
            .collect();
        draw_series(&mut chart, study, &style, &series, path)?;
    }
    // The fastest run of each resolved level, circled once with every level it wins.
    let mut marked: Vec<(usize, Vec<f64>)> = Vec::new();
    for level in LEVELS.into_iter().filter(|&l| study.resolves(l)) {
        if let Some(i) = study.fastest(level, None) {
            match marked.iter_mut().find(|(j, _)| *j == i) {
                Some((_, levels)) => levels.push(level),
                None => marked.push((i, vec![level])),
            }
        }
    }
    for (i, levels) in marked {
        let r = &study.runs[i];
        let (t, e) = (
            r.wall_time().unwrap_or(t_lo),
            err(100.0 * r.error.unwrap_or(0.0)),
        );
        let levels: Vec<String> = levels
            .iter()
            .map(|l| format!("{:.0}%", 100.0 * l))
            .collect();
        chart
            .draw_series([Circle::new((t, e), 11, BLACK.stroke_width(2))])
            .map_err(|e| plot_error(path, e))?;
        chart
            .draw_series([Text::new(
                format!("fastest <= {}", levels.join(", ")),
                (t, e),
                ("sans-serif", 15).into_font().color(&BLACK).pos(
                    plotters::style::text_anchor::Pos::new(
                        plotters::style::text_anchor::HPos::Right,
                        plotters::style::text_anchor::VPos::Bottom,
                    ),
                ),
            )])
            .map_err(|e| plot_error(path, e))?;
    }
    finish_plot(
        &mut chart,
        &root,
        SeriesLabelPosition::UpperRight,
        true,
        path,
    )
}

/// How one series is drawn: one color per method; the first element solid with circles, the
/// others dashed with triangles.
struct SeriesStyle {
    method: String,
    element: String,
    color: RGBAColor,
    solid: bool,
}

impl SeriesStyle {
    /// Whether `run` belongs to this series.
    fn has(&self, run: &StudyRun) -> bool {
        run.method == self.method && run.element == self.element
    }
}

/// The style of every series of `study`, in the order of its runs.
fn series_styles(study: &Study) -> Vec<SeriesStyle> {
    let keys = study.series_keys();
    let mut methods: Vec<&str> = Vec::new();
    let mut elements: Vec<&str> = Vec::new();
    for (m, e) in &keys {
        if !methods.contains(&m.as_str()) {
            methods.push(m);
        }
        if !elements.contains(&e.as_str()) {
            elements.push(e);
        }
    }
    keys.iter()
        .map(|(method, element)| SeriesStyle {
            method: method.clone(),
            element: element.clone(),
            color: Palette99::pick(methods.iter().position(|m| m == method).unwrap_or(0)).to_rgba(),
            solid: elements.first() == Some(&element.as_str()),
        })
        .collect()
}

/// Draws one series' `(x, y, swept value)` points: the curve in its style, a marker and
/// `KEY=VALUE` at each point, and its legend entry. Nothing for no points.
fn draw_series<'a, X, Y>(
    chart: &mut ChartContext<'a, BitMapBackend<'a>, Cartesian2d<X, Y>>,
    study: &Study,
    style: &SeriesStyle,
    series: &[(f64, f64, String)],
    path: &Path,
) -> Result<(), SceneError>
where
    X: Ranged<ValueType = f64>,
    Y: Ranged<ValueType = f64>,
{
    if series.is_empty() {
        return Ok(());
    }
    let (color, solid) = (style.color, style.solid);
    let line = series.iter().map(|p| (p.0, p.1));
    let drawn = if solid {
        chart.draw_series(LineSeries::new(line, color.stroke_width(2)))
    } else {
        chart.draw_series(DashedLineSeries::new(line, 10, 5, color.stroke_width(2)))
    };
    drawn
        .map_err(|e| plot_error(path, e))?
        .label(study.label(&style.method, &style.element))
        .legend(move |(x, y)| {
            let length = if solid { 20 } else { 8 };
            PathElement::new(vec![(x, y), (x + length, y)], color.stroke_width(2))
        });
    if solid {
        chart.draw_series(
            series
                .iter()
                .map(|p| Circle::new((p.0, p.1), 4, color.filled())),
        )
    } else {
        chart.draw_series(
            series
                .iter()
                .map(|p| TriangleMarker::new((p.0, p.1), 6, color.filled())),
        )
    }
    .map_err(|e| plot_error(path, e))?;
    chart
        .draw_series(series.iter().map(|p| {
            Text::new(
                format!("{}={}", study.sweep_key, p.2),
                (p.0, p.1),
                ("sans-serif", 13).into_font().color(&color),
            )
        }))
        .map_err(|e| plot_error(path, e))?;
    Ok(())
}

/// The probe's value against the unknowns (log scale), one curve per series in the styles of
/// [`plot_study`], with the reference as a black line (dashed lines at its uncertainty, when
/// it has one): how each method approaches the reference as the mesh is refined (Francu et
/// al. 2021, Fig. 10). Runs that did not converge are left out.
pub fn plot_unknowns(path: &Path, study: &Study) -> Result<(), SceneError> {
    crate::output::register_font();
    let points: Vec<(usize, f64, f64)> = study
        .runs
        .iter()
        .enumerate()
        .filter_map(|(i, r)| Some((i, r.converged()?.dofs as f64, r.value?)))
        .filter(|p| p.1 > 0.0)
        .collect();
    let (n_lo, n_hi) = points
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), p| {
            (lo.min(p.1), hi.max(p.1))
        });
    let (n_lo, n_hi) = if n_lo <= n_hi {
        (n_lo / 1.5, n_hi * 1.5)
    } else {
        (1.0, 10.0)
    };
    let reference = study
        .reference
        .as_ref()
        .map(|r| (r.value(), r.value().abs() * r.relative_uncertainty()));
    let band = reference.into_iter().flat_map(|(v, u)| [v - u, v, v + u]);
    let (v_lo, v_hi) = range(points.iter().map(|p| p.2).chain(band));
    let root = BitMapBackend::new(path, (1000, 650)).into_drawing_area();
    root.fill(&WHITE).map_err(|e| plot_error(path, e))?;
    let title = match &study.reference {
        Some(r) => format!(
            "{}: {} against unknowns (reference {:.4e}, uncertain by {:.2}%)",
            study.scene,
            study.probe,
            r.value(),
            100.0 * r.relative_uncertainty()
        ),
        None => format!(
            "{}: {} against unknowns (no reference)",
            study.scene, study.probe
        ),
    };
    let mut chart = ChartBuilder::on(&root)
        .caption(title, ("sans-serif", 17))
        .margin(15)
        .x_label_area_size(45)
        .y_label_area_size(90)
        .build_cartesian_2d((n_lo..n_hi).log_scale(), v_lo..v_hi)
        .map_err(|e| plot_error(path, e))?;
    chart
        .configure_mesh()
        .x_desc("unknowns")
        .y_desc(study.probe.as_str())
        .x_label_formatter(&|v| format!("{v:.0}"))
        .y_label_formatter(&|v| format!("{v:.4}"))
        .draw()
        .map_err(|e| plot_error(path, e))?;
    if let Some((value, uncertainty)) = reference {
        chart
            .draw_series(LineSeries::new(
                [(n_lo, value), (n_hi, value)],
                BLACK.stroke_width(2),
            ))
            .map_err(|e| plot_error(path, e))?
            .label("reference")
            .legend(|(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], BLACK.stroke_width(2)));
        if uncertainty > 0.0 {
            for y in [value - uncertainty, value + uncertainty] {
                chart
                    .draw_series(DashedLineSeries::new(
                        [(n_lo, y), (n_hi, y)],
                        8,
                        6,
                        RGBColor(130, 130, 130).stroke_width(1),
                    ))
                    .map_err(|e| plot_error(path, e))?;
            }
        }
    }
    for style in series_styles(study) {
        let series: Vec<(f64, f64, String)> = points
            .iter()
            .filter(|p| style.has(&study.runs[p.0]))
            .map(|p| (p.1, p.2, study.runs[p.0].label.clone()))
            .collect();
        draw_series(&mut chart, study, &style, &series, path)?;
    }
    finish_plot(
        &mut chart,
        &root,
        SeriesLabelPosition::UpperRight,
        true,
        path,
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn richardson_recovers_order_and_limit() {
        // f = 2 - 3 h^1.5 at h = 1/2, 1/4, 1/8 and at a non-constant ratio.
        let f = |r: f64| 2.0 - 3.0 * (1.0 / r).powf(1.5);
        for rs in [[2.0, 4.0, 8.0], [2.0, 3.0, 5.0]] {
            let (p, l) = richardson(rs.map(|r| (r, f(r)))).unwrap();
            assert!((p - 1.5).abs() < 1e-8, "{p}");
            assert!((l - 2.0).abs() < 1e-10, "{l}");
        }
        // Oscillating or diverging values are not extrapolated.
        assert!(richardson([(1.0, 1.0), (2.0, 2.0), (4.0, 1.5)]).is_none());
        assert!(richardson([(1.0, 1.0), (2.0, 1.1), (4.0, 1.3)]).is_none());
    }
}
