//! `isochor penalties`: Fig. 3 of Sheen et al. 2021, the volumetric penalties `U(J)` and their
//! stresses `U'(J)` over `J` in `(0, 3]` with `lambda = 1`, as `penalties.csv` and
//! `penalties.png`.
//!
//! The curves: the neo-Hookean `(log J)^2 / 2` (eq. 4), Stable neo-Hookean `(J - 1)^2 / 2`
//! (`U(J; 0)`, after eq. 15), its second-order expansion SNH2, and `U(J; beta)` (eq. 13) for
//! `beta = 1` and `6`, and for the figure's Kikuuwe et al. 2009 curve, whose formula the paper
//! does not write, our reading: the Saint Venant-Kirchhoff volumetric term under pure dilation
//! ([`StvkPenalty`]).

use crate::error::SceneError;
use crate::output::{finish_plot, plot_error, register_font, OutputDir, OutputIdentity};
use isochor_energies::{
    LogPenalty, QuadraticPenalty, SheenPenalty, Snh2Penalty, StvkPenalty, VolumetricPenalty,
};
use plotters::prelude::*;
use std::fmt::Write;
use std::path::{Path, PathBuf};

/// Samples of `J`: `3 k / SAMPLES` for `k = 1..=SAMPLES`.
pub const SAMPLES: usize = 300;

/// The plotted ranges of `U` and `U'` (the CSV holds every value): the neo-Hookean term
/// leaves them as `J -> 0+`, `U(J; 6)` near `J = 3`.
const U_RANGE: (f64, f64) = (0.0, 4.0);
const DU_RANGE: (f64, f64) = (-5.0, 5.0);

/// A penalty of the figure: its CSV column stem, the penalty and its colour.
type Curve = (&'static str, Box<dyn VolumetricPenalty>, RGBColor);

/// The penalties of Fig. 3, in the figure's colours where it names them.
fn penalties() -> Result<Vec<Curve>, SceneError> {
    Ok(vec![
        ("neo_hookean", Box::new(LogPenalty), BLUE),
        (
            "stable_neo_hookean",
            Box::new(QuadraticPenalty),
            RGBColor(255, 127, 14),
        ),
        ("snh2", Box::new(Snh2Penalty), RED),
        ("kikuuwe_stvk", Box::new(StvkPenalty), RGBColor(230, 190, 0)),
        (
            "ours_beta_1",
            Box::new(SheenPenalty::new(1.0)?),
            RGBColor(148, 103, 189),
        ),
        (
            "ours_beta_6",
            Box::new(SheenPenalty::new(6.0)?),
            RGBColor(44, 160, 44),
        ),
    ])
}

/// `U` or `U'` of `u` at `j`, `None` where it is undefined (the neo-Hookean term at `J <= 0`).
fn sample(u: &dyn VolumetricPenalty, j: f64, derivative: bool) -> Option<f64> {
    let v = if derivative {
        u.first_derivative(j)
    } else {
        u.value(j)
    };
    v.ok()
}

/// Writes `penalties.csv` (columns `J`, then `U_NAME` and `dU_NAME` per penalty) and
/// `penalties.png` (`U` above, `U'` below) to `out`, replacing an earlier output there.
pub fn write_penalty_plot(out: &Path) -> Result<PathBuf, SceneError> {
    let dir = OutputDir::create(out, OutputIdentity::new("penalties", ""))?;
    let curves = penalties()?;
    let js: Vec<f64> = (1..=SAMPLES)
        .map(|k| 3.0 * k as f64 / SAMPLES as f64)
        .collect();
    let mut csv = String::from("J");
    for (name, ..) in &curves {
        let _ = write!(csv, ",U_{name},dU_{name}");
    }
    csv.push('\n');
    for &j in &js {
        let _ = write!(csv, "{j:e}");
        for (_, u, _) in &curves {
            for derivative in [false, true] {
                let v = sample(u.as_ref(), j, derivative).unwrap_or(f64::NAN);
                let _ = write!(csv, ",{v:e}");
            }
        }
        csv.push('\n');
    }
    crate::output::write_file(&dir.path().join("penalties.csv"), csv.as_bytes())?;
    plot(&dir.path().join("penalties.png"), &curves, &js)?;
    dir.commit()
}

/// Two panels over `J`: `U` and `U'`, one line per penalty, clipped to the plotted ranges.
fn plot(path: &Path, curves: &[Curve], js: &[f64]) -> Result<(), SceneError> {
    register_font();
    let root = BitMapBackend::new(path, (1000, 1000)).into_drawing_area();
    root.fill(&WHITE).map_err(|e| plot_error(path, e))?;
    let panels = root.split_evenly((2, 1));
    let titles = [
        (
            "Penalties U(J), lambda = 1 (Fig. 3 of Sheen et al. 2021)",
            "U(J)",
            U_RANGE,
        ),
        ("Stresses U'(J)", "U'(J)", DU_RANGE),
    ];
    for (panel, (derivative, (title, label, (lo, hi)))) in
        panels.iter().zip([false, true].into_iter().zip(titles))
    {
        let mut chart = ChartBuilder::on(panel)
            .caption(title, ("sans-serif", 22))
            .margin(15)
            .x_label_area_size(40)
            .y_label_area_size(60)
            .build_cartesian_2d(0f64..3f64, lo..hi)
            .map_err(|e| plot_error(path, e))?;
        chart
            .configure_mesh()
            .x_desc("J")
            .y_desc(label)
            .draw()
            .map_err(|e| plot_error(path, e))?;
        for (name, u, color) in curves {
            let color = *color;
            let points = js.iter().filter_map(|&j| {
                sample(u.as_ref(), j, derivative)
                    .filter(|v| (lo..=hi).contains(v))
                    .map(|v| (j, v))
            });
            chart
                .draw_series(LineSeries::new(points, color.stroke_width(2)))
                .map_err(|e| plot_error(path, e))?
                .label(*name)
                .legend(move |(x, y)| {
                    PathElement::new(vec![(x, y), (x + 20, y)], color.stroke_width(2))
                });
        }
        let position = if derivative {
            SeriesLabelPosition::UpperLeft
        } else {
            SeriesLabelPosition::UpperMiddle
        };
        finish_plot(&mut chart, panel, position, true, path)?;
    }
    Ok(())
}
