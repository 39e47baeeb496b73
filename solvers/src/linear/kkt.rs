//! Direct solver for the saddle-point (KKT) systems of saddle-point Newton,
//!
//! ```text
//! [ K   G^T ] [du]   [f]
//! [ G   -C  ] [dp] = [g]        (eq. 21 / 24 of Francu et al. 2021)
//! ```
//!
//! with `K` symmetric `n x n`, `G` the `m x n` constraint Jacobian and `C` the symmetric
//! positive semi-definite compliance (possibly exactly zero, `nu = 0.5`).
//!
//! Method: symmetric diagonal scaling `S A S` (the Jacobi scales of
//! [`super::saddle_point_diagonal`], so that pivot thresholds are scale free), an
//! anchored fill-reducing order ([`KktOptions::ordering`], see `ordering.rs`), and a supernodal `LDL^T` without
//! pivoting whose symbolic factorization is computed once and reused.
//!
//! Pivots of magnitude below `epsilon` are replaced by `+-delta` during the
//! factorization, keeping their sign, and the solve is refined iteratively against the
//! unregularized matrix. At `C = 0` such pivots come from the exactly singular P1-P1 KKT
//! (3 spurious pressure modes on structured boxes) and from singular leading blocks of
//! the elimination order. The factor is then exact for `A + E`, `E` diagonal with
//! `|E| <= delta` (relative to the scaled matrix), so by Weyl's inequality the signs of
//! `D` are the inertia of `A` except for eigenvalues of `A` within `delta` of zero.
//! `K` is positive definite on the null space of `G` exactly when `A` has `n` positive
//! eigenvalues (`rank G` negative, the rest zero). Each replaced pivot is a rank-one change
//! of `A`, which moves at most one eigenvalue across zero (interlacing), so with `r`
//! replaced pivots fewer than `n - r` positive pivots proves a wrong inertia:
//! [`LinearError::WrongInertia`], which asks the caller to shift `K` and retry. Between
//! `n - r` and `n` the factor cannot tell and is accepted (the line search still guards the
//! step); with `C > 0` and no replaced pivots the check is exact. (Regularizing
//! with the expected signs `+1`/`-1` instead would also flip large pivots of the wrong
//! sign, which are legitimate when `K` is indefinite along the range of `G^T`.)
//! Sparse `LU` is the fallback of an unregularized factor; a regularized one whose solution
//! stays inaccurate under AMD is analysed again under nested dissection (at `C = 0` AMD's
//! order can meet singular leading blocks, whose replaced pivots then spoil the factor).

use super::jacobi::{diagonal, saddle_point_diagonal};
use super::operator::{norm, LinearOperator, SymmetricLower};
use super::ordering::anchored_ordering;
use super::pattern::{copy_structure, entry_pairs, same_structure};
use super::{
    Factorization, Inertia, LinearError, Ordering, ShiftSchedule, SolveReport, SparsityPattern,
    Triangle,
};
use faer::dyn_stack::{MemBuffer, MemStack};
use faer::linalg::cholesky::ldlt::factor::{LdltError, LdltRegularization};
use faer::linalg::solvers::Solve;
use faer::perm::PermRef;
use faer::sparse::linalg::cholesky::supernodal::{
    factorize_supernodal_numeric_ldlt, factorize_supernodal_numeric_ldlt_scratch,
    SupernodalLdltRef, SymbolicSupernodalCholesky,
};
use faer::sparse::linalg::cholesky::{
    factorize_symbolic_cholesky, CholeskySymbolicParams, SymbolicCholesky, SymbolicCholeskyRaw,
    SymmetricOrdering,
};
use faer::sparse::linalg::solvers::{Lu, SymbolicLu};
use faer::sparse::linalg::SupernodalThreshold;
use faer::sparse::{SparseColMat, SparseColMatRef, SymbolicSparseColMat, SymbolicSparseColMatRef};
use faer::{Conj, MatMut, Side};
use std::time::Instant;

/// Pivot regularization of the scaled `LDL^T` (faer's `LdltRegularization` without
/// prescribed signs): a pivot below `epsilon` in magnitude is replaced by `delta` with
/// the pivot's sign.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PivotRegularization {
    /// Threshold below which a (scaled) pivot counts as zero.
    pub epsilon: f64,
    /// Magnitude of a replaced pivot.
    pub delta: f64,
}

impl Default for PivotRegularization {
    fn default() -> Self {
        Self {
            epsilon: 1e-10,
            delta: 1e-8,
        }
    }
}

/// Options of [`KktSolver`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct KktOptions {
    /// Replacement of tiny pivots; `None` disables it (tiny pivots then count as zero
    /// and send the factorization to the `LU` fallback or fail with
    /// [`LinearError::Singular`]).
    pub pivot_regularization: Option<PivotRegularization>,
    /// Without regularization, scaled pivots of at most this magnitude count as zero and
    /// send the factorization to the `LU` fallback (or fail as singular).
    pub zero_pivot_tolerance: f64,
    /// Most iterative refinement steps per solve.
    pub max_refinement_steps: usize,
    /// Refinement stops once the relative residual, the smaller of `|b - A x| / |b|` and
    /// `|S (b - A x)| / |S b|` (`S` the diagonal scaling), is below this.
    pub refinement_tolerance: f64,
    /// A solve whose final relative residual exceeds this is an error
    /// ([`LinearError::InaccurateSolution`]) unless the `LU` fallback does better.
    pub residual_tolerance: f64,
    /// Whether to fall back to sparse `LU` when `LDL^T` breaks down or is inaccurate.
    pub lu_fallback: bool,
    /// Fill-reducing ordering of the compressed graph (constraints merged into their
    /// anchors) before the anchored expansion.
    pub ordering: Ordering,
}

impl Default for KktOptions {
    fn default() -> Self {
        Self {
            pivot_regularization: Some(PivotRegularization::default()),
            zero_pivot_tolerance: 1e-10,
            max_refinement_steps: 10,
            refinement_tolerance: 1e-10,
            residual_tolerance: 1e-8,
            lu_fallback: true,
            ordering: Ordering::default(),
        }
    }
}

/// The numeric factorization in use.
#[derive(Debug)]
enum Factor {
    None,
    Ldlt,
    Lu(Box<Lu<usize, f64>>),
}

/// `LDL^T` solver for `[[K, G^T], [G, -C]]` with a fixed pattern.
#[derive(Debug)]
pub struct KktSolver {
    n: usize,
    m: usize,
    k_structure: SymbolicSparseColMat<usize>,
    g_structure: SymbolicSparseColMat<usize>,
    c_structure: Option<SymbolicSparseColMat<usize>>,
    anchors: Vec<Option<usize>>,
    /// `fwd[new] = old` over the `n + m` unknowns.
    fwd: Vec<usize>,
    /// Lower triangle of the permuted matrix; inputs are, in order, the entries of `K`,
    /// `G`, `C` and the `n + m` diagonal entries.
    pattern: SparsityPattern,
    /// The scaled, permuted, lower-triangular matrix `S A S` as factorized.
    matrix: SparseColMat<usize, f64>,
    /// The diagonal scaling `S` in the original numbering.
    scale: Vec<f64>,
    symbolic: SymbolicCholesky<usize>,
    values: Vec<f64>,
    factor: Factor,
    options: KktOptions,
    report: SolveReport,
}

impl KktSolver {
    /// Symbolic analysis for the patterns of `K` (`n x n`, both triangles or lower), `G`
    /// (`m x n`) and `C` (`m x m`, `None` if `C = 0` always). `anchors[i]` is the DOF after
    /// which constraint `i` is eliminated (`None` for dense rows, eliminated last).
    pub fn new(
        k: SymbolicSparseColMatRef<'_, usize>,
        g: SymbolicSparseColMatRef<'_, usize>,
        c: Option<SymbolicSparseColMatRef<'_, usize>>,
        anchors: &[Option<usize>],
        options: KktOptions,
    ) -> Result<Self, LinearError> {
        let start = Instant::now();
        let n = LinearError::square("K", k.nrows(), k.ncols())?;
        let m = g.nrows();
        if g.ncols() != n {
            return Err(LinearError::DimensionMismatch {
                what: "columns of G",
                expected: n,
                got: g.ncols(),
            });
        }
        if let Some(c) = c {
            if c.nrows() != m || c.ncols() != m {
                return Err(LinearError::DimensionMismatch {
                    what: "size of C",
                    expected: m,
                    got: c.nrows().max(c.ncols()),
                });
            }
        }
        let ordering = options.ordering.resolve(n);
        let fwd = anchored_ordering(k, g, anchors, ordering)?;
        let mut inv = vec![0usize; n + m];
        fwd.iter()
            .enumerate()
            .for_each(|(new, &old)| inv[old] = new);
        // Pairs in the permuted numbering; the pattern keeps the lower triangle.
        let place = |(i, j): (usize, usize)| {
            let (a, b) = (inv[i], inv[j]);
            (a.max(b), a.min(b))
        };
        // An upper-triangle pair: the Lower pattern skips it (only used when n + m >= 2).
        let skipped = (0, n + m - 1);
        let mut pairs: Vec<(usize, usize)> = Vec::new();
        pairs.extend(
            entry_pairs(k, "K (uncompressed storage)")?
                .into_iter()
                .map(|(i, j)| if i >= j { place((i, j)) } else { skipped }),
        );
        pairs.extend(
            entry_pairs(g, "G (uncompressed storage)")?
                .into_iter()
                .map(|(i, j)| place((n + i, j))),
        );
        if let Some(c) = c {
            pairs.extend(
                entry_pairs(c, "C (uncompressed storage)")?
                    .into_iter()
                    .map(|(i, j)| {
                        if i >= j {
                            place((n + i, n + j))
                        } else {
                            skipped
                        }
                    }),
            );
        }
        pairs.extend((0..n + m).map(|i| place((i, i))));
        let pattern = SparsityPattern::new(n + m, n + m, &pairs, Triangle::Lower)?;
        let identity: Vec<usize> = (0..n + m).collect();
        let symbolic = factorize_symbolic_cholesky(
            pattern.symbolic(),
            Side::Lower,
            SymmetricOrdering::Custom(PermRef::new_checked(&identity, &identity, n + m)),
            CholeskySymbolicParams {
                supernodal_flop_ratio_threshold: SupernodalThreshold::FORCE_SUPERNODAL,
                ..Default::default()
            },
        )?;
        let report = SolveReport {
            symbolic_time: start.elapsed(),
            factor_nnz: symbolic.len_val(),
            ordering,
            residual: f64::NAN,
            ..Default::default()
        };
        Ok(Self {
            n,
            m,
            k_structure: copy_structure(k),
            g_structure: copy_structure(g),
            c_structure: c.map(copy_structure),
            anchors: anchors.to_vec(),
            fwd,
            matrix: pattern.zeros(),
            pattern,
            scale: vec![1.0; n + m],
            values: vec![0.0; symbolic.len_val()],
            symbolic,
            factor: Factor::None,
            options,
            report,
        })
    }

    /// Number of displacement unknowns `n` and of constraints `m`.
    pub fn dims(&self) -> (usize, usize) {
        (self.n, self.m)
    }

    /// The options in use.
    pub fn options(&self) -> &KktOptions {
        &self.options
    }

    /// Timings and diagnostics of the latest factorization and solve.
    pub fn report(&self) -> &SolveReport {
        &self.report
    }

    /// Numeric factorization of `[[K + shift I, G^T], [G, -C]]` (`shift` absolute,
    /// usually 0) with the patterns given to [`Self::new`]. Checks the inertia; on
    /// success [`SolveReport::inertia`] and [`SolveReport::regularized_pivots`] describe
    /// the factor.
    pub fn factorize(
        &mut self,
        k: SparseColMatRef<'_, usize, f64>,
        g: SparseColMatRef<'_, usize, f64>,
        c: Option<SparseColMatRef<'_, usize, f64>>,
        shift: f64,
    ) -> Result<(), LinearError> {
        let start = Instant::now();
        self.factor = Factor::None;
        self.report.factorizations = 0;
        let result = self
            .fill(k, g, c, shift)
            .and_then(|()| self.factorize_filled());
        self.report.shift = shift;
        self.report.numeric_time = start.elapsed();
        result
    }

    /// Factorizes with the shifts of `schedule` (relative to `max |K_ii|`) added to `K`
    /// until the inertia is right; returns the absolute shift used.
    pub fn factorize_with_shifts(
        &mut self,
        k: SparseColMatRef<'_, usize, f64>,
        g: SparseColMatRef<'_, usize, f64>,
        c: Option<SparseColMatRef<'_, usize, f64>>,
        schedule: &ShiftSchedule,
    ) -> Result<f64, LinearError> {
        let start = Instant::now();
        let mut attempts = 0;
        let result = schedule.retry(super::max_abs_diagonal(k), |shift| {
            let r = self.factorize(k, g, c, shift);
            attempts += self.report.factorizations;
            r
        });
        self.report.factorizations = attempts;
        self.report.numeric_time = start.elapsed();
        result.map(|((), shift)| shift)
    }

    /// Copies `S [[K + shift I, G^T], [G, -C]] S` into the permuted lower matrix.
    fn fill(
        &mut self,
        k: SparseColMatRef<'_, usize, f64>,
        g: SparseColMatRef<'_, usize, f64>,
        c: Option<SparseColMatRef<'_, usize, f64>>,
        shift: f64,
    ) -> Result<(), LinearError> {
        if !same_structure(k.symbolic(), self.k_structure.as_ref()) {
            return Err(LinearError::PatternMismatch { what: "K" });
        }
        if !same_structure(g.symbolic(), self.g_structure.as_ref()) {
            return Err(LinearError::PatternMismatch { what: "G" });
        }
        match (c, &self.c_structure) {
            (None, _) => {}
            (Some(c), Some(s)) if same_structure(c.symbolic(), s.as_ref()) => {}
            (Some(_), _) => return Err(LinearError::PatternMismatch { what: "C" }),
        }
        let finite = |a: SparseColMatRef<'_, usize, f64>| a.val().iter().all(|v| v.is_finite());
        if !finite(k) || !shift.is_finite() {
            return Err(LinearError::NonFiniteInput { what: "K" });
        }
        if !finite(g) {
            return Err(LinearError::NonFiniteInput { what: "G" });
        }
        if !c.is_none_or(finite) {
            return Err(LinearError::NonFiniteInput { what: "C" });
        }
        let n = self.n;
        let mut k_diag = diagonal(k);
        k_diag.iter_mut().for_each(|d| *d += shift);
        let c_diag = c.map(diagonal);
        self.scale = saddle_point_diagonal(&k_diag, g, c_diag.as_deref())
            .into_iter()
            .map(|d| 1.0 / d.sqrt())
            .collect();
        let s = &self.scale;
        let vals = self.matrix.val_mut();
        vals.fill(0.0);
        let mut input = 0;
        let mut add = |a: SparseColMatRef<'_, usize, f64>, row0: usize, col0: usize, sign: f64| {
            let rows = a.symbolic().row_idx();
            for j in 0..a.ncols() {
                for p in a.col_range(j) {
                    if let Some(slot) = self.pattern.slot(input) {
                        let (i, jj) = (row0 + rows[p], col0 + j);
                        vals[slot] += sign * a.val()[p] * s[i] * s[jj];
                    }
                    input += 1;
                }
            }
        };
        add(k, 0, 0, 1.0);
        add(g, n, 0, 1.0);
        if let Some(c) = c {
            add(c, n, n, -1.0);
        } else if let Some(cs) = &self.c_structure {
            input += cs.row_idx().len();
        }
        for (i, si) in s.iter().enumerate().take(n) {
            if let Some(slot) = self.pattern.slot(input + i) {
                vals[slot] += shift * si * si;
            }
        }
        Ok(())
    }

    /// `LDL^T` (regularized if configured) with the inertia check; `LU` if pivots
    /// vanish and no regularization is configured.
    fn factorize_filled(&mut self) -> Result<(), LinearError> {
        let (n, m) = (self.n, self.m);
        let regularization =
            self.options
                .pivot_regularization
                .map_or_else(LdltRegularization::default, |r| LdltRegularization {
                    dynamic_regularization_signs: None,
                    dynamic_regularization_delta: r.delta,
                    dynamic_regularization_epsilon: r.epsilon,
                });
        let pivot = match self.ldlt(regularization) {
            Ok(()) => {
                let pivots = self.pivots()?;
                let (inertia, regularized) = match self.options.pivot_regularization {
                    // The factor is exact for A + E, E diagonal with one entry per
                    // replaced pivot (those are exactly +-delta): the inertia of A is
                    // that of the pivots up to one sign per replaced pivot.
                    Some(r) => (
                        count_inertia(&pivots, 0.0),
                        pivots.iter().filter(|d| d.abs() == r.delta).count(),
                    ),
                    None => (count_inertia(&pivots, self.options.zero_pivot_tolerance), 0),
                };
                if inertia.zero == 0 {
                    if inertia.positive + regularized < n {
                        return Err(wrong_inertia(inertia, n, m));
                    }
                    self.factor = Factor::Ldlt;
                    self.report.factorization = match regularized {
                        0 => Factorization::Ldlt,
                        _ => Factorization::RegularizedLdlt,
                    };
                    self.report.inertia = Some(inertia);
                    self.report.regularized_pivots = regularized;
                    return Ok(());
                }
                0
            }
            Err(LinearError::Singular { pivot }) => pivot,
            Err(e) => return Err(e),
        };
        if self.options.lu_fallback {
            return self.factorize_lu();
        }
        Err(LinearError::Singular { pivot })
    }

    /// One numeric `LDL^T` of the filled matrix, or [`LinearError::Singular`] at a zero
    /// pivot.
    fn ldlt(&mut self, regularization: LdltRegularization<'_, f64>) -> Result<(), LinearError> {
        self.report.factorizations += 1;
        let par = faer::get_global_parallelism();
        let symbolic = supernodal(&self.symbolic)?;
        let req = factorize_supernodal_numeric_ldlt_scratch::<usize, f64>(
            symbolic,
            par,
            Default::default(),
        );
        let mut mem =
            MemBuffer::try_new(req).map_err(|_| LinearError::Faer("out of memory".into()))?;
        factorize_supernodal_numeric_ldlt(
            &mut self.values,
            self.matrix.as_ref(),
            regularization,
            symbolic,
            par,
            MemStack::new(&mut mem),
            Default::default(),
        )
        .map(|_| ())
        .map_err(|LdltError::ZeroPivot { index }| LinearError::Singular { pivot: index })
    }

    /// The pivots `D` (diagonals of the supernodes' diagonal blocks), in elimination order.
    fn pivots(&self) -> Result<Vec<f64>, LinearError> {
        let symbolic = supernodal(&self.symbolic)?;
        let factor = SupernodalLdltRef::new(symbolic, &self.values);
        Ok((0..symbolic.n_supernodes())
            .flat_map(|s| {
                let block = factor.supernode(s).val();
                (0..block.ncols()).map(move |i| block[(i, i)])
            })
            .collect())
    }

    /// Sparse `LU` of the full (both triangles) scaled, permuted matrix.
    fn factorize_lu(&mut self) -> Result<(), LinearError> {
        self.report.factorizations += 1;
        let a = self.matrix.as_ref();
        let rows = a.symbolic().row_idx();
        let mut pairs = Vec::with_capacity(2 * rows.len());
        let mut vals = Vec::with_capacity(2 * rows.len());
        for j in 0..a.ncols() {
            for p in a.col_range(j) {
                let i = rows[p];
                pairs.extend([(i, j), (j, i)]);
                vals.extend([a.val()[p], if i == j { 0.0 } else { a.val()[p] }]);
            }
        }
        let full =
            SparsityPattern::new(a.nrows(), a.ncols(), &pairs, Triangle::Full)?.assemble(&vals)?;
        let symbolic = SymbolicLu::try_new(full.symbolic())?;
        let lu = Lu::try_new_with_symbolic(symbolic, full.as_ref()).map_err(|e| match e {
            faer::sparse::linalg::LuError::SymbolicSingular { index } => {
                LinearError::Singular { pivot: index }
            }
            faer::sparse::linalg::LuError::Generic(e) => e.into(),
        })?;
        self.factor = Factor::Lu(Box::new(lu));
        self.report.factorization = Factorization::Lu;
        self.report.inertia = None;
        self.report.regularized_pivots = 0;
        Ok(())
    }

    /// Solves in the scaled, permuted space with the current factor.
    fn apply_factor(&self, y: &mut [f64]) -> Result<(), LinearError> {
        let dim = y.len();
        match &self.factor {
            Factor::None => return Err(LinearError::NotFactorized),
            Factor::Ldlt => {
                let symbolic = supernodal(&self.symbolic)?;
                let par = faer::get_global_parallelism();
                let mut mem = MemBuffer::try_new(symbolic.solve_in_place_scratch::<f64>(1, par))
                    .map_err(|_| LinearError::Faer("out of memory".into()))?;
                SupernodalLdltRef::new(symbolic, &self.values).solve_in_place_with_conj(
                    Conj::No,
                    MatMut::from_column_major_slice_mut(y, dim, 1),
                    par,
                    MemStack::new(&mut mem),
                );
            }
            Factor::Lu(lu) => lu.solve_in_place(MatMut::from_column_major_slice_mut(y, dim, 1)),
        }
        Ok(())
    }

    /// Solves `[[K, G^T], [G, -C]] (du, dp) = (f, g)` in place: `rhs` holds `(f, g)`
    /// (length `n + m`) on entry and `(du, dp)` on return. Refines iteratively against
    /// the unregularized matrix and records the final relative residual (the smaller of
    /// the unscaled and the scaled one) in the report.
    pub fn solve_in_place(&mut self, rhs: &mut [f64]) -> Result<(), LinearError> {
        let start = Instant::now();
        let dim = self.n + self.m;
        if rhs.len() != dim {
            return Err(LinearError::DimensionMismatch {
                what: "right-hand side",
                expected: dim,
                got: rhs.len(),
            });
        }
        if rhs.iter().any(|v| !v.is_finite()) {
            return Err(LinearError::NonFiniteInput {
                what: "right-hand side",
            });
        }
        // The fallbacks below solve again from the right-hand side the failed attempt overwrote.
        let b = rhs.to_vec();
        let mut result = self.solve_refined(rhs);
        // LU is tried when LDL^T produced NaN, or an inaccurate solution of a system it
        // found nonsingular; a singular system (regularized pivots) with an inconsistent
        // right-hand side has no solution, and LU would not find one either.
        let ldlt_failed = matches!(self.factor, Factor::Ldlt)
            && match result {
                Err(LinearError::NonFiniteSolution) => true,
                Err(LinearError::InaccurateSolution { .. }) => {
                    self.report.factorization == Factorization::Ldlt
                }
                _ => false,
            };
        if ldlt_failed && self.options.lu_fallback {
            let t = Instant::now();
            self.factorize_lu()?;
            self.report.numeric_time += t.elapsed();
            rhs.copy_from_slice(&b);
            result = self.solve_refined(rhs);
        }
        // A regularized factor whose solution stays inaccurate under AMD: at C = 0 its order
        // can meet singular leading blocks (pivots replaced far from the null space of the
        // matrix), which nested dissection's order, eliminating separators last, avoids.
        let regularized_amd = matches!(self.factor, Factor::Ldlt)
            && self.report.factorization == Factorization::RegularizedLdlt
            && self.report.ordering == Ordering::Amd
            && matches!(result, Err(LinearError::InaccurateSolution { .. }));
        if regularized_amd {
            let t = Instant::now();
            self.reorder(Ordering::NestedDissection)?;
            self.report.numeric_time += t.elapsed();
            rhs.copy_from_slice(&b);
            result = self.solve_refined(rhs);
        }
        self.report.solve_time = start.elapsed();
        result
    }

    /// Analyses the patterns again under `ordering` and factorizes the matrix of the latest
    /// [`Self::factorize`] in the new order; later factorizations keep the new analysis.
    fn reorder(&mut self, ordering: Ordering) -> Result<(), LinearError> {
        let options = KktOptions {
            ordering,
            ..self.options
        };
        let mut fresh = Self::new(
            self.k_structure.as_ref(),
            self.g_structure.as_ref(),
            self.c_structure.as_ref().map(|c| c.as_ref()),
            &self.anchors,
            options,
        )?;
        let mut inv = vec![0usize; self.fwd.len()];
        fresh
            .fwd
            .iter()
            .enumerate()
            .for_each(|(new, &old)| inv[old] = new);
        let old = self.matrix.as_ref();
        let target = fresh.pattern.symbolic();
        let values = fresh.matrix.val_mut();
        for j in 0..old.ncols() {
            for p in old.col_range(j) {
                let (a, b) = (inv[self.fwd[old.row_idx()[p]]], inv[self.fwd[j]]);
                let (row, col) = (a.max(b), a.min(b));
                let rows = &target.row_idx()[target.col_range(col)];
                let slot = rows
                    .binary_search(&row)
                    .map_err(|_| LinearError::PatternMismatch {
                        what: "reordered KKT",
                    })?;
                values[target.col_range(col).start + slot] = old.val()[p];
            }
        }
        fresh.scale = std::mem::take(&mut self.scale);
        fresh.report.shift = self.report.shift;
        fresh.report.factorizations = self.report.factorizations;
        fresh.report.symbolic_time += self.report.symbolic_time;
        let result = fresh.factorize_filled();
        *self = fresh;
        result
    }

    /// Solves and returns `(du, dp)` for the right-hand side `(f, g)`.
    pub fn solve(&mut self, b: &[f64]) -> Result<Vec<f64>, LinearError> {
        let mut x = b.to_vec();
        self.solve_in_place(&mut x)?;
        Ok(x)
    }

    /// `x = S y` with `(S A S) y = S b`, refined on the residual `b - A x`, measured as the
    /// smaller of two relative residuals: the system's, `|b - A x| / |b|`, and that of the
    /// scaled system the factor solves, `|S (b - A x)| / |S b|`. Unscaled, the rows of large
    /// entries (stiffnesses of `E h` in `K`) weigh their rounding against a right-hand side
    /// carried by rows of small ones (a cavity's volume row) and refuse backward-stable
    /// solutions; scaled, the slowly refined modes of regularized pivots can weigh more.
    fn solve_refined(&mut self, rhs: &mut [f64]) -> Result<(), LinearError> {
        let dim = rhs.len();
        // Permuted, scaled right-hand side and residual.
        let mut r: Vec<f64> = self.fwd.iter().map(|&i| rhs[i]).collect();
        let s: Vec<f64> = self.fwd.iter().map(|&i| self.scale[i]).collect();
        let b = r.clone();
        let scaled_norm =
            |v: &[f64]| norm(&v.iter().zip(&s).map(|(vi, si)| vi * si).collect::<Vec<_>>());
        let positive = |x: f64| if x > 0.0 { x } else { 1.0 };
        let (b_norm, b_scaled_norm) = (positive(norm(&b)), positive(scaled_norm(&b)));
        let mut y = vec![0.0; dim];
        let mut ay = vec![0.0; dim];
        let mut residual = 1.0;
        let mut best = (f64::INFINITY, y.clone());
        let mut steps = 0;
        loop {
            let mut dy: Vec<f64> = r.iter().zip(&s).map(|(ri, si)| ri * si).collect();
            self.apply_factor(&mut dy)?;
            y.iter_mut().zip(&dy).for_each(|(yi, di)| *yi += di);
            SymmetricLower(self.matrix.as_ref()).apply(&y, &mut ay);
            // r = b - A x = b - S^-1 (S A S) y
            for i in 0..dim {
                r[i] = b[i] - ay[i] / s[i];
            }
            let new_residual = (norm(&r) / b_norm).min(scaled_norm(&r) / b_scaled_norm);
            if !new_residual.is_finite() {
                break;
            }
            if new_residual < best.0 {
                best = (new_residual, y.clone());
            }
            let stalled = new_residual > 0.5 * residual && steps > 0;
            residual = new_residual;
            if residual <= self.options.refinement_tolerance
                || stalled
                || steps >= self.options.max_refinement_steps
            {
                break;
            }
            steps += 1;
        }
        self.report.refinement_steps = steps;
        self.report.residual = best.0;
        if !best.0.is_finite() {
            return Err(LinearError::NonFiniteSolution);
        }
        for (k, &i) in self.fwd.iter().enumerate() {
            rhs[i] = s[k] * best.1[k];
        }
        if rhs.iter().any(|v| !v.is_finite()) {
            return Err(LinearError::NonFiniteSolution);
        }
        if best.0 > self.options.residual_tolerance {
            return Err(LinearError::InaccurateSolution {
                residual: best.0,
                refinement_steps: steps,
                tolerance: self.options.residual_tolerance,
            });
        }
        Ok(())
    }
}

fn wrong_inertia(inertia: Inertia, n: usize, m: usize) -> LinearError {
    LinearError::WrongInertia {
        positive: inertia.positive,
        negative: inertia.negative,
        zero: inertia.zero,
        expected_positive: n,
        expected_negative: m,
    }
}

/// The supernodal part of a symbolic factorization made with `FORCE_SUPERNODAL`.
fn supernodal(
    symbolic: &SymbolicCholesky<usize>,
) -> Result<&SymbolicSupernodalCholesky<usize>, LinearError> {
    match symbolic.raw() {
        SymbolicCholeskyRaw::Supernodal(s) => Ok(s),
        SymbolicCholeskyRaw::Simplicial(_) => Err(LinearError::Faer(
            "expected a supernodal symbolic factorization".into(),
        )),
    }
}

/// Signs of the pivots; those of magnitude at most `zero` count as zero.
fn count_inertia(pivots: &[f64], zero: f64) -> Inertia {
    let mut inertia = Inertia::default();
    for &d in pivots {
        if d.abs() <= zero || !d.is_finite() {
            inertia.zero += 1;
        } else if d > 0.0 {
            inertia.positive += 1;
        } else {
            inertia.negative += 1;
        }
    }
    inertia
}
