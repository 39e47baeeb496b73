//! Runs the CCD on a query file of the benchmark of Wang et al. 2021 (the format of
//! `mesh/tests/data/ccd-queries/README.md`) and prints
//! `queries N, touching T, false negatives FN, false positives FP`.
//!
//! `cargo run --release -p isochor-mesh --example ccd_queries -- FILE.csv [--edge-edge]
//! [--tolerance T]`: vertex-face queries unless `--edge-edge` is given or a folder of the path
//! is named `edge-edge`; several files add up; `--tolerance` sets the CCD's (default `1e-6`).

use isochor_mesh::contact::{read_ccd_queries, CcdSettings, CcdTally, QueryKind};
use std::path::PathBuf;
use std::process::ExitCode;

fn main() -> ExitCode {
    let usage = "usage: ccd_queries FILE.csv... [--edge-edge] [--tolerance T]";
    let mut args = std::env::args().skip(1);
    let (mut edge_edge, mut files, mut settings) = (false, Vec::new(), CcdSettings::default());
    while let Some(arg) = args.next() {
        match arg.as_str() {
            "--edge-edge" => edge_edge = true,
            "--tolerance" => match args.next().and_then(|t| t.parse::<f64>().ok()) {
                Some(t) if t > 0.0 => settings.tolerance = t,
                _ => {
                    eprintln!("--tolerance needs a positive number; {usage}");
                    return ExitCode::FAILURE;
                }
            },
            _ => files.push(PathBuf::from(arg)),
        }
    }
    if files.is_empty() {
        eprintln!("{usage}");
        return ExitCode::FAILURE;
    }
    let mut total = CcdTally::default();
    for file in &files {
        let kind = if edge_edge {
            QueryKind::EdgeEdge
        } else {
            QueryKind::from_path(file)
        };
        match read_ccd_queries(file, kind) {
            Ok(queries) => total = total.plus(CcdTally::of(&queries, &settings)),
            Err(e) => {
                eprintln!("{e}");
                return ExitCode::FAILURE;
            }
        }
    }
    println!("{total}");
    ExitCode::SUCCESS
}
