//! Lagged smoothed Coulomb friction between surfaces (Li et al. 2020, sec. 5, eq. 15) as an
//! energy term: `D(x) = sum_k mu_k lambda_k f0(|T_k^T Gamma_k (x - x_start)|)` over the
//! barrier pairs within `dhat` at the lagged state, each with its normal force `lambda_k`,
//! tangent basis `T_k` and closest-point weights `Gamma_k` frozen there
//! ([`crate::contact::FrictionPair`]); `x_start` is the step's start, so the slip is the
//! step's displacement increment (quasi-static) or velocity times time step (dynamics).
//!
//! A pair may have a meshed obstacle's vertices among its nodes (numbered after the bodies'
//! nodes, each obstacle one more body): their motion over the step is prescribed, so the slip
//! is relative (a moving plate drags a block along), and their rows are no degrees of
//! freedom ([`super::pair_rows`]).
//!
//! The stepping driver lags the pairs at the step's start, solves, and lags them again at
//! the solution until their forces settle (a bounded number of times). The pairs, and so the
//! Hessian pattern, change only at those lags.

use super::contact::FRICTION_SETTLED;
use super::pair_rows::PairRows;
use super::EnergyTerm;
use crate::contact::{FrictionPair, PairForce};
use crate::error::SolverError;
use crate::problem::friction::SurfaceFrictionSpec;
use crate::problem::schedule::LoadLevel;
use isochor_mesh::Vec3;
use nalgebra::SVector;
use rayon::prelude::*;
use std::sync::{RwLock, RwLockReadGuard};

/// What the barrier hands friction at a lagged state
/// ([`super::SurfaceContact::friction_lag`]).
#[derive(Debug, Clone, PartialEq)]
pub struct FrictionLag {
    /// Every position: the bodies' nodes, then the meshed obstacles' vertices where they
    /// stand.
    pub positions: Vec<Vec3>,
    /// The body of every position (meshed obstacle `k` after `B` bodies is body `B + k`).
    pub bodies: Vec<usize>,
    /// The motion of every obstacle vertex over the step (from where it stood at the step's
    /// start), in the order of `positions`.
    pub obstacle_motion: Vec<Vec3>,
    /// The barrier's pairs within `dhat` with their normal forces.
    pub forces: Vec<PairForce>,
}

/// The frozen pairs, the step's start positions and the obstacles' motion over the step.
#[derive(Debug, Default)]
struct Lagged {
    start: Vec<Vec3>,
    obstacle_motion: Vec<Vec3>,
    pairs: Vec<([usize; 4], FrictionPair)>,
    /// Whether the pairs' nodes changed since the pattern was last taken.
    pattern_changed: bool,
}

/// Friction between the surfaces of a mesh.
#[derive(Debug)]
pub struct SurfaceFriction {
    spec: SurfaceFrictionSpec,
    epsv: f64,
    lagged: RwLock<Lagged>,
}

impl Lagged {
    /// The pairs' degrees of freedom: the bodies' nodes, those of the start positions.
    fn rows(&self) -> PairRows {
        PairRows {
            num_nodes: self.start.len(),
        }
    }

    /// The motion over the step of a pair's `nodes` at body positions `x`: a body node's
    /// displacement from the step's start, an obstacle vertex's prescribed motion.
    fn motion(&self, nodes: &[usize; 4], x: &[Vec3]) -> [Vec3; 4] {
        nodes.map(|n| match n.checked_sub(self.start.len()) {
            None => x[n] - self.start[n],
            Some(vertex) => self.obstacle_motion[vertex],
        })
    }
}

impl SurfaceFriction {
    /// Friction of `spec` with slip length `epsv`, without pairs until the first lag.
    pub fn new(spec: SurfaceFrictionSpec, epsv: f64) -> Self {
        SurfaceFriction {
            spec,
            epsv,
            lagged: RwLock::new(Lagged::default()),
        }
    }

    fn read(&self) -> RwLockReadGuard<'_, Lagged> {
        self.lagged.read().unwrap_or_else(|e| e.into_inner())
    }

    /// Freezes the pairs of `lag` (the barrier's at the lagged state), the slip of the
    /// bodies' nodes measured from their positions `start`; returns whether the lagged
    /// forces `mu lambda` settled: the same pairs, none moved by more than 1% of the
    /// largest.
    pub fn lag(&self, start: &[Vec3], lag: &FrictionLag) -> bool {
        let bodies = &lag.bodies;
        let pairs: Vec<([usize; 4], FrictionPair)> = lag
            .forces
            .iter()
            .filter_map(|f| {
                // Side one is node 0 (the point, or the first edge), side two node 3.
                let mu = self
                    .spec
                    .coefficient(bodies[f.nodes[0]], bodies[f.nodes[3]]);
                (mu > 0.0).then(|| {
                    let y = f.nodes.map(|n| lag.positions[n]);
                    (
                        f.nodes,
                        FrictionPair::new(f.kind, &y, mu * f.lambda, self.epsv),
                    )
                })
            })
            .collect();
        let mut lagged = self.lagged.write().unwrap_or_else(|e| e.into_inner());
        let same_nodes = pairs.len() == lagged.pairs.len()
            && pairs.iter().zip(&lagged.pairs).all(|(a, b)| a.0 == b.0);
        let largest = pairs.iter().map(|p| p.1.mu_lambda).fold(0.0, f64::max);
        let settled = same_nodes
            && pairs
                .iter()
                .zip(&lagged.pairs)
                .all(|(a, b)| (a.1.mu_lambda - b.1.mu_lambda).abs() <= FRICTION_SETTLED * largest);
        lagged.pattern_changed |= !same_nodes;
        lagged.pairs = pairs;
        lagged.start = start.to_vec();
        lagged.obstacle_motion = lag.obstacle_motion.clone();
        settled
    }

    /// Whether the pairs' nodes changed since the last call (the pattern must be rebuilt).
    pub fn take_pattern_change(&self) -> bool {
        let mut lagged = self.lagged.write().unwrap_or_else(|e| e.into_inner());
        std::mem::take(&mut lagged.pattern_changed)
    }

    /// The number of frozen pairs.
    pub fn num_pairs(&self) -> usize {
        self.read().pairs.len()
    }

    /// Every frozen pair with the gradient of its potential at body positions `x` on its
    /// four nodes (12 coordinates, node-major; an obstacle vertex's entries are those of its
    /// prescribed motion): minus it is the friction force on each node.
    pub fn pair_gradients(&self, x: &[Vec3]) -> Vec<([usize; 4], SVector<f64, 12>)> {
        let lagged = self.read();
        lagged
            .pairs
            .iter()
            .map(|(nodes, pair)| (*nodes, pair.derivatives(&lagged.motion(nodes, x)).gradient))
            .collect()
    }
}

impl EnergyTerm for SurfaceFriction {
    fn name(&self) -> &'static str {
        "surface friction"
    }

    fn hessian_pattern(&self) -> Vec<(usize, usize)> {
        let lagged = self.read();
        let rows = lagged.rows();
        lagged
            .pairs
            .iter()
            .flat_map(|(nodes, _)| rows.pattern(nodes))
            .collect()
    }

    /// `D(x)`, its gradient and its Hessian, each pair's block positive semidefinite by
    /// construction ([`FrictionPair::derivatives`]).
    fn evaluate(
        &self,
        x: &[Vec3],
        _level: &LoadLevel,
        gradient: Option<&mut [f64]>,
        hessian: Option<&mut [f64]>,
    ) -> Result<f64, SolverError> {
        let lagged = self.read();
        let rows = lagged.rows();
        // Each pair's values in parallel (rayon), summed and scattered in pair order: the
        // same bits on any number of threads.
        let energy: f64 = if gradient.is_none() && hessian.is_none() {
            let energies: Vec<f64> = lagged
                .pairs
                .par_iter()
                .map(|(nodes, pair)| pair.potential(&lagged.motion(nodes, x)))
                .collect();
            energies.iter().sum()
        } else {
            // Each pair's slot of the Hessian values, in pair order.
            let mut slots: Vec<Option<&mut [f64]>> = Vec::with_capacity(lagged.pairs.len());
            match hessian {
                Some(mut h) => {
                    for (nodes, _) in &lagged.pairs {
                        let (slot, tail) = h.split_at_mut(rows.block_len(nodes));
                        slots.push(Some(slot));
                        h = tail;
                    }
                }
                None => slots.resize_with(lagged.pairs.len(), || None),
            }
            let shares: Vec<(f64, SVector<f64, 12>)> = lagged
                .pairs
                .par_iter()
                .zip(slots)
                .map(|((nodes, pair), slot)| {
                    let d = pair.derivatives(&lagged.motion(nodes, x));
                    if let Some(slot) = slot {
                        rows.copy_block(nodes, &d.hessian, slot);
                    }
                    (d.value, d.gradient)
                })
                .collect();
            if let Some(g) = gradient {
                for ((nodes, _), (_, local)) in lagged.pairs.iter().zip(&shares) {
                    rows.scatter(nodes, local.as_slice(), g);
                }
            }
            shares.iter().map(|s| s.0).sum()
        };
        if !energy.is_finite() {
            return Err(SolverError::NonFinite("the friction energy"));
        }
        Ok(energy)
    }
}
