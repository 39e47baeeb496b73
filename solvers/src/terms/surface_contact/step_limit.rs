//! Continuous collision detection for the surface-contact term: the earliest time of impact
//! of any pair over a linear motion of all positions (bodies' nodes and obstacle vertices),
//! which limits the line search's step ([`SurfaceContact::max_step`]) and refuses an
//! obstacle motion that would cross a body ([`SurfaceContact::begin_attempt`]).

use super::SurfaceContact;
use crate::error::SolverError;
use crate::problem::schedule::LoadLevel;
use isochor_mesh::contact::{
    contact_candidates, edge_edge_ccd, edge_edge_squared_distance, point_triangle_ccd,
    point_triangle_squared_distance, CcdSettings,
};
use isochor_mesh::Vec3;
use rayon::prelude::*;
use std::sync::atomic::{AtomicU64, Ordering};

/// The fraction of the time of impact a line search may go: the pair keeps a fifth of its
/// gap (IPC takes 0.8 as well).
const TOI_FRACTION: f64 = 0.8;

impl SurfaceContact {
    /// The earliest time of impact in `[0, 1]` of any pair moving linearly from `x0` to `x1`
    /// (all positions, obstacle vertices included), `None` if no pair touches.
    fn earliest_impact(&self, x0: &[Vec3], x1: &[Vec3]) -> Option<f64> {
        let mut swept = contact_candidates(&self.surface, x0, Some(x1), 0.0, self.filter());
        self.drop_rigid_pairs(&mut swept);
        let tris = self.surface.triangles();
        let edges = self.surface.edges();
        // A pair whose two sides move less in all than their distance apart cannot touch
        // over the step (the distance is 1-Lipschitz in each side's motion): no CCD needed.
        let moves = |n: usize| (x1[n] - x0[n]).norm();
        let cannot_touch = |reach: f64, d_sq: f64| reach * reach < d_sq;
        // The earliest impact found so far (as bits: for non-negative doubles their order is
        // the numbers'); every query stops there, so the pairs are searched in parallel and
        // the minimum is the same on any number of threads (a query cut short at `t_max` had
        // no earlier impact).
        let earliest = AtomicU64::new(f64::INFINITY.to_bits());
        let settings = || CcdSettings {
            t_max: f64::from_bits(earliest.load(Ordering::Relaxed)).min(1.0),
            ..self.ccd
        };
        let found = |toi: Option<f64>| {
            if let Some(t) = toi {
                earliest.fetch_min(t.to_bits(), Ordering::Relaxed);
            }
        };
        swept.point_triangle.par_iter().for_each(|&[p, t]| {
            let [a, b, c] = tris[t];
            let reach = moves(p) + moves(a).max(moves(b)).max(moves(c));
            if cannot_touch(
                reach,
                point_triangle_squared_distance(&x0[p], &x0[a], &x0[b], &x0[c]),
            ) {
                return;
            }
            found(point_triangle_ccd(
                &x0[p],
                &x0[a],
                &x0[b],
                &x0[c],
                &x1[p],
                &x1[a],
                &x1[b],
                &x1[c],
                &settings(),
            ));
        });
        swept.edge_edge.par_iter().for_each(|&[i, j]| {
            let ([a0, a1], [b0, b1]) = (edges[i], edges[j]);
            let reach = moves(a0).max(moves(a1)) + moves(b0).max(moves(b1));
            if cannot_touch(
                reach,
                edge_edge_squared_distance(&x0[a0], &x0[a1], &x0[b0], &x0[b1]),
            ) {
                return;
            }
            found(edge_edge_ccd(
                &x0[a0],
                &x0[a1],
                &x0[b0],
                &x0[b1],
                &x1[a0],
                &x1[a1],
                &x1[b0],
                &x1[b1],
                &settings(),
            ));
        });
        let earliest = f64::from_bits(earliest.into_inner());
        earliest.is_finite().then_some(earliest)
    }

    /// The largest step `alpha` in `(0, 1]` along `direction` (three entries per body node)
    /// from `x` that no pair crosses: `0.8` times the earliest time of impact, or 1. The
    /// obstacles stand still within an attempt.
    pub fn max_step(&self, x: &[Vec3], direction: &[f64]) -> f64 {
        let x0 = self.rigid.extend(x);
        let mut x1 = x0.to_vec();
        for (i, p) in x1.iter_mut().take(x.len()).enumerate() {
            *p += Vec3::new(direction[3 * i], direction[3 * i + 1], direction[3 * i + 2]);
        }
        match self.earliest_impact(&x0, &x1) {
            None => 1.0,
            Some(toi) => (TOI_FRACTION * toi).min(1.0),
        }
    }

    /// Places the meshed obstacles at the attempt's `level`, the bodies at the step's start
    /// `x`. Their motion from where the last accepted step left them must cross no body
    /// surface (checked by CCD with the bodies held at `x`): a prescribed motion is not
    /// stopped by the barrier, so a crossing is an [`SolverError::ObstacleCrossing`] and the
    /// stepping cuts the increment. After a restored checkpoint the first motion is not
    /// swept.
    pub fn begin_attempt(&self, x: &[Vec3], level: &LoadLevel) -> Result<(), SolverError> {
        if self.rigid.is_empty() {
            return Ok(());
        }
        let (previous, new) = self.rigid.begin_attempt(level);
        let Some(previous) = previous.filter(|p| *p != new) else {
            return Ok(());
        };
        let x0: Vec<Vec3> = x.iter().chain(&previous).copied().collect();
        let x1: Vec<Vec3> = x.iter().chain(&new).copied().collect();
        if self.earliest_impact(&x0, &x1).is_none() {
            return Ok(());
        }
        // Name the first obstacle that moved.
        let n = x.len();
        let obstacle = (0..self.rigid.obstacles().len())
            .find(|&k| self.rigid.range(k).any(|i| previous[i - n] != new[i - n]))
            .map_or_else(String::new, |k| self.rigid.obstacles()[k].name.clone());
        Err(SolverError::ObstacleCrossing {
            obstacle,
            t: level.t,
        })
    }

    /// Takes the obstacles' placement of the attempt as the accepted step's.
    pub fn accept_step(&self) {
        self.rigid.accept();
    }

    /// Forgets where the obstacles stood (a restored checkpoint's state is not the last
    /// accepted one).
    pub fn forget_placement(&self) {
        self.rigid.forget();
    }
}
