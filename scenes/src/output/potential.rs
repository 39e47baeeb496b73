//! The total potential energy against a probe, step by step (`output.potential_against`):
//! `potential.csv` and `potential.png`, like Fig. 9 of Francu et al. 2021 (energy against the
//! spine arm's deflection in implicit dynamics; the minimum marks where the run settles).

use super::atomic::write_file;
use super::plots::{finish_plot, plot_error, range, register_font};
use crate::error::SceneError;
use crate::record::StepRecord;
use plotters::prelude::*;
use std::fmt::Write;
use std::path::Path;

/// `(probe, potential energy)` of every step that recorded the probe.
pub fn potential_series(history: &[StepRecord]) -> Vec<(f64, f64)> {
    history
        .iter()
        .filter_map(|s| Some((s.tracked_probe?, s.potential_energy())))
        .collect()
}

/// The index of the point of least energy (the first of equal ones), ignoring non-finite
/// points; `None` if there is none.
pub fn minimum(points: &[(f64, f64)]) -> Option<usize> {
    points
        .iter()
        .enumerate()
        .filter(|(_, (x, e))| x.is_finite() && e.is_finite())
        .min_by(|a, b| a.1 .1.total_cmp(&b.1 .1))
        .map(|(i, _)| i)
}

/// `potential.csv`: per step its time, the probe, the potential and kinetic energies.
pub fn write_potential_csv(
    path: &Path,
    probe: &str,
    history: &[StepRecord],
) -> Result<(), SceneError> {
    let mut out = format!("step,t,{probe},potential_energy,kinetic_energy\n");
    for s in history {
        if let Some(v) = s.tracked_probe {
            let _ = writeln!(
                out,
                "{},{:e},{v:e},{:e},{:e}",
                s.step,
                s.t,
                s.potential_energy(),
                s.kinetic_energy
            );
        }
    }
    write_file(path, out.as_bytes())
}

/// Potential energy against the probe, one line per labelled series, each minimum marked by
/// a cross-hair and its probe value.
pub fn plot_potential(
    path: &Path,
    title: &str,
    probe: &str,
    series: &[(String, Vec<(f64, f64)>)],
) -> Result<(), SceneError> {
    register_font();
    let all = || series.iter().flat_map(|(_, points)| points.iter());
    let (x0, x1) = range(all().map(|p| p.0));
    let (y0, y1) = range(all().map(|p| p.1));
    let root = BitMapBackend::new(path, (1000, 600)).into_drawing_area();
    root.fill(&WHITE).map_err(|e| plot_error(path, e))?;
    let mut chart = ChartBuilder::on(&root)
        .caption(format!("Potential energy: {title}"), ("sans-serif", 24))
        .margin(15)
        .x_label_area_size(45)
        .y_label_area_size(90)
        .build_cartesian_2d(x0..x1, y0..y1)
        .map_err(|e| plot_error(path, e))?;
    chart
        .configure_mesh()
        .x_desc(probe)
        .y_desc("elastic + constraint + external energy (J)")
        .y_label_formatter(&|v| format!("{v:.3e}"))
        .draw()
        .map_err(|e| plot_error(path, e))?;
    let (dx, dy) = (0.03 * (x1 - x0), 0.05 * (y1 - y0));
    for (k, (label, points)) in series.iter().enumerate() {
        let color = Palette99::pick(k).to_rgba();
        chart
            .draw_series(LineSeries::new(
                points.iter().copied(),
                color.stroke_width(2),
            ))
            .map_err(|e| plot_error(path, e))?
            .label(label)
            .legend(move |(x, y)| {
                PathElement::new(vec![(x, y), (x + 20, y)], color.stroke_width(2))
            });
        if let Some(i) = minimum(points) {
            let (x, y) = points[i];
            let cross = GREEN.stroke_width(2);
            chart
                .draw_series([
                    PathElement::new(vec![(x - dx, y), (x + dx, y)], cross),
                    PathElement::new(vec![(x, y - dy), (x, y + dy)], cross),
                ])
                .map_err(|e| plot_error(path, e))?;
            chart
                .draw_series([Text::new(
                    format!("{x:.4}"),
                    (x, y - dy),
                    ("sans-serif", 15).into_font().color(&color),
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

    /// The minimum is the least finite energy, the first of a tie, and none without points.
    #[test]
    fn minimum_is_the_least_finite_energy() {
        // An oscillation about the equilibrium at 0.11: overshoot, back, settle.
        let swing = [
            (0.0, 0.0),
            (0.05, -0.3),
            (0.12, -0.5),
            (0.09, -0.45),
            (0.11, -0.49),
        ];
        assert_eq!(minimum(&swing), Some(2));
        assert_eq!(minimum(&[(0.0, 1.0), (1.0, f64::NAN), (2.0, 1.0)]), Some(0));
        assert_eq!(minimum(&[(f64::NAN, -1.0), (2.0, 3.0)]), Some(1));
        assert_eq!(minimum(&[]), None);
    }
}
