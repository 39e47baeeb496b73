//! A study's plots: error against wall time, and the probe against the unknowns.

use super::results::{Reference, Study, StudyRun, LEVELS};
use crate::error::SceneError;
use crate::output::{finish_plot, plot_error, range, register_font, tick};
use plotters::prelude::*;
use std::path::Path;

/// Log-log plot of error (percent) against wall time, one curve per series (a color per
/// method, dashed for the second element), with the error
/// levels as dashed lines and the fastest run for each level circled.
pub fn plot_study(path: &Path, study: &Study) -> Result<(), SceneError> {
    register_font();
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
    register_font();
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
