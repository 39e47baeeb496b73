//! A sparsity pattern built once from `(row, col)` pairs with duplicates, refilled with
//! new values every Newton iteration (patterns built once, values refilled: docs/toolchain.md).
//!
//! Every input pair gets a precomputed *slot* in the compressed-column value array, so a
//! refill is a zeroing pass plus one scatter-add per input value, with no sorting.

use super::LinearError;
use faer::sparse::{SparseColMat, SymbolicSparseColMat, SymbolicSparseColMatRef};

/// Which entries of the input a pattern keeps.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Triangle {
    /// Every entry (general matrices such as `G`).
    Full,
    /// Only `row >= col` of a square symmetric matrix given with both triangles, as the
    /// quadrature kernels emit it. The factorizations of this module read the lower
    /// triangle (`faer::Side::Lower`); entries above the diagonal are skipped on refill.
    Lower,
}

/// Slot marking an input entry that the pattern does not store (upper triangle).
const SKIPPED: usize = usize::MAX;

/// A fixed compressed-column pattern plus the slot of every input pair.
#[derive(Debug, Clone)]
pub struct SparsityPattern {
    symbolic: SymbolicSparseColMat<usize>,
    slots: Vec<usize>,
    triangle: Triangle,
}

impl SparsityPattern {
    /// Builds the pattern of an `nrows x ncols` matrix from `pairs` (duplicates allowed,
    /// any order). For [`Triangle::Lower`] the matrix must be square.
    pub fn new(
        nrows: usize,
        ncols: usize,
        pairs: &[(usize, usize)],
        triangle: Triangle,
    ) -> Result<Self, LinearError> {
        if triangle == Triangle::Lower && nrows != ncols {
            return Err(LinearError::NotSquare {
                what: "symmetric pattern",
                nrows,
                ncols,
            });
        }
        let keep = |&(r, c): &(usize, usize)| triangle == Triangle::Full || r >= c;
        let mut col_count = vec![0usize; ncols + 1];
        for &(row, col) in pairs {
            if row >= nrows || col >= ncols {
                return Err(LinearError::IndexOutOfBounds {
                    row,
                    col,
                    nrows,
                    ncols,
                });
            }
            if keep(&(row, col)) {
                col_count[col + 1] += 1;
            }
        }
        for j in 0..ncols {
            col_count[j + 1] += col_count[j];
        }
        // Counting sort of the kept input indices by column.
        let mut next = col_count.clone();
        let mut by_col = vec![0usize; col_count[ncols]];
        for (k, pair) in pairs.iter().enumerate() {
            if keep(pair) {
                by_col[next[pair.1]] = k;
                next[pair.1] += 1;
            }
        }
        // Per column: the distinct rows (marked with the column's stamp), sorted, then each
        // input entry's slot through the row's position. Sorting the few distinct rows
        // rather than every duplicate entry (an element mesh repeats each entry once per
        // element around it) is what keeps this linear in the input.
        let mut slots = vec![SKIPPED; pairs.len()];
        let mut col_ptr = Vec::with_capacity(ncols + 1);
        let mut row_idx = Vec::new();
        let mut stamp = vec![usize::MAX; nrows];
        let mut position = vec![0usize; nrows];
        col_ptr.push(0);
        for j in 0..ncols {
            let bucket = &by_col[col_count[j]..col_count[j + 1]];
            let start = row_idx.len();
            for &k in bucket {
                let row = pairs[k].0;
                if stamp[row] != j {
                    stamp[row] = j;
                    row_idx.push(row);
                }
            }
            row_idx[start..].sort_unstable();
            for (slot, &row) in row_idx[start..].iter().enumerate() {
                position[row] = start + slot;
            }
            for &k in bucket {
                slots[k] = position[pairs[k].0];
            }
            col_ptr.push(row_idx.len());
        }
        let symbolic = SymbolicSparseColMat::new_checked(nrows, ncols, col_ptr, None, row_idx);
        Ok(Self {
            symbolic,
            slots,
            triangle,
        })
    }

    /// A pattern from its compressed-column structure (`col_ptr`, sorted `row_idx`) and the
    /// slot of every input, all stored: for builders that know the structure.
    pub(crate) fn from_parts(
        nrows: usize,
        ncols: usize,
        col_ptr: Vec<usize>,
        row_idx: Vec<usize>,
        slots: Vec<usize>,
        triangle: Triangle,
    ) -> Self {
        let symbolic = SymbolicSparseColMat::new_checked(nrows, ncols, col_ptr, None, row_idx);
        Self {
            symbolic,
            slots,
            triangle,
        }
    }

    /// The stored (deduplicated) structure.
    pub fn symbolic(&self) -> SymbolicSparseColMatRef<'_, usize> {
        self.symbolic.as_ref()
    }

    /// Which triangle is stored.
    pub fn triangle(&self) -> Triangle {
        self.triangle
    }

    /// Number of input pairs (the length of the value arrays to assemble).
    pub fn num_inputs(&self) -> usize {
        self.slots.len()
    }

    /// Number of stored entries.
    pub fn nnz(&self) -> usize {
        self.symbolic.row_idx().len()
    }

    /// Position in the stored value array of input pair `k`, or `None` if the pair is
    /// not stored (upper triangle of a [`Triangle::Lower`] pattern) or out of range.
    pub fn slot(&self, k: usize) -> Option<usize> {
        self.slots.get(k).copied().filter(|&s| s != SKIPPED)
    }

    /// A matrix with this pattern and all values zero.
    pub fn zeros(&self) -> SparseColMat<usize, f64> {
        SparseColMat::new(self.symbolic.clone(), vec![0.0; self.nnz()])
    }

    /// Assembles a new matrix from one value per input pair, summing duplicates.
    pub fn assemble(&self, values: &[f64]) -> Result<SparseColMat<usize, f64>, LinearError> {
        let mut out = self.zeros();
        self.assemble_into(values, &mut out)?;
        Ok(out)
    }

    /// Overwrites the values of `out` (a matrix made by [`Self::zeros`] or
    /// [`Self::assemble`]) with the sum of `values` per stored entry.
    pub fn assemble_into(
        &self,
        values: &[f64],
        out: &mut SparseColMat<usize, f64>,
    ) -> Result<(), LinearError> {
        if out.symbolic().row_idx().len() != self.nnz()
            || out.nrows() != self.symbolic.nrows()
            || out.ncols() != self.symbolic.ncols()
        {
            return Err(LinearError::PatternMismatch {
                what: "assembly target",
            });
        }
        let vals = out.val_mut();
        vals.fill(0.0);
        self.scatter_add(0, values, 1.0, vals)
    }

    /// Adds `scale * values[i]` into `out[slot(first + i)]`: the building block of
    /// [`Self::assemble_into`], usable to fill one pattern from several value sources
    /// (for instance elastic and geometric stiffness) without concatenating them.
    pub fn scatter_add(
        &self,
        first: usize,
        values: &[f64],
        scale: f64,
        out: &mut [f64],
    ) -> Result<(), LinearError> {
        let slots = first
            .checked_add(values.len())
            .and_then(|end| self.slots.get(first..end))
            .ok_or(LinearError::DimensionMismatch {
                what: "values past the end of the pattern inputs",
                expected: self.slots.len().saturating_sub(first),
                got: values.len(),
            })?;
        if out.len() != self.nnz() {
            return Err(LinearError::DimensionMismatch {
                what: "stored values",
                expected: self.nnz(),
                got: out.len(),
            });
        }
        for (&s, &v) in slots.iter().zip(values) {
            if s != SKIPPED {
                out[s] += scale * v;
            }
        }
        Ok(())
    }
}

/// The `(row, col)` pairs of a compressed-column structure in storage order, so that
/// the `k`-th pair belongs to `val()[k]`. Uncompressed storage (explicit column counts)
/// is rejected.
pub fn entry_pairs(
    a: SymbolicSparseColMatRef<'_, usize>,
    what: &'static str,
) -> Result<Vec<(usize, usize)>, LinearError> {
    if a.col_nnz().is_some() {
        return Err(LinearError::PatternMismatch { what });
    }
    let rows = a.row_idx();
    Ok((0..a.ncols())
        .flat_map(|j| a.col_range(j).map(move |p| (rows[p], j)))
        .collect())
}

/// An owned copy of a structure, to check later that a matrix has the analysed pattern.
pub(crate) fn copy_structure(a: SymbolicSparseColMatRef<'_, usize>) -> SymbolicSparseColMat<usize> {
    SymbolicSparseColMat::new_checked(
        a.nrows(),
        a.ncols(),
        a.col_ptr().to_vec(),
        a.col_nnz().map(<[usize]>::to_vec),
        a.row_idx().to_vec(),
    )
}

/// Whether two structures store the same entries in the same order.
pub(crate) fn same_structure(
    a: SymbolicSparseColMatRef<'_, usize>,
    b: SymbolicSparseColMatRef<'_, usize>,
) -> bool {
    a.nrows() == b.nrows()
        && a.ncols() == b.ncols()
        && (0..a.ncols()).all(|j| a.row_idx()[a.col_range(j)] == b.row_idx()[b.col_range(j)])
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Deterministic pseudo-random numbers (xorshift), enough for test inputs.
    fn rng(seed: &mut u64) -> u64 {
        *seed ^= *seed << 13;
        *seed ^= *seed >> 7;
        *seed ^= *seed << 17;
        *seed
    }

    #[test]
    fn assembly_matches_dense_reference_with_duplicates() {
        let (nrows, ncols) = (13, 9);
        let mut seed = 0x9e3779b97f4a7c15;
        let pairs: Vec<(usize, usize)> = (0..400)
            .map(|_| {
                (
                    (rng(&mut seed) % nrows as u64) as usize,
                    (rng(&mut seed) % ncols as u64) as usize,
                )
            })
            .collect();
        let values: Vec<f64> = (0..pairs.len())
            .map(|_| (rng(&mut seed) % 1000) as f64 / 100.0 - 5.0)
            .collect();
        let pattern = SparsityPattern::new(nrows, ncols, &pairs, Triangle::Full).unwrap();
        let mut dense = vec![vec![0.0; ncols]; nrows];
        for (&(r, c), &v) in pairs.iter().zip(&values) {
            dense[r][c] += v;
        }
        let mat = pattern.assemble(&values).unwrap();
        let got = mat.to_dense();
        for (r, row) in dense.iter().enumerate() {
            for (c, &want) in row.iter().enumerate() {
                assert!((got[(r, c)] - want).abs() < 1e-12, "({r}, {c})");
            }
        }
        // Refill in place with new values gives the new sum.
        let mut mat = mat;
        let doubled: Vec<f64> = values.iter().map(|v| 2.0 * v).collect();
        pattern.assemble_into(&doubled, &mut mat).unwrap();
        let got = mat.to_dense();
        assert!((got[(3, 4)] - 2.0 * dense[3][4]).abs() < 1e-12);
    }

    #[test]
    fn lower_pattern_keeps_lower_triangle_only() {
        let pairs = [(0, 0), (1, 0), (0, 1), (1, 1), (2, 1), (1, 2), (1, 0)];
        let pattern = SparsityPattern::new(3, 3, &pairs, Triangle::Lower).unwrap();
        assert_eq!(pattern.nnz(), 4);
        assert_eq!(pattern.slot(2), None);
        let m = pattern
            .assemble(&[1.0, 2.0, 2.0, 3.0, 4.0, 4.0, 0.5])
            .unwrap()
            .to_dense();
        assert_eq!(m[(1, 0)], 2.5);
        assert_eq!(m[(0, 1)], 0.0);
        assert_eq!(m[(2, 1)], 4.0);
    }

    #[test]
    fn bad_input_is_an_error() {
        assert!(matches!(
            SparsityPattern::new(2, 2, &[(2, 0)], Triangle::Full),
            Err(LinearError::IndexOutOfBounds { .. })
        ));
        assert!(matches!(
            SparsityPattern::new(2, 3, &[], Triangle::Lower),
            Err(LinearError::NotSquare { .. })
        ));
        let p = SparsityPattern::new(2, 2, &[(0, 0)], Triangle::Full).unwrap();
        assert!(p.assemble(&[1.0, 2.0]).is_err());
    }
}
