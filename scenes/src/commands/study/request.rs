//! A study's request: what to run and what to measure against, and its parsing.

use crate::error::SceneError;
use crate::format::{ElementName, Override};
use isochor_mesh::element::TetElement;
use isochor_solvers::Method;
use std::path::PathBuf;

/// A study request.
#[derive(Debug, Clone, Default)]
pub struct StudyRequest {
    /// Built-in name or scene path.
    pub scene: String,
    /// Methods to compare.
    pub methods: Vec<Method>,
    /// Elements to run every method on (empty: the scene's element).
    pub elements: Vec<TetElement>,
    /// `KEY=V1,V2,...` over mesh resolutions (default `res=1,2,4,8`).
    pub sweep: Option<String>,
    /// The probe to measure (default: the scene's deflection probe).
    pub probe: Option<String>,
    /// Where the reference comes from (default: the best-converging series).
    pub reference: ReferenceSpec,
    /// Skip runs with more unknowns than this (and the finer runs of their series).
    pub max_unknowns: Option<usize>,
    /// `--set` overrides applied to every run.
    pub overrides: Vec<Override>,
    /// Output folder for `study.csv`, `study.md`, `study.png` and `study-unknowns.png`.
    pub out: Option<PathBuf>,
    /// Progress bars on stderr.
    pub progress: bool,
}

/// Where the reference of a study comes from.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub enum ReferenceSpec {
    /// The extrapolation of the best-converging series.
    #[default]
    Best,
    /// The extrapolation of one method's series: on `element`, or, when `None`, the
    /// best-converging of that method's series.
    Series {
        /// The method.
        method: Method,
        /// The element, if the method runs on several.
        element: Option<TetElement>,
    },
    /// A value known from elsewhere (an independent, finer computation).
    Value {
        /// The reference value of the probe (finite, not zero: errors are relative to it).
        value: f64,
        /// Its relative uncertainty (0 when taken as exact): levels finer than this are not
        /// resolved.
        relative_uncertainty: f64,
    },
}

impl ReferenceSpec {
    /// Parses `--reference METHOD[/ELEMENT]`.
    pub fn parse_series(text: &str) -> Result<ReferenceSpec, SceneError> {
        let (method, element) = match text.trim().split_once('/') {
            Some((m, e)) => (m.trim(), Some(parse_element(e.trim())?)),
            None => (text.trim(), None),
        };
        Ok(ReferenceSpec::Series {
            method: method.parse()?,
            element,
        })
    }
}

/// Parses one element name (`tet4`, `tet10`).
pub fn parse_element(name: &str) -> Result<TetElement, SceneError> {
    name.parse::<ElementName>()
        .map(|e| e.0)
        .map_err(SceneError::Usage)
}

/// Parses a comma-separated element list (`--elements tet4,tet10`).
pub fn parse_elements(list: &str) -> Result<Vec<TetElement>, SceneError> {
    list.split(',')
        .map(str::trim)
        .filter(|s| !s.is_empty())
        .map(parse_element)
        .collect()
}
