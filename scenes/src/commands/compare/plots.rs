//! The plots of a comparison, drawn like the run plots ([`crate::output`]):
//!
//! - `compare.png`: every probe against the swept value, one line per method or variant, the
//!   published values as crosses (for Poisson's ratio the x axis is `0.5 - nu` on a log
//!   scale: Table 2 and Fig. 11 of Francu et al. 2021 read as a distance from
//!   incompressibility).
//! - `compare-residuals.png`: the Newton force residual against the iterations accumulated
//!   over the steps, one line per run (Fig. 7 of Francu et al. 2021).
//! - `compare-energy.png` (dynamic scenes): the total and the potential energy and the
//!   volume change against time, one line per run (Fig. 8 of Sheen et al. 2021).

use super::comparison::{CompareRow, Comparison};
use crate::error::SceneError;
use crate::format::overrides::dotted;
use crate::output::{draw_legend, finish_plot, plot_error, range, register_font, tick};
use crate::record::{RunResult, StepRecord};
use plotters::coord::ranged1d::{AsRangedCoord, ValueFormatter};
use plotters::coord::Shift;
use plotters::prelude::*;
use std::path::Path;

/// Width of the plots, and height of one panel.
const SIZE: (u32, u32) = (1000, 500);

/// The x axis of a sweep: how a swept value is placed, its title and whether it is on a log
/// scale.
struct SweepAxis {
    nu: bool,
    title: String,
    log: bool,
}

impl SweepAxis {
    fn new(comparison: &Comparison) -> SweepAxis {
        let key = comparison.sweep_key.clone().unwrap_or_default();
        let nu = dotted(&key) == "material.nu";
        let mut axis = SweepAxis {
            nu,
            title: if nu { "0.5 - nu".into() } else { key },
            log: false,
        };
        let xs: Vec<f64> = comparison
            .rows
            .iter()
            .filter_map(|r| Some(axis.x(r.sweep_number()?)))
            .collect();
        let (lo, hi) = xs.iter().fold((f64::INFINITY, 0.0f64), |(lo, hi), &x| {
            (lo.min(x), hi.max(x))
        });
        axis.log = xs.iter().all(|&x| x > 0.0) && hi >= 10.0 * lo;
        if axis.log {
            axis.title += " (log scale)";
        }
        axis
    }

    fn x(&self, value: f64) -> f64 {
        if self.nu {
            0.5 - value
        } else {
            value
        }
    }
}

/// Every probe against the swept value (one panel per probe), one line per method or
/// variant through its converged runs, the published values as crosses of the same color.
pub fn plot_sweep(path: &Path, comparison: &Comparison) -> Result<(), SceneError> {
    register_font();
    let axis = SweepAxis::new(comparison);
    let probes = comparison.probe_names();
    let panels = probes.len().max(1) as u32;
    let root = BitMapBackend::new(path, (SIZE.0, SIZE.1 * panels)).into_drawing_area();
    root.fill(&WHITE).map_err(|e| plot_error(path, e))?;
    let areas = root.split_evenly((panels as usize, 1));
    let xs = comparison
        .rows
        .iter()
        .filter_map(|r| Some(axis.x(r.sweep_number()?)));
    let (lo, hi) = if axis.log {
        let (lo, hi) = xs.fold((f64::INFINITY, 0.0f64), |(lo, hi), x| {
            (lo.min(x), hi.max(x))
        });
        (lo / 1.5, hi * 1.5)
    } else {
        range(xs)
    };
    for (probe, area) in probes.iter().zip(&areas) {
        if axis.log {
            panel(area, (lo..hi).log_scale(), comparison, &axis, probe, path)?;
        } else {
            panel(area, lo..hi, comparison, &axis, probe, path)?;
        }
    }
    root.present().map_err(|e| plot_error(path, e))
}

/// One probe's panel on the x axis `x`.
fn panel<X>(
    area: &DrawingArea<BitMapBackend<'_>, Shift>,
    x: X,
    comparison: &Comparison,
    axis: &SweepAxis,
    probe: &str,
    path: &Path,
) -> Result<(), SceneError>
where
    X: AsRangedCoord<Value = f64>,
    X::CoordDescType: ValueFormatter<f64>,
{
    let labels = comparison.labels();
    let point = |row: &CompareRow, value: f64| {
        Some((axis.x(row.sweep_number()?), comparison.shown(probe, value)))
    };
    let ours = |label: &str| -> Vec<(f64, f64)> {
        comparison
            .rows
            .iter()
            .filter(|r| r.label == label)
            .filter_map(|r| point(r, r.converged_probe(probe)?))
            .collect()
    };
    let published = |label: &str| -> Vec<(f64, f64)> {
        comparison
            .rows
            .iter()
            .filter(|r| r.label == label)
            .filter_map(|r| point(r, comparison.paper_value(r, probe)?))
            .collect()
    };
    let values = labels
        .iter()
        .flat_map(|l| ours(l).into_iter().chain(published(l)))
        .map(|p| p.1);
    // From zero, so that the factor a line loses reads off the plot, with room above the
    // values for the legend's lines.
    let (lo, hi) = range(values.chain([0.0]));
    let entries = labels.len()
        * if comparison.paper_probes().is_empty() {
            1
        } else {
            2
        };
    let hi = hi + 0.07 * entries as f64 * (hi - lo);
    let title = comparison.probe_title(probe);
    let mut chart = ChartBuilder::on(area)
        .caption(
            format!("{}: {title} against {}", comparison.scene, axis.title),
            ("sans-serif", 22),
        )
        .margin(15)
        .x_label_area_size(45)
        .y_label_area_size(80)
        .build_cartesian_2d(x, lo..hi)
        .map_err(|e| plot_error(path, e))?;
    chart
        .configure_mesh()
        .x_desc(axis.title.as_str())
        .y_desc(title.as_str())
        .x_label_formatter(&|v| tick(*v))
        .draw()
        .map_err(|e| plot_error(path, e))?;
    for (k, label) in labels.iter().enumerate() {
        let color = Palette99::pick(k).to_rgba();
        let line = ours(label);
        chart
            .draw_series(LineSeries::new(line.clone(), color.stroke_width(2)))
            .map_err(|e| plot_error(path, e))?
            .label(label.as_str())
            .legend(move |(x, y)| {
                PathElement::new(vec![(x, y), (x + 20, y)], color.stroke_width(2))
            });
        chart
            .draw_series(line.iter().map(|&p| Circle::new(p, 4, color.filled())))
            .map_err(|e| plot_error(path, e))?;
        let paper = published(label);
        if !paper.is_empty() {
            chart
                .draw_series(
                    paper
                        .iter()
                        .map(|&p| Cross::new(p, 7, color.stroke_width(3))),
                )
                .map_err(|e| plot_error(path, e))?
                .label(format!("{label} (paper)"))
                .legend(move |(x, y)| Cross::new((x + 10, y), 6, color.stroke_width(3)));
        }
    }
    draw_legend(&mut chart, SeriesLabelPosition::UpperRight, path)
}

/// The force residual before every Newton iteration of every attempt (cut attempts and a
/// failed last step included) and after its last, at the iterations accumulated until then.
fn residual_points(r: &RunResult) -> Vec<(f64, f64)> {
    let mut points = Vec::new();
    let mut done = 0;
    for step in r.history.iter().chain(&r.failed) {
        let attempts = step.cuts.iter().map(|c| &c.iterations.force_residuals);
        for residuals in attempts.chain([&step.iterations.force_residuals]) {
            points.extend(
                residuals
                    .iter()
                    .enumerate()
                    .map(|(i, v)| ((done + i) as f64, *v)),
            );
            done += residuals.len().saturating_sub(1);
        }
    }
    points.retain(|p| p.1.is_finite() && p.1 > 0.0);
    points
}

/// The Newton force residual against the accumulated iterations of every run, one color per
/// method or variant, paler for the earlier swept values.
pub fn plot_residuals(path: &Path, comparison: &Comparison) -> Result<(), SceneError> {
    register_font();
    let labels = comparison.labels();
    // Per run: its legend, the index of its method or variant, its residuals.
    type Run = (String, usize, Vec<(f64, f64)>);
    let runs: Vec<Run> = comparison
        .rows
        .iter()
        .filter_map(|row| {
            let r = row.result.as_ref().ok()?;
            let k = labels.iter().position(|l| *l == row.label)?;
            let name = match (&comparison.sweep_key, &row.sweep_value) {
                (Some(key), Some(v)) => format!("{}, {key}={v}", row.label),
                _ => row.label.clone(),
            };
            Some((name, k, residual_points(r)))
        })
        .collect();
    let all = runs.iter().flat_map(|r| r.2.iter());
    let (lo, hi, last) = all.fold((f64::INFINITY, 0.0f64, 1.0f64), |(lo, hi, last), p| {
        (lo.min(p.1), hi.max(p.1), last.max(p.0))
    });
    let (lo, hi) = if lo <= hi {
        (lo / 2.0, hi * 2.0)
    } else {
        (1e-12, 1.0)
    };
    let root = BitMapBackend::new(path, SIZE).into_drawing_area();
    root.fill(&WHITE).map_err(|e| plot_error(path, e))?;
    let mut chart = ChartBuilder::on(&root)
        .caption(
            format!(
                "Newton residuals: {} (as Fig. 7 of Francu et al. 2021)",
                comparison.scene
            ),
            ("sans-serif", 22),
        )
        .margin(15)
        .x_label_area_size(45)
        .y_label_area_size(80)
        .build_cartesian_2d(0f64..last, (lo..hi).log_scale())
        .map_err(|e| plot_error(path, e))?;
    chart
        .configure_mesh()
        .x_desc("Newton iterations, accumulated over the steps")
        .y_desc("force residual")
        .x_label_formatter(&|v| format!("{v:.0}"))
        .y_label_formatter(&|v| format!("{v:.0e}"))
        .draw()
        .map_err(|e| plot_error(path, e))?;
    let per_label = |k: usize| runs.iter().filter(|r| r.1 == k).count();
    let mut seen = vec![0usize; labels.len()];
    for (name, k, points) in &runs {
        seen[*k] += 1;
        // The last swept value of each method or variant in full color, the earlier paler.
        let alpha = 0.3 + 0.7 * seen[*k] as f64 / per_label(*k) as f64;
        let color = Palette99::pick(*k).to_rgba().mix(alpha);
        chart
            .draw_series(LineSeries::new(points.clone(), color.stroke_width(2)))
            .map_err(|e| plot_error(path, e))?
            .label(name.as_str())
            .legend(move |(x, y)| {
                PathElement::new(vec![(x, y), (x + 20, y)], color.stroke_width(2))
            });
        chart
            .draw_series(points.iter().map(|&p| Circle::new(p, 3, color.filled())))
            .map_err(|e| plot_error(path, e))?;
    }
    finish_plot(
        &mut chart,
        &root,
        SeriesLabelPosition::UpperRight,
        !runs.is_empty(),
        path,
    )
}

/// One per-frame series of a run against time.
type Series = fn(&StepRecord) -> f64;

/// The total energy, the potential energy and the volume change (%) of every run against
/// time, one panel each, one color per run (Fig. 8 of Sheen et al. 2021 plots the energy).
pub fn plot_energies(path: &Path, comparison: &Comparison) -> Result<(), SceneError> {
    register_font();
    let panels: [(&str, Series); 3] = [
        ("total energy (J)", StepRecord::total_energy),
        ("potential energy (J)", StepRecord::potential_energy),
        ("volume change (%)", |s| 100.0 * s.volume_change),
    ];
    let runs: Vec<(String, &RunResult)> = comparison
        .rows
        .iter()
        .filter_map(|row| {
            let r = row.result.as_ref().ok()?;
            let name = match (&comparison.sweep_key, &row.sweep_value) {
                (Some(key), Some(v)) => format!("{}, {key}={v}", row.label),
                _ => row.label.clone(),
            };
            Some((name, r))
        })
        .collect();
    let end = runs
        .iter()
        .flat_map(|(_, r)| r.history.last().map(|s| s.t))
        .fold(0.0, f64::max);
    let root = BitMapBackend::new(path, (SIZE.0, SIZE.1 * panels.len() as u32)).into_drawing_area();
    root.fill(&WHITE).map_err(|e| plot_error(path, e))?;
    for ((title, value), area) in panels.iter().zip(root.split_evenly((panels.len(), 1))) {
        let series = |r: &RunResult| -> Vec<(f64, f64)> {
            r.history.iter().map(|s| (s.t, value(s))).collect()
        };
        let (lo, hi) = range(runs.iter().flat_map(|(_, r)| series(r)).map(|p| p.1));
        let mut chart = ChartBuilder::on(&area)
            .caption(
                format!(
                    "{}: {title} (as Fig. 8 of Sheen et al. 2021)",
                    comparison.scene
                ),
                ("sans-serif", 22),
            )
            .margin(15)
            .x_label_area_size(45)
            .y_label_area_size(90)
            .build_cartesian_2d(0.0..end.max(f64::MIN_POSITIVE), lo..hi)
            .map_err(|e| plot_error(path, e))?;
        chart
            .configure_mesh()
            .x_desc("time (s)")
            .y_desc(*title)
            .y_label_formatter(&|v| format!("{v:.3e}"))
            .draw()
            .map_err(|e| plot_error(path, e))?;
        for (k, (name, r)) in runs.iter().enumerate() {
            let color = Palette99::pick(k).to_rgba();
            chart
                .draw_series(LineSeries::new(series(r), color.stroke_width(2)))
                .map_err(|e| plot_error(path, e))?
                .label(name.as_str())
                .legend(move |(x, y)| {
                    PathElement::new(vec![(x, y), (x + 20, y)], color.stroke_width(2))
                });
        }
        draw_legend(&mut chart, SeriesLabelPosition::UpperRight, path)?;
    }
    root.present().map_err(|e| plot_error(path, e))
}
