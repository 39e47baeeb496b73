//! Vertex adjacency in compressed (CSR) storage, and k-rings of tets around a vertex
//! (the 1-ring zones of Irving et al. 2007 and the k-ring zones of Sheen et al. 2021, Fig. 5).

use crate::{MeshError, TetMesh};

/// Compressed rows: row `i` is `items[offsets[i]..offsets[i + 1]]`.
#[derive(Debug, Clone, PartialEq, Eq)]
struct Csr {
    offsets: Vec<usize>,
    items: Vec<usize>,
}

impl Csr {
    /// Rows from `(row, item)` pairs; every row is sorted and duplicate-free.
    fn from_pairs(rows: usize, mut pairs: Vec<(usize, usize)>) -> Self {
        pairs.sort_unstable();
        pairs.dedup();
        let mut offsets = vec![0; rows + 1];
        for &(r, _) in &pairs {
            offsets[r + 1] += 1;
        }
        for r in 0..rows {
            offsets[r + 1] += offsets[r];
        }
        Csr {
            offsets,
            items: pairs.into_iter().map(|(_, i)| i).collect(),
        }
    }

    fn row(&self, r: usize) -> &[usize] {
        &self.items[self.offsets[r]..self.offsets[r + 1]]
    }
}

/// Vertex-to-tet and vertex-to-vertex adjacency of a [`TetMesh`].
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Adjacency {
    vertex_tets: Csr,
    vertex_vertices: Csr,
}

impl Adjacency {
    /// Builds both adjacencies in `O(tets log tets)`.
    pub fn new(mesh: &TetMesh) -> Self {
        let n = mesh.num_vertices();
        let tets = mesh.tets();
        let incidence = tets
            .iter()
            .enumerate()
            .flat_map(|(e, t)| t.iter().map(move |&v| (v, e)))
            .collect();
        let edges = tets
            .iter()
            .flat_map(|t| {
                (0..4).flat_map(move |a| (0..4).filter(move |&b| b != a).map(move |b| (t[a], t[b])))
            })
            .collect();
        Adjacency {
            vertex_tets: Csr::from_pairs(n, incidence),
            vertex_vertices: Csr::from_pairs(n, edges),
        }
    }

    /// Number of vertices.
    pub fn num_vertices(&self) -> usize {
        self.vertex_tets.offsets.len() - 1
    }

    /// Sorted tets incident to vertex `v` (its 1-ring).
    pub fn vertex_tets(&self, v: usize) -> &[usize] {
        self.vertex_tets.row(v)
    }

    /// Sorted vertices sharing a tet (equivalently an edge) with vertex `v`, excluding `v`.
    pub fn vertex_neighbors(&self, v: usize) -> &[usize] {
        self.vertex_vertices.row(v)
    }

    /// The sorted k-ring of tets around vertex `v`: the 1-ring is the tets incident to `v`,
    /// the k-ring is the tets incident to any vertex of a (k-1)-ring tet. Equivalently, the
    /// tets incident to a vertex within `k - 1` edges of `v`.
    pub fn k_ring(&self, v: usize, k: usize) -> Result<Vec<usize>, MeshError> {
        if v >= self.num_vertices() {
            return Err(MeshError::VertexOutOfRange {
                vertex: v,
                vertices: self.num_vertices(),
            });
        }
        if k == 0 {
            return Err(MeshError::parameter("k", k, "a k-ring needs k >= 1"));
        }
        let mut scratch = RingScratch::new(self);
        let mut ring = Vec::new();
        self.k_ring_into(v, k, &mut scratch, &mut ring);
        ring.sort_unstable();
        Ok(ring)
    }

    /// The k-ring of `v` (unsorted) into `ring`, reusing `scratch` so that many rings cost
    /// only their own size. Requires `v` in range and `k >= 1`.
    pub(crate) fn k_ring_into(
        &self,
        v: usize,
        k: usize,
        scratch: &mut RingScratch,
        ring: &mut Vec<usize>,
    ) {
        scratch.stamp += 1;
        let stamp = scratch.stamp;
        ring.clear();
        let mut frontier = vec![v];
        scratch.vertex_seen[v] = stamp;
        for depth in 0..k {
            let mut next = Vec::new();
            for &u in &frontier {
                for &e in self.vertex_tets(u) {
                    if scratch.tet_seen[e] != stamp {
                        scratch.tet_seen[e] = stamp;
                        ring.push(e);
                    }
                }
                if depth + 1 < k {
                    for &w in self.vertex_neighbors(u) {
                        if scratch.vertex_seen[w] != stamp {
                            scratch.vertex_seen[w] = stamp;
                            next.push(w);
                        }
                    }
                }
            }
            frontier = next;
        }
    }
}

/// Visit marks for [`Adjacency::k_ring_into`]: an entry equal to the current stamp means
/// "seen in this ring", so no clearing is needed between rings.
pub(crate) struct RingScratch {
    stamp: u64,
    vertex_seen: Vec<u64>,
    tet_seen: Vec<u64>,
}

impl RingScratch {
    pub(crate) fn new(adjacency: &Adjacency) -> Self {
        let tets = adjacency
            .vertex_tets
            .items
            .iter()
            .max()
            .map_or(0, |&e| e + 1);
        RingScratch {
            stamp: 0,
            vertex_seen: vec![0; adjacency.num_vertices()],
            tet_seen: vec![0; tets],
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::generate::box_grid;
    use crate::Vec3;

    #[test]
    fn one_ring_and_neighbors_of_grid_vertices() {
        // 3x3x3 cells; vertex (i, j, k) = i + 4 (j + 4 k).
        let mesh = box_grid(Vec3::zeros(), Vec3::repeat(3.0), [3, 3, 3]).unwrap();
        let adj = Adjacency::new(&mesh);
        let center = 1 + 4 * (1 + 4);
        // An interior Kuhn vertex touches 24 tets and 14 vertices (6 axis + 6 face diagonals
        // + 2 body diagonals).
        assert_eq!(adj.vertex_tets(center).len(), 24);
        assert_eq!(adj.vertex_neighbors(center).len(), 14);
        // The corner (0,0,0) is corner 0 of one hex: all 6 of its tets; (3,0,0) is corner 1 of
        // one hex: 2 tets.
        assert_eq!(adj.vertex_tets(0).len(), 6);
        assert_eq!(adj.vertex_tets(3).len(), 2);
        for v in 0..mesh.num_vertices() {
            let tets = adj.vertex_tets(v);
            assert!(tets.windows(2).all(|w| w[0] < w[1]));
            assert!(tets.iter().all(|&e| mesh.tets()[e].contains(&v)));
            assert!(!adj.vertex_neighbors(v).contains(&v));
        }
        let total: usize = (0..mesh.num_vertices())
            .map(|v| adj.vertex_tets(v).len())
            .sum();
        assert_eq!(total, 4 * mesh.num_tets());
    }

    #[test]
    fn k_rings_grow_to_the_whole_grid() {
        let mesh = box_grid(Vec3::zeros(), Vec3::repeat(4.0), [4, 4, 4]).unwrap();
        let adj = Adjacency::new(&mesh);
        let center = 2 + 5 * (2 + 5 * 2);
        let sizes: Vec<usize> = (1..=4)
            .map(|k| adj.k_ring(center, k).unwrap().len())
            .collect();
        // 1-ring: 24 tets. 2-ring: tets touching the 15 vertices of the 1-ring, i.e. every tet
        // of the 4 x 4 x 4 hexes around the centre except those whose vertices all lie outside.
        assert_eq!(sizes[0], 24);
        assert!(sizes[1] > sizes[0] && sizes[2] > sizes[1]);
        assert_eq!(sizes[3], mesh.num_tets());
        let two = adj.k_ring(center, 2).unwrap();
        let one_ring_vertices: Vec<usize> = adj
            .k_ring(center, 1)
            .unwrap()
            .iter()
            .flat_map(|&e| mesh.tets()[e])
            .collect();
        for e in 0..mesh.num_tets() {
            let touches = mesh.tets()[e].iter().any(|v| one_ring_vertices.contains(v));
            assert_eq!(two.binary_search(&e).is_ok(), touches, "tet {e}");
        }
        assert!(adj.k_ring(center, 0).is_err());
        assert!(matches!(
            adj.k_ring(1000, 1),
            Err(MeshError::VertexOutOfRange { vertex: 1000, .. })
        ));
    }
}
