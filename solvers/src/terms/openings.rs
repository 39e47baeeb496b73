//! The openings of a face set capped: every boundary loop closed by the ruled fan from the
//! loop's centroid `c` (the mean of its corners) to the loop's edges, curved 6-node edges
//! included. On that fan `(x - c) . n = 0`, so its cone volume about an origin `o` is
//! `(1/3) (c - o) . A_cap`, and its area vector `A_cap = -(1/2) sum_edges integral g x g' ds`
//! follows from the loop alone (the edges run along the faces' orientation): `a x b` for a
//! straight edge, `(4/3) a x m - (1/3) a x b + (4/3) m x b` for a quadratic one through `m`.
//! The cap's term `T = -(1/6) sum w_ij (c - o) . (p_i x p_j)` is trilinear in the loop's nodes,
//! with exact gradient and Hessian (docs/scene-format.md#volume-control).

use super::Faces;
use crate::error::SolverError;
use isochor_mesh::Vec3;
use nalgebra::{DMatrix, Matrix3};
use std::collections::HashMap;

/// A directed edge `(a, b)` of a face and its mid-edge node, if any.
type Edge = (usize, usize, Option<usize>);

/// One boundary loop: its nodes, its corners (local indices) and the weighted node pairs
/// `(i, j, w_ij)` of `sum_edges integral g x g' ds = sum w_ij p_i x p_j`.
#[derive(Debug, Clone)]
struct Loop {
    nodes: Vec<usize>,
    corners: Vec<usize>,
    pairs: Vec<(usize, usize, f64)>,
}

/// The capped openings of a face set.
#[derive(Debug, Clone, Default)]
pub struct Openings {
    loops: Vec<Loop>,
}

impl Openings {
    /// The boundary loops of `faces` (edges of one face only). Errors: an edge shared by
    /// more than two faces or twice in one direction (the faces are not an oriented
    /// surface), or a boundary vertex where loops do not pass through (cannot be capped).
    pub fn of(faces: &Faces) -> Result<Self, SolverError> {
        let quadratic = faces.nodes_per_face() == 6;
        // Directed edges (a, b) with their mid-edge node, by undirected key.
        let mut edges: HashMap<(usize, usize), Vec<Edge>> = HashMap::new();
        for face in faces.iter() {
            for k in 0..3 {
                let (a, b) = (face[k], face[(k + 1) % 3]);
                let m = quadratic.then(|| face[3 + k]);
                edges
                    .entry((a.min(b), a.max(b)))
                    .or_default()
                    .push((a, b, m));
            }
        }
        let bad = |reason: &str| {
            Err(SolverError::InvalidProblem(format!(
                "the faces' openings cannot be capped: {reason}"
            )))
        };
        let mut boundary = Vec::new();
        for uses in edges.values() {
            match uses.as_slice() {
                [one] => boundary.push(*one),
                [(a, _, _), (c, _, _)] if a != c => {}
                _ => {
                    return bad(
                        "an edge is shared by more than two faces, or twice in one direction",
                    )
                }
            }
        }
        boundary.sort_unstable();
        // Loops: the connected components of the boundary edges (by their corners).
        let mut parent: HashMap<usize, usize> = HashMap::new();
        fn root(parent: &mut HashMap<usize, usize>, v: usize) -> usize {
            let p = *parent.entry(v).or_insert(v);
            if p == v {
                return v;
            }
            let r = root(parent, p);
            parent.insert(v, r);
            r
        }
        let mut balance: HashMap<usize, i64> = HashMap::new();
        for &(a, b, _) in &boundary {
            let (ra, rb) = (root(&mut parent, a), root(&mut parent, b));
            parent.insert(ra, rb);
            *balance.entry(a).or_default() += 1;
            *balance.entry(b).or_default() -= 1;
        }
        if balance.values().any(|&d| d != 0) {
            return bad("a boundary vertex is not passed through by a loop");
        }
        let mut by_root: HashMap<usize, Vec<Edge>> = HashMap::new();
        for &edge in &boundary {
            by_root
                .entry(root(&mut parent, edge.0))
                .or_default()
                .push(edge);
        }
        let mut roots: Vec<usize> = by_root.keys().copied().collect();
        roots.sort_unstable();
        let loops = roots
            .into_iter()
            .map(|r| {
                let mut local: HashMap<usize, usize> = HashMap::new();
                let mut nodes = Vec::new();
                let mut index = |v: usize| {
                    *local.entry(v).or_insert_with(|| {
                        nodes.push(v);
                        nodes.len() - 1
                    })
                };
                let mut corners = Vec::new();
                let mut pairs = Vec::new();
                for &(a, b, m) in &by_root[&r] {
                    let (ia, ib) = (index(a), index(b));
                    corners.push(ia);
                    match m {
                        None => pairs.push((ia, ib, 1.0)),
                        Some(m) => {
                            let im = index(m);
                            pairs.extend([
                                (ia, im, 4.0 / 3.0),
                                (ia, ib, -1.0 / 3.0),
                                (im, ib, 4.0 / 3.0),
                            ]);
                        }
                    }
                }
                Loop {
                    nodes,
                    corners,
                    pairs,
                }
            })
            .collect();
        Ok(Openings { loops })
    }

    /// Whether there are no openings.
    pub fn is_empty(&self) -> bool {
        self.loops.is_empty()
    }

    /// The nodes of every loop, loop-major (the order of the gradient and Hessian blocks).
    pub fn loop_nodes(&self) -> impl Iterator<Item = &[usize]> {
        self.loops.iter().map(|l| l.nodes.as_slice())
    }

    /// `s` times the caps' cone volume about `origin`; adds `s` times its gradient into
    /// `gradient` (loop-major, `3 n_k` entries per loop) and writes `s` times its Hessian
    /// (one dense column-major `3 n_k x 3 n_k` block per loop) into `hessian` when asked.
    pub fn evaluate(
        &self,
        x: &[Vec3],
        origin: Vec3,
        s: f64,
        mut gradient: Option<&mut [f64]>,
        mut hessian: Option<&mut [f64]>,
    ) -> f64 {
        let (mut g_at, mut h_at) = (0, 0);
        let mut value = 0.0;
        for l in &self.loops {
            let n = l.nodes.len();
            let p: Vec<Vec3> = l.nodes.iter().map(|&v| x[v]).collect();
            let nc = l.corners.len() as f64;
            let u = l.corners.iter().map(|&i| p[i]).sum::<Vec3>() / nc - origin;
            let mut g = vec![Vec3::zeros(); n];
            let mut gc = Vec3::zeros();
            let mut h = DMatrix::<f64>::zeros(3 * n, 3 * n);
            let add = |h: &mut DMatrix<f64>, a: usize, b: usize, m: Matrix3<f64>| {
                let mut view = h.fixed_view_mut::<3, 3>(3 * a, 3 * b);
                view += m;
                let mut view = h.fixed_view_mut::<3, 3>(3 * b, 3 * a);
                view += m.transpose();
            };
            for &(i, j, w) in &l.pairs {
                let k = -s * w / 6.0;
                value += k * u.dot(&p[i].cross(&p[j]));
                g[i] += k * p[j].cross(&u);
                g[j] += k * u.cross(&p[i]);
                gc += k * p[i].cross(&p[j]);
                if hessian.is_some() {
                    add(&mut h, i, j, -k * u.cross_matrix());
                    for &c in &l.corners {
                        add(&mut h, c, i, -k / nc * p[j].cross_matrix());
                        add(&mut h, c, j, k / nc * p[i].cross_matrix());
                    }
                }
            }
            for &c in &l.corners {
                g[c] += gc / nc;
            }
            if let Some(out) = gradient.as_deref_mut() {
                for (a, gi) in g.iter().enumerate() {
                    for d in 0..3 {
                        out[g_at + 3 * a + d] += gi[d];
                    }
                }
            }
            if let Some(out) = hessian.as_deref_mut() {
                out[h_at..h_at + 9 * n * n].copy_from_slice(h.as_slice());
            }
            g_at += 3 * n;
            h_at += 9 * n * n;
        }
        value
    }
}
