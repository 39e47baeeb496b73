//! Zero-fill incomplete Cholesky, IC(0) (Meijerink and van der Vorst 1977): `L L^T ~ A`
//! with `L` on the lower-triangle pattern of `A`, the fill of exact elimination dropped.
//! Where a pivot turns non-positive (IC(0) of an SPD matrix may break down unless `A` is
//! an M-matrix), the factorization is retried on `A + alpha diag(A)` with `alpha` doubling
//! from [`FIRST_SHIFT`]: Manteuffel's shifted incomplete Cholesky (Manteuffel 1980, "An
//! incomplete factorization technique for positive definite linear systems"). Any
//! completed factorization has positive pivots, so `M = L L^T` is SPD.

use super::{LinearError, Preconditioner};
use faer::sparse::SparseColMatRef;

/// The first nonzero relative diagonal shift `alpha` tried after a breakdown.
pub const FIRST_SHIFT: f64 = 1e-3;

/// Shifted retries after the unshifted attempt (`alpha` up to `FIRST_SHIFT * 2^29 ~ 5e5`,
/// where `A + alpha diag(A)` is diagonally dominant for any FEM stiffness).
const SHIFT_RETRIES: usize = 30;

/// The IC(0) factor `L`, stored by columns with the diagonal first, then the rows below it
/// in increasing order.
#[derive(Debug, Clone)]
pub struct IncompleteCholesky {
    col_ptr: Vec<usize>,
    row_idx: Vec<usize>,
    values: Vec<f64>,
    shift: f64,
}

impl IncompleteCholesky {
    /// IC(0) of the SPD matrix whose lower triangle (`row >= col`) `a` stores (the upper
    /// one is ignored, so both triangles may be given), shifted as the module says if
    /// needed. Errors: `a` not square, a non-finite entry, a non-positive diagonal entry
    /// ([`LinearError::NotPositiveDefinite`]: no shift of `diag(A)` can help), or every
    /// shift failing.
    pub fn new(a: SparseColMatRef<'_, usize, f64>) -> Result<Self, LinearError> {
        let n = LinearError::square("incomplete Cholesky matrix", a.nrows(), a.ncols())?;
        let rows = a.symbolic().row_idx();
        let vals = a.val();
        let mut col_ptr = Vec::with_capacity(n + 1);
        col_ptr.push(0);
        let mut row_idx = Vec::new();
        let mut lower = Vec::new();
        let mut column: Vec<(usize, f64)> = Vec::new();
        for j in 0..n {
            column.clear();
            column.push((j, 0.0));
            for p in a.col_range(j) {
                if !vals[p].is_finite() {
                    return Err(LinearError::NonFiniteInput {
                        what: "incomplete Cholesky matrix",
                    });
                }
                match rows[p] {
                    i if i == j => column[0].1 += vals[p],
                    i if i > j => column.push((i, vals[p])),
                    _ => {}
                }
            }
            if column[0].1 <= 0.0 {
                return Err(LinearError::NotPositiveDefinite { pivot: j });
            }
            column[1..].sort_unstable_by_key(|&(i, _)| i);
            // Duplicates (allowed in faer's storage) are summed; the diagonal is pushed first.
            for &(i, v) in column.iter() {
                if i > j && row_idx.last() == Some(&i) {
                    *lower.last_mut().expect("an entry was pushed") += v;
                } else {
                    row_idx.push(i);
                    lower.push(v);
                }
            }
            col_ptr.push(row_idx.len());
        }
        let mut factor = IncompleteCholesky {
            col_ptr,
            row_idx,
            values: Vec::new(),
            shift: 0.0,
        };
        let mut shift = 0.0;
        for _ in 0..=SHIFT_RETRIES {
            if factor.factorize(&lower, shift) {
                factor.shift = shift;
                return Ok(factor);
            }
            shift = if shift == 0.0 {
                FIRST_SHIFT
            } else {
                2.0 * shift
            };
        }
        Err(LinearError::RegularizationFailed {
            attempts: SHIFT_RETRIES + 1,
            last_shift: shift / 2.0,
            last_error: Box::new(LinearError::Breakdown {
                method: "incomplete Cholesky",
                iterations: 0,
                reason: "a pivot stayed non-positive",
            }),
        })
    }

    /// The relative diagonal shift `alpha` the factorization needed (0 if none).
    pub fn shift(&self) -> f64 {
        self.shift
    }

    /// Right-looking IC(0) of `lower + alpha diag(lower)` into `self.values`; `false` on a
    /// non-positive pivot.
    fn factorize(&mut self, lower: &[f64], alpha: f64) -> bool {
        let (cp, ri) = (&self.col_ptr, &self.row_idx);
        let l = &mut self.values;
        l.clear();
        l.extend_from_slice(lower);
        for j in 0..cp.len() - 1 {
            l[cp[j]] *= 1.0 + alpha;
        }
        for j in 0..cp.len() - 1 {
            let pivot = l[cp[j]];
            if !(pivot > 0.0 && pivot.is_finite()) {
                return false;
            }
            let ljj = pivot.sqrt();
            l[cp[j]] = ljj;
            l[cp[j] + 1..cp[j + 1]].iter_mut().for_each(|v| *v /= ljj);
            // Column k > j loses L_ik L_kj for every row i >= k of column j that column k
            // stores (both lists ascend: a merge; fill outside the pattern is dropped).
            for p in cp[j] + 1..cp[j + 1] {
                let (k, lkj) = (ri[p], l[p]);
                let mut q = cp[k];
                for s in p..cp[j + 1] {
                    let i = ri[s];
                    while q < cp[k + 1] && ri[q] < i {
                        q += 1;
                    }
                    if q == cp[k + 1] {
                        break;
                    }
                    if ri[q] == i {
                        l[q] -= l[s] * lkj;
                    }
                }
            }
        }
        true
    }
}

impl Preconditioner for IncompleteCholesky {
    fn dim(&self) -> usize {
        self.col_ptr.len() - 1
    }

    /// `z = L^-T L^-1 r`.
    fn apply(&self, r: &[f64], z: &mut [f64]) {
        let (cp, ri, l) = (&self.col_ptr, &self.row_idx, &self.values);
        z.copy_from_slice(r);
        for j in 0..self.dim() {
            let zj = z[j] / l[cp[j]];
            z[j] = zj;
            for p in cp[j] + 1..cp[j + 1] {
                z[ri[p]] -= l[p] * zj;
            }
        }
        for j in (0..self.dim()).rev() {
            let mut s = z[j];
            for p in cp[j] + 1..cp[j + 1] {
                s -= l[p] * z[ri[p]];
            }
            z[j] = s / l[cp[j]];
        }
    }
}
