//! Matrix-free linear operators `y = A x`, so that the iterative solvers can apply `K`
//! as a sparse matrix (or as force differentials) and `G`, `G^T` separately, as the
//! conjugate-residual solver of sec. 8 of Francu et al. 2021 does.

use faer::sparse::SparseColMatRef;

/// A linear map `y = A x` on `f64` vectors.
pub trait LinearOperator {
    /// Length of `y`.
    fn nrows(&self) -> usize;
    /// Length of `x`.
    fn ncols(&self) -> usize;
    /// Overwrites `y` with `A x`. Callers pass slices of lengths `ncols` and `nrows`.
    fn apply(&self, x: &[f64], y: &mut [f64]);
}

/// A general sparse matrix, all stored entries used.
impl LinearOperator for SparseColMatRef<'_, usize, f64> {
    fn nrows(&self) -> usize {
        self.symbolic().nrows()
    }

    fn ncols(&self) -> usize {
        self.symbolic().ncols()
    }

    fn apply(&self, x: &[f64], y: &mut [f64]) {
        y.fill(0.0);
        let rows = self.symbolic().row_idx();
        let vals = self.val();
        for (j, &xj) in x.iter().enumerate().take(self.symbolic().ncols()) {
            for p in self.col_range(j) {
                y[rows[p]] += vals[p] * xj;
            }
        }
    }
}

/// A symmetric matrix of which only the lower triangle (`row >= col`) is read, as the
/// patterns of [`super::Triangle::Lower`] store it.
#[derive(Debug, Clone, Copy)]
pub struct SymmetricLower<'a>(pub SparseColMatRef<'a, usize, f64>);

impl LinearOperator for SymmetricLower<'_> {
    fn nrows(&self) -> usize {
        self.0.nrows()
    }

    fn ncols(&self) -> usize {
        self.0.ncols()
    }

    fn apply(&self, x: &[f64], y: &mut [f64]) {
        y.fill(0.0);
        let rows = self.0.symbolic().row_idx();
        let vals = self.0.val();
        for j in 0..self.0.ncols() {
            let mut yj = 0.0;
            for p in self.0.col_range(j) {
                let i = rows[p];
                if i > j {
                    y[i] += vals[p] * x[j];
                    yj += vals[p] * x[i];
                } else if i == j {
                    yj += vals[p] * x[j];
                }
            }
            y[j] += yj;
        }
    }
}

/// The saddle-point operator `[[K, G^T], [G, -C]]` of eq. 21/24 acting on `(u, p)`,
/// `u` of length `n` and `p` of length `m`. `C = None` means `C = 0` (`nu = 0.5`).
#[derive(Clone, Copy)]
pub struct SaddlePoint<'a> {
    /// The `n x n` stiffness block (any symmetric operator).
    pub k: &'a dyn LinearOperator,
    /// The `m x n` constraint Jacobian.
    pub g: SparseColMatRef<'a, usize, f64>,
    /// The `m x m` compliance block, or `None` for `C = 0`.
    pub c: Option<&'a dyn LinearOperator>,
}

impl LinearOperator for SaddlePoint<'_> {
    fn nrows(&self) -> usize {
        self.k.nrows() + self.g.nrows()
    }

    fn ncols(&self) -> usize {
        self.nrows()
    }

    fn apply(&self, x: &[f64], y: &mut [f64]) {
        let n = self.k.nrows();
        let (xu, xp) = x.split_at(n);
        let (yu, yp) = y.split_at_mut(n);
        self.k.apply(xu, yu);
        match self.c {
            Some(c) => {
                c.apply(xp, yp);
                yp.iter_mut().for_each(|v| *v = -*v);
            }
            None => yp.fill(0.0),
        }
        // One pass over the columns of G gives both G u and G^T p.
        let rows = self.g.symbolic().row_idx();
        let vals = self.g.val();
        for (j, yuj) in yu.iter_mut().enumerate() {
            let mut acc = 0.0;
            for q in self.g.col_range(j) {
                let i = rows[q];
                yp[i] += vals[q] * xu[j];
                acc += vals[q] * xp[i];
            }
            *yuj += acc;
        }
    }
}

/// Euclidean norm.
pub(crate) fn norm(v: &[f64]) -> f64 {
    v.iter().map(|x| x * x).sum::<f64>().sqrt()
}

/// Relative residual `|b - A x| / |b|` (absolute if `b = 0`).
pub fn relative_residual(a: &dyn LinearOperator, x: &[f64], b: &[f64]) -> f64 {
    let mut r = vec![0.0; b.len()];
    a.apply(x, &mut r);
    r.iter_mut().zip(b).for_each(|(ri, bi)| *ri = bi - *ri);
    let nb = norm(b);
    norm(&r) / if nb > 0.0 { nb } else { 1.0 }
}
