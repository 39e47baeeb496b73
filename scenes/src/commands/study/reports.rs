//! A study's reports: the text summary, `study.csv` and `study.md`.

use super::results::{Reference, Study, LEVELS};
use std::fmt::Write;

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
