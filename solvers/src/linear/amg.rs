//! Smoothed-aggregation algebraic multigrid (Vanek, Mandel and Brezina 1996, "Algebraic
//! multigrid by smoothed aggregation for second and fourth order elliptic problems"), one
//! V-cycle per application as the SPD preconditioner of CG and of the `K` block of MINRES.
//!
//! Setup, level by level until at most [`COARSEST`] unknowns: aggregates and the tentative
//! prolongator from the near null space (the rigid-body modes, `aggregation.rs`), the
//! smoothed prolongator `P = (I - omega D^-1 A) P_t` with `omega = 4 / (3 rho(D^-1 A))`, and
//! the Galerkin coarse matrix `A_c = P^T A P`; the coarsest level is factorized densely.
//! The cycle smooths with the same Chebyshev polynomial before and after the coarse
//! correction (`chebyshev.rs`), so `M^-1` is symmetric; for SPD `A` it is positive definite
//! because the smoother converges in the energy norm (its interval reaches Gershgorin's bound
//! on the spectrum).
//!
//! Unlike IC(0), whose Krylov iterations grow like `1 / h`, the V-cycle's iteration count
//! stays nearly constant under refinement (`solvers/tests/preconditioners.rs` measures both).

use super::aggregation::{tentative, NearNullSpace, FINEST_STRENGTH};
use super::chebyshev::{multiply, Chebyshev};
use super::{LinearError, Preconditioner};
use faer::sparse::SparseColMatRef;
use nalgebra::{Cholesky, DMatrix, DVector, Dyn};
use sprs::{CsMat, TriMat};

/// Coarsening stops at this many unknowns.
pub const COARSEST: usize = 500;

/// The coarsest level is factorized densely; a hierarchy whose coarsening stalls above this
/// size is refused rather than factorized at `O(n^3)`.
const DENSE_LIMIT: usize = 5000;

/// Levels at most (coarsening by aggregation shrinks each level about tenfold).
const MAX_LEVELS: usize = 20;

/// One level above the coarsest: its matrix, prolongator, restriction and smoother.
#[derive(Debug)]
struct Level {
    a: CsMat<f64>,
    p: CsMat<f64>,
    restriction: CsMat<f64>,
    smoother: Chebyshev,
}

/// The multigrid hierarchy of an SPD matrix.
#[derive(Debug)]
pub struct SmoothedAggregation {
    levels: Vec<Level>,
    coarsest: Cholesky<f64, Dyn>,
}

impl SmoothedAggregation {
    /// The hierarchy of the SPD matrix whose lower triangle `k` stores (the upper one is
    /// ignored), with the near null space `space` on its DOFs. Errors: `k` not square or of
    /// another dimension than `space`, a non-finite entry, a non-positive diagonal entry, a
    /// coarsest matrix that is not positive definite, or coarsening that stalls.
    pub fn new(
        k: SparseColMatRef<'_, usize, f64>,
        space: NearNullSpace,
    ) -> Result<Self, LinearError> {
        let n = LinearError::square("multigrid matrix", k.nrows(), k.ncols())?;
        if space.dim() != n {
            return Err(LinearError::DimensionMismatch {
                what: "multigrid near null space rows",
                expected: n,
                got: space.dim(),
            });
        }
        let mut a = full_symmetric(k)?;
        let mut space = space;
        let mut epsilon = FINEST_STRENGTH;
        let mut levels = Vec::new();
        while a.rows() > COARSEST && levels.len() + 1 < MAX_LEVELS {
            let inverse_diagonal = inverse_diagonal(&a)?;
            let smoother = Chebyshev::new(&a, inverse_diagonal.clone());
            let tentative = tentative(&a, &space, epsilon);
            if tentative.prolongator.cols() >= a.rows() {
                break;
            }
            let omega = 4.0 / (3.0 * smoother.spectral_radius());
            let mut correction = &a * &tentative.prolongator;
            scale_rows(&mut correction, |i| omega * inverse_diagonal[i]);
            let p = &tentative.prolongator - &correction;
            let restriction = p.transpose_view().to_csr();
            let coarse = &restriction * &(&a * &p);
            levels.push(Level {
                a,
                p,
                restriction,
                smoother,
            });
            a = coarse;
            space = tentative.coarse;
            epsilon *= 0.5;
        }
        if a.rows() > DENSE_LIMIT {
            return Err(LinearError::Multigrid(format!(
                "coarsening stalled at {} unknowns after {} levels",
                a.rows(),
                levels.len()
            )));
        }
        let mut dense = DMatrix::zeros(a.rows(), a.cols());
        for (i, row) in a.outer_iterator().enumerate() {
            for (j, v) in row.iter() {
                dense[(i, j)] += 0.5 * v;
                dense[(j, i)] += 0.5 * v;
            }
        }
        let coarsest = Cholesky::new(dense).ok_or_else(|| {
            LinearError::Multigrid(format!(
                "the coarsest matrix ({} unknowns) is not positive definite",
                a.rows()
            ))
        })?;
        Ok(SmoothedAggregation { levels, coarsest })
    }

    /// Unknowns per level, finest first, the coarsest last.
    pub fn level_sizes(&self) -> Vec<usize> {
        let mut sizes: Vec<usize> = self.levels.iter().map(|l| l.a.rows()).collect();
        sizes.push(self.coarsest.l_dirty().nrows());
        sizes
    }

    /// One V-cycle on `A x = b` from `x = 0` at `level`.
    fn cycle(&self, level: usize, b: &[f64], x: &mut [f64]) {
        let Some(l) = self.levels.get(level) else {
            let solution = self.coarsest.solve(&DVector::from_column_slice(b));
            x.copy_from_slice(solution.as_slice());
            return;
        };
        x.fill(0.0);
        l.smoother.smooth(&l.a, b, x);
        let mut r = vec![0.0; b.len()];
        multiply(&l.a, x, &mut r);
        r.iter_mut().zip(b).for_each(|(ri, bi)| *ri = bi - *ri);
        let mut coarse_r = vec![0.0; l.restriction.rows()];
        multiply(&l.restriction, &r, &mut coarse_r);
        let mut coarse_x = vec![0.0; coarse_r.len()];
        self.cycle(level + 1, &coarse_r, &mut coarse_x);
        multiply(&l.p, &coarse_x, &mut r);
        x.iter_mut().zip(&r).for_each(|(xi, ci)| *xi += ci);
        l.smoother.smooth(&l.a, b, x);
    }
}

impl Preconditioner for SmoothedAggregation {
    fn dim(&self) -> usize {
        self.levels
            .first()
            .map_or(self.coarsest.l_dirty().nrows(), |l| l.a.rows())
    }

    fn apply(&self, r: &[f64], z: &mut [f64]) {
        self.cycle(0, r, z);
    }
}

/// Both triangles of the symmetric matrix whose lower triangle `k` stores, as CSR.
fn full_symmetric(k: SparseColMatRef<'_, usize, f64>) -> Result<CsMat<f64>, LinearError> {
    let n = k.nrows();
    let rows = k.symbolic().row_idx();
    let values = k.val();
    let mut triplets = TriMat::new((n, n));
    for j in 0..n {
        for p in k.col_range(j) {
            let (i, v) = (rows[p], values[p]);
            if !v.is_finite() {
                return Err(LinearError::NonFiniteInput {
                    what: "multigrid matrix",
                });
            }
            if i > j {
                triplets.add_triplet(i, j, v);
                triplets.add_triplet(j, i, v);
            } else if i == j {
                triplets.add_triplet(i, i, v);
            }
        }
    }
    Ok(triplets.to_csr())
}

/// `1 / A_ii`; a non-positive diagonal entry means `A` is not SPD.
fn inverse_diagonal(a: &CsMat<f64>) -> Result<Vec<f64>, LinearError> {
    a.outer_iterator()
        .enumerate()
        .map(|(i, row)| {
            let d = row.get(i).copied().unwrap_or(0.0);
            if d > 0.0 {
                Ok(1.0 / d)
            } else {
                Err(LinearError::NotPositiveDefinite { pivot: i })
            }
        })
        .collect()
}

/// Multiplies row `i` of `a` by `factor(i)`.
fn scale_rows(a: &mut CsMat<f64>, factor: impl Fn(usize) -> f64) {
    for (i, mut row) in a.outer_iterator_mut().enumerate() {
        let f = factor(i);
        row.iter_mut().for_each(|(_, v)| *v *= f);
    }
}
