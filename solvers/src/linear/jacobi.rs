//! Diagonal (Jacobi) scaling of SPD and saddle-point systems. Sec. 8 of Francu et al.
//! 2021: CR and CG "required diagonal pre-conditioning ... because the constraint
//! equation needs to be scaled several orders of magnitude to match the force balance
//! equation". The constraint rows are scaled by the diagonal of the Schur complement
//! estimate `G diag(K)^-1 G^T + C` (the approximation of eq. 38 by `diag(K)`).

use super::Preconditioner;
use faer::sparse::SparseColMatRef;

/// The diagonal of a square sparse matrix (zeros where no entry is stored).
pub fn diagonal(a: SparseColMatRef<'_, usize, f64>) -> Vec<f64> {
    let rows = a.symbolic().row_idx();
    let vals = a.val();
    let mut d = vec![0.0; a.nrows().min(a.ncols())];
    for (j, dj) in d.iter_mut().enumerate() {
        for p in a.col_range(j) {
            if rows[p] == j {
                *dj += vals[p];
            }
        }
    }
    d
}

/// Positive scale of every row of `[[K, G^T], [G, -C]]`: `|K_ii|` for the `n`
/// displacement rows, `sum_j G_ij^2 / |K_jj| + |C_ii|` for the `m` constraint rows.
/// Zero or non-finite scales are replaced by 1.
pub fn saddle_point_diagonal(
    k_diag: &[f64],
    g: SparseColMatRef<'_, usize, f64>,
    c_diag: Option<&[f64]>,
) -> Vec<f64> {
    let n = k_diag.len();
    let m = g.nrows();
    let fix = |d: f64| if d > 0.0 && d.is_finite() { d } else { 1.0 };
    let mut d = Vec::with_capacity(n + m);
    d.extend(k_diag.iter().map(|k| fix(k.abs())));
    d.extend(std::iter::repeat_n(0.0, m));
    let rows = g.symbolic().row_idx();
    let vals = g.val();
    for j in 0..g.ncols().min(n) {
        for q in g.col_range(j) {
            d[n + rows[q]] += vals[q] * vals[q] / d[j];
        }
    }
    if let Some(c) = c_diag {
        d[n..]
            .iter_mut()
            .zip(c)
            .for_each(|(di, ci)| *di += ci.abs());
    }
    d[n..].iter_mut().for_each(|di| *di = fix(*di));
    d
}

/// The Jacobi preconditioner `M^-1 = diag(d)^-1` for a positive diagonal `d`.
#[derive(Debug, Clone, PartialEq)]
pub struct Jacobi {
    inv_diag: Vec<f64>,
}

impl Jacobi {
    /// From a diagonal; absolute values are used and zero or non-finite entries become 1,
    /// so the preconditioner is always SPD (as MINRES requires).
    pub fn from_diagonal(d: &[f64]) -> Self {
        let inv_diag = d
            .iter()
            .map(|x| {
                let a = x.abs();
                if a > 0.0 && a.is_finite() {
                    1.0 / a
                } else {
                    1.0
                }
            })
            .collect();
        Self { inv_diag }
    }

    /// The identity (no preconditioning) of dimension `n`.
    pub fn identity(n: usize) -> Self {
        Self {
            inv_diag: vec![1.0; n],
        }
    }
}

impl Preconditioner for Jacobi {
    fn dim(&self) -> usize {
        self.inv_diag.len()
    }

    fn apply(&self, r: &[f64], z: &mut [f64]) {
        z.iter_mut()
            .zip(r.iter().zip(&self.inv_diag))
            .for_each(|(zi, (ri, di))| *zi = ri * di);
    }
}
