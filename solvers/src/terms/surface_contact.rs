//! Contact between surfaces, and of a surface with itself, as an energy term: the barrier
//! potential of IPC (Li et al. 2020, eq. 5) over the point-triangle and edge-edge pairs of
//! the mesh's boundary within `dhat`, with continuous collision detection limiting every
//! line-search step so that no pair crosses.
//!
//! The pairs come and go: the term keeps the pairs of its current Hessian pattern (those
//! within `dhat` at the latest [`SurfaceContact::update`]) and reports when they change, so
//! the assembly rebuilds its pattern and the solvers their symbolic factorization only then.
//! Energies and gradients away from that state (line-search trials) take the pairs within
//! `dhat` of the trial state itself, so the line search sees every pair.

use super::{block_pattern, EnergyTerm};
use crate::contact::{BarrierPotential, PairForce, StiffnessBounds};
use crate::error::SolverError;
use crate::problem::schedule::LoadLevel;
use isochor_mesh::contact::{
    contact_candidates, edge_edge_ccd, edge_edge_squared_distance, point_triangle_ccd,
    point_triangle_squared_distance, Candidates, CcdSettings, ContactSurface, PairFilter,
};
use isochor_mesh::Vec3;
use std::sync::RwLock;

/// What a scene asks of surface contact.
#[derive(Debug, Clone, PartialEq)]
pub struct SurfaceContactSpec {
    /// The barrier's reach (m).
    pub dhat: f64,
    /// Whether a body's surface may touch itself (pairs sharing a node never count).
    pub self_contact: bool,
    /// The body of each node (contact between bodies only when `self_contact` is off).
    pub node_bodies: Vec<usize>,
}

/// The pairs of the current pattern, the stiffness, and how often the pattern changed.
#[derive(Debug, Clone, Default)]
struct Active {
    candidates: Candidates,
    kappa: f64,
    previous_min_distance: f64,
    rebuilds: usize,
}

/// The barrier contact term of a mesh's boundary surface.
#[derive(Debug)]
pub struct SurfaceContact {
    spec: SurfaceContactSpec,
    surface: ContactSurface,
    rest: Vec<Vec3>,
    bounds: StiffnessBounds,
    bbox_diagonal: f64,
    ccd: CcdSettings,
    active: RwLock<Active>,
}

/// The fraction of the time of impact a line search may go: the pair keeps a fifth of its
/// gap (IPC takes 0.8 as well).
const TOI_FRACTION: f64 = 0.8;

impl SurfaceContact {
    /// The term on `surface` (node indices of `rest`), with stiffness bounds for a body
    /// whose nodes weigh `stiffness_scale` on average (the average nodal mass in dynamics,
    /// an elastic stiffness per node in quasi-static stepping; Li et al. 2020, supplement).
    pub fn new(
        spec: SurfaceContactSpec,
        surface: ContactSurface,
        rest: Vec<Vec3>,
        stiffness_scale: f64,
    ) -> Result<Self, SolverError> {
        if !(spec.dhat.is_finite() && spec.dhat > 0.0) {
            return Err(SolverError::InvalidProblem(format!(
                "contact dhat must be finite and positive, not {}",
                spec.dhat
            )));
        }
        if spec.node_bodies.len() != rest.len() {
            return Err(SolverError::InvalidProblem(format!(
                "{} node bodies for {} nodes",
                spec.node_bodies.len(),
                rest.len()
            )));
        }
        let (lo, hi) = rest
            .iter()
            .fold((rest[0], rest[0]), |(lo, hi), x| (lo.inf(x), hi.sup(x)));
        let bbox_diagonal = (hi - lo).norm();
        let bounds = StiffnessBounds::new(bbox_diagonal, spec.dhat, stiffness_scale);
        Ok(SurfaceContact {
            ccd: CcdSettings::for_scale(0.0, bbox_diagonal),
            active: RwLock::new(Active {
                kappa: bounds.min,
                previous_min_distance: f64::INFINITY,
                ..Active::default()
            }),
            spec,
            surface,
            rest,
            bounds,
            bbox_diagonal,
        })
    }

    fn filter(&self) -> PairFilter<'_> {
        if self.spec.self_contact {
            PairFilter::All
        } else {
            PairFilter::BetweenBodies(&self.spec.node_bodies)
        }
    }

    /// The pairs within `dhat` of each other at `x`.
    fn candidates(&self, x: &[Vec3]) -> Candidates {
        contact_candidates(&self.surface, x, None, self.spec.dhat, self.filter())
    }

    fn potential(&self) -> BarrierPotential {
        BarrierPotential {
            dhat: self.spec.dhat,
            kappa: self.read().kappa,
        }
    }

    fn read(&self) -> std::sync::RwLockReadGuard<'_, Active> {
        self.active.read().unwrap_or_else(|e| e.into_inner())
    }

    /// Takes the pairs within `dhat` at `x` as the pattern's and raises the stiffness while
    /// the smallest distance keeps shrinking near zero (Li et al. 2020, sec. 4.3); returns
    /// whether the pairs changed (the pattern must then be rebuilt).
    pub fn update(&self, x: &[Vec3]) -> bool {
        let candidates = self.candidates(x);
        let min_distance =
            BarrierPotential::min_distance(&self.surface, &candidates, &self.rest, x);
        let mut active = self.active.write().unwrap_or_else(|e| e.into_inner());
        active.kappa = crate::contact::update_barrier_stiffness(
            active.kappa,
            active.previous_min_distance,
            min_distance,
            self.bbox_diagonal,
            &self.bounds,
        );
        active.previous_min_distance = min_distance;
        if candidates == active.candidates {
            return false;
        }
        active.candidates = candidates;
        active.rebuilds += 1;
        true
    }

    /// How many times the pairs (and so the pattern) changed.
    pub fn rebuilds(&self) -> usize {
        self.read().rebuilds
    }

    /// The number of pairs of the current pattern.
    pub fn num_pairs(&self) -> usize {
        self.read().candidates.len()
    }

    /// The pairs within `dhat` at `x` with their normal forces at the current stiffness:
    /// what lagged friction is built from.
    pub fn pair_forces(&self, x: &[Vec3]) -> Vec<PairForce> {
        self.potential()
            .pair_forces(&self.surface, &self.candidates(x), &self.rest, x)
    }

    /// The smallest distance between two surface primitives within `dhat` at `x` (`+inf`
    /// when none is that close).
    pub fn min_distance(&self, x: &[Vec3]) -> f64 {
        BarrierPotential::min_distance(&self.surface, &self.candidates(x), &self.rest, x)
    }

    /// The largest step `alpha` in `(0, 1]` along `direction` (three entries per node) from
    /// `x` that no pair crosses: `0.8` times the earliest time of impact, or 1.
    pub fn max_step(&self, x: &[Vec3], direction: &[f64]) -> f64 {
        let x1: Vec<Vec3> = x
            .iter()
            .enumerate()
            .map(|(i, p)| {
                p + Vec3::new(direction[3 * i], direction[3 * i + 1], direction[3 * i + 2])
            })
            .collect();
        let swept = contact_candidates(&self.surface, x, Some(&x1), 0.0, self.filter());
        let tris = self.surface.triangles();
        let edges = self.surface.edges();
        // A pair whose two sides move less in all than their distance apart cannot touch
        // over the step (the distance is 1-Lipschitz in each side's motion): no CCD needed.
        let moves = |n: usize| (x1[n] - x[n]).norm();
        let cannot_touch = |reach: f64, d_sq: f64| reach * reach < d_sq;
        let pt = swept.point_triangle.iter().filter_map(|&[p, t]| {
            let [a, b, c] = tris[t];
            let reach = moves(p) + moves(a).max(moves(b)).max(moves(c));
            if cannot_touch(
                reach,
                point_triangle_squared_distance(&x[p], &x[a], &x[b], &x[c]),
            ) {
                return None;
            }
            point_triangle_ccd(
                &x[p], &x[a], &x[b], &x[c], &x1[p], &x1[a], &x1[b], &x1[c], &self.ccd,
            )
        });
        let ee = swept.edge_edge.iter().filter_map(|&[i, j]| {
            let ([a0, a1], [b0, b1]) = (edges[i], edges[j]);
            let reach = moves(a0).max(moves(a1)) + moves(b0).max(moves(b1));
            if cannot_touch(
                reach,
                edge_edge_squared_distance(&x[a0], &x[a1], &x[b0], &x[b1]),
            ) {
                return None;
            }
            edge_edge_ccd(
                &x[a0], &x[a1], &x[b0], &x[b1], &x1[a0], &x1[a1], &x1[b0], &x1[b1], &self.ccd,
            )
        });
        match pt
            .chain(ee)
            .fold(None, |m: Option<f64>, t| Some(m.map_or(t, |m| m.min(t))))
        {
            None => 1.0,
            Some(toi) => (TOI_FRACTION * toi).min(1.0),
        }
    }
}

impl EnergyTerm for SurfaceContact {
    fn name(&self) -> &'static str {
        "surface contact"
    }

    fn hessian_pattern(&self) -> Vec<(usize, usize)> {
        let active = self.read();
        BarrierPotential::pair_nodes(&self.surface, &active.candidates, &self.rest)
            .iter()
            .flat_map(|nodes| block_pattern(nodes).collect::<Vec<_>>())
            .collect()
    }

    fn evaluate(
        &self,
        x: &[Vec3],
        _level: &LoadLevel,
        gradient: Option<&mut [f64]>,
        hessian: Option<&mut [f64]>,
    ) -> Result<f64, SolverError> {
        let potential = self.potential();
        // With a Hessian, the pattern's pairs (updated at this state); else the trial's own.
        let (guard, own);
        let candidates = if hessian.is_some() {
            guard = self.read();
            &guard.candidates
        } else {
            own = self.candidates(x);
            &own
        };
        let energy = potential.energy(&self.surface, candidates, &self.rest, x);
        if let Some(g) = gradient {
            potential.add_gradient(&self.surface, candidates, &self.rest, x, g);
        }
        if let Some(h) = hessian {
            let blocks = potential.hessian_blocks(&self.surface, candidates, &self.rest, x);
            for (chunk, (_, block)) in h.chunks_exact_mut(144).zip(&blocks) {
                // Column-major, as `block_pattern` lists the entries.
                chunk.copy_from_slice(block.as_slice());
            }
        }
        Ok(energy)
    }

    fn rounding_scale(&self) -> f64 {
        0.0
    }
}
