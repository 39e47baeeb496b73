//! Assembly over free DOFs: the sparsity pattern of all terms is built once; every Newton
//! iteration refills a flat value buffer in parallel (each term writes its own slice, each
//! element its own chunk) and gathers the free-free entries into the fixed pattern.

use super::node_pattern::{HessianBlock, NodePattern};
use crate::error::SolverError;
use crate::linear::{SparsityPattern, Triangle};
use crate::model::dofs::Dofs;
use faer::sparse::SparseColMat;

/// Maps the entries of a list of `(row, col)` pairs (with `row` and `col` full-space indices
/// of the given kinds) to a fixed sparse pattern over free indices, and records the entries
/// that couple a free row to a prescribed column.
#[derive(Debug)]
pub struct Layout {
    kept: Vec<usize>,
    coupling: Vec<(usize, usize, usize)>,
    pattern: SparsityPattern,
}

impl Layout {
    /// Layout of a symmetric `3n x 3n` Hessian whose blocks give both triangles; the pattern
    /// keeps the lower triangle of the free-free block (built per node pair where the
    /// blocks allow, [`super::node_pattern`]).
    pub fn hessian(blocks: &[HessianBlock], dofs: &Dofs) -> Result<Self, SolverError> {
        let NodePattern {
            kept,
            coupling,
            pattern,
        } = NodePattern::new(blocks, dofs)?;
        Ok(Layout {
            kept,
            coupling,
            pattern,
        })
    }

    /// Layout of a constraint Jacobian `G` (`rows x 3n`): all rows kept, prescribed columns
    /// moved to the coupling list.
    pub fn jacobian(
        pairs: &[(usize, usize)],
        rows: usize,
        dofs: &Dofs,
    ) -> Result<Self, SolverError> {
        let mut kept = Vec::new();
        let mut reduced = Vec::new();
        let mut coupling = Vec::new();
        for (k, &(row, c)) in pairs.iter().enumerate() {
            match dofs.free_index(c) {
                Some(col) => {
                    kept.push(k);
                    reduced.push((row, col));
                }
                None => coupling.push((k, row, c)),
            }
        }
        let pattern = SparsityPattern::new(rows, dofs.num_free(), &reduced, Triangle::Full)
            .map_err(|e| SolverError::Linear(e.to_string()))?;
        Ok(Layout {
            kept,
            coupling,
            pattern,
        })
    }

    /// The assembled free-free matrix from the full value buffer.
    pub fn matrix(&self, values: &[f64]) -> Result<SparseColMat<usize, f64>, SolverError> {
        let reduced: Vec<f64> = self.kept.iter().map(|&k| values[k]).collect();
        self.pattern
            .assemble(&reduced)
            .map_err(|e| SolverError::Linear(e.to_string()))
    }

    /// Adds `scale * A_fc g` to `out` (indexed by reduced row): the action of the
    /// free-prescribed block on a full-space vector `gap` of prescribed increments.
    pub fn add_coupling(&self, values: &[f64], gap: &[f64], scale: f64, out: &mut [f64]) {
        for &(k, row, col) in &self.coupling {
            out[row] += scale * values[k] * gap[col];
        }
    }
}

impl Layout {
    /// The fixed pattern over free indices.
    pub fn pattern(&self) -> &SparsityPattern {
        &self.pattern
    }
}
