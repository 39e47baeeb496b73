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
//!
//! Meshed rigid obstacles ([`MeshObstacle`], added by [`SurfaceContact::with_obstacles`])
//! join the surface: their triangles' vertices follow the bodies' nodes in the term's
//! position vector, placed at the attempt's load level ([`SurfaceContact::begin_attempt`]);
//! they are no degrees of freedom, so their gradient entries and Hessian rows are dropped
//! ([`super::pair_rows`]), and pairs between two obstacle primitives never count.

mod rigid;
mod step_limit;

use super::pair_rows::PairRows;
use super::surface_friction::{FrictionLag, SurfaceFriction};
use super::EnergyTerm;
use crate::contact::{BarrierPotential, HessianBlocks, StiffnessBounds};
use crate::error::SolverError;
use crate::problem::mesh_obstacle::MeshObstacle;
use crate::problem::schedule::LoadLevel;
use isochor_mesh::contact::{
    contact_candidates, intersecting_triangles, Candidates, CcdSettings, ContactSurface, PairFilter,
};
use isochor_mesh::Vec3;
use nalgebra::{SMatrix, SVector};
use rigid::RigidSurfaces;
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

/// What the surface contact is at a state, for outputs.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct SurfaceContactSummary {
    /// The pairs of primitives closer than `dhat`.
    pub pairs_within_dhat: usize,
    /// The smallest distance between two primitives (`+inf` when none is within `dhat`).
    pub min_distance: f64,
    /// The force each meshed obstacle exerts on the bodies, in order: normal (the barrier's)
    /// and tangential (the friction's).
    pub obstacle_forces: Vec<Vec3>,
    /// For each pair of bodies `(a, b)`, `a < b`, in the order `(0, 1), (0, 2), ..., (1, 2),
    /// ...`: the force body `b` exerts on body `a`, normal and tangential (empty with one
    /// body).
    pub body_pair_forces: Vec<Vec3>,
}

/// The pairs of the current pattern, the stiffness, how often the pattern changed, and
/// whether the pair Hessians are exact or PSD-projected.
#[derive(Debug, Clone, Default)]
struct Active {
    candidates: Candidates,
    kappa: f64,
    previous_min_distance: f64,
    rebuilds: usize,
    exact_hessian: bool,
}

/// The barrier contact term of a mesh's boundary surface (and of meshed obstacles).
#[derive(Debug)]
pub struct SurfaceContact {
    /// The scene's ask; `node_bodies` extended over the obstacle vertices (each obstacle a
    /// body of its own).
    spec: SurfaceContactSpec,
    /// The bodies' triangles, then the obstacles'.
    surface: ContactSurface,
    /// The rest positions of the bodies' nodes, then the obstacles' start positions.
    rest: Vec<Vec3>,
    rigid: RigidSurfaces,
    bounds: StiffnessBounds,
    bbox_diagonal: f64,
    ccd: CcdSettings,
    active: RwLock<Active>,
}

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
            rigid: RigidSurfaces::new(Vec::new(), rest.len()),
            spec,
            surface,
            rest,
            bounds,
            bbox_diagonal,
        })
    }

    /// The term with the meshed obstacles `obstacles` joining the bodies' surface (each an
    /// obstacle of its own: no pair between two obstacle primitives). Errors: a bad
    /// obstacle ([`MeshObstacle::validate`]), or one whose triangles intersect a body's at
    /// the start (naming the obstacle and how many triangle pairs).
    pub fn with_obstacles(self, obstacles: Vec<MeshObstacle>) -> Result<Self, SolverError> {
        for o in &obstacles {
            o.validate()?;
        }
        let num_nodes = self.rigid.num_nodes();
        let rigid = RigidSurfaces::new(obstacles, num_nodes);
        let bodies = self.spec.node_bodies[..num_nodes]
            .iter()
            .max()
            .map_or(0, |b| b + 1);
        let mut spec = self.spec;
        spec.node_bodies.truncate(num_nodes);
        for k in 0..rigid.obstacles().len() {
            spec.node_bodies.extend(rigid.range(k).map(|_| bodies + k));
        }
        let body_triangles = self
            .surface
            .triangles()
            .iter()
            .filter(|t| t[0] < num_nodes)
            .count();
        let mut triangles = self.surface.triangles()[..body_triangles].to_vec();
        triangles.extend(rigid.triangles());
        let surface = ContactSurface::from_triangles(triangles);
        let mut rest = self.rest;
        rest.truncate(num_nodes);
        rest.extend(rigid.start());
        let crossing = intersecting_triangles(&surface, &rest)
            .into_iter()
            .filter(|&[i, j]| (i < body_triangles) != (j < body_triangles))
            .map(|[i, j]| spec.node_bodies[surface.triangles()[i.max(j)][0]] - bodies)
            .fold(vec![0usize; rigid.obstacles().len()], |mut count, k| {
                count[k] += 1;
                count
            });
        if let Some(k) = crossing.iter().position(|&c| c > 0) {
            return Err(SolverError::InvalidProblem(format!(
                "meshed obstacle '{}' intersects a body at the start: {} of its triangles cross the body's surface",
                rigid.obstacles()[k].name, crossing[k]
            )));
        }
        Ok(SurfaceContact {
            spec,
            surface,
            rest,
            rigid,
            ..self
        })
    }

    /// The meshed obstacles.
    pub fn obstacles(&self) -> &[MeshObstacle] {
        self.rigid.obstacles()
    }

    /// Where every meshed obstacle's vertices stand now (at the latest attempt's level).
    pub fn placed_obstacles(&self) -> Vec<Vec<Vec3>> {
        self.rigid.current()
    }

    /// Drops the pairs between two obstacle primitives (a primitive's nodes are all a body's
    /// or all an obstacle's).
    fn drop_rigid_pairs(&self, candidates: &mut Candidates) {
        if self.rigid.is_empty() {
            return;
        }
        let n = self.rigid.num_nodes();
        let tris = self.surface.triangles();
        let edges = self.surface.edges();
        candidates
            .point_triangle
            .retain(|&[p, t]| p < n || tris[t][0] < n);
        candidates
            .edge_edge
            .retain(|&[i, j]| edges[i][0] < n || edges[j][0] < n);
    }

    fn filter(&self) -> PairFilter<'_> {
        if self.spec.self_contact {
            PairFilter::All
        } else {
            PairFilter::BetweenBodies(&self.spec.node_bodies)
        }
    }

    /// The pairs within `dhat` of each other at `x` (all positions, obstacles included).
    fn candidates(&self, x: &[Vec3]) -> Candidates {
        let mut candidates =
            contact_candidates(&self.surface, x, None, self.spec.dhat, self.filter());
        self.drop_rigid_pairs(&mut candidates);
        candidates
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
        let x = self.rigid.extend(x);
        let candidates = self.candidates(&x);
        let min_distance =
            BarrierPotential::min_distance(&self.surface, &candidates, &self.rest, &x);
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

    /// What friction freezes at body positions `x` (obstacles where they stand now): the
    /// pairs within `dhat` with their normal forces at the current stiffness, every
    /// position and its body, and the obstacles' motion since they stood at `start_level`
    /// (the step's start).
    pub fn friction_lag(&self, x: &[Vec3], start_level: &LoadLevel) -> FrictionLag {
        let positions = self.rigid.extend(x).into_owned();
        let forces = self.potential().pair_forces(
            &self.surface,
            &self.candidates(&positions),
            &self.rest,
            &positions,
        );
        FrictionLag {
            obstacle_motion: self.rigid.motion_since(start_level),
            bodies: self.spec.node_bodies.clone(),
            positions,
            forces,
        }
    }

    /// The smallest distance between two surface primitives within `dhat` at body
    /// positions `x` (obstacles where they stand now; `+inf` when none is that close).
    pub fn min_distance(&self, x: &[Vec3]) -> f64 {
        let x = self.rigid.extend(x);
        BarrierPotential::min_distance(&self.surface, &self.candidates(&x), &self.rest, &x)
    }

    /// The pairs within `dhat`, the smallest distance, the meshed obstacles' forces and the
    /// forces between bodies at body positions `x`: the barrier's, plus the tangential
    /// forces of `friction` (the surface friction at its latest lag) if given.
    pub fn summary(&self, x: &[Vec3], friction: Option<&SurfaceFriction>) -> SurfaceContactSummary {
        let mut pairs = self.barrier_pair_gradients(x);
        if let Some(friction) = friction {
            pairs.extend(friction.pair_gradients(x));
        }
        let (obstacle_forces, body_pair_forces) = self.forces_of(&pairs);
        SurfaceContactSummary {
            pairs_within_dhat: self.pairs_within_dhat(x),
            min_distance: self.min_distance(x),
            obstacle_forces,
            body_pair_forces,
        }
    }

    /// The number of bodies (their nodes numbered `0..`, the obstacles' after them).
    fn num_bodies(&self) -> usize {
        self.spec.node_bodies[..self.rigid.num_nodes()]
            .iter()
            .max()
            .map_or(0, |b| b + 1)
    }

    /// The barrier's pairs within `dhat` at body positions `x` with their gradients.
    fn barrier_pair_gradients(&self, x: &[Vec3]) -> Vec<([usize; 4], SVector<f64, 12>)> {
        let full = self.rigid.extend(x);
        self.potential()
            .pair_gradients(&self.surface, &self.candidates(&full), &self.rest, &full)
    }

    /// From pairs with the gradients of their potentials: the force each meshed obstacle
    /// exerts on the bodies, and for each pair of bodies `(a, b)`, `a < b` (in the order of
    /// [`SurfaceContactSummary::body_pair_forces`]; empty with one body), the force `b`
    /// exerts on `a`. A pair's force on a body is minus its gradient summed over that
    /// body's nodes (the lower-numbered of its two sides: bodies come before obstacles);
    /// pairs within one body (self-contact) exert none between bodies.
    fn forces_of(&self, pairs: &[([usize; 4], SVector<f64, 12>)]) -> (Vec<Vec3>, Vec<Vec3>) {
        let bodies = self.num_bodies();
        let mut obstacles = vec![Vec3::zeros(); self.rigid.obstacles().len()];
        let mut between = vec![Vec3::zeros(); bodies * bodies.saturating_sub(1) / 2];
        for (nodes, gradient) in pairs {
            let body = |i: usize| self.spec.node_bodies[nodes[i]];
            // Node 0 is on the pair's first side (a point or the first edge), node 3 on the other.
            let (a, b) = (body(0).min(body(3)), body(0).max(body(3)));
            if a == b {
                continue;
            }
            let on_a: Vec3 = (0..4)
                .filter(|&i| body(i) == a)
                .map(|i| -Vec3::new(gradient[3 * i], gradient[3 * i + 1], gradient[3 * i + 2]))
                .sum();
            if b < bodies {
                // The index of pair (a, b), a < b, in row-major upper-triangle order.
                between[a * (2 * bodies - a - 1) / 2 + (b - a - 1)] += on_a;
            } else {
                obstacles[b - bodies] += on_a;
            }
        }
        (obstacles, between)
    }

    /// For each pair of bodies `(a, b)`, `a < b` (in the order of
    /// [`SurfaceContactSummary::body_pair_forces`]), the force the barrier of `b` exerts on
    /// `a` at body positions `x`: minus the gradient of the pairs between them, summed over
    /// `a`'s nodes.
    pub fn body_pair_forces(&self, x: &[Vec3]) -> Vec<Vec3> {
        self.forces_of(&self.barrier_pair_gradients(x)).1
    }

    /// The number of pairs closer than `dhat` at body positions `x`.
    pub fn pairs_within_dhat(&self, x: &[Vec3]) -> usize {
        let x = self.rigid.extend(x);
        self.potential()
            .count_within(&self.surface, &self.candidates(&x), &self.rest, &x)
    }

    /// The force each meshed obstacle's barrier exerts on the bodies at body positions `x`:
    /// minus the barrier's gradient of the pairs with the obstacle, summed over the bodies'
    /// nodes.
    pub fn obstacle_forces(&self, x: &[Vec3]) -> Vec<Vec3> {
        self.forces_of(&self.barrier_pair_gradients(x)).0
    }

    /// Which of a pair's nodes are degrees of freedom (the bodies').
    fn rows(&self) -> PairRows {
        PairRows {
            num_nodes: self.rigid.num_nodes(),
        }
    }
}

impl EnergyTerm for SurfaceContact {
    fn name(&self) -> &'static str {
        "surface contact"
    }

    fn hessian_pattern(&self) -> Vec<(usize, usize)> {
        let active = self.read();
        let rows = self.rows();
        BarrierPotential::pair_nodes(&self.surface, &active.candidates, &self.rest)
            .iter()
            .flat_map(|nodes| rows.pattern(nodes))
            .collect()
    }

    /// As IPC does, every pair's block projected onto the positive semidefinite cone by
    /// default: that keeps Newton's matrix definite but slows its convergence to linear.
    fn project_hessian(&self, projected: bool) -> bool {
        let mut active = self.active.write().unwrap_or_else(|e| e.into_inner());
        active.exact_hessian = !projected;
        !active.candidates.is_empty()
    }

    fn evaluate(
        &self,
        x: &[Vec3],
        _level: &LoadLevel,
        gradient: Option<&mut [f64]>,
        hessian: Option<&mut [f64]>,
    ) -> Result<f64, SolverError> {
        let potential = self.potential();
        let body = x;
        let x = self.rigid.extend(body);
        // With a Hessian, the pattern's pairs (updated at this state); else the trial's own.
        let (guard, own);
        let (candidates, project) = if hessian.is_some() {
            guard = self.read();
            (&guard.candidates, !guard.exact_hessian)
        } else {
            own = self.candidates(&x);
            (&own, true)
        };
        // Each pair's block goes straight into its part of the pattern's values.
        let rows = self.rows();
        let write = |nodes: &[usize; 4], block: &SMatrix<f64, 12, 12>, slot: &mut [f64]| {
            rows.copy_block(nodes, block, slot);
        };
        let blocks = hessian.map(|mut h| {
            let nodes = BarrierPotential::pair_nodes(&self.surface, candidates, &self.rest);
            let mut slots = Vec::with_capacity(nodes.len());
            for n in &nodes {
                let (slot, tail) = h.split_at_mut(rows.block_len(n));
                slots.push(slot);
                h = tail;
            }
            HessianBlocks {
                slots,
                write: &write,
                project,
            }
        });
        let evaluate = |g: Option<&mut [f64]>| {
            potential.evaluate(&self.surface, candidates, &self.rest, &x, g, blocks)
        };
        let energy = match gradient {
            Some(g) if !self.rigid.is_empty() => {
                // The obstacles' entries are dropped: they are no degrees of freedom.
                let mut full = vec![0.0; 3 * x.len()];
                let energy = evaluate(Some(&mut full));
                for (gi, fi) in g.iter_mut().zip(&full[..3 * body.len()]) {
                    *gi += fi;
                }
                energy
            }
            g => evaluate(g),
        };
        Ok(energy)
    }

    fn rounding_scale(&self) -> f64 {
        0.0
    }
}
