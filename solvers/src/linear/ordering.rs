//! Fill-reducing order for the saddle-point matrix `[[K, G^T], [G, -C]]` that keeps
//! `LDL^T` without pivoting stable at `C = 0` (docs/toolchain.md: AMD alone meets zero
//! pivots there): every constraint row is placed right after its *anchor* DOF (for
//! nodal P1 constraints, the node's last free displacement DOF), so its pivot is
//! formed after the displacement it couples to has been eliminated. Constraints without
//! an anchor (dense zonal rows) go last.
//!
//! The order is found by a fill-reducing ordering (AMD or nested dissection, see
//! [`Ordering`]) of the compressed graph whose vertices are the `n` DOFs, each anchored
//! constraint merged into its anchor, and then expanded.
//!
//! A constraint's pivot is `-g_E^T S_E^-1 g_E` over the DOFs `E` of its row eliminated
//! before it. The entries of a nodal volume constraint on its own node cancel for
//! interior nodes (moving the centre of a closed star does not change its volume), so
//! the pivot is exactly zero when the ordering eliminates the node before all its neighbours.
//! Such a constraint is therefore delayed until the DOFs of one other node of its row
//! are eliminated; "nodes" are the supervariables of `G` (DOFs whose columns of `G`
//! have the same rows), so nothing about the mesh is assumed.

use super::fill_reducing::fill_reducing;
use super::{LinearError, Ordering, SparsityPattern, Triangle};
use faer::sparse::SymbolicSparseColMatRef;
use std::collections::HashMap;

/// Forward permutation of the `n + m` KKT unknowns: `fwd[new] = old`, with DOFs
/// `0..n` and constraint `i` numbered `n + i`.
pub(crate) fn anchored_ordering(
    k: SymbolicSparseColMatRef<'_, usize>,
    g: SymbolicSparseColMatRef<'_, usize>,
    anchors: &[Option<usize>],
    ordering: Ordering,
) -> Result<Vec<usize>, LinearError> {
    let n = k.nrows();
    let m = g.nrows();
    if anchors.len() != m {
        return Err(LinearError::DimensionMismatch {
            what: "constraint anchors",
            expected: m,
            got: anchors.len(),
        });
    }
    if let Some((constraint, &Some(dof))) = anchors
        .iter()
        .enumerate()
        .find(|(_, a)| a.is_some_and(|d| d >= n))
    {
        return Err(LinearError::BadAnchor { constraint, dof, n });
    }
    // Compressed graph: K's edges, plus (anchor, dof) for every G entry of an anchored row.
    let mut pairs: Vec<(usize, usize)> = (0..n).map(|i| (i, i)).collect();
    for j in 0..n {
        pairs.extend(k.col_range(j).map(|p| (k.row_idx()[p], j)));
    }
    for j in 0..g.ncols() {
        for q in g.col_range(j) {
            if let Some(a) = anchors[g.row_idx()[q]] {
                pairs.push((a, j));
                pairs.push((j, a));
            }
        }
    }
    let graph = SparsityPattern::new(n, n, &pairs, Triangle::Full)?;
    let (fwd, inv) = fill_reducing(graph.symbolic(), ordering)?;
    // Expand: each DOF followed by the constraints placed after it, free rows last.
    let supervariable = supervariables(g);
    let mut row_dofs: Vec<Vec<usize>> = vec![Vec::new(); m];
    for j in 0..g.ncols() {
        for q in g.col_range(j) {
            row_dofs[g.row_idx()[q]].push(j);
        }
    }
    let mut anchored: Vec<Vec<usize>> = vec![Vec::new(); n];
    let mut free = Vec::new();
    for (i, a) in anchors.iter().enumerate() {
        match a {
            Some(a) => {
                // Per other node of the row: the position where its last DOF is eliminated.
                let mut done: HashMap<usize, usize> = HashMap::new();
                for &j in &row_dofs[i] {
                    if supervariable[j] != supervariable[*a] {
                        let t = done.entry(supervariable[j]).or_insert(0);
                        *t = (*t).max(inv[j]);
                    }
                }
                let after = done.values().min().map_or(inv[*a], |&t| t.max(inv[*a]));
                anchored[fwd[after]].push(n + i);
            }
            None => free.push(n + i),
        }
    }
    let mut order = Vec::with_capacity(n + m);
    for &d in &fwd {
        order.push(d);
        order.extend_from_slice(&anchored[d]);
    }
    order.extend(free);
    Ok(order)
}

/// Group id of every column of `g`: columns with the same row indices share one.
fn supervariables(g: SymbolicSparseColMatRef<'_, usize>) -> Vec<usize> {
    let mut ids: HashMap<&[usize], usize> = HashMap::new();
    (0..g.ncols())
        .map(|j| {
            let next = ids.len();
            *ids.entry(&g.row_idx()[g.col_range(j)]).or_insert(next)
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn constraints_follow_their_anchors_and_free_rows_go_last_under_both_orderings() {
        // K: a path 0-1-2-3; G: row 0 on DOFs {0, 1}, row 1 on {2, 3}, row 2 on all.
        let kp = [
            (0, 0),
            (1, 0),
            (0, 1),
            (1, 1),
            (2, 1),
            (1, 2),
            (2, 2),
            (3, 2),
            (2, 3),
            (3, 3),
        ];
        let k = SparsityPattern::new(4, 4, &kp, Triangle::Full).unwrap();
        let gp = [
            (0, 0),
            (0, 1),
            (1, 2),
            (1, 3),
            (2, 0),
            (2, 1),
            (2, 2),
            (2, 3),
        ];
        let g = SparsityPattern::new(3, 4, &gp, Triangle::Full).unwrap();
        for ordering in [Ordering::Amd, Ordering::NestedDissection] {
            let anchors = [Some(1), Some(3), None];
            let order = anchored_ordering(k.symbolic(), g.symbolic(), &anchors, ordering).unwrap();
            let pos = |v: usize| order.iter().position(|&x| x == v).unwrap();
            assert_eq!(order.len(), 7);
            assert_eq!(pos(4), pos(1) + 1, "{ordering:?}");
            assert_eq!(pos(5), pos(3) + 1, "{ordering:?}");
            assert_eq!(pos(6), 6, "{ordering:?}");
            let mut sorted = order.clone();
            sorted.sort_unstable();
            assert_eq!(sorted, (0..7).collect::<Vec<_>>());
            assert!(matches!(
                anchored_ordering(k.symbolic(), g.symbolic(), &[Some(9), None, None], ordering),
                Err(LinearError::BadAnchor { dof: 9, .. })
            ));
        }
    }

    #[test]
    fn a_constraint_waits_for_another_node_of_its_row_under_both_orderings() {
        // DOFs {0, 1} form one node (same G columns), {2, 3} another.
        let kp = [
            (0, 0),
            (1, 1),
            (2, 2),
            (3, 3),
            (1, 0),
            (0, 1),
            (2, 1),
            (1, 2),
            (3, 2),
            (2, 3),
        ];
        let k = SparsityPattern::new(4, 4, &kp, Triangle::Full).unwrap();
        let gp = [(0, 0), (0, 1), (0, 2), (0, 3), (1, 2), (1, 3)];
        let g = SparsityPattern::new(2, 4, &gp, Triangle::Full).unwrap();
        for ordering in [Ordering::Amd, Ordering::NestedDissection] {
            let anchors = [Some(1), Some(3)];
            let order = anchored_ordering(k.symbolic(), g.symbolic(), &anchors, ordering).unwrap();
            let pos = |v: usize| order.iter().position(|&x| x == v).unwrap();
            assert!((0..4).all(|d| pos(4) > pos(d)), "{ordering:?}: {order:?}");
            assert!(
                pos(5) > pos(2) && pos(5) > pos(3),
                "{ordering:?}: {order:?}"
            );
        }
    }
}
