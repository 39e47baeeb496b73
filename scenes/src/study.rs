//! `isochor study`: the speed/accuracy trade of several methods over mesh resolutions.
//!
//! Every method runs at every resolution of the sweep (`--sweep res=1,2,4,8`, the mesh size
//! taken as `h = 1 / value`). Each run records its wall time, unknowns, Newton iterations and
//! one probe. The reference is the Richardson extrapolation of the three finest converged
//! runs of the best-converging method (the one whose extrapolation moves least from its
//! finest value, unless `--reference METHOD` names it): with `f = f_inf + C h^p`, the observed
//! order `p` solves `(f1 - f2) / (f2 - f3) = (h1^p - h2^p) / (h2^p - h3^p)`. Its error
//! estimate is the change of the extrapolation when the finest run is added (the difference
//! between the limits of the last two triples), or, with only three runs, the conservative
//! `|f_inf - f3|`. The error of a run is `|probe - reference| / |reference|`; for 1% and 5%
//! the fastest run within them is marked, with a warning when the reference is not known to
//! better than the level.
//! Outputs: `study.csv`, `study.md` and the log-log plot `study.png` of error against time.

use crate::output::{finish_plot, plot_error, write_file, OutputDir};
use crate::overrides::{parse_sweep, Override};
use crate::result::RunResult;
use crate::run::{run_scene, RunOptions};
use crate::{SceneError, SceneSource};
use isochor_solvers::Method;
use plotters::prelude::*;
use std::fmt::Write;
use std::path::{Path, PathBuf};

/// Error levels at which the fastest run is marked.
pub const LEVELS: [f64; 2] = [0.01, 0.05];

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
    /// `KEY=V1,V2,...` over mesh resolutions (default `res=1,2,4,8`).
    pub sweep: Option<String>,
    /// The probe to measure (default: the scene's deflection probe).
    pub probe: Option<String>,
    /// The method whose extrapolation is the reference (default: the best-converging).
    pub reference: Option<Method>,
    /// `--set` overrides applied to every run.
    pub overrides: Vec<Override>,
    /// Output folder for `study.csv`, `study.md` and `study.png`.
    pub out: Option<PathBuf>,
    /// Progress bars on stderr.
    pub progress: bool,
}

/// One run of the study.
#[derive(Debug, Clone)]
pub struct StudyRun {
    /// Method name.
    pub method: String,
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

/// A Richardson extrapolation from three runs of one method.
#[derive(Debug, Clone, PartialEq)]
pub struct Richardson {
    /// The method.
    pub method: String,
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

/// The result of a study.
#[derive(Debug, Clone)]
pub struct Study {
    /// Scene name.
    pub scene: String,
    /// The swept key.
    pub sweep_key: String,
    /// The probe measured.
    pub probe: String,
    /// Every run, method-major, coarse to fine.
    pub runs: Vec<StudyRun>,
    /// The extrapolation of every method that allowed one.
    pub extrapolations: Vec<Richardson>,
    /// The reference (one of `extrapolations`).
    pub reference: Option<Richardson>,
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
    for method in &request.methods {
        for (r, v) in &levels {
            let mut overrides = request.overrides.clone();
            overrides.push(Override::new(
                "method",
                toml::Value::String(method.name().into()),
            ));
            overrides.push(Override::new(key.clone(), v.clone()));
            let scene = source.load(None, &overrides)?;
            let label = Override::new("", v.clone()).display_value();
            plans.push((method.name().to_string(), label, *r, overrides, scene));
        }
    }
    let out = request.out.as_deref().map(OutputDir::create).transpose()?;
    let mut runs = Vec::new();
    for (method, label, resolution, overrides, scene) in plans {
        let options = RunOptions {
            out: None,
            progress: request.progress,
            variant: None,
            overrides: overrides
                .iter()
                .map(|o| format!("{}={}", o.key, o.display_value()))
                .collect(),
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
            label,
            resolution,
            result,
            value,
            error: None,
        });
    }
    let study = Study::from_runs(base.name.clone(), key, probe, runs, request.reference)?;
    let written = match out {
        Some(dir) => {
            write_file(&dir.path().join("study.csv"), study.to_csv().as_bytes())?;
            write_file(&dir.path().join("study.md"), study.to_markdown().as_bytes())?;
            plot_study(&dir.path().join("study.png"), &study)?;
            Some(dir.commit()?)
        }
        None => None,
    };
    Ok((study, written))
}

impl Study {
    /// The study of finished runs (method-major, coarse to fine): extrapolates every method
    /// with three converged runs, takes `wanted`'s extrapolation (or the best-converging one)
    /// as the reference and measures every run's error against it.
    pub fn from_runs(
        scene: String,
        sweep_key: String,
        probe: String,
        runs: Vec<StudyRun>,
        wanted: Option<Method>,
    ) -> Result<Study, SceneError> {
        let mut study = Study {
            scene,
            sweep_key,
            probe,
            runs,
            extrapolations: Vec::new(),
            reference: None,
        };
        study.extrapolate(wanted)?;
        Ok(study)
    }

    /// Converged (resolution, value) pairs of one method, coarse to fine.
    fn series(&self, method: &str) -> Vec<(f64, f64)> {
        self.runs
            .iter()
            .filter(|r| r.method == method)
            .filter_map(|r| r.value.map(|v| (r.resolution, v)))
            .collect()
    }

    fn methods(&self) -> Vec<String> {
        let mut m: Vec<String> = Vec::new();
        for r in &self.runs {
            if !m.contains(&r.method) {
                m.push(r.method.clone());
            }
        }
        m
    }

    fn extrapolate(&mut self, wanted: Option<Method>) -> Result<(), SceneError> {
        for method in self.methods() {
            let s = self.series(&method);
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
                resolutions: [s[n - 3].0, s[n - 2].0, s[n - 1].0],
                values: [s[n - 3].1, s[n - 2].1, s[n - 1].1],
                order,
                limit,
                finest_gap: (limit - s[n - 1].1).abs(),
                previous_gap,
            });
        }
        self.reference = match wanted {
            Some(m) => Some(
                self.extrapolations
                    .iter()
                    .find(|e| e.method == m.name())
                    .cloned()
                    .ok_or_else(|| {
                        SceneError::Usage(format!(
                            "{} cannot be extrapolated: it needs three converged runs whose values converge monotonically",
                            m.name()
                        ))
                    })?,
            ),
            None => self
                .extrapolations
                .iter()
                .min_by(|a, b| a.relative_estimate().total_cmp(&b.relative_estimate()))
                .cloned(),
        };
        if let Some(reference) = &self.reference {
            let limit = reference.limit;
            for run in &mut self.runs {
                run.error = run.value.map(|v| (v - limit).abs() / limit.abs());
            }
        }
        Ok(())
    }

    /// Whether the reference is known to within `level` (relative), so that errors at that
    /// level mean something.
    pub fn resolves(&self, level: f64) -> bool {
        self.reference
            .as_ref()
            .is_some_and(|r| r.relative_estimate() <= level)
    }

    /// Index of the fastest converged run with error at most `level`, of `method` if given.
    pub fn fastest(&self, level: f64, method: Option<&str>) -> Option<usize> {
        self.runs
            .iter()
            .enumerate()
            .filter(|(_, r)| method.is_none_or(|m| r.method == m))
            .filter(|(_, r)| r.error.is_some_and(|e| e <= level))
            .filter_map(|(i, r)| r.wall_time().map(|t| (i, t)))
            .min_by(|a, b| a.1.total_cmp(&b.1))
            .map(|(i, _)| i)
    }

    fn header(&self) -> Vec<String> {
        [
            "method",
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

    fn rows(&self) -> Vec<Vec<String>> {
        self.runs
            .iter()
            .map(|run| {
                let mut c = vec![run.method.clone(), run.label.clone()];
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
                        c.resize(10, String::new());
                    }
                }
                c
            })
            .collect()
    }

    /// The reference and the fastest runs per error level, for people.
    pub fn summary(&self) -> String {
        let mut s = String::new();
        for e in &self.extrapolations {
            let _ = writeln!(
                s,
                "extrapolation of {} from {} = {:?}: {:?} -> {:.6e} (observed order {:.2}; |limit - finest| = {:.2e} ({:.3}%){})",
                e.method,
                self.sweep_key,
                e.resolutions,
                e.values,
                e.limit,
                e.order,
                e.finest_gap,
                100.0 * e.finest_gap / e.limit.abs(),
                e.previous_gap
                    .map(|g| format!(", |limit - previous limit| = {g:.2e} ({:.3}%)", 100.0 * g / e.limit.abs()))
                    .unwrap_or_default()
            );
        }
        match &self.reference {
            Some(r) => {
                let _ = writeln!(
                    s,
                    "reference {} = {:.6e} (Richardson extrapolation of {}), estimated error {:.2e} ({:.3}%)",
                    self.probe,
                    r.limit,
                    r.method,
                    r.estimate(),
                    100.0 * r.relative_estimate()
                );
            }
            None => {
                let _ = writeln!(
                    s,
                    "no reference: no method has three converged runs that converge monotonically"
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
                    100.0 * r.relative_estimate()
                );
                continue;
            }
            let Some(best) = self.fastest(level, None) else {
                let _ = writeln!(s, "error <= {:.0}%: no run", 100.0 * level);
                continue;
            };
            let b = &self.runs[best];
            let t = b.wall_time().unwrap_or(f64::NAN);
            let mut line = format!(
                "error <= {:.0}%: fastest {} at {} = {} ({:.3} s, error {:.2}%)",
                100.0 * level,
                b.method,
                self.sweep_key,
                b.label,
                t,
                100.0 * b.error.unwrap_or(f64::NAN)
            );
            let others: Vec<String> = self
                .methods()
                .into_iter()
                .filter(|m| *m != b.method)
                .map(|m| match self.fastest(level, Some(&m)) {
                    Some(i) => {
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
                    None => format!("{m} does not reach it"),
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
                        run.method,
                        self.sweep_key,
                        run.label,
                        r.failed_step.unwrap_or(0)
                    );
                }
            }
        }
        out + &self.summary()
    }

    /// Every run as CSV, with the reference in the last columns.
    pub fn to_csv(&self) -> String {
        let mut header = self.header();
        header[8] = format!("probe:{}", self.probe);
        header.push("reference".into());
        let reference = self
            .reference
            .as_ref()
            .map_or(String::new(), |r| format!("{:.9e}", r.limit));
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

    /// The table and summary as Markdown.
    pub fn to_markdown(&self) -> String {
        let header = self.header();
        let mut out = format!("# Study: {} ({})\n\n", self.scene, self.probe);
        let _ = writeln!(out, "| {} |", header.join(" | "));
        let _ = writeln!(out, "|{}|", vec!["---"; header.len()].join("|"));
        for row in self.rows() {
            let cells: Vec<String> = row.iter().map(|c| c.replace('|', "\\|")).collect();
            let _ = writeln!(out, "| {} |", cells.join(" | "));
        }
        out += "\n```text\n";
        out += &self.summary();
        out += "```\n";
        out
    }
}

/// Log-log plot of error (percent) against wall time, one curve per method, with the error
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
        Some(r) => format!(
            "{}: error of {} against time (reference {:.4e} from {}, est. error {:.2}%)",
            study.scene,
            study.probe,
            r.limit,
            r.method,
            100.0 * r.relative_estimate()
        ),
        None => format!("{}: no reference", study.scene),
    };
    let mut chart = ChartBuilder::on(&root)
        .caption(title, ("sans-serif", 20))
        .margin(15)
        .x_label_area_size(45)
        .y_label_area_size(70)
        .build_cartesian_2d((t_lo..t_hi).log_scale(), (e_lo..e_hi).log_scale())
        .map_err(|e| plot_error(path, e))?;
    chart
        .configure_mesh()
        .x_desc("wall time (s)")
        .y_desc("relative error (%)")
        .x_label_formatter(&|v| format!("{v:.2}"))
        .y_label_formatter(&|v| format!("{v:.2}"))
        .draw()
        .map_err(|e| plot_error(path, e))?;
    for (level, color) in LEVELS
        .iter()
        .zip([RGBColor(120, 120, 120), RGBColor(170, 170, 170)])
    {
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
    for (k, method) in study.methods().iter().enumerate() {
        let color = Palette99::pick(k).to_rgba();
        let series: Vec<(f64, f64, String)> = points
            .iter()
            .filter(|p| study.runs[p.0].method == *method)
            .map(|p| (p.1, err(p.2), study.runs[p.0].label.clone()))
            .collect();
        if series.is_empty() {
            continue;
        }
        chart
            .draw_series(LineSeries::new(
                series.iter().map(|p| (p.0, p.1)),
                color.stroke_width(2),
            ))
            .map_err(|e| plot_error(path, e))?
            .label(method.clone())
            .legend(move |(x, y)| {
                PathElement::new(vec![(x, y), (x + 20, y)], color.stroke_width(2))
            });
        chart
            .draw_series(
                series
                    .iter()
                    .map(|p| Circle::new((p.0, p.1), 4, color.filled())),
            )
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
    }
    for level in LEVELS.into_iter().filter(|&l| study.resolves(l)) {
        if let Some(i) = study.fastest(level, None) {
            let r = &study.runs[i];
            let (t, e) = (
                r.wall_time().unwrap_or(t_lo),
                err(100.0 * r.error.unwrap_or(0.0)),
            );
            chart
                .draw_series([Circle::new((t, e), 11, BLACK.stroke_width(2))])
                .map_err(|e| plot_error(path, e))?;
            chart
                .draw_series([Text::new(
                    format!("fastest <= {:.0}%", 100.0 * level),
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
