//! The result of one run, as `--json` prints it and `summary.json` stores it. The keys of
//! docs/contracts.md are fields of [`RunResult`]; everything else is extra.

use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;

/// One accepted step or frame.
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
pub struct StepRecord {
    /// Step or frame index, from 1.
    pub step: usize,
    /// Load parameter (quasi-static) or time in seconds (dynamics).
    pub t: f64,
    /// The increment of the load parameter or time the step took.
    pub increment: f64,
    /// Attempts of this step that failed and were retried with half the increment.
    pub cuts: Vec<CutRecord>,
    /// Newton (or dual) iterations of the step.
    pub newton_iterations: usize,
    /// Whether the step met both tolerances.
    pub converged: bool,
    /// Its Newton iterations.
    #[serde(flatten)]
    pub iterations: Iterations,
    /// Whole-body volume change (deformed/rest - 1) of the accepted state.
    pub volume_change: f64,
    /// Inverted tets in the accepted state.
    pub inverted_tets: usize,
    /// Kinetic energy.
    pub kinetic_energy: f64,
    /// Elastic energy (the distortional part for the mixed methods).
    pub elastic_energy: f64,
    /// Energy of the compliant volume constraints (see [`isochor_solvers::Energies`]).
    #[serde(default)]
    pub constraint_energy: f64,
    /// Potential of the external loads.
    pub external_energy: f64,
    /// Wall time of the step in seconds.
    pub wall_time_s: f64,
    /// Rebuilds of the Newton matrix's sparsity pattern and symbolic factorization in the
    /// step, because the surface contact's or friction's pairs changed.
    #[serde(default)]
    pub pattern_rebuilds: usize,
    /// The value of the probe `output.potential_against` names, at this step (`None` when
    /// the scene names none).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub tracked_probe: Option<f64>,
    /// Contact forces of the accepted state (zeros without obstacles).
    pub contact: ContactRecord,
    /// Every pressure load's pressure and enclosed volume ratio, in the order of
    /// `[[loads.pressure]]`.
    #[serde(default)]
    pub pressure_loads: Vec<PressureLoadRecord>,
    /// Every probe of the scene at this step, by name (NaN where one cannot be evaluated).
    #[serde(default)]
    pub probes: BTreeMap<String, f64>,
}

/// A pressure load at one step.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct PressureLoadRecord {
    /// The pressure (Pa, given or solved for; positive inflates).
    pub pressure: f64,
    /// The enclosed volume over the rest volume.
    pub volume_ratio: f64,
}

/// Where a run's time went, in seconds, summed over every attempt (cut ones included).
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize)]
pub struct RunTimings {
    /// Resolving the scene and building its model (meshes generated or read, promoted to
    /// 10 nodes, selections, zones, the terms), before the first step; not part of
    /// `wall_time_s`.
    pub model_s: f64,
    /// Sparsity patterns and symbolic factorizations: at the first step, and again where
    /// contact pairs change the pattern.
    pub setup_s: f64,
    /// Element evaluation and sparse assembly of the Newton systems.
    pub assembly_s: f64,
    /// Numeric factorizations (and preconditioner set-ups on the iterative path).
    pub factorization_s: f64,
    /// Triangular and iterative solves.
    pub solve_s: f64,
    /// Line searches: collision detection, trial states' checks and evaluations.
    pub line_search_s: f64,
    /// Numeric factorizations of the direct linear solvers.
    pub factorizations: usize,
}

impl RunTimings {
    /// The timings of the solver's `reports` after a model built in `model_s` seconds.
    pub fn of(model_s: f64, reports: &[isochor_solvers::StepReport]) -> Self {
        let mut t = isochor_solvers::Timings::default();
        for r in reports {
            t += r.timings;
        }
        RunTimings {
            model_s,
            setup_s: t.setup.as_secs_f64(),
            assembly_s: t.assembly.as_secs_f64(),
            factorization_s: t.factorization.as_secs_f64(),
            solve_s: t.solve.as_secs_f64(),
            line_search_s: t.line_search.as_secs_f64(),
            factorizations: reports.iter().map(|r| r.factorizations).sum(),
        }
    }
}

/// The Newton iterations of one attempt of a step: residuals per iteration (before each),
/// then the final ones; the line search and the linear solve per iteration.
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
pub struct Iterations {
    /// Force residual per iteration, then the final one.
    pub force_residuals: Vec<f64>,
    /// Constraint residual per iteration, then the final one.
    pub constraint_residuals: Vec<f64>,
    /// Volume error (L1 norm of the constraint residual over the rest volume, Francu et al.
    /// 2021, Fig. 8) per iteration, then the final one.
    #[serde(default)]
    pub volume_errors: Vec<f64>,
    /// Accepted step length per iteration.
    #[serde(default)]
    pub step_lengths: Vec<f64>,
    /// Line-search backtracks per iteration.
    #[serde(default)]
    pub backtracks: Vec<usize>,
    /// Diagonal shift added to the stiffness per iteration (0 when none was needed).
    #[serde(default)]
    pub shifts: Vec<f64>,
    /// Per iteration: whether the barrier contact's pair and the cloth's element Hessians
    /// were PSD-projected (the matrix with the exact ones did not factorize).
    #[serde(default)]
    pub hessian_projected: Vec<bool>,
}

/// An attempted step that failed and was cut.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct CutRecord {
    /// The load parameter or time it aimed at.
    pub t: f64,
    /// Its increment.
    pub increment: f64,
    /// Its Newton iterations.
    #[serde(flatten)]
    pub iterations: Iterations,
    /// Why it failed.
    pub error: String,
}

/// The contact of one accepted step.
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
pub struct ContactRecord {
    /// Total normal force the obstacles (analytic and meshed) exert on the bodies (N).
    pub force: [f64; 3],
    /// The same per obstacle, in the scene's order (N).
    #[serde(default)]
    pub obstacle_forces: Vec<[f64; 3]>,
    /// Vertices with a positive contact force.
    pub active_vertices: usize,
    /// Largest penetration into an obstacle (m, within the contact tolerance).
    pub max_penetration: f64,
    /// Multiplier updates of the step.
    pub iterations: usize,
    /// Pairs of surface primitives (bodies and meshed obstacles) closer than the barrier's
    /// `dhat` (0 without barrier contact).
    #[serde(default)]
    pub pairs: usize,
    /// The smallest distance between two surface primitives within `dhat` (m; `None` when
    /// none is that close or barrier contact is off).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub min_distance: Option<f64>,
    /// For each pair of bodies `(a, b)`, `a < b` in the scene's order, the force body `b`
    /// exerts on body `a` through barrier contact (N; empty with one body or without it).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub body_pair_forces: Vec<[f64; 3]>,
}

/// The summary of a run.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct RunResult {
    /// Scene name.
    pub scene: String,
    /// The variant run, if any.
    pub variant: Option<String>,
    /// Method name.
    pub method: String,
    /// Element name: `"tet4"` or `"tet10"`.
    pub element: String,
    /// Poisson's ratio.
    pub nu: f64,
    /// Mesh vertices (element corners).
    pub vertices: usize,
    /// Mesh nodes: the vertices plus, for `tet10`, the mid-edge nodes.
    pub nodes: usize,
    /// Mesh elements (tets).
    pub tets: usize,
    /// Free displacement DOFs plus pressure/multiplier unknowns.
    pub dofs: usize,
    /// Steps or frames completed (accepted).
    pub steps: usize,
    /// Steps or frames asked for.
    pub steps_requested: usize,
    /// Newton (or dual) iterations over all steps, cut attempts included.
    pub newton_iterations: usize,
    /// Failed attempts retried with half the increment (adaptive stepping, dynamics).
    pub cuts: usize,
    /// Whether every step converged and the run completed.
    pub converged: bool,
    /// Wall time of the run in seconds.
    pub wall_time_s: f64,
    /// Where the time went.
    pub timings: RunTimings,
    /// Whole-body deformed/rest volume minus one, in the last accepted state.
    pub volume_change: f64,
    /// Named probe results on the last accepted state.
    pub probes: BTreeMap<String, f64>,
    /// The most inverted tets in any accepted state.
    pub max_inverted_tets: usize,
    /// Final constraint residual.
    pub constraint_residual: f64,
    /// Why the run stopped early, if it did.
    pub error: Option<String>,
    /// The step that failed, if any.
    pub failed_step: Option<usize>,
    /// The `--set` overrides applied, as `KEY=VALUE`.
    pub overrides: Vec<String>,
    /// What the scene asks for that a user may not mean, and what the run did that the
    /// result alone does not say (an obstacle that touched nothing); left out when empty.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub warnings: Vec<String>,
    /// Per-step records (left out of `--json`; written to the CSV logs).
    #[serde(skip)]
    pub history: Vec<StepRecord>,
    /// The iterations of the failed step, if any (written to `iterations.csv` after the
    /// accepted steps, to show how it failed; its state fields are those of the last
    /// accepted state).
    #[serde(skip)]
    pub failed: Option<StepRecord>,
    /// Whether the scene is dynamic.
    #[serde(skip)]
    pub dynamic: bool,
    /// The obstacles' names in the scene's order, for the per-obstacle columns of
    /// `steps.csv` (`obstacle<i>` unless a meshed obstacle is named).
    #[serde(skip)]
    pub obstacles: Vec<String>,
    /// The pairs of bodies `a_b` (`a` before `b` in the scene's order), for the per-pair
    /// columns of `steps.csv` (empty with one body).
    #[serde(skip)]
    pub body_pairs: Vec<String>,
}

impl StepRecord {
    /// The total potential energy: elastic, constraint and external (no kinetic).
    pub fn potential_energy(&self) -> f64 {
        self.elastic_energy + self.constraint_energy + self.external_energy
    }

    /// The total energy: kinetic plus potential.
    pub fn total_energy(&self) -> f64 {
        self.kinetic_energy + self.potential_energy()
    }
}

impl RunResult {
    /// The JSON object of the command-line contract (non-finite numbers become `null`).
    pub fn to_json(&self) -> serde_json::Value {
        serde_json::to_value(self).expect("a run result always serializes")
    }
}
