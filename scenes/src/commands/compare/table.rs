//! The comparison as tables: every column in SI units for `compare.csv`, and a narrower one
//! for people (screen and `compare.md`): probes in their display units beside the published
//! values, columns that are equal in every row moved to a line above, then the factors.

use super::comparison::Comparison;
use crate::format::overrides::dotted;
use std::fmt::Write;

/// The width the screen tables fit in (wider tables are split, repeating the row labels).
const WIDTH: usize = 100;

/// One column of a table for people.
struct Column {
    title: String,
    cells: Vec<String>,
}

impl Column {
    fn new(title: impl Into<String>, cells: Vec<String>) -> Column {
        Column {
            title: title.into(),
            cells,
        }
    }

    /// The one value of every non-empty cell, if there is one.
    fn constant(&self) -> Option<&str> {
        let mut filled = self.cells.iter().filter(|c| !c.is_empty());
        let first = filled.next()?;
        filled.all(|c| c == first).then_some(first.as_str())
    }
}

/// Four significant digits (`13.19`, `0.6120`, `1.234e-5`).
fn significant(v: f64) -> String {
    let a = v.abs();
    if !v.is_finite() || a == 0.0 {
        format!("{v}")
    } else if (1e-3..1e5).contains(&a) {
        let decimals = (3 - a.log10().floor() as i32).max(0) as usize;
        format!("{v:.decimals$}")
    } else {
        format!("{v:.3e}")
    }
}

/// A published value as it was printed: its shortest decimal form after rounding away the
/// unit conversion's last bits (`11.2`, not `11.200000000000001`).
fn published(v: f64) -> String {
    let rounded: f64 = format!("{v:.9e}").parse().unwrap_or(v);
    format!("{rounded}")
}

impl Comparison {
    /// Header and cells of the full table (`compare.csv`): SI units, then the published
    /// values as `paper:PROBE` columns.
    fn table(&self) -> (Vec<String>, Vec<Vec<String>>) {
        let probes = self.probe_names();
        let paper = self.paper_probes();
        let mut header = Vec::new();
        if let Some(k) = &self.sweep_key {
            header.push(k.clone());
        }
        header.extend(
            [
                "config",
                "method",
                "nu",
                "tets",
                "dofs",
                "steps",
                "newton_iterations",
                "converged",
            ]
            .map(String::from),
        );
        header.extend(probes.iter().cloned());
        header.extend(
            ["volume_change_percent", "max_inverted_tets", "wall_time_s"].map(String::from),
        );
        header.extend(paper.iter().map(|p| format!("paper:{p}")));
        let rows = self
            .rows
            .iter()
            .map(|row| {
                let mut cells = Vec::new();
                if self.sweep_key.is_some() {
                    cells.push(row.sweep_value.clone().unwrap_or_default());
                }
                cells.push(row.label.clone());
                match &row.result {
                    Ok(r) => {
                        cells.push(r.method.clone());
                        cells.push(format!("{}", r.nu));
                        cells.push(r.tets.to_string());
                        cells.push(r.dofs.to_string());
                        cells.push(if r.converged {
                            r.steps.to_string()
                        } else {
                            format!("{}/{}", r.steps, r.steps_requested)
                        });
                        cells.push(r.newton_iterations.to_string());
                        cells.push(if r.converged {
                            "yes".into()
                        } else {
                            "no".into()
                        });
                        for p in &probes {
                            cells.push(
                                r.probes
                                    .get(p)
                                    .map_or(String::new(), |v| format!("{v:.6e}")),
                            );
                        }
                        cells.push(format!("{:.4e}", 100.0 * r.volume_change));
                        cells.push(r.max_inverted_tets.to_string());
                        cells.push(format!("{:.3}", r.wall_time_s));
                    }
                    Err(e) => {
                        cells.push(format!("error: {e}"));
                        cells.resize(header.len() - paper.len(), String::new());
                    }
                }
                for p in &paper {
                    cells.push(
                        self.paper_value(row, p)
                            .map_or(String::new(), |v| format!("{v:.6e}")),
                    );
                }
                cells
            })
            .collect();
        (header, rows)
    }

    /// The columns for people: the sweep and the label first, then what differs between runs.
    fn columns(&self) -> Vec<Column> {
        let cell = |f: &dyn Fn(&crate::record::RunResult) -> String| -> Vec<String> {
            self.rows
                .iter()
                .map(|row| row.result.as_ref().map_or(String::new(), f))
                .collect()
        };
        let mut columns = Vec::new();
        if let Some(k) = &self.sweep_key {
            let values = self.rows.iter().map(|r| r.sweep_value.clone());
            columns.push(Column::new(
                k,
                values.map(Option::unwrap_or_default).collect(),
            ));
        }
        let labels = self.rows.iter().map(|r| r.label.clone());
        columns.push(Column::new("config", labels.collect()));
        if self
            .rows
            .iter()
            .any(|r| r.result.as_ref().is_ok_and(|res| res.method != r.label))
        {
            columns.push(Column::new("method", cell(&|r| r.method.clone())));
        }
        columns.push(Column::new("element", cell(&|r| r.element.clone())));
        if self
            .sweep_key
            .as_deref()
            .is_none_or(|k| dotted(k) != "material.nu")
        {
            columns.push(Column::new("nu", cell(&|r| r.nu.to_string())));
        }
        columns.push(Column::new("tets", cell(&|r| r.tets.to_string())));
        columns.push(Column::new("unknowns", cell(&|r| r.dofs.to_string())));
        columns.push(Column::new(
            "newton",
            cell(&|r| r.newton_iterations.to_string()),
        ));
        columns.push(Column::new(
            "converged",
            cell(&|r| match r.converged {
                true => "yes".into(),
                false => format!("no ({}/{} steps)", r.steps, r.steps_requested),
            }),
        ));
        let paper = self.paper_probes();
        for probe in self.probe_names() {
            let shown = |r: &crate::record::RunResult| {
                r.probes
                    .get(&probe)
                    .map_or(String::new(), |v| significant(self.shown(&probe, *v)))
            };
            columns.push(Column::new(self.probe_title(&probe), cell(&shown)));
            if paper.contains(&probe) {
                let published = self.rows.iter().map(|row| {
                    self.paper_value(row, &probe)
                        .map_or(String::new(), |v| published(self.shown(&probe, v)))
                });
                columns.push(Column::new("paper", published.collect()));
            }
        }
        columns.push(Column::new(
            "volume (%)",
            cell(&|r| format!("{:+.2e}", 100.0 * r.volume_change)),
        ));
        if self
            .rows
            .iter()
            .any(|r| r.result.as_ref().is_ok_and(|r| r.max_inverted_tets > 0))
        {
            columns.push(Column::new(
                "inverted",
                cell(&|r| r.max_inverted_tets.to_string()),
            ));
        }
        columns.push(Column::new(
            "time (s)",
            cell(&|r| format!("{:.2}", r.wall_time_s)),
        ));
        columns
    }

    /// The columns for people without those equal in every row, and those as `name value`
    /// (the sweep, the label and the measured values always stay columns).
    fn screen(&self) -> (Vec<String>, Vec<Column>) {
        const MOVABLE: [&str; 4] = ["method", "element", "nu", "tets"];
        let mut context = Vec::new();
        let mut kept = Vec::new();
        for column in self.columns() {
            match column.constant() {
                Some(value) if MOVABLE.contains(&column.title.as_str()) => {
                    context.push(format!("{} {value}", column.title));
                }
                _ => kept.push(column),
            }
        }
        (context, kept)
    }

    /// The factors as columns: the label, then per probe ours and the published one.
    fn factor_columns(&self) -> Vec<Column> {
        let factors = self.factors();
        let labels = self.labels();
        let x = |f: Option<f64>| f.map_or("-".to_string(), |f| format!("{f:.2}x"));
        let mut columns = vec![Column::new("config", labels.clone())];
        for probe in self.probe_names() {
            let of = |label: &String| {
                factors
                    .iter()
                    .find(|f| f.probe == probe && f.label == *label)
            };
            columns.push(Column::new(
                probe.clone(),
                labels
                    .iter()
                    .map(|l| x(of(l).and_then(|f| f.ours)))
                    .collect(),
            ));
            if factors
                .iter()
                .any(|f| f.probe == probe && f.paper.is_some())
            {
                columns.push(Column::new(
                    "paper",
                    labels
                        .iter()
                        .map(|l| x(of(l).and_then(|f| f.paper)))
                        .collect(),
                ));
            }
        }
        columns
    }

    /// What the factors mean: which values they divide.
    fn factor_caption(&self) -> Option<String> {
        let key = self.sweep_key.as_ref()?;
        let first = self.rows.first()?.sweep_value.as_ref()?;
        let last = self.rows.last()?.sweep_value.as_ref()?;
        Some(format!(
            "factor over the sweep: the value at {key} = {first} over the value at {key} = {last}"
        ))
    }

    /// The tables for people as aligned text, each at most 100 columns wide.
    pub fn to_text(&self) -> String {
        let (context, columns) = self.screen();
        let mut out = format!("scene: {}", self.scene);
        for c in &context {
            out += ", ";
            out += c;
        }
        out += "\n";
        for note in self.paper_notes() {
            out += &wrapped(&note);
        }
        out += &aligned(&columns, self.sweep_key.is_some() as usize + 1);
        if !self.factors().is_empty() {
            if let Some(caption) = self.factor_caption() {
                let _ = writeln!(out, "\n{caption}:");
            }
            out += &aligned(&self.factor_columns(), 1);
        }
        for row in &self.rows {
            let at = match (&self.sweep_key, &row.sweep_value) {
                (Some(k), Some(v)) => format!(" at {k} = {v}"),
                _ => String::new(),
            };
            match &row.result {
                Ok(r) => {
                    if let Some(e) = &r.error {
                        let step = r.failed_step.unwrap_or(0);
                        let _ = writeln!(out, "{}{at}: stopped at step {step}: {e}", row.label);
                    }
                }
                Err(e) => {
                    let _ = writeln!(out, "{}{at}: error: {e}", row.label);
                }
            }
        }
        out
    }

    /// The full table as CSV (SI units).
    pub fn to_csv(&self) -> String {
        let (header, rows) = self.table();
        let quote = |c: &String| {
            if c.contains([',', '"', '\n']) {
                format!("\"{}\"", c.replace('"', "\"\""))
            } else {
                c.clone()
            }
        };
        let mut out = String::new();
        for row in std::iter::once(&header).chain(&rows) {
            let _ = writeln!(
                out,
                "{}",
                row.iter().map(quote).collect::<Vec<_>>().join(",")
            );
        }
        out
    }

    /// The tables for people as Markdown.
    pub fn to_markdown(&self) -> String {
        let (context, columns) = self.screen();
        let mut out = format!("# {}\n\n", self.scene);
        if !context.is_empty() {
            let _ = writeln!(out, "{}\n", context.join(", "));
        }
        for note in self.paper_notes() {
            let _ = writeln!(out, "{note}\n");
        }
        out += &markdown(&columns);
        if !self.factors().is_empty() {
            if let Some(caption) = self.factor_caption() {
                let _ = writeln!(out, "\n{caption}:\n");
            }
            out += &markdown(&self.factor_columns());
        }
        out
    }
}

/// Columns as aligned text, split into tables of at most [`WIDTH`] characters that each
/// repeat the first `lead` columns.
fn aligned(columns: &[Column], lead: usize) -> String {
    let width = |c: &Column| {
        c.cells
            .iter()
            .map(String::len)
            .chain([c.title.len()])
            .max()
            .unwrap_or(0)
    };
    let lead = lead.min(columns.len());
    let lead_width: usize = columns[..lead].iter().map(|c| width(c) + 2).sum();
    let mut blocks: Vec<Vec<&Column>> = Vec::new();
    let mut used = WIDTH;
    for column in &columns[lead..] {
        if used + width(column) > WIDTH {
            blocks.push(columns[..lead].iter().collect());
            used = lead_width;
        }
        used += width(column) + 2;
        blocks.last_mut().expect("a block was started").push(column);
    }
    let rows = columns.first().map_or(0, |c| c.cells.len());
    let mut out = String::new();
    for (b, block) in blocks.iter().enumerate() {
        if b > 0 {
            out += "\n";
        }
        let widths: Vec<usize> = block.iter().map(|c| width(c)).collect();
        let line = |cells: Vec<&str>| {
            let padded: Vec<String> = cells
                .iter()
                .zip(&widths)
                .map(|(c, w)| format!("{c:<w$}"))
                .collect();
            padded.join("  ").trim_end().to_string()
        };
        let _ = writeln!(
            out,
            "{}",
            line(block.iter().map(|c| c.title.as_str()).collect())
        );
        for i in 0..rows {
            let _ = writeln!(
                out,
                "{}",
                line(block.iter().map(|c| c.cells[i].as_str()).collect())
            );
        }
    }
    out
}

/// Text broken into lines of at most [`WIDTH`] characters (at spaces; a longer word stays
/// whole).
fn wrapped(text: &str) -> String {
    let mut out = String::new();
    let mut line = String::new();
    for word in text.split_whitespace() {
        if !line.is_empty() && line.len() + 1 + word.len() > WIDTH {
            out += &line;
            out += "\n";
            line.clear();
        }
        if !line.is_empty() {
            line += " ";
        }
        line += word;
    }
    out + &line + "\n"
}

/// Columns as a Markdown table.
fn markdown(columns: &[Column]) -> String {
    let cell = |c: &str| c.replace('|', "\\|");
    let line = |cells: Vec<String>| format!("| {} |\n", cells.join(" | "));
    let mut out = line(columns.iter().map(|c| cell(&c.title)).collect());
    out += &format!("|{}|\n", vec!["---"; columns.len()].join("|"));
    let rows = columns.first().map_or(0, |c| c.cells.len());
    for i in 0..rows {
        out += &line(columns.iter().map(|c| cell(&c.cells[i])).collect());
    }
    out
}
