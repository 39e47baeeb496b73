//! The Hessian layout built per node pair: terms whose elements couple whole nodes (dense
//! `3n x 3n` element blocks, [`ElementBlocks`]) contribute their node pairs, a ninth of their
//! `(dof, dof)` pairs, to a node pattern; the free-free lower pattern over DOFs is expanded
//! once from it, and every element entry finds its slot through its node pair's. Other
//! terms' `(dof, dof)` pairs (contact, inertia) are merged in per column.
//!
//! The result is the layout that the same entries given pair by pair would have: the same
//! stored structure, the same kept entries in the same order and the same slots, so every
//! assembled matrix is bit for bit the same.

use crate::error::SolverError;
use crate::linear::{SparsityPattern, Triangle};
use crate::model::dofs::Dofs;
use crate::terms::ElementBlocks;

/// One term's Hessian pattern: dense element blocks or plain `(dof, dof)` pairs.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum HessianBlock {
    /// `(dof, dof)` of every entry.
    Pairs(Vec<(usize, usize)>),
    /// Dense element blocks.
    Elements(ElementBlocks),
}

impl HessianBlock {
    /// Number of entries (values the term writes).
    pub fn len(&self) -> usize {
        match self {
            HessianBlock::Pairs(p) => p.len(),
            HessianBlock::Elements(b) => b.entries(),
        }
    }

    /// Whether the block has no entries.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// Whether the two list the same pairs in the same order.
    pub fn same_pattern(&self, other: &HessianBlock) -> bool {
        match (self, other) {
            (HessianBlock::Pairs(p), HessianBlock::Elements(e))
            | (HessianBlock::Elements(e), HessianBlock::Pairs(p)) => {
                p.len() == e.entries() && *p == e.pairs()
            }
            _ => self == other,
        }
    }
}

/// Marks a node-table entry that holds no stored DOF pair.
const NONE: usize = usize::MAX;

/// The lower free-free pattern of the Hessian entries of a list of blocks (in order, both
/// triangles given), with the fate of every entry.
#[derive(Debug)]
pub struct NodePattern {
    /// The global index of every stored entry, in order (the pattern's inputs).
    pub kept: Vec<usize>,
    /// `(entry, free row, column DOF)` of every entry coupling a free row to a prescribed
    /// column.
    pub coupling: Vec<(usize, usize, usize)>,
    /// The stored pattern over free DOFs; input `i` is entry `kept[i]`.
    pub pattern: SparsityPattern,
}

impl NodePattern {
    /// The layout of `blocks` over the free DOFs of `dofs`.
    pub fn new(blocks: &[HessianBlock], dofs: &Dofs) -> Result<Self, SolverError> {
        let linear = |e: crate::linear::LinearError| SolverError::Linear(e.to_string());
        let total = dofs.num_dofs();
        let n = dofs.num_free();
        let free = |d: usize| dofs.free_index(d);
        for block in blocks {
            let bad = match block {
                HessianBlock::Pairs(p) => p.iter().any(|&(r, c)| r.max(c) >= total),
                HessianBlock::Elements(b) => {
                    b.per_element == 0
                        || b.nodes.len() % b.per_element != 0
                        || b.nodes.iter().any(|&v| 3 * v + 2 >= total)
                }
            };
            if bad {
                return Err(SolverError::InvalidProblem(
                    "a Hessian pattern entry past the DOFs".into(),
                ));
            }
        }
        // Node pattern (row node >= column node) over every element block, one input per node
        // pair of each element, listed as the block lists its entries.
        let mut node_pairs = Vec::new();
        for block in blocks {
            if let HessianBlock::Elements(b) = block {
                for element in b.nodes.chunks_exact(b.per_element) {
                    for &p in element {
                        node_pairs.extend(element.iter().map(|&q| b.order.pair(p, q)));
                    }
                }
            }
        }
        let nodes = SparsityPattern::new(total / 3, total / 3, &node_pairs, Triangle::Lower)
            .map_err(linear)?;
        let node_cols = nodes.symbolic();
        let node_rows = node_cols.row_idx();
        // The pairs' free-free lower entries, bucketed by column (counting sort).
        let reduced: Vec<(usize, usize)> = blocks
            .iter()
            .filter_map(|b| match b {
                HessianBlock::Pairs(p) => Some(p),
                HessianBlock::Elements(_) => None,
            })
            .flatten()
            .filter_map(|&(r, c)| Some((free(r)?, free(c)?)))
            .filter(|(i, j)| i >= j)
            .collect();
        let mut start = vec![0usize; n + 1];
        reduced.iter().for_each(|&(_, j)| start[j + 1] += 1);
        (0..n).for_each(|j| start[j + 1] += start[j]);
        let mut next = start.clone();
        let mut by_col = vec![0usize; reduced.len()];
        for (k, &(_, j)) in reduced.iter().enumerate() {
            by_col[next[j]] = k;
            next[j] += 1;
        }
        // Per free column: the expansion of its node's column (sorted already: free indices
        // grow with the DOF), merged with the pairs' rows (then sorted). `table[9 s + 3 c + r]`
        // is the slot of DOF row `r` of the node pair stored at `s`, in the column of DOF `c`.
        let mut table = vec![NONE; 9 * node_rows.len()];
        let mut reduced_slots = vec![0usize; reduced.len()];
        let mut col_ptr = Vec::with_capacity(n + 1);
        let mut row_idx = Vec::new();
        let mut stamp = vec![usize::MAX; n];
        let mut position = vec![0usize; n];
        col_ptr.push(0);
        for (j, &dof) in dofs.free().iter().enumerate() {
            let (node, c) = (dof / 3, dof % 3);
            let first = row_idx.len();
            for s in node_cols.col_range(node) {
                for r in 0..3 {
                    if let Some(i) = free(3 * node_rows[s] + r).filter(|&i| i >= j) {
                        table[9 * s + 3 * c + r] = row_idx.len();
                        stamp[i] = j;
                        row_idx.push(i);
                    }
                }
            }
            let bucket = &by_col[start[j]..start[j + 1]];
            if !bucket.is_empty() {
                for &k in bucket {
                    let i = reduced[k].0;
                    if stamp[i] != j {
                        stamp[i] = j;
                        row_idx.push(i);
                    }
                }
                row_idx[first..].sort_unstable();
                for (p, &i) in row_idx[first..].iter().enumerate() {
                    position[i] = first + p;
                }
                for &k in bucket {
                    reduced_slots[k] = position[reduced[k].0];
                }
                for s in node_cols.col_range(node) {
                    for r in 0..3 {
                        if let Some(i) = free(3 * node_rows[s] + r).filter(|&i| i >= j) {
                            table[9 * s + 3 * c + r] = position[i];
                        }
                    }
                }
            }
            col_ptr.push(row_idx.len());
        }
        // Every entry in block order: kept (with its slot), coupling, or dropped.
        let entries: usize = blocks.iter().map(HessianBlock::len).sum();
        let mut kept = Vec::with_capacity(entries / 2 + n);
        let mut slots = Vec::with_capacity(entries / 2 + n);
        let mut coupling = Vec::new();
        let (mut k, mut node_input, mut pair) = (0, 0, 0);
        for block in blocks {
            match block {
                HessianBlock::Pairs(p) => {
                    for &(r, c) in p {
                        if let Some(i) = free(r) {
                            match free(c) {
                                Some(j) if i >= j => {
                                    kept.push(k);
                                    slots.push(reduced_slots[pair]);
                                    pair += 1;
                                }
                                Some(_) => {}
                                None => coupling.push((k, i, c)),
                            }
                        }
                        k += 1;
                    }
                }
                HessianBlock::Elements(b) => {
                    let per = b.per_element;
                    let dim = 3 * per;
                    let mut local = vec![(0, None); dim];
                    for element in b.nodes.chunks_exact(per) {
                        for (l, slot) in local.iter_mut().enumerate() {
                            let d = 3 * element[l / 3] + l % 3;
                            *slot = (d, free(d));
                        }
                        for outer in 0..dim {
                            for inner in 0..dim {
                                let (r, c) = b.order.pair(outer, inner);
                                if let Some(i) = local[r].1 {
                                    match local[c].1 {
                                        Some(j) if i >= j => {
                                            let input = node_input + (outer / 3) * per + inner / 3;
                                            let s = nodes.slot(input).ok_or_else(|| {
                                                SolverError::Linear("node pair not stored".into())
                                            })?;
                                            kept.push(k);
                                            slots.push(table[9 * s + 3 * (c % 3) + r % 3]);
                                        }
                                        Some(_) => {}
                                        None => coupling.push((k, i, local[c].0)),
                                    }
                                }
                                k += 1;
                            }
                        }
                        node_input += per * per;
                    }
                }
            }
        }
        let pattern = SparsityPattern::from_parts(n, n, col_ptr, row_idx, slots, Triangle::Lower);
        Ok(NodePattern {
            kept,
            coupling,
            pattern,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::terms::BlockOrder;
    use crate::{Dirichlet, Motion};

    /// The layout of the same entries given pair by pair, built with
    /// [`SparsityPattern::new`] (the layout before node patterns).
    fn by_pairs(blocks: &[HessianBlock], dofs: &Dofs) -> NodePattern {
        let pairs = blocks.iter().flat_map(|b| match b {
            HessianBlock::Pairs(p) => p.clone(),
            HessianBlock::Elements(e) => e.pairs(),
        });
        let (mut kept, mut reduced, mut coupling) = (Vec::new(), Vec::new(), Vec::new());
        for (k, (r, c)) in pairs.enumerate() {
            let Some(i) = dofs.free_index(r) else {
                continue;
            };
            match dofs.free_index(c) {
                Some(j) if i >= j => {
                    kept.push(k);
                    reduced.push((i, j));
                }
                Some(_) => {}
                None => coupling.push((k, i, c)),
            }
        }
        let n = dofs.num_free();
        let pattern = SparsityPattern::new(n, n, &reduced, Triangle::Lower).unwrap();
        NodePattern {
            kept,
            coupling,
            pattern,
        }
    }

    #[test]
    fn node_layout_is_the_layout_of_the_pairs() {
        // Seven nodes, node 1 held in x and z, node 5 in all three; tets sharing faces and
        // edges in both block orders, beside plain pairs (a diagonal and one off-node
        // coupling, with a duplicate) and a cloth node (6) that only the pairs reach.
        let held = |nodes: Vec<usize>, axes| Dirichlet {
            nodes,
            axes,
            motion: Motion::Fixed,
            curve: None,
        };
        let dofs = Dofs::new(
            7,
            &[held(vec![1], [true, false, true]), held(vec![5], [true; 3])],
        )
        .unwrap();
        let tets = vec![0, 1, 2, 3, 1, 2, 3, 4, 4, 3, 5, 0];
        let blocks = vec![
            HessianBlock::Elements(ElementBlocks {
                nodes: tets.clone(),
                per_element: 4,
                order: BlockOrder::ColumnMajor,
            }),
            HessianBlock::Pairs(
                (0..21)
                    .map(|d| (d, d))
                    .chain([(19, 2), (2, 19), (19, 2)])
                    .collect(),
            ),
            HessianBlock::Elements(ElementBlocks {
                nodes: tets[4..].to_vec(),
                per_element: 4,
                order: BlockOrder::RowMajor,
            }),
            HessianBlock::Pairs(vec![(20, 0), (0, 20)]),
        ];
        let got = NodePattern::new(&blocks, &dofs).unwrap();
        let want = by_pairs(&blocks, &dofs);
        assert_eq!(got.kept, want.kept);
        assert_eq!(got.coupling, want.coupling);
        let (g, w) = (got.pattern.symbolic(), want.pattern.symbolic());
        assert_eq!(g.col_ptr(), w.col_ptr());
        assert_eq!(g.row_idx(), w.row_idx());
        assert_eq!(got.pattern.num_inputs(), want.pattern.num_inputs());
        for i in 0..want.pattern.num_inputs() {
            assert_eq!(got.pattern.slot(i), want.pattern.slot(i), "input {i}");
        }
        assert!(!got.coupling.is_empty() && got.pattern.nnz() > 0);
    }

    #[test]
    fn bad_blocks_are_errors() {
        let dofs = Dofs::new(2, &[]).unwrap();
        let elements = |nodes: Vec<usize>, per_element| {
            HessianBlock::Elements(ElementBlocks {
                nodes,
                per_element,
                order: BlockOrder::ColumnMajor,
            })
        };
        assert!(NodePattern::new(&[elements(vec![0, 2], 2)], &dofs).is_err());
        assert!(NodePattern::new(&[elements(vec![0, 1, 1], 2)], &dofs).is_err());
        assert!(NodePattern::new(&[HessianBlock::Pairs(vec![(6, 0)])], &dofs).is_err());
    }
}
