//! The query files of the CCD benchmark of Wang et al. 2021 ("A Large-Scale Benchmark and an
//! Inclusion-Based Algorithm for Continuous Collision Detection", ACM TOG 40(5); the
//! Sample-Queries repository): eight rows per query, one per vertex (start positions, then
//! end positions), each `x_num, x_den, y_num, y_den, z_num, z_den, truth` with exact
//! rational coordinates and the exact answer (1: the primitives touch during the step).
//!
//! A coordinate that is not a double exactly is rounded to nearest and its rounding error
//! kept: the query is then run with the minimum separation widened by twice the largest
//! error, because every coordinate of `F` (see [`super::ccd`]) is a difference of two convex
//! combinations of vertex coordinates and moves by at most that much. A touching query then
//! still must be reported, so the test stays honest.

use super::ccd::{edge_edge_ccd, point_triangle_ccd, CcdSettings};
use crate::{MeshError, Vec3};
use std::fmt;
use std::path::Path;

/// Which primitives a query file holds.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum QueryKind {
    /// A point and a triangle: rows `v, f0, f1, f2` at the start, then at the end.
    VertexFace,
    /// Two edges: rows `ea0, ea1, eb0, eb1` at the start, then at the end.
    EdgeEdge,
}

impl QueryKind {
    /// `EdgeEdge` when a component of `path` is named `edge-edge`, else `VertexFace`.
    pub fn from_path(path: &Path) -> Self {
        if path.components().any(|c| c.as_os_str() == "edge-edge") {
            QueryKind::EdgeEdge
        } else {
            QueryKind::VertexFace
        }
    }
}

/// One benchmark query.
#[derive(Debug, Clone, PartialEq)]
pub struct CcdQuery {
    /// The primitives.
    pub kind: QueryKind,
    /// The four vertices at the start of the step.
    pub start: [Vec3; 4],
    /// The four vertices at the end.
    pub end: [Vec3; 4],
    /// The exact answer: whether the primitives touch during the step.
    pub touching: bool,
    /// The largest error of rounding a rational coordinate to a double (0 when all are
    /// doubles exactly).
    pub rounding: f64,
}

impl CcdQuery {
    /// The CCD's time of impact with `settings`, the minimum separation widened by twice
    /// the rounding error (module docs).
    pub fn time_of_impact(&self, settings: &CcdSettings) -> Option<f64> {
        let settings = CcdSettings {
            min_separation: settings.min_separation + 2.0 * self.rounding,
            ..*settings
        };
        let [a, b, c, d] = &self.start;
        let [e, f, g, h] = &self.end;
        match self.kind {
            QueryKind::VertexFace => point_triangle_ccd(a, b, c, d, e, f, g, h, &settings),
            QueryKind::EdgeEdge => edge_edge_ccd(a, b, c, d, e, f, g, h, &settings),
        }
    }
}

/// The nearest double to `num / den` and a bound on its error (0 when exact).
pub fn rational_to_f64(num: i128, den: i128) -> Option<(f64, f64)> {
    if den == 0 {
        return None;
    }
    let (num, den) = if den < 0 { (-num, -den) } else { (num, den) };
    let exact_integer = |n: i128| (n as f64) as i128 == n && n.unsigned_abs() < 1 << 126;
    if den & (den - 1) == 0 && exact_integer(num) {
        // A power-of-two denominator (at most 2^126) scales exactly.
        return Some(((num as f64) / (den as f64), 0.0));
    }
    // Three roundings (numerator, denominator, quotient): relative error below 4 eps.
    let value = (num as f64) / (den as f64);
    Some((value, 4.0 * f64::EPSILON * value.abs() + f64::MIN_POSITIVE))
}

/// Reads the queries of a benchmark file.
pub fn read_ccd_queries(path: &Path, kind: QueryKind) -> Result<Vec<CcdQuery>, MeshError> {
    let text = std::fs::read_to_string(path).map_err(|e| MeshError::io(path, e))?;
    parse_ccd_queries(&text, path, kind)
}

/// Parses the queries of a benchmark file's text; `path` names the file in errors.
pub fn parse_ccd_queries(
    text: &str,
    path: &Path,
    kind: QueryKind,
) -> Result<Vec<CcdQuery>, MeshError> {
    let parse_error = |line: usize, message: String| MeshError::Parse {
        path: path.to_path_buf(),
        line,
        message,
    };
    let mut rows = Vec::new();
    for (index, line) in text.lines().enumerate() {
        let line_number = index + 1;
        if line.trim().is_empty() {
            continue;
        }
        let fields: Vec<i128> = line
            .split(',')
            .map(|f| f.trim().parse::<i128>())
            .collect::<Result<_, _>>()
            .map_err(|e| parse_error(line_number, format!("{line:?}: {e}")))?;
        if fields.len() != 7 {
            return Err(parse_error(
                line_number,
                format!("{} columns, expected 7", fields.len()),
            ));
        }
        let mut point = Vec3::zeros();
        let mut rounding: f64 = 0.0;
        for a in 0..3 {
            let (value, error) = rational_to_f64(fields[2 * a], fields[2 * a + 1])
                .ok_or_else(|| parse_error(line_number, "zero denominator".into()))?;
            point[a] = value;
            rounding = rounding.max(error);
        }
        if fields[6] != 0 && fields[6] != 1 {
            return Err(parse_error(
                line_number,
                format!("ground truth {}, expected 0 or 1", fields[6]),
            ));
        }
        rows.push((line_number, point, fields[6] == 1, rounding));
    }
    if rows.len() % 8 != 0 {
        return Err(MeshError::Format {
            path: path.to_path_buf(),
            message: format!("{} rows, not a multiple of 8", rows.len()),
        });
    }
    rows.chunks(8)
        .map(|q| {
            if q.iter().any(|r| r.2 != q[0].2) {
                return Err(parse_error(
                    q[0].0,
                    "ground truth differs within a query".into(),
                ));
            }
            Ok(CcdQuery {
                kind,
                start: std::array::from_fn(|i| q[i].1),
                end: std::array::from_fn(|i| q[4 + i].1),
                touching: q[0].2,
                rounding: q.iter().map(|r| r.3).fold(0.0, f64::max),
            })
        })
        .collect()
}

/// The outcome of the CCD over a set of queries against their exact answers.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct CcdTally {
    /// Queries run.
    pub queries: usize,
    /// Queries whose exact answer is "touching".
    pub touching: usize,
    /// Touching queries the CCD called safe (must be 0).
    pub false_negatives: usize,
    /// Safe queries the CCD called touching.
    pub false_positives: usize,
}

impl CcdTally {
    /// Runs every query with `settings` and counts.
    pub fn of(queries: &[CcdQuery], settings: &CcdSettings) -> Self {
        let mut tally = CcdTally::default();
        for q in queries {
            let reported = q.time_of_impact(settings).is_some();
            tally.queries += 1;
            tally.touching += usize::from(q.touching);
            tally.false_negatives += usize::from(q.touching && !reported);
            tally.false_positives += usize::from(!q.touching && reported);
        }
        tally
    }

    /// The sum of two tallies.
    pub fn plus(self, other: CcdTally) -> CcdTally {
        CcdTally {
            queries: self.queries + other.queries,
            touching: self.touching + other.touching,
            false_negatives: self.false_negatives + other.false_negatives,
            false_positives: self.false_positives + other.false_positives,
        }
    }
}

impl fmt::Display for CcdTally {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "queries {}, touching {}, false negatives {}, false positives {}",
            self.queries, self.touching, self.false_negatives, self.false_positives
        )
    }
}
