//! The degrees of freedom of a contact pair: its nodes numbered below `num_nodes` (the
//! bodies'); the meshed obstacles' vertices, numbered after them, are prescribed positions,
//! so a pair's gradient entries and Hessian rows and columns of those vertices are dropped.
//! The barrier ([`super::SurfaceContact`]) and friction ([`super::SurfaceFriction`]) both
//! place their pairs' blocks through it.

use super::block_pattern;
use nalgebra::SMatrix;

/// Which nodes of a pair are degrees of freedom: those below `num_nodes`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct PairRows {
    /// The number of body nodes (the first obstacle vertex's index).
    pub num_nodes: usize,
}

impl PairRows {
    /// The pair's nodes that are degrees of freedom, in order.
    fn free_nodes(&self, nodes: &[usize; 4]) -> Vec<usize> {
        nodes
            .iter()
            .copied()
            .filter(|&v| v < self.num_nodes)
            .collect()
    }

    /// The `(dof, dof)` entries of the pair's block over its free nodes, column-major (the
    /// order [`Self::copy_block`] writes).
    pub fn pattern(&self, nodes: &[usize; 4]) -> Vec<(usize, usize)> {
        block_pattern(&self.free_nodes(nodes)).collect()
    }

    /// The number of entries of the pair's block over its free nodes (what
    /// [`Self::copy_block`] writes).
    pub fn block_len(&self, nodes: &[usize; 4]) -> usize {
        let free = nodes.iter().filter(|&&v| v < self.num_nodes).count();
        9 * free * free
    }

    /// Adds the pair's gradient `local` (12 coordinates, node-major) into `global` over its
    /// free nodes.
    pub fn scatter(&self, nodes: &[usize; 4], local: &[f64], global: &mut [f64]) {
        for (a, &v) in nodes.iter().enumerate() {
            if v < self.num_nodes {
                for k in 0..3 {
                    global[3 * v + k] += local[3 * a + k];
                }
            }
        }
    }

    /// Copies the rows and columns of the pair's free nodes of `block` column-major into the
    /// front of `out`; returns the entries written.
    pub fn copy_block(
        &self,
        nodes: &[usize; 4],
        block: &SMatrix<f64, 12, 12>,
        out: &mut [f64],
    ) -> usize {
        let free: Vec<usize> = (0..12).filter(|&l| nodes[l / 3] < self.num_nodes).collect();
        let mut written = 0;
        for &c in &free {
            for &r in &free {
                out[written] = block[(r, c)];
                written += 1;
            }
        }
        written
    }
}
