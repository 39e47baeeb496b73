//! Aggregation of one level of smoothed-aggregation multigrid (Vanek, Mandel and Brezina
//! 1996, "Algebraic multigrid by smoothed aggregation for second and fourth order elliptic
//! problems", sec. 3): the strength-filtered graph of the level's nodes (blocks of DOFs:
//! a vertex's free displacements on the finest level, an aggregate's coarse DOFs below),
//! greedy aggregates of strongly connected nodes, and the tentative prolongator that
//! restricts the near null space to each aggregate and orthonormalizes it there.

use nalgebra::DMatrix;
use sprs::{CsMat, TriMat};

/// The DOFs of a level grouped into nodes, with the near null space on them.
#[derive(Debug, Clone)]
pub struct NearNullSpace {
    /// `node_start[i]..node_start[i + 1]` are the DOFs of node `i` (contiguous, in order).
    node_start: Vec<usize>,
    /// The near-null-space vectors as columns (one row per DOF).
    modes: DMatrix<f64>,
}

impl NearNullSpace {
    /// The rigid-body modes of linear elasticity on the free DOFs `free` (full-space indices
    /// `3 v + axis`, increasing) at the positions `x`: three translations and three
    /// rotations about the free vertices' centroid (Vanek et al. 1996, sec. 4). A vertex's
    /// free DOFs form one node.
    pub fn rigid_body(free: &[usize], x: &[isochor_mesh::Vec3]) -> Self {
        let mut node_start = vec![0];
        for (i, w) in free.windows(2).enumerate() {
            if w[0] / 3 != w[1] / 3 {
                node_start.push(i + 1);
            }
        }
        node_start.push(free.len());
        let count = free.len().max(1) as f64;
        let centroid = free.iter().map(|&d| x[d / 3]).sum::<isochor_mesh::Vec3>() / count;
        let mut modes = DMatrix::zeros(free.len(), 6);
        for (row, &dof) in free.iter().enumerate() {
            let (axis, r) = (dof % 3, x[dof / 3] - centroid);
            modes[(row, axis)] = 1.0;
            // Rotation about axis `k`: u = e_k x r, whose `axis` component is
            // eps_{axis, k, l} r_l.
            for k in (0..3).filter(|&k| k != axis) {
                let l = 3 - axis - k;
                let sign = if (axis + 1) % 3 == k { 1.0 } else { -1.0 };
                modes[(row, 3 + k)] = sign * r[l];
            }
        }
        NearNullSpace { node_start, modes }
    }

    /// Nodes of one DOF each with the constant vector as the near null space (a scalar
    /// problem such as a Laplacian).
    pub fn scalar(n: usize) -> Self {
        NearNullSpace {
            node_start: (0..=n).collect(),
            modes: DMatrix::from_element(n, 1, 1.0),
        }
    }

    /// Number of DOFs.
    pub fn dim(&self) -> usize {
        self.modes.nrows()
    }

    fn num_nodes(&self) -> usize {
        self.node_start.len() - 1
    }

    fn node_of_dofs(&self) -> Vec<usize> {
        let mut node = vec![0; self.dim()];
        for (i, w) in self.node_start.windows(2).enumerate() {
            node[w[0]..w[1]].fill(i);
        }
        node
    }
}

/// Strength threshold of the finest level (Vanek et al. 1996, sec. 3: `epsilon = 0.08`,
/// halved on every coarser level).
pub const FINEST_STRENGTH: f64 = 0.08;

/// The strong neighbours of every node of `a` (full symmetric, CSR): `j` is strong for `i`
/// when `|A_ij|_F >= epsilon sqrt(|A_ii|_F |A_jj|_F)` (Frobenius norms of the node blocks).
fn strong_neighbours(a: &CsMat<f64>, space: &NearNullSpace, epsilon: f64) -> Vec<Vec<usize>> {
    let node = space.node_of_dofs();
    let nodes = space.num_nodes();
    let mut diagonal = vec![0.0; nodes];
    for (i, row) in a.outer_iterator().enumerate() {
        for (j, v) in row.iter() {
            if node[i] == node[j] {
                diagonal[node[i]] += v * v;
            }
        }
    }
    let mut sums = vec![0.0; nodes];
    let mut touched = Vec::new();
    (0..nodes)
        .map(|ni| {
            touched.clear();
            for i in space.node_start[ni]..space.node_start[ni + 1] {
                let Some(row) = a.outer_view(i) else { continue };
                for (j, v) in row.iter() {
                    let nj = node[j];
                    if nj != ni {
                        if sums[nj] == 0.0 {
                            touched.push(nj);
                        }
                        sums[nj] += v * v;
                    }
                }
            }
            let strong = touched
                .iter()
                .copied()
                .filter(|&nj| {
                    sums[nj] > 0.0
                        && sums[nj].powi(2) >= epsilon.powi(4) * diagonal[ni] * diagonal[nj]
                })
                .collect();
            for &nj in &touched {
                sums[nj] = 0.0;
            }
            strong
        })
        .collect()
}

/// Greedy aggregation (Vanek et al. 1996, sec. 3, its three passes): nodes whose strong
/// neighbours are all free seed an aggregate with them; the rest join a neighbouring
/// aggregate; what is left forms aggregates with its free strong neighbours. Returns the
/// aggregate of every node and the number of aggregates.
fn aggregate(neighbours: &[Vec<usize>]) -> (Vec<usize>, usize) {
    const FREE: usize = usize::MAX;
    let mut of = vec![FREE; neighbours.len()];
    let mut count = 0;
    for (i, nbrs) in neighbours.iter().enumerate() {
        if of[i] == FREE && nbrs.iter().all(|&j| of[j] == FREE) {
            of[i] = count;
            nbrs.iter().for_each(|&j| of[j] = count);
            count += 1;
        }
    }
    let first_pass = of.clone();
    for (i, nbrs) in neighbours.iter().enumerate() {
        if of[i] == FREE {
            if let Some(&j) = nbrs.iter().find(|&&j| first_pass[j] != FREE) {
                of[i] = first_pass[j];
            }
        }
    }
    for (i, nbrs) in neighbours.iter().enumerate() {
        if of[i] == FREE {
            of[i] = count;
            for &j in nbrs {
                if of[j] == FREE {
                    of[j] = count;
                }
            }
            count += 1;
        }
    }
    (of, count)
}

/// The tentative prolongator of one level and the next level's near null space.
pub struct Tentative {
    /// `n x n_c`, orthonormal columns, one block of columns per aggregate.
    pub prolongator: CsMat<f64>,
    /// The coarse level's nodes (aggregates) and near null space.
    pub coarse: NearNullSpace,
}

/// Aggregates the nodes of `a` and builds the tentative prolongator: on each aggregate the
/// rows of the near null space `B_a = Q_a R_a` (thin QR), `Q_a` its block of `P`, `R_a`
/// its rows of the coarse near null space (so `P B_c = B`). An aggregate with fewer DOFs
/// than modes keeps as many coarse DOFs as it has DOFs.
pub fn tentative(a: &CsMat<f64>, space: &NearNullSpace, epsilon: f64) -> Tentative {
    let (of, count) = aggregate(&strong_neighbours(a, space, epsilon));
    let mut members = vec![Vec::new(); count];
    for (node, &agg) in of.iter().enumerate() {
        members[agg].extend(space.node_start[node]..space.node_start[node + 1]);
    }
    let k = space.modes.ncols();
    let mut coarse_start = vec![0];
    let mut coarse_rows = Vec::new();
    let mut triplets = Vec::new();
    for rows in &members {
        let b = DMatrix::from_fn(rows.len(), k, |r, c| space.modes[(rows[r], c)]);
        let qr = b.qr();
        let (q, r) = (qr.q(), qr.r());
        let offset = *coarse_start.last().expect("starts with 0");
        for (local, &row) in rows.iter().enumerate() {
            for c in 0..q.ncols() {
                triplets.push((row, offset + c, q[(local, c)]));
            }
        }
        coarse_rows.push(r);
        coarse_start.push(offset + q.ncols());
    }
    let n_c = *coarse_start.last().expect("starts with 0");
    let mut p = TriMat::new((space.dim(), n_c));
    for (r, c, v) in triplets {
        p.add_triplet(r, c, v);
    }
    let mut modes = DMatrix::zeros(n_c, k);
    for (block, r) in coarse_rows.iter().enumerate() {
        modes.rows_mut(coarse_start[block], r.nrows()).copy_from(r);
    }
    Tentative {
        prolongator: p.to_csr(),
        coarse: NearNullSpace {
            node_start: coarse_start,
            modes,
        },
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every node lands in exactly one aggregate, and a path graph's aggregates are runs
    /// of neighbours.
    #[test]
    fn aggregates_cover_a_path() {
        let n: usize = 10;
        let neighbours: Vec<Vec<usize>> = (0..n)
            .map(|i| {
                [i.checked_sub(1), (i + 1 < n).then_some(i + 1)]
                    .into_iter()
                    .flatten()
                    .collect()
            })
            .collect();
        let (of, count) = aggregate(&neighbours);
        assert!(of.iter().all(|&a| a < count));
        for a in 0..count {
            let members: Vec<usize> = (0..n).filter(|&i| of[i] == a).collect();
            assert!(members.windows(2).all(|w| w[1] == w[0] + 1), "{members:?}");
        }
        assert!(count < n, "aggregation must coarsen a connected graph");
    }

    /// The rigid-body modes are what they say: a translation moves every DOF along its
    /// axis, a rotation about z moves (x, y) as (-y, x).
    #[test]
    fn rigid_body_modes_are_translations_and_rotations() {
        let x = [
            isochor_mesh::Vec3::new(0.0, 0.0, 0.0),
            isochor_mesh::Vec3::new(2.0, 0.0, 0.0),
        ];
        let free: Vec<usize> = (0..6).collect();
        let space = NearNullSpace::rigid_body(&free, &x);
        assert_eq!(space.node_start, vec![0, 3, 6]);
        // Vertex 1 sits at +1 along x from the centroid.
        assert_eq!(space.modes[(3, 0)], 1.0);
        assert_eq!(
            space.modes[(4, 5)],
            1.0,
            "rotation about z moves +x along +y"
        );
        assert_eq!(
            space.modes[(5, 4)],
            -1.0,
            "rotation about y moves +x along -z"
        );
        assert_eq!(space.modes[(3, 5)], 0.0);
    }
}
