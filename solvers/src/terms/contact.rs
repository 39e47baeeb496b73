//! Frictionless contact of mesh vertices against rigid obstacles, as inequality constraints
//! `d_k(x_i) >= 0` (signed distance of vertex `i` to obstacle `k`, positive outside).
//!
//! Sec. 8.2 of Francu et al. 2021 treats contacts as bilateral soft constraints for a frame;
//! sec. 8.3 notes that the dual method can instead project the contact multipliers onto
//! `R_+`, which is the complementarity formulation. This term is that projected dual ascent,
//! augmented (an augmented Lagrangian for inequalities, Nocedal & Wright 17.4): for fixed
//! multipliers `lambda >= 0` and a penalty `rho` per vertex, each pair contributes
//!
//! `psi(d) = (max(0, lambda - rho d)^2 - lambda^2) / (2 rho)`,
//!
//! a C1, piecewise smooth, convex function of `d` whose force on the vertex is
//! `f n = max(0, lambda - rho d) grad d`. The stepping driver minimizes (or makes stationary)
//! the total energy with the multipliers fixed, then projects `lambda <- max(0, lambda - rho d)`,
//! until no multiplier moves by more than `rho` times the penetration tolerance: then no
//! vertex is inside an obstacle by more than the tolerance, every multiplier is non-negative
//! by construction, and a multiplier is positive only where the gap is within the tolerance
//! (complementarity). Because contact is just another energy term, every solver (Newton,
//! saddle-point Newton with zero-compliance constraints, dual ascent) handles it unchanged.
//!
//! The multipliers converge linearly, at a rate set by how the penalty compares with the
//! stiffness the body opposes to a vertex pushed along the normal: a nearly incompressible
//! body or a stiff neighbourhood makes it slow. As in the penalty update of the augmented
//! Lagrangian framework (Nocedal & Wright, Framework 17.3), an update whose largest
//! constraint violation (`|lambda_new - lambda| / rho`) is not below a quarter of the previous
//! one multiplies every penalty by 10 for the rest of the step (at most 10^3 times the base).
//!
//! Friction (optional, per obstacle): lagged smoothed Coulomb friction as in IPC (Li et al.
//! 2020, sec. 5), `mu_k lambda_ik f0(|T^T (u_i - u_k)|)` per pair, with the multiplier
//! `lambda_ik` (the normal force) and the obstacle's tangent plane `T` at the vertex frozen
//! at the last [`Contact::lag_friction`], `u_i` the vertex's displacement over the step and
//! `u_k` the obstacle's own translation over it ([`crate::contact::FrictionPair`]). Without
//! friction the term is exactly the frictionless one.

use super::EnergyTerm;
use crate::contact::{plane_basis, FrictionPair};
use crate::error::SolverError;
use crate::problem::obstacle::Obstacle;
use crate::problem::schedule::LoadLevel;
use isochor_mesh::contact::Derivatives;
use isochor_mesh::Vec3;
use nalgebra::Matrix3;
use std::sync::{RwLock, RwLockWriteGuard};

/// Totals of the contact forces at a state.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct ContactSummary {
    /// Sum of the forces the obstacles exert on the body: normal, plus the friction's
    /// tangential ones.
    pub force: Vec3,
    /// The same per obstacle, in the problem's order (two cylinders squeezing a body push
    /// with opposite forces that cancel in the sum).
    pub obstacle_forces: Vec<Vec3>,
    /// Vertices with a positive contact force.
    pub active_vertices: usize,
    /// Largest penetration `max(0, -d)` over all vertex-obstacle pairs.
    pub max_penetration: f64,
}

/// The multipliers (one per candidate vertex and obstacle, vertex-major) and the load level
/// the obstacles stand at: what rolls a failed step back.
#[derive(Debug, Clone, PartialEq)]
pub struct ContactState {
    multipliers: Vec<f64>,
    level: LoadLevel,
    /// Factor on every penalty, raised within a step while the violation falls too slowly.
    penalty_scale: f64,
    /// Largest violation `|lambda_new - lambda| / rho` of the step's previous update.
    last_violation: Option<f64>,
}

/// An update must cut the violation below this fraction of the previous one...
const SLOW_PROGRESS: f64 = 0.25;
/// ...or the penalties grow by this factor...
const PENALTY_GROWTH: f64 = 10.0;
/// ...up to this multiple of the base penalties.
const MAX_PENALTY_SCALE: f64 = 1e3;

/// Lagged friction forces that moved by less than this fraction of the largest one have
/// settled.
pub(crate) const FRICTION_SETTLED: f64 = 1e-2;

/// Augmented-Lagrangian contact of `vertices` against `obstacles`.
#[derive(Debug)]
pub struct Contact {
    obstacles: Vec<Obstacle>,
    vertices: Vec<usize>,
    /// Penalty `rho` of each candidate vertex (force per length).
    stiffness: Vec<f64>,
    state: RwLock<ContactState>,
    /// The friction coefficient of each obstacle (empty: frictionless) and the slip length.
    friction: Vec<f64>,
    epsv: f64,
    lagged: RwLock<LaggedFriction>,
}

/// The frozen friction of every vertex-obstacle pair (vertex-major, `None` without a normal
/// force), the candidates' start positions and the obstacles' translations over the step.
#[derive(Debug, Default)]
struct LaggedFriction {
    pairs: Vec<Option<FrictionPair>>,
    start: Vec<Vec3>,
    motion: Vec<Vec3>,
}

impl Contact {
    /// Contact of `vertices` (those that may touch, e.g. the boundary surface) against
    /// `obstacles` with per-vertex penalties `stiffness`; multipliers start at 0.
    pub fn new(vertices: Vec<usize>, obstacles: Vec<Obstacle>, stiffness: Vec<f64>) -> Self {
        let pairs = vertices.len() * obstacles.len();
        Contact {
            obstacles,
            vertices,
            stiffness,
            state: RwLock::new(ContactState {
                multipliers: vec![0.0; pairs],
                level: LoadLevel::quasi_static(0.0),
                penalty_scale: 1.0,
                last_violation: None,
            }),
            friction: Vec::new(),
            epsv: 0.0,
            lagged: RwLock::new(LaggedFriction::default()),
        }
    }

    /// Friction with coefficient `friction[k]` against obstacle `k` and slip length `epsv`
    /// (a length; see [`crate::FrictionSpec`]); an error if the count is not the obstacles'.
    pub fn set_friction(&mut self, friction: Vec<f64>, epsv: f64) -> Result<(), SolverError> {
        if friction.len() != self.obstacles.len() {
            return Err(SolverError::InvalidProblem(format!(
                "{} friction coefficients for {} obstacles",
                friction.len(),
                self.obstacles.len()
            )));
        }
        self.friction = if friction.iter().all(|&mu| mu == 0.0) {
            Vec::new()
        } else {
            friction
        };
        self.epsv = epsv;
        Ok(())
    }

    /// Whether any obstacle has friction.
    pub fn has_friction(&self) -> bool {
        !self.friction.is_empty()
    }

    /// Freezes the friction of every pair: its normal force (the current multiplier) and
    /// the obstacle's tangent plane at the vertex's position in `positions` (the obstacles
    /// where the current step's level puts them); the slip measured from `start`, where the
    /// obstacles stood at `start_level`. Returns whether the lagged forces `mu lambda`
    /// settled: none moved by more than 1% of the largest.
    pub fn lag_friction(&self, start: &[Vec3], positions: &[Vec3], start_level: LoadLevel) -> bool {
        if self.friction.is_empty() {
            return true;
        }
        let (multipliers, level) = {
            let state = self.state();
            (state.multipliers.clone(), state.level)
        };
        let m = self.obstacles.len();
        let pairs = self
            .pairs(positions, level)
            .map(|(a, k, _, n, _)| {
                let mu_lambda = self.friction[k] * multipliers[a * m + k];
                (mu_lambda > 0.0 && n.norm() > 0.0).then(|| FrictionPair {
                    basis: plane_basis(&n),
                    weights: [1.0, -1.0, 0.0, 0.0],
                    mu_lambda,
                    epsv: self.epsv,
                })
            })
            .collect::<Vec<Option<FrictionPair>>>();
        let motion = self
            .obstacles
            .iter()
            .map(|o| {
                let curve = o.curve.as_ref();
                o.translate * (level.motion_parameter(curve) - start_level.motion_parameter(curve))
            })
            .collect();
        let force = |p: &Option<FrictionPair>| p.as_ref().map_or(0.0, |p| p.mu_lambda);
        let largest = pairs.iter().map(force).fold(0.0, f64::max);
        let mut lagged = self.lagged.write().unwrap_or_else(|e| e.into_inner());
        let settled = lagged.pairs.len() == pairs.len()
            && lagged
                .pairs
                .iter()
                .zip(&pairs)
                .all(|(a, b)| (force(a) - force(b)).abs() <= FRICTION_SETTLED * largest);
        *lagged = LaggedFriction {
            pairs,
            start: self.vertices.iter().map(|&v| start[v]).collect(),
            motion,
        };
        settled
    }

    fn state(&self) -> RwLockWriteGuard<'_, ContactState> {
        // A poisoned lock only means another thread panicked mid-write of plain floats.
        self.state.write().unwrap_or_else(|e| e.into_inner())
    }

    /// The candidate vertices.
    pub fn vertices(&self) -> &[usize] {
        &self.vertices
    }

    /// Replaces the penalties (e.g. when the time step changes the inertia scale).
    pub fn set_stiffness(&mut self, stiffness: Vec<f64>) {
        self.stiffness = stiffness;
    }

    /// Moves the obstacles to where `level` puts them and starts a step: the penalties
    /// return to their base values.
    pub fn begin_step(&self, level: LoadLevel) {
        let mut state = self.state();
        state.level = level;
        state.penalty_scale = 1.0;
        state.last_violation = None;
    }

    /// The factor on the base penalties the current step has reached.
    pub fn penalty_scale(&self) -> f64 {
        self.state().penalty_scale
    }

    /// The multipliers (normal force magnitudes), vertex-major over the obstacles.
    pub fn multipliers(&self) -> Vec<f64> {
        self.state().multipliers.clone()
    }

    /// Replaces the multipliers (a resumed run's); an error if their number is wrong.
    pub fn set_multipliers(&self, multipliers: Vec<f64>) -> Result<(), SolverError> {
        let mut state = self.state();
        if multipliers.len() != state.multipliers.len() {
            return Err(SolverError::InvalidProblem(format!(
                "{} contact multipliers given for {} vertex-obstacle pairs",
                multipliers.len(),
                state.multipliers.len()
            )));
        }
        state.multipliers = multipliers;
        Ok(())
    }

    /// A copy of the multipliers and the obstacles' level.
    pub fn snapshot(&self) -> ContactState {
        self.state().clone()
    }

    /// Restores a [`Contact::snapshot`].
    pub fn restore(&self, snapshot: ContactState) {
        *self.state() = snapshot;
    }

    /// `(candidate index, obstacle index, d, grad d, Hess d)` of every pair at `x`.
    fn pairs<'a>(
        &'a self,
        x: &'a [Vec3],
        level: LoadLevel,
    ) -> impl Iterator<Item = (usize, usize, f64, Vec3, Matrix3<f64>)> + 'a {
        self.vertices.iter().enumerate().flat_map(move |(a, &v)| {
            self.obstacles.iter().enumerate().map(move |(k, o)| {
                let t = level.motion_parameter(o.curve.as_ref());
                let (d, n, h) = o.distance(&x[v], t);
                (a, k, d, n, h)
            })
        })
    }

    /// The projected multiplier update `lambda <- max(0, lambda - rho d)` at the solution `x`
    /// of the current subproblem; returns whether every multiplier moved by at most
    /// `rho * tolerance` (then penetrations are within `tolerance` and complementarity holds
    /// to it). An update that leaves the violation above a quarter of the previous one raises
    /// the penalties for the next subproblem (module docs).
    pub fn update(&self, x: &[Vec3], tolerance: f64) -> bool {
        let mut state = self.state();
        let level = state.level;
        let scale = state.penalty_scale;
        let m = self.obstacles.len();
        let mut converged = true;
        let mut violation = 0.0f64;
        for (a, k, d, _, _) in self.pairs(x, level) {
            let rho = scale * self.stiffness[a];
            let lambda = &mut state.multipliers[a * m + k];
            let next = (*lambda - rho * d).max(0.0);
            converged &= (next - *lambda).abs() <= rho * tolerance;
            violation = violation.max((next - *lambda).abs() / rho);
            *lambda = next;
        }
        if !converged
            && state
                .last_violation
                .is_some_and(|v| violation > SLOW_PROGRESS * v)
        {
            state.penalty_scale = (scale * PENALTY_GROWTH).min(MAX_PENALTY_SCALE);
        }
        state.last_violation = Some(violation);
        converged
    }

    /// Contact force `lambda grad d` on every mesh vertex (`num_vertices` entries) at `x`.
    /// After a converged [`Contact::update`] the multipliers are exactly the forces of the
    /// subproblem just solved, so these balance the other forces at `x`.
    pub fn vertex_forces(&self, x: &[Vec3]) -> Vec<Vec3> {
        let state = self.state();
        let m = self.obstacles.len();
        let mut forces = vec![Vec3::zeros(); x.len()];
        for (a, k, _, n, _) in self.pairs(x, state.level) {
            forces[self.vertices[a]] += state.multipliers[a * m + k] * n;
        }
        forces
    }

    /// Total force (the normal forces of the multipliers, as [`Contact::vertex_forces`],
    /// plus the lagged friction's tangential forces, minus its gradient), active vertices (a
    /// positive multiplier) and largest penetration at `x`.
    pub fn summary(&self, x: &[Vec3]) -> ContactSummary {
        let state = self.state();
        let m = self.obstacles.len();
        let mut summary = ContactSummary {
            obstacle_forces: vec![Vec3::zeros(); m],
            ..ContactSummary::default()
        };
        let mut active = vec![false; self.vertices.len()];
        for (a, k, d, n, _) in self.pairs(x, state.level) {
            let f = state.multipliers[a * m + k];
            summary.force += f * n;
            summary.obstacle_forces[k] += f * n;
            active[a] |= f > 0.0;
            summary.max_penetration = summary.max_penetration.max(-d);
        }
        self.for_each_friction_pair(x, |_, k, d| {
            let f = -Vec3::new(d.gradient[0], d.gradient[1], d.gradient[2]);
            summary.force += f;
            summary.obstacle_forces[k] += f;
        });
        summary.active_vertices = active.iter().filter(|&&b| b).count();
        summary
    }
}

impl Contact {
    /// Calls `each(a, k, derivatives)` for every frozen friction pair of candidate vertex `a`
    /// and obstacle `k` with the derivatives of its potential at `x` (the vertex's
    /// coordinates first).
    fn for_each_friction_pair(
        &self,
        x: &[Vec3],
        mut each: impl FnMut(usize, usize, &Derivatives<12>),
    ) {
        let lagged = self.lagged.read().unwrap_or_else(|e| e.into_inner());
        let m = self.obstacles.len();
        for (index, pair) in lagged.pairs.iter().enumerate() {
            let Some(pair) = pair else { continue };
            let (a, k) = (index / m, index % m);
            let u = [
                x[self.vertices[a]] - lagged.start[a],
                lagged.motion[k],
                Vec3::zeros(),
                Vec3::zeros(),
            ];
            each(a, k, &pair.derivatives(&u));
        }
    }

    /// The lagged friction at `x`: its energy, gradient and Hessian (the vertex's `3 x 3`
    /// block of the pair's, positive semidefinite) added in.
    fn add_friction(
        &self,
        x: &[Vec3],
        mut gradient: Option<&mut [f64]>,
        mut hessian: Option<&mut [f64]>,
    ) -> f64 {
        let mut energy = 0.0;
        self.for_each_friction_pair(x, |a, _, d| {
            energy += d.value;
            let v = self.vertices[a];
            if let Some(g) = gradient.as_deref_mut() {
                for c in 0..3 {
                    g[3 * v + c] += d.gradient[c];
                }
            }
            if let Some(h) = hessian.as_deref_mut() {
                for c in 0..3 {
                    for r in 0..3 {
                        h[9 * a + 3 * c + r] += d.hessian[(r, c)];
                    }
                }
            }
        });
        energy
    }
}

impl EnergyTerm for Contact {
    fn name(&self) -> &'static str {
        "contact"
    }

    /// One 3x3 block per candidate vertex (the obstacles' contributions summed), column-major.
    fn hessian_pattern(&self) -> Vec<(usize, usize)> {
        self.vertices
            .iter()
            .flat_map(|&v| (0..3).flat_map(move |c| (0..3).map(move |r| (3 * v + r, 3 * v + c))))
            .collect()
    }

    /// `sum psi(d)`; gradient `-f grad d` and Hessian `rho grad d grad d^T - f Hess d` with
    /// `f = max(0, lambda - rho d)`, on pairs with `lambda - rho d >= 0` (at the kink the
    /// active branch is taken, so a body resting exactly on an obstacle is supported from
    /// the first Newton step).
    fn evaluate(
        &self,
        x: &[Vec3],
        _level: &LoadLevel,
        mut gradient: Option<&mut [f64]>,
        mut hessian: Option<&mut [f64]>,
    ) -> Result<f64, SolverError> {
        let (multipliers, level, scale) = {
            let state = self.state();
            (state.multipliers.clone(), state.level, state.penalty_scale)
        };
        if let Some(h) = hessian.as_deref_mut() {
            h.fill(0.0);
        }
        let m = self.obstacles.len();
        let mut energy = 0.0;
        for (a, k, d, n, hd) in self.pairs(x, level) {
            let rho = scale * self.stiffness[a];
            let lambda = multipliers[a * m + k];
            let s = lambda - rho * d;
            let f = s.max(0.0);
            energy += (f * f - lambda * lambda) / (2.0 * rho);
            if s < 0.0 {
                continue;
            }
            let v = self.vertices[a];
            if let Some(g) = gradient.as_deref_mut() {
                for c in 0..3 {
                    g[3 * v + c] -= f * n[c];
                }
            }
            if let Some(h) = hessian.as_deref_mut() {
                let block = rho * n * n.transpose() - f * hd;
                for c in 0..3 {
                    for r in 0..3 {
                        h[9 * a + 3 * c + r] += block[(r, c)];
                    }
                }
            }
        }
        if !self.friction.is_empty() {
            energy += self.add_friction(x, gradient, hessian);
        }
        if !energy.is_finite() {
            return Err(SolverError::NonFinite("the contact energy"));
        }
        Ok(energy)
    }
}
