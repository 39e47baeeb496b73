//! PNG plots drawn with `plotters` on its pure-Rust bitmap backend; text uses DejaVu Sans
//! embedded by the `dejavu` crate (no system font libraries needed).
//!
//! - `residuals.png`: the Newton force (and constraint) residual of every iteration across
//!   the steps, on a log scale (like Fig. 7 of Francu et al. 2021).
//! - `pressure-volume.png`: every pressure load's pressure against its enclosed volume ratio
//!   over the accepted steps (the curve designers of soft actuators read).
//! - `energy.png`: kinetic, elastic, constraint, external and total energy against time
//!   (like Fig. 8 of Sheen et al. 2021).

use crate::error::SceneError;
use crate::record::StepRecord;
use plotters::prelude::*;
use plotters::style::FontStyle;
use std::path::Path;
use std::sync::Once;

const SIZE: (u32, u32) = (1000, 600);

pub(crate) fn register_font() {
    static ONCE: Once = Once::new();
    ONCE.call_once(|| {
        // The embedded font is valid; if registration failed anyway, text would be missing.
        let _ = plotters::style::register_font(
            "sans-serif",
            FontStyle::Normal,
            dejavu::sans::regular(),
        );
    });
}

/// Draws the legend at `position` (when `legend`) and writes the PNG: the end of every plot.
pub(crate) fn finish_plot<'a, X, Y>(
    chart: &mut ChartContext<'a, BitMapBackend<'a>, Cartesian2d<X, Y>>,
    root: &DrawingArea<BitMapBackend<'a>, plotters::coord::Shift>,
    position: SeriesLabelPosition,
    legend: bool,
    path: &Path,
) -> Result<(), SceneError>
where
    X: plotters::coord::ranged1d::Ranged,
    Y: plotters::coord::ranged1d::Ranged,
{
    if legend {
        draw_legend(chart, position, path)?;
    }
    root.present().map_err(|e| plot_error(path, e))
}

/// Draws the series' legend at `position` on a white, framed box.
pub(crate) fn draw_legend<'a, X, Y>(
    chart: &mut ChartContext<'a, BitMapBackend<'a>, Cartesian2d<X, Y>>,
    position: SeriesLabelPosition,
    path: &Path,
) -> Result<(), SceneError>
where
    X: plotters::coord::ranged1d::Ranged,
    Y: plotters::coord::ranged1d::Ranged,
{
    chart
        .configure_series_labels()
        .position(position)
        .background_style(WHITE.mix(0.8))
        .border_style(BLACK)
        .draw()
        .map_err(|e| plot_error(path, e))
}

pub(crate) fn plot_error(path: &Path, e: impl std::fmt::Display) -> SceneError {
    SceneError::Output(format!("{}: {e}", path.display()))
}

/// Padded `(lo, hi)` of finite values, never empty.
pub(crate) fn range(values: impl Iterator<Item = f64>) -> (f64, f64) {
    let (lo, hi) = values
        .filter(|v| v.is_finite())
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), v| {
            (lo.min(v), hi.max(v))
        });
    if lo.partial_cmp(&hi).is_none_or(|o| o.is_gt()) {
        return (0.0, 1.0);
    }
    let pad = if hi > lo {
        0.05 * (hi - lo)
    } else {
        lo.abs().max(1.0) * 0.05
    };
    (lo - pad, hi + pad)
}

/// A log-axis tick with as many decimals as its first significant digit needs (`0.001`,
/// `0.05`, `10`).
pub(crate) fn tick(v: f64) -> String {
    if !(v.is_finite() && v > 0.0) {
        return format!("{v}");
    }
    let decimals = (-v.log10().floor()).max(0.0) as usize;
    format!("{v:.decimals$}")
}

/// Newton residuals and the volume error per iteration across steps, log scale.
pub fn plot_residuals(path: &Path, title: &str, history: &[StepRecord]) -> Result<(), SceneError> {
    register_font();
    let positive = |v: &f64| v.is_finite() && *v > 0.0;
    let all = history
        .iter()
        .flat_map(|s| {
            s.iterations
                .force_residuals
                .iter()
                .chain(&s.iterations.constraint_residuals)
                .chain(&s.iterations.volume_errors)
        })
        .copied()
        .filter(positive);
    let (lo, hi) = all.fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), v| {
        (lo.min(v), hi.max(v))
    });
    let (lo, hi) = if lo <= hi {
        (lo / 2.0, hi * 2.0)
    } else {
        (1e-12, 1.0)
    };
    let total: usize = history
        .iter()
        .map(|s| s.iterations.force_residuals.len())
        .sum::<usize>()
        .max(2);
    let root = BitMapBackend::new(path, SIZE).into_drawing_area();
    root.fill(&WHITE).map_err(|e| plot_error(path, e))?;
    let mut chart = ChartBuilder::on(&root)
        .caption(format!("Newton residuals: {title}"), ("sans-serif", 24))
        .margin(15)
        .x_label_area_size(45)
        .y_label_area_size(80)
        .build_cartesian_2d(0f64..(total - 1) as f64, (lo..hi).log_scale())
        .map_err(|e| plot_error(path, e))?;
    chart
        .configure_mesh()
        .x_desc("iteration (all steps)")
        .y_desc("residual")
        .y_label_formatter(&|v| format!("{v:.0e}"))
        .draw()
        .map_err(|e| plot_error(path, e))?;
    let mut offset = 0usize;
    const LABELS: [&str; 3] = ["force residual", "constraint residual", "volume error (L1)"];
    let mut labelled = [false; 3];
    for s in history {
        let series = [
            (&s.iterations.force_residuals, BLUE),
            (&s.iterations.constraint_residuals, RED),
            (&s.iterations.volume_errors, GREEN),
        ];
        for (k, (series, color)) in series.into_iter().enumerate() {
            let points: Vec<(f64, f64)> = series
                .iter()
                .enumerate()
                .filter(|(_, v)| positive(v))
                .map(|(i, v)| ((offset + i) as f64, *v))
                .collect();
            if points.is_empty() {
                continue;
            }
            let drawn = chart
                .draw_series(LineSeries::new(points.clone(), color.stroke_width(2)))
                .map_err(|e| plot_error(path, e))?;
            if !labelled[k] {
                labelled[k] = true;
                drawn.label(LABELS[k]).legend(move |(x, y)| {
                    PathElement::new(vec![(x, y), (x + 20, y)], color.stroke_width(2))
                });
            }
            chart
                .draw_series(points.iter().map(|&p| Circle::new(p, 3, color.filled())))
                .map_err(|e| plot_error(path, e))?;
        }
        offset += s.iterations.force_residuals.len();
    }
    let legend = labelled.iter().any(|&l| l);
    finish_plot(
        &mut chart,
        &root,
        SeriesLabelPosition::MiddleRight,
        legend,
        path,
    )
}

/// Energies against time.
pub fn plot_energy(path: &Path, title: &str, history: &[StepRecord]) -> Result<(), SceneError> {
    register_font();
    type Pick = fn(&StepRecord) -> f64;
    let series: [(&str, RGBColor, Pick); 5] = [
        ("kinetic", RED, |s| s.kinetic_energy),
        ("elastic", BLUE, |s| s.elastic_energy),
        ("constraint", MAGENTA, |s| s.constraint_energy),
        ("external", GREEN, |s| s.external_energy),
        ("total", BLACK, StepRecord::total_energy),
    ];
    let (t0, t1) = range(history.iter().map(|s| s.t));
    let (lo, hi) = range(
        history
            .iter()
            .flat_map(|s| series.iter().map(move |(_, _, f)| f(s))),
    );
    let root = BitMapBackend::new(path, SIZE).into_drawing_area();
    root.fill(&WHITE).map_err(|e| plot_error(path, e))?;
    let mut chart = ChartBuilder::on(&root)
        .caption(format!("Energy: {title}"), ("sans-serif", 24))
        .margin(15)
        .x_label_area_size(45)
        .y_label_area_size(90)
        .build_cartesian_2d(t0..t1, lo..hi)
        .map_err(|e| plot_error(path, e))?;
    chart
        .configure_mesh()
        .x_desc("time (s)")
        .y_desc("energy (J)")
        .y_label_formatter(&|v| format!("{v:.3e}"))
        .draw()
        .map_err(|e| plot_error(path, e))?;
    for (name, color, f) in series {
        chart
            .draw_series(LineSeries::new(
                history.iter().map(|s| (s.t, f(s))),
                color.stroke_width(2),
            ))
            .map_err(|e| plot_error(path, e))?
            .label(name)
            .legend(move |(x, y)| {
                PathElement::new(vec![(x, y), (x + 20, y)], color.stroke_width(2))
            });
    }
    finish_plot(
        &mut chart,
        &root,
        SeriesLabelPosition::MiddleRight,
        true,
        path,
    )
}

/// Every pressure load's pressure against its enclosed volume ratio (nothing without one).
pub fn plot_pressure_volume(
    path: &Path,
    title: &str,
    history: &[StepRecord],
) -> Result<(), SceneError> {
    let loads = history
        .iter()
        .map(|s| s.pressure_loads.len())
        .max()
        .unwrap_or(0);
    if loads == 0 {
        return Ok(());
    }
    register_font();
    // From the rest state: no pressure, the rest volume.
    let curve = |k: usize| {
        std::iter::once((1.0, 0.0)).chain(
            history
                .iter()
                .filter_map(move |s| s.pressure_loads.get(k))
                .map(|r| (r.volume_ratio, r.pressure)),
        )
    };
    let (v0, v1) = range((0..loads).flat_map(|k| curve(k).map(|c| c.0)));
    let (p0, p1) = range((0..loads).flat_map(|k| curve(k).map(|c| c.1)));
    let root = BitMapBackend::new(path, SIZE).into_drawing_area();
    root.fill(&WHITE).map_err(|e| plot_error(path, e))?;
    let mut chart = ChartBuilder::on(&root)
        .caption(format!("Pressure-volume: {title}"), ("sans-serif", 24))
        .margin(15)
        .x_label_area_size(45)
        .y_label_area_size(90)
        .build_cartesian_2d(v0..v1, p0..p1)
        .map_err(|e| plot_error(path, e))?;
    chart
        .configure_mesh()
        .x_desc("enclosed volume / rest volume")
        .y_desc("pressure (Pa)")
        .y_label_formatter(&|v| format!("{v:.3e}"))
        .draw()
        .map_err(|e| plot_error(path, e))?;
    let colors = [BLUE, RED, GREEN, MAGENTA, BLACK, CYAN];
    for k in 0..loads {
        let color = colors[k % colors.len()];
        chart
            .draw_series(LineSeries::new(curve(k), color.stroke_width(2)))
            .map_err(|e| plot_error(path, e))?
            .label(format!("loads.pressure.{k}"))
            .legend(move |(x, y)| {
                PathElement::new(vec![(x, y), (x + 20, y)], color.stroke_width(2))
            });
    }
    finish_plot(
        &mut chart,
        &root,
        SeriesLabelPosition::UpperLeft,
        true,
        path,
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::record::Iterations;

    fn record(step: usize, residuals: &[f64]) -> StepRecord {
        StepRecord {
            step,
            t: step as f64 * 0.1,
            increment: 0.1,
            cuts: Vec::new(),
            newton_iterations: residuals.len() - 1,
            converged: true,
            iterations: Iterations {
                force_residuals: residuals.to_vec(),
                constraint_residuals: residuals.iter().map(|r| r * 0.1).collect(),
                volume_errors: residuals.iter().map(|r| r * 0.01).collect(),
                step_lengths: vec![1.0; residuals.len() - 1],
                backtracks: vec![0; residuals.len() - 1],
                shifts: vec![0.0; residuals.len() - 1],
                hessian_projected: vec![false; residuals.len() - 1],
            },
            volume_change: 0.0,
            inverted_tets: 0,
            kinetic_energy: (step as f64).sin().abs(),
            elastic_energy: 1.0,
            constraint_energy: 0.0,
            external_energy: -0.5 * step as f64,
            wall_time_s: 0.0,
            pattern_rebuilds: 0,
            tracked_probe: None,
            contact: Default::default(),
            pressure_loads: Vec::new(),
            probes: Default::default(),
        }
    }

    #[test]
    fn plots_are_png_files() {
        let dir = std::env::temp_dir().join(format!("isochor-plots-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let history: Vec<StepRecord> = (1..=4)
            .map(|s| record(s, &[1.0, 1e-3, 1e-8, 1e-13]))
            .collect();
        plot_residuals(&dir.join("r.png"), "test", &history).unwrap();
        plot_energy(&dir.join("e.png"), "test", &history).unwrap();
        for f in ["r.png", "e.png"] {
            let bytes = std::fs::read(dir.join(f)).unwrap();
            assert_eq!(&bytes[1..4], b"PNG", "{f}");
        }
        // Degenerate input (no iterations, zero residuals) still draws.
        plot_residuals(&dir.join("empty.png"), "empty", &[record(1, &[0.0])]).unwrap();
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
