//! A study's runs and what they show: the series, their extrapolations, the reference, the
//! fastest run within each error level.

use super::request::ReferenceSpec;
use super::richardson::{richardson, Richardson};
use crate::error::SceneError;
use crate::record::RunResult;

/// Error levels at which the fastest run is marked, coarse to fine.
pub const LEVELS: [f64; 3] = [0.10, 0.05, 0.01];

/// The label of a series: `METHOD/ELEMENT`, or `METHOD` alone when the study has one element.
pub(super) fn series_label(method: &str, element: &str, several_elements: bool) -> String {
    if several_elements {
        format!("{method}/{element}")
    } else {
        method.to_string()
    }
}

/// One run of the study.
#[derive(Debug, Clone)]
pub struct StudyRun {
    /// Method name.
    pub method: String,
    /// Element name (`tet4`, `tet10`).
    pub element: String,
    /// The swept value as given.
    pub label: String,
    /// The swept value as a number (the resolution; `h = 1 / resolution`).
    pub resolution: f64,
    /// The run, or why it could not start.
    pub result: Result<RunResult, String>,
    /// The probe's value, if the run converged.
    pub value: Option<f64>,
    /// `|value - reference| / |reference|`.
    pub error: Option<f64>,
}

impl StudyRun {
    pub(super) fn converged(&self) -> Option<&RunResult> {
        self.result.as_ref().ok().filter(|r| r.converged)
    }

    pub(super) fn wall_time(&self) -> Option<f64> {
        self.converged().map(|r| r.wall_time_s)
    }
}

/// The reference a study measures errors against.
#[derive(Debug, Clone, PartialEq)]
pub enum Reference {
    /// The extrapolation of one series.
    Extrapolated(Richardson),
    /// A value given with the study (`--reference-value`).
    Given {
        /// The value.
        value: f64,
        /// Its relative uncertainty.
        relative_uncertainty: f64,
    },
}

impl Reference {
    /// The reference value of the probe.
    pub fn value(&self) -> f64 {
        match self {
            Reference::Extrapolated(r) => r.limit,
            Reference::Given { value, .. } => *value,
        }
    }

    /// Its relative uncertainty: the extrapolation's relative estimate, or the given one.
    pub fn relative_uncertainty(&self) -> f64 {
        match self {
            Reference::Extrapolated(r) => r.relative_estimate(),
            Reference::Given {
                relative_uncertainty,
                ..
            } => *relative_uncertainty,
        }
    }

    /// The extrapolation, if the reference is one.
    pub fn extrapolation(&self) -> Option<&Richardson> {
        match self {
            Reference::Extrapolated(r) => Some(r),
            Reference::Given { .. } => None,
        }
    }
}

/// A run left out by `--max-unknowns`.
#[derive(Debug, Clone, PartialEq)]
pub struct Skipped {
    /// Method name.
    pub method: String,
    /// Element name.
    pub element: String,
    /// The swept value as given.
    pub label: String,
    /// Its unknowns, if counted (a finer run of a series already over the limit is not).
    pub unknowns: Option<usize>,
}

/// The result of a study.
#[derive(Debug, Clone)]
pub struct Study {
    /// Scene name.
    pub scene: String,
    /// The swept key.
    pub sweep_key: String,
    /// The probe measured.
    pub probe: String,
    /// Every run, series by series (method-major, then element), coarse to fine.
    pub runs: Vec<StudyRun>,
    /// The extrapolation of every series that allowed one.
    pub extrapolations: Vec<Richardson>,
    /// The reference: given, or one of `extrapolations`.
    pub reference: Option<Reference>,
    /// Runs left out by `--max-unknowns`, with the limit.
    pub skipped: Vec<Skipped>,
    /// The `--max-unknowns` limit, if any.
    pub max_unknowns: Option<usize>,
}

impl Study {
    /// The study of finished runs (series by series, coarse to fine): extrapolates every
    /// series with three converged runs, takes the reference `wanted` asks for and measures
    /// every run's error against it.
    pub fn from_runs(
        scene: String,
        sweep_key: String,
        probe: String,
        runs: Vec<StudyRun>,
        wanted: ReferenceSpec,
    ) -> Result<Study, SceneError> {
        let mut study = Study {
            scene,
            sweep_key,
            probe,
            runs,
            extrapolations: Vec::new(),
            reference: None,
            skipped: Vec::new(),
            max_unknowns: None,
        };
        study.extrapolate(wanted)?;
        Ok(study)
    }

    /// Whether the study runs more than one element (series are then labelled
    /// `METHOD/ELEMENT`).
    pub fn several_elements(&self) -> bool {
        self.runs
            .iter()
            .map(|r| &r.element)
            .chain(self.skipped.iter().map(|s| &s.element))
            .any(|e| self.runs.first().is_some_and(|f| f.element != *e))
    }

    /// The label of the series of `method` on `element`.
    pub fn label(&self, method: &str, element: &str) -> String {
        series_label(method, element, self.several_elements())
    }

    /// The label of a run's series.
    pub fn run_label(&self, run: &StudyRun) -> String {
        self.label(&run.method, &run.element)
    }

    /// Converged (resolution, value) pairs of one series, coarse to fine.
    pub(super) fn series(&self, method: &str, element: &str) -> Vec<(f64, f64)> {
        self.runs
            .iter()
            .filter(|r| r.method == method && r.element == element)
            .filter_map(|r| r.value.map(|v| (r.resolution, v)))
            .collect()
    }

    /// The (method, element) pairs, in the order of the runs.
    pub fn series_keys(&self) -> Vec<(String, String)> {
        let mut keys: Vec<(String, String)> = Vec::new();
        for r in &self.runs {
            if !keys.iter().any(|(m, e)| *m == r.method && *e == r.element) {
                keys.push((r.method.clone(), r.element.clone()));
            }
        }
        keys
    }

    /// The series labels, in the order of the runs.
    pub fn series_labels(&self) -> Vec<String> {
        self.series_keys()
            .iter()
            .map(|(m, e)| self.label(m, e))
            .collect()
    }

    pub(super) fn extrapolate(&mut self, wanted: ReferenceSpec) -> Result<(), SceneError> {
        for (method, element) in self.series_keys() {
            let s = self.series(&method, &element);
            if s.len() < 3 {
                continue;
            }
            let n = s.len();
            let Some((order, limit)) = richardson([s[n - 3], s[n - 2], s[n - 1]]) else {
                continue;
            };
            let previous_gap = (n >= 4)
                .then(|| richardson([s[n - 4], s[n - 3], s[n - 2]]))
                .flatten()
                .map(|(_, l)| (limit - l).abs());
            self.extrapolations.push(Richardson {
                method: method.clone(),
                element: element.clone(),
                resolutions: [s[n - 3].0, s[n - 2].0, s[n - 1].0],
                values: [s[n - 3].1, s[n - 2].1, s[n - 1].1],
                order,
                limit,
                finest_gap: (limit - s[n - 1].1).abs(),
                previous_gap,
            });
        }
        let best = |candidates: Vec<&Richardson>| {
            candidates
                .into_iter()
                .min_by(|a, b| a.relative_estimate().total_cmp(&b.relative_estimate()))
                .cloned()
                .map(Reference::Extrapolated)
        };
        self.reference = match wanted {
            ReferenceSpec::Best => best(self.extrapolations.iter().collect()),
            ReferenceSpec::Series { method, element } => {
                let candidates: Vec<&Richardson> = self
                    .extrapolations
                    .iter()
                    .filter(|e| e.method == method.name())
                    .filter(|e| element.is_none_or(|el| e.element == el.name()))
                    .collect();
                let name = match element {
                    Some(e) => format!("{}/{}", method.name(), e.name()),
                    None => method.name().to_string(),
                };
                Some(best(candidates).ok_or_else(|| {
                    SceneError::Usage(format!(
                        "{name} cannot be extrapolated: it needs three converged runs whose values converge monotonically"
                    ))
                })?)
            }
            ReferenceSpec::Value {
                value,
                relative_uncertainty,
            } => Some(Reference::Given {
                value,
                relative_uncertainty,
            }),
        };
        if let Some(reference) = &self.reference {
            let value = reference.value();
            for run in &mut self.runs {
                run.error = run.value.map(|v| (v - value).abs() / value.abs());
            }
        }
        Ok(())
    }

    /// Whether the reference is known to within `level` (relative), so that errors at that
    /// level mean something.
    pub fn resolves(&self, level: f64) -> bool {
        self.reference
            .as_ref()
            .is_some_and(|r| r.relative_uncertainty() <= level)
    }

    /// The relative distance of the series labelled `series`' own extrapolated limit from the
    /// reference, if the series converges elsewhere at `level`: when even the nearest reading
    /// of both (the distance minus the extrapolation's estimate and the reference's
    /// uncertainty) is farther than `level`. Its runs within `level` are then crossings on the
    /// way to another limit (a method that solves a different model, such as `zonal` with its
    /// own penalty), which no resolution can be chosen in advance to hit, and are not counted
    /// as reaching the level.
    pub fn converges_elsewhere(&self, level: f64, series: &str) -> Option<f64> {
        let reference = self.reference.as_ref()?;
        let value = reference.value();
        let e = self
            .extrapolations
            .iter()
            .find(|e| self.label(&e.method, &e.element) == series)?;
        let distance = (e.limit - value).abs() / value.abs();
        (distance - e.relative_estimate() - reference.relative_uncertainty() > level)
            .then_some(distance)
    }

    /// Index of the fastest converged run with error at most `level`, of the series labelled
    /// `series` if given (see [`Study::label`]), leaving out series that converge elsewhere
    /// (see [`Study::converges_elsewhere`]).
    pub fn fastest(&self, level: f64, series: Option<&str>) -> Option<usize> {
        self.runs
            .iter()
            .enumerate()
            .filter(|(_, r)| series.is_none_or(|s| self.run_label(r) == s))
            .filter(|(_, r)| r.error.is_some_and(|e| e <= level))
            .filter(|(_, r)| {
                self.converges_elsewhere(level, &self.run_label(r))
                    .is_none()
            })
            .filter_map(|(i, r)| r.wall_time().map(|t| (i, t)))
            .min_by(|a, b| a.1.total_cmp(&b.1))
            .map(|(i, _)| i)
    }
}
