//! The records of a run's steps, from the solver's reports.

use crate::record::{ContactRecord, CutRecord, Iterations, StepRecord};
use isochor_mesh::ElementMesh;
use isochor_solvers::{Energies, IterationReport, State, StepReport, SurfaceContactSummary};

/// The iterations of `report`.
fn iterations(report: &StepReport) -> Iterations {
    let history = |each: fn(&IterationReport) -> f64, last: f64| {
        report.iterations.iter().map(each).chain([last]).collect()
    };
    let each = report.iterations.iter();
    Iterations {
        force_residuals: history(|i| i.force_residual, report.force_residual),
        constraint_residuals: history(|i| i.constraint_residual, report.constraint_residual),
        volume_errors: history(|i| i.volume_error, report.volume_error),
        step_lengths: each.clone().map(|i| i.step_length).collect(),
        backtracks: each.clone().map(|i| i.backtracks).collect(),
        shifts: each.clone().map(|i| i.regularization).collect(),
        hessian_projected: each.map(|i| i.hessian_projected).collect(),
    }
}

/// The record of a failed attempt that was retried with a smaller increment.
pub(super) fn cut_record(report: &StepReport) -> CutRecord {
    CutRecord {
        t: report.t,
        increment: report.increment,
        iterations: iterations(report),
        error: report.failure.clone().unwrap_or_default(),
    }
}

/// The contact record of a step: the analytic obstacles' forces from `report`, the meshed
/// ones' from `surface` (the barrier contact at the state, if on), merged in the scene's
/// order (`meshed[i]`: whether obstacle `i` is meshed; zeros for a meshed obstacle without
/// a summary), and their total.
fn contact_record(
    report: &StepReport,
    surface: Option<&SurfaceContactSummary>,
    meshed: &[bool],
) -> ContactRecord {
    let mut analytic = report.contact.obstacle_forces.iter();
    let mut barrier = surface.map(|s| s.obstacle_forces.iter());
    let obstacle_forces: Vec<[f64; 3]> = meshed
        .iter()
        .map(|&m| {
            let next = if m {
                barrier.as_mut().and_then(Iterator::next)
            } else {
                analytic.next()
            };
            next.map_or([0.0; 3], |&f| f.into())
        })
        .collect();
    let meshed_total = surface.map_or(isochor_mesh::Vec3::zeros(), |s| {
        s.obstacle_forces.iter().sum()
    });
    ContactRecord {
        force: (report.contact.force + meshed_total).into(),
        obstacle_forces,
        active_vertices: report.contact.active_vertices,
        max_penetration: report.contact.max_penetration,
        iterations: report.contact_iterations,
        pairs: surface.map_or(0, |s| s.pairs_within_dhat),
        min_distance: surface.map(|s| s.min_distance).filter(|d| d.is_finite()),
        body_pair_forces: surface.map_or_else(Vec::new, |s| {
            s.body_pair_forces.iter().map(|&f| f.into()).collect()
        }),
    }
}

/// The record of one step: its iterations and the state it ended in (`surface` and
/// `meshed` as in [`contact_record`]).
pub(super) fn record(
    mesh: &ElementMesh,
    state: &State,
    report: &StepReport,
    inverted_tets: usize,
    energies: Energies,
    surface: Option<&SurfaceContactSummary>,
    meshed: &[bool],
) -> StepRecord {
    StepRecord {
        step: report.step,
        t: report.t,
        increment: report.increment,
        cuts: Vec::new(),
        newton_iterations: report.newton_iterations(),
        converged: report.converged,
        iterations: iterations(report),
        volume_change: mesh.total_volume_at(&state.positions) / mesh.rest_volume() - 1.0,
        inverted_tets,
        kinetic_energy: energies.kinetic,
        elastic_energy: energies.elastic,
        constraint_energy: energies.constraint,
        external_energy: energies.external,
        wall_time_s: report.wall_time.as_secs_f64(),
        pattern_rebuilds: report.pattern_rebuilds,
        tracked_probe: None,
        contact: contact_record(report, surface, meshed),
        pressure_loads: Vec::new(),
        probes: Default::default(),
    }
}
