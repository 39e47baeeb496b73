//! The barrier potential of IPC over a set of candidate pairs (Li et al. 2020, eq. 5 and
//! 12): `kappa sum_PT b(d) + kappa sum_EE e_k b(d)`, each pair at its closest-feature
//! distance, edge-edge pairs mollified; with its gradient and the PSD-projected Hessian of
//! every pair, on the global vector of node positions (three coordinates per node). Pairs
//! are IPC's: a point-edge distance reached from two triangles counts twice. The pairs are
//! evaluated in parallel (rayon), each on its own, and summed or scattered in pair order,
//! so every value has the same bits on any number of threads.

use super::barrier::{barrier, barrier_first_derivative, barrier_second_derivative, normal_force};
use isochor_energies::project_to_psd;
use isochor_mesh::contact::{
    edge_edge_distance_kind, edge_edge_mollifier, edge_edge_mollifier_derivatives,
    edge_edge_mollifier_threshold, point_triangle_distance_kind, Candidates, ContactSurface,
    Derivatives, DistanceKind,
};
use isochor_mesh::Vec3;
use nalgebra::{SMatrix, SVector};
use rayon::prelude::*;

/// The barrier potential with reach `dhat` (a distance) and stiffness `kappa`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BarrierPotential {
    /// The distance below which the barrier acts.
    pub dhat: f64,
    /// The barrier stiffness.
    pub kappa: f64,
}

/// A pair within `dhat` with the normal force it carries: what lagged friction freezes (Li
/// et al. 2020, sec. 5).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PairForce {
    /// The pair's four nodes (point then triangle, or edge then edge).
    pub nodes: [usize; 4],
    /// Its closest features at the state it was taken at.
    pub kind: DistanceKind,
    /// The magnitude of its contact force, `-d(kappa e b)/d(distance)` (edge-edge pairs
    /// with their mollifier `e` held fixed, as IPC does).
    pub lambda: f64,
}

/// A pair of the candidate set: its four nodes, and for edge-edge pairs the mollifier
/// threshold at rest.
struct Pair {
    nodes: [usize; 4],
    eps_x: Option<f64>,
}

/// The candidate set as indexed pairs: the point-triangle pairs, then the edge-edge pairs.
#[derive(Clone, Copy)]
struct Pairs<'a> {
    surface: &'a ContactSurface,
    candidates: &'a Candidates,
    rest: &'a [Vec3],
}

impl<'a> Pairs<'a> {
    /// The pairs of `candidates` on `surface` at rest positions `rest`.
    fn new(surface: &'a ContactSurface, candidates: &'a Candidates, rest: &'a [Vec3]) -> Self {
        Pairs {
            surface,
            candidates,
            rest,
        }
    }

    /// Pair `i`.
    fn get(&self, i: usize) -> Pair {
        let pt = &self.candidates.point_triangle;
        if let Some(&[p, t]) = pt.get(i) {
            let tri = self.surface.triangles()[t];
            return Pair {
                nodes: [p, tri[0], tri[1], tri[2]],
                eps_x: None,
            };
        }
        let edges = self.surface.edges();
        let [i, j] = self.candidates.edge_edge[i - pt.len()];
        let nodes = [edges[i][0], edges[i][1], edges[j][0], edges[j][1]];
        let r = nodes.map(|n| self.rest[n]);
        Pair {
            nodes,
            eps_x: Some(edge_edge_mollifier_threshold(&r[0], &r[1], &r[2], &r[3])),
        }
    }

    /// `f` of every pair with its nodes' positions in `x` and its own input (`inputs`: one
    /// per pair, in pair order), in parallel (rayon), the results in pair order: each pair's
    /// result computed on its own, so the same bits on any number of threads (callers sum
    /// and scatter them in that order).
    fn map_with<S: Send, T: Send>(
        &self,
        x: &[Vec3],
        inputs: Vec<S>,
        f: impl Fn(&Pair, &[Vec3; 4], S) -> T + Sync,
    ) -> Vec<T> {
        assert_eq!(inputs.len(), self.candidates.len(), "one input per pair");
        inputs
            .into_par_iter()
            .enumerate()
            .map(|(i, input)| {
                let pair = self.get(i);
                f(&pair, &pair.nodes.map(|n| x[n]), input)
            })
            .collect()
    }

    /// [`Self::map_with`] without inputs.
    fn map<T: Send>(&self, x: &[Vec3], f: impl Fn(&Pair, &[Vec3; 4]) -> T + Sync) -> Vec<T> {
        let inputs = vec![(); self.candidates.len()];
        self.map_with(x, inputs, |pair, y, ()| f(pair, y))
    }
}

/// Writes a pair's `12 x 12` block (its nodes, the block) into the pair's slot.
pub type WriteBlock<'a> = dyn Fn(&[usize; 4], &SMatrix<f64, 12, 12>, &mut [f64]) + Sync + 'a;

/// Where [`BarrierPotential::evaluate`] puts the Hessian block of each pair (zero beyond
/// `dhat`): `write(nodes, block, slot)` into the pair's own slot, one slot per candidate
/// pair in the candidates' order (point-triangle pairs, then edge-edge pairs).
pub struct HessianBlocks<'a> {
    /// Each pair's part of the output.
    pub slots: Vec<&'a mut [f64]>,
    /// Writes a pair's block into its slot.
    pub write: &'a WriteBlock<'a>,
    /// Whether each block is projected onto the positive semidefinite cone (IPC's choice)
    /// or left exact.
    pub project: bool,
}

impl Pair {
    fn kind(&self, x: &[Vec3; 4]) -> DistanceKind {
        match self.eps_x {
            None => point_triangle_distance_kind(&x[0], &x[1], &x[2], &x[3]),
            Some(_) => edge_edge_distance_kind(&x[0], &x[1], &x[2], &x[3]),
        }
    }
}

impl BarrierPotential {
    fn dhat_sq(&self) -> f64 {
        self.dhat * self.dhat
    }

    /// The potential at node positions `x` (`rest`: the rest positions, for the mollifier);
    /// `+inf` when a pair touches.
    pub fn energy(
        &self,
        surface: &ContactSurface,
        candidates: &Candidates,
        rest: &[Vec3],
        x: &[Vec3],
    ) -> f64 {
        self.evaluate(surface, candidates, rest, x, None, None)
    }

    /// The potential at `x` (as [`Self::energy`]), with its gradient added to `gradient`
    /// (three entries per node) when given and every pair's Hessian block (PSD-projected
    /// or exact, as `hessian` asks) written by `hessian` when given (the blocks' nodes depend on the candidates only, so
    /// a fixed candidate set has a fixed sparsity pattern). One parallel pass over the
    /// pairs, each written into its own slot, the energies summed and the gradients
    /// scattered in pair order: the same bits on any number of threads.
    pub fn evaluate(
        &self,
        surface: &ContactSurface,
        candidates: &Candidates,
        rest: &[Vec3],
        x: &[Vec3],
        gradient: Option<&mut [f64]>,
        hessian: Option<HessianBlocks<'_>>,
    ) -> f64 {
        let pairs = Pairs::new(surface, candidates, rest);
        let derivatives = gradient.is_some() || hessian.is_some();
        let (slots, write, project) = match hessian {
            Some(h) => (
                h.slots.into_iter().map(Some).collect(),
                Some(h.write),
                h.project,
            ),
            None => ((0..candidates.len()).map(|_| None).collect(), None, true),
        };
        let shares = pairs.map_with(x, slots, |pair, y, slot| {
            let energy = self.pair_energy(pair, y);
            if !derivatives {
                return (pair.nodes, energy, None);
            }
            let local = self.local(pair, y);
            if let (Some(slot), Some(write)) = (slot, write) {
                let block = match &local {
                    None => SMatrix::zeros(),
                    Some(l) if project => project_to_psd(&l.hessian),
                    Some(l) => l.hessian,
                };
                write(&pair.nodes, &block, slot);
            }
            (pair.nodes, energy, local.map(|l| l.gradient))
        });
        if let Some(g) = gradient {
            for (nodes, _, local) in &shares {
                if let Some(local) = local {
                    scatter(nodes, local, g);
                }
            }
        }
        shares.iter().map(|s| s.1).sum()
    }

    /// The pair's potential at its nodes' positions `y`.
    fn pair_energy(&self, pair: &Pair, y: &[Vec3; 4]) -> f64 {
        let b = barrier(pair.kind(y).squared_distance(y), self.dhat_sq());
        let mollifier = pair.eps_x.map_or(1.0, |eps| edge_edge_mollifier(y, eps));
        // A zero mollifier (parallel edges) times a zero barrier (beyond dhat) is 0.
        if b == 0.0 {
            0.0
        } else {
            self.kappa * mollifier * b
        }
    }

    /// The pair's potential with its gradient and (unprojected) Hessian, `None` beyond
    /// `dhat`.
    fn local(&self, pair: &Pair, y: &[Vec3; 4]) -> Option<Derivatives<12>> {
        let d = pair.kind(y).derivatives(y);
        if d.value >= self.dhat_sq() {
            return None;
        }
        let (b, b1, b2) = (
            barrier(d.value, self.dhat_sq()),
            barrier_first_derivative(d.value, self.dhat_sq()),
            barrier_second_derivative(d.value, self.dhat_sq()),
        );
        // The barrier of the distance: b, b' grad d, b'' grad d grad d^T + b' hess d.
        let barrier = Derivatives {
            value: b,
            gradient: d.gradient * b1,
            hessian: d.gradient * d.gradient.transpose() * b2 + d.hessian * b1,
        };
        let local = match pair.eps_x {
            None => barrier,
            Some(eps) => {
                // The product rule with the mollifier m.
                let m = edge_edge_mollifier_derivatives(y, eps);
                let cross = m.gradient * barrier.gradient.transpose();
                Derivatives {
                    value: m.value * barrier.value,
                    gradient: barrier.gradient * m.value + m.gradient * barrier.value,
                    hessian: barrier.hessian * m.value
                        + m.hessian * barrier.value
                        + cross
                        + cross.transpose(),
                }
            }
        };
        Some(Derivatives {
            value: self.kappa * local.value,
            gradient: local.gradient * self.kappa,
            hessian: local.hessian * self.kappa,
        })
    }

    /// Adds the gradient of the potential at `x` to `gradient` (three entries per node).
    pub fn add_gradient(
        &self,
        surface: &ContactSurface,
        candidates: &Candidates,
        rest: &[Vec3],
        x: &[Vec3],
        gradient: &mut [f64],
    ) {
        self.evaluate(surface, candidates, rest, x, Some(gradient), None);
    }

    /// Every candidate pair within `dhat` at `x` with the gradient of its potential on its
    /// four nodes (12 coordinates, node-major), in the candidates' order.
    pub fn pair_gradients(
        &self,
        surface: &ContactSurface,
        candidates: &Candidates,
        rest: &[Vec3],
        x: &[Vec3],
    ) -> Vec<([usize; 4], SVector<f64, 12>)> {
        let pairs = Pairs::new(surface, candidates, rest);
        pairs
            .map(x, |pair, y| {
                Some((pair.nodes, self.local(pair, y)?.gradient))
            })
            .into_iter()
            .flatten()
            .collect()
    }

    /// The four nodes of every candidate pair, in the order of [`HessianBlocks::slots`].
    pub fn pair_nodes(
        surface: &ContactSurface,
        candidates: &Candidates,
        rest: &[Vec3],
    ) -> Vec<[usize; 4]> {
        let pairs = Pairs::new(surface, candidates, rest);
        (0..candidates.len()).map(|i| pairs.get(i).nodes).collect()
    }

    /// The Hessian of the potential at `x` as `(row, column, value)` triplets (duplicates
    /// add up), each pair's 12 x 12 block projected onto the positive semidefinite cone.
    pub fn hessian_triplets(
        &self,
        surface: &ContactSurface,
        candidates: &Candidates,
        rest: &[Vec3],
        x: &[Vec3],
    ) -> Vec<(usize, usize, f64)> {
        const LEN: usize = 144;
        let mut values = vec![0.0; LEN * candidates.len()];
        let copy = |_: &[usize; 4], block: &SMatrix<f64, 12, 12>, slot: &mut [f64]| {
            slot.copy_from_slice(block.as_slice());
        };
        let blocks = HessianBlocks {
            slots: values.chunks_mut(LEN).collect(),
            write: &copy,
            project: true,
        };
        self.evaluate(surface, candidates, rest, x, None, Some(blocks));
        let nodes = Self::pair_nodes(surface, candidates, rest);
        let mut triplets = Vec::new();
        for (nodes, h) in nodes.iter().zip(values.chunks(LEN)) {
            let h = SMatrix::<f64, 12, 12>::from_column_slice(h);
            if h.iter().all(|&v| v == 0.0) {
                continue;
            }
            for (i, &ni) in nodes.iter().enumerate() {
                for (j, &nj) in nodes.iter().enumerate() {
                    for a in 0..3 {
                        for b in 0..3 {
                            triplets.push((3 * ni + a, 3 * nj + b, h[(3 * i + a, 3 * j + b)]));
                        }
                    }
                }
            }
        }
        triplets
    }

    /// Every candidate pair within `dhat` at `x` with its closest features and normal force.
    pub fn pair_forces(
        &self,
        surface: &ContactSurface,
        candidates: &Candidates,
        rest: &[Vec3],
        x: &[Vec3],
    ) -> Vec<PairForce> {
        let pairs = Pairs::new(surface, candidates, rest);
        pairs
            .map(x, |pair, y| {
                let kind = pair.kind(y);
                let d = kind.squared_distance(y);
                if !(d > 0.0 && d < self.dhat_sq()) {
                    return None;
                }
                let mollifier = pair.eps_x.map_or(1.0, |eps| edge_edge_mollifier(y, eps));
                let lambda = mollifier * normal_force(self.kappa, d, self.dhat_sq());
                (lambda > 0.0).then_some(PairForce {
                    nodes: pair.nodes,
                    kind,
                    lambda,
                })
            })
            .into_iter()
            .flatten()
            .collect()
    }

    /// The number of candidate pairs closer than `dhat` at `x`.
    pub fn count_within(
        &self,
        surface: &ContactSurface,
        candidates: &Candidates,
        rest: &[Vec3],
        x: &[Vec3],
    ) -> usize {
        let pairs = Pairs::new(surface, candidates, rest);
        pairs
            .map(x, |pair, y| {
                pair.kind(y).squared_distance(y) < self.dhat_sq()
            })
            .into_iter()
            .filter(|&within| within)
            .count()
    }

    /// The smallest distance (not squared) over the candidate pairs at `x`; `+inf` for none.
    pub fn min_distance(
        surface: &ContactSurface,
        candidates: &Candidates,
        rest: &[Vec3],
        x: &[Vec3],
    ) -> f64 {
        let pairs = Pairs::new(surface, candidates, rest);
        pairs
            .map(x, |pair, y| pair.kind(y).squared_distance(y))
            .into_iter()
            .fold(f64::INFINITY, f64::min)
            .sqrt()
    }
}

/// Adds a pair's gradient `local` (12 coordinates, node-major) into `global`.
fn scatter(nodes: &[usize; 4], local: &SVector<f64, 12>, global: &mut [f64]) {
    for (i, &n) in nodes.iter().enumerate() {
        for a in 0..3 {
            global[3 * n + a] += local[3 * i + a];
        }
    }
}
