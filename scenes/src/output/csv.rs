//! CSV logs: every Newton iteration, and every step.

use super::atomic::write_file;
use crate::error::SceneError;
use crate::record::{Iterations, StepRecord};
use std::fmt::Write;
use std::path::Path;

/// `iterations.csv`: one row per Newton iteration of every attempt of every step (the final
/// residuals of an attempt have empty `step_length`, `backtracks`, `shift` and
/// `hessian_projected`); `attempt` counts the attempts of a step, cut ones (with their `t`)
/// before the accepted one; `volume_error` is the L1 norm of the constraint residual over
/// the rest volume; `hessian_projected` is 1 where the barrier's pair and the cloth's element
/// Hessians were PSD-projected (the exact ones did not factorize), else 0.
pub fn write_iterations_csv(path: &Path, history: &[StepRecord]) -> Result<(), SceneError> {
    let mut out = String::from(
        "step,t,iteration,force_residual,constraint_residual,volume_error,step_length,backtracks,shift,attempt,hessian_projected\n",
    );
    for s in history {
        let attempts = s.cuts.iter().map(|c| (c.t, &c.iterations));
        for (attempt, (t, iterations)) in attempts.chain([(s.t, &s.iterations)]).enumerate() {
            write_iterations(&mut out, iterations, s.step, t, attempt + 1);
        }
    }
    write_file(path, out.as_bytes())
}

/// One row per iteration of one attempt (the last residuals without a step) into `out`.
fn write_iterations(out: &mut String, it: &Iterations, step: usize, t: f64, attempt: usize) {
    let rows = it.force_residuals.iter().zip(&it.constraint_residuals);
    for (i, (f, c)) in rows.enumerate() {
        let (len, back, shift) = match (
            it.step_lengths.get(i),
            it.backtracks.get(i),
            it.shifts.get(i),
        ) {
            (Some(l), Some(b), Some(r)) => (format!("{l:e}"), b.to_string(), format!("{r:e}")),
            _ => Default::default(),
        };
        let projected = match (it.shifts.get(i), it.hessian_projected.get(i)) {
            (Some(_), Some(&p)) => u8::from(p).to_string(),
            (Some(_), None) => "0".to_string(),
            _ => String::new(),
        };
        let v = volume_error(&it.volume_errors, i);
        let _ = writeln!(
            out,
            "{step},{t:e},{i},{f:e},{c:e},{v},{len},{back},{shift},{attempt},{projected}"
        );
    }
}

/// The `i`-th volume error, empty if not recorded (a run resumed from an older checkpoint).
fn volume_error(errors: &[f64], i: usize) -> String {
    errors.get(i).map(|v| format!("{v:e}")).unwrap_or_default()
}

/// `steps.csv`: one row per accepted step or frame; after the fixed columns, the barrier's
/// `contact_pairs` and the step's `pattern_rebuilds`, per obstacle of `obstacles` (their names, in the scene's order) the force
/// it exerts on the bodies as `contact_force_<name>_x,_y,_z`, and per pair of bodies `a_b`
/// of `body_pairs` the force body `b` exerts on body `a` as `contact_force_a_b_x,_y,_z`.
pub fn write_steps_csv(
    path: &Path,
    history: &[StepRecord],
    obstacles: &[String],
    body_pairs: &[String],
) -> Result<(), SceneError> {
    let mut out = String::from(
        "step,t,newton_iterations,converged,force_residual,constraint_residual,volume_change,inverted_tets,kinetic_energy,elastic_energy,external_energy,total_energy,constraint_energy,wall_time_s,contact_force_x,contact_force_y,contact_force_z,active_contacts,max_penetration,contact_iterations,increment,cuts,contact_pairs,pattern_rebuilds",
    );
    for name in obstacles.iter().chain(body_pairs) {
        for axis in ["x", "y", "z"] {
            let _ = write!(out, ",contact_force_{name}_{axis}");
        }
    }
    // Then `pressure_k,enclosed_volume_ratio_k` for every pressure load k.
    let loads = history
        .iter()
        .map(|s| s.pressure_loads.len())
        .max()
        .unwrap_or(0);
    for k in 0..loads {
        let _ = write!(out, ",pressure_{k},enclosed_volume_ratio_{k}");
    }
    out.push('\n');
    for s in history {
        let _ = write!(
            out,
            "{},{:e},{},{},{:e},{:e},{:e},{},{:e},{:e},{:e},{:e},{:e},{:e},{:e},{:e},{:e},{},{:e},{},{:e},{}",
            s.step,
            s.t,
            s.newton_iterations,
            s.converged,
            s.iterations.force_residuals.last().copied().unwrap_or(0.0),
            s.iterations.constraint_residuals.last().copied().unwrap_or(0.0),
            s.volume_change,
            s.inverted_tets,
            s.kinetic_energy,
            s.elastic_energy,
            s.external_energy,
            s.total_energy(),
            s.constraint_energy,
            s.wall_time_s,
            s.contact.force[0],
            s.contact.force[1],
            s.contact.force[2],
            s.contact.active_vertices,
            s.contact.max_penetration,
            s.contact.iterations,
            s.increment,
            s.cuts.len()
        );
        // The row's tail: the pairs, the pattern rebuilds, each obstacle's force, each pair of bodies' force,
        // each pressure load's pressure and volume ratio.
        out.pop();
        let _ = write!(out, ",{},{}", s.contact.pairs, s.pattern_rebuilds);
        let forces = |all: &[[f64; 3]], k: usize| all.get(k).copied().unwrap_or([0.0; 3]);
        for f in (0..obstacles.len())
            .map(|k| forces(&s.contact.obstacle_forces, k))
            .chain((0..body_pairs.len()).map(|k| forces(&s.contact.body_pair_forces, k)))
        {
            let _ = write!(out, ",{:e},{:e},{:e}", f[0], f[1], f[2]);
        }
        for k in 0..loads {
            let r = s.pressure_loads.get(k);
            let (p, v) = r.map_or((f64::NAN, f64::NAN), |r| (r.pressure, r.volume_ratio));
            let _ = write!(out, ",{p:e},{v:e}");
        }
        out.push('\n');
    }
    write_file(path, out.as_bytes())
}

/// `probes.csv`: every probe of the scene at every accepted step: `step`, `t`, `load_level`
/// (the load scale of a load without a curve: `t` in quasi-static stepping, 1 in dynamics)
/// and one column per probe, in name order (NaN where a probe cannot be evaluated).
pub fn write_probes_csv(
    path: &Path,
    history: &[StepRecord],
    dynamic: bool,
) -> Result<(), SceneError> {
    let names: Vec<&String> = history
        .last()
        .map_or(Vec::new(), |s| s.probes.keys().collect());
    let mut out = String::from("step,t,load_level");
    for name in &names {
        let _ = write!(out, ",{name}");
    }
    out.push('\n');
    for s in history {
        let level = if dynamic { 1.0 } else { s.t };
        let _ = write!(out, "{},{:e},{level:e}", s.step, s.t);
        for name in &names {
            let _ = write!(
                out,
                ",{:e}",
                s.probes.get(*name).copied().unwrap_or(f64::NAN)
            );
        }
        out.push('\n');
    }
    write_file(path, out.as_bytes())
}
