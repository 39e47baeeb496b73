//! Sparse Cholesky `LL^T` for SPD systems (standard FEM stiffness, condensed systems of
//! eq. 37): the fill-reducing ordering and symbolic factorization are computed once per
//! pattern and reused by every numeric refactorization.

use super::fill_reducing::fill_reducing;
use super::operator::{norm, LinearOperator, SymmetricLower};
use super::pattern::{copy_structure, entry_pairs, same_structure};
use super::{
    Factorization, LinearError, Ordering, ShiftSchedule, SolveReport, SparsityPattern, Triangle,
};
use faer::dyn_stack::{MemBuffer, MemStack};
use faer::linalg::cholesky::llt::factor::LltRegularization;
use faer::perm::PermRef;
use faer::sparse::linalg::cholesky::{
    factorize_symbolic_cholesky, LltRef, SymbolicCholesky, SymmetricOrdering,
};
use faer::sparse::{SparseColMat, SparseColMatRef, SymbolicSparseColMat, SymbolicSparseColMatRef};
use faer::{Conj, MatMut, Side};
use std::time::Instant;

/// `LL^T` solver for a fixed pattern of a symmetric matrix `K`, given with both
/// triangles or only the lower one (only `row >= col` is read).
#[derive(Debug)]
pub struct CholeskySolver {
    /// Structure of `K` as the caller stores it, to check later matrices against.
    structure: SymbolicSparseColMat<usize>,
    /// Lower triangle of `K` plus every diagonal entry (where shifts go).
    lower: SparsityPattern,
    /// `K + shift I`, lower triangle, as factorized.
    matrix: SparseColMat<usize, f64>,
    symbolic: SymbolicCholesky<usize>,
    factor: Vec<f64>,
    factorized: bool,
    report: SolveReport,
}

impl CholeskySolver {
    /// Symbolic analysis (fill-reducing ordering chosen by size, elimination tree,
    /// supernodes) of the pattern of `K`.
    pub fn new(k: SymbolicSparseColMatRef<'_, usize>) -> Result<Self, LinearError> {
        Self::with_ordering(k, Ordering::default())
    }

    /// Symbolic analysis of the pattern of `K` under the fill-reducing `ordering`.
    pub fn with_ordering(
        k: SymbolicSparseColMatRef<'_, usize>,
        ordering: Ordering,
    ) -> Result<Self, LinearError> {
        let start = Instant::now();
        let n = LinearError::square("K", k.nrows(), k.ncols())?;
        let mut pairs = entry_pairs(k, "K (uncompressed storage)")?;
        pairs.extend((0..n).map(|i| (i, i)));
        let lower = SparsityPattern::new(n, n, &pairs, Triangle::Lower)?;
        let ordering = ordering.resolve(n);
        // AMD is faer's built-in (the same algorithm and control as `Ordering::Amd`
        // elsewhere); other orderings are handed in as a permutation.
        let permutation = match ordering {
            Ordering::Amd => None,
            _ => Some(fill_reducing(lower.symbolic(), ordering)?),
        };
        let symbolic = factorize_symbolic_cholesky(
            lower.symbolic(),
            Side::Lower,
            match &permutation {
                Some((fwd, inv)) => SymmetricOrdering::Custom(PermRef::new_checked(fwd, inv, n)),
                None => SymmetricOrdering::Amd,
            },
            Default::default(),
        )?;
        let report = SolveReport {
            factorization: Factorization::Cholesky,
            symbolic_time: start.elapsed(),
            factor_nnz: symbolic.len_val(),
            ordering,
            residual: f64::NAN,
            ..Default::default()
        };
        Ok(Self {
            structure: copy_structure(k),
            matrix: lower.zeros(),
            factor: vec![0.0; symbolic.len_val()],
            lower,
            symbolic,
            factorized: false,
            report,
        })
    }

    /// Dimension `n`.
    pub fn dim(&self) -> usize {
        self.structure.nrows()
    }

    /// Numeric factorization of `K + shift I` (`shift` absolute, usually 0). `K` must
    /// have the pattern given to [`Self::new`]. A matrix that is not SPD gives
    /// [`LinearError::NotPositiveDefinite`]; see [`Self::factorize_with_shifts`].
    pub fn factorize(
        &mut self,
        k: SparseColMatRef<'_, usize, f64>,
        shift: f64,
    ) -> Result<(), LinearError> {
        let start = Instant::now();
        self.factorized = false;
        if !same_structure(k.symbolic(), self.structure.as_ref()) {
            return Err(LinearError::PatternMismatch { what: "K" });
        }
        if !shift.is_finite() || k.val().iter().any(|v| !v.is_finite()) {
            return Err(LinearError::NonFiniteInput { what: "K" });
        }
        let n = self.dim();
        let nnz_k = k.val().len();
        let vals = self.matrix.val_mut();
        vals.fill(0.0);
        self.lower.scatter_add(0, k.val(), 1.0, vals)?;
        for i in 0..n {
            if let Some(s) = self.lower.slot(nnz_k + i) {
                vals[s] += shift;
            }
        }
        let par = faer::get_global_parallelism();
        let params = Default::default();
        let mut mem = MemBuffer::try_new(
            self.symbolic
                .factorize_numeric_llt_scratch::<f64>(par, params),
        )
        .map_err(|_| LinearError::Faer("out of memory".into()))?;
        let result = self.symbolic.factorize_numeric_llt(
            &mut self.factor,
            self.matrix.as_ref(),
            Side::Lower,
            LltRegularization::default(),
            par,
            MemStack::new(&mut mem),
            params,
        );
        self.report.numeric_time = start.elapsed();
        self.report.factorizations = 1;
        self.report.shift = shift;
        match result {
            Ok(_) => {
                self.factorized = true;
                Ok(())
            }
            Err(e) => Err(LinearError::NotPositiveDefinite {
                pivot: match e {
                    faer::linalg::cholesky::llt::factor::LltError::NonPositivePivot { index } => {
                        index
                    }
                },
            }),
        }
    }

    /// Factorizes `K + shift I` for the shifts of `schedule` (relative to `max |K_ii|`)
    /// until one is positive definite; returns the absolute shift used (0 if `K` is SPD).
    pub fn factorize_with_shifts(
        &mut self,
        k: SparseColMatRef<'_, usize, f64>,
        schedule: &ShiftSchedule,
    ) -> Result<f64, LinearError> {
        let scale = super::max_abs_diagonal(k);
        let start = Instant::now();
        let mut attempts = 0;
        let result = schedule.retry(scale, |shift| {
            attempts += 1;
            self.factorize(k, shift)
        });
        self.report.numeric_time = start.elapsed();
        self.report.factorizations = attempts;
        result.map(|((), shift)| shift)
    }

    /// Solves `(K + shift I) x = b` in place (`rhs` holds `b` on entry, `x` on return),
    /// recording the relative residual in the report.
    pub fn solve_in_place(&mut self, rhs: &mut [f64]) -> Result<(), LinearError> {
        let start = Instant::now();
        if !self.factorized {
            return Err(LinearError::NotFactorized);
        }
        let n = self.dim();
        if rhs.len() != n {
            return Err(LinearError::DimensionMismatch {
                what: "right-hand side",
                expected: n,
                got: rhs.len(),
            });
        }
        if rhs.iter().any(|v| !v.is_finite()) {
            return Err(LinearError::NonFiniteInput {
                what: "right-hand side",
            });
        }
        let b = rhs.to_vec();
        let par = faer::get_global_parallelism();
        let mut mem = MemBuffer::try_new(self.symbolic.solve_in_place_scratch::<f64>(1, par))
            .map_err(|_| LinearError::Faer("out of memory".into()))?;
        LltRef::new(&self.symbolic, &self.factor).solve_in_place_with_conj(
            Conj::No,
            MatMut::from_column_major_slice_mut(rhs, n, 1),
            par,
            MemStack::new(&mut mem),
        );
        if rhs.iter().any(|v| !v.is_finite()) {
            return Err(LinearError::NonFiniteSolution);
        }
        let mut r = vec![0.0; n];
        SymmetricLower(self.matrix.as_ref()).apply(rhs, &mut r);
        r.iter_mut().zip(&b).for_each(|(ri, bi)| *ri -= bi);
        let nb = norm(&b);
        self.report.residual = norm(&r) / if nb > 0.0 { nb } else { 1.0 };
        self.report.refinement_steps = 0;
        self.report.solve_time = start.elapsed();
        Ok(())
    }

    /// Solves `(K + shift I) x = b` and returns `x`.
    pub fn solve(&mut self, b: &[f64]) -> Result<Vec<f64>, LinearError> {
        let mut x = b.to_vec();
        self.solve_in_place(&mut x)?;
        Ok(x)
    }

    /// Timings and diagnostics of the latest factorization and solve.
    pub fn report(&self) -> &SolveReport {
        &self.report
    }
}
