//! The preconditioner of a Krylov solve, `z = M^-1 r` with `M` symmetric positive
//! definite, so that diagonal scaling, incomplete Cholesky and the block-diagonal
//! saddle-point preconditioner are interchangeable in [`super::cg`] and [`super::minres`].

/// An SPD preconditioner `z = M^-1 r`, built once per Newton iteration and shared by its
/// solves.
pub trait Preconditioner: Send + Sync + std::fmt::Debug {
    /// Dimension.
    fn dim(&self) -> usize;
    /// Overwrites `z` with `M^-1 r`. Callers pass slices of length [`Preconditioner::dim`].
    fn apply(&self, r: &[f64], z: &mut [f64]);
}

/// `diag(first, second)` acting on `(u, p)`: the block-diagonal preconditioner of a
/// saddle-point system, `first` for the `K` block and `second` for the Schur complement
/// (Elman, Silvester and Wathen, "Finite Elements and Fast Iterative Solvers", 2nd ed.,
/// sec. 4.2: MINRES with `diag(P_K, S)`, `S` spectrally equivalent to `G K^-1 G^T + C`).
#[derive(Debug)]
pub struct BlockDiagonal<'a> {
    /// The preconditioner of the first (displacement) block.
    pub first: &'a dyn Preconditioner,
    /// The preconditioner of the second (pressure) block.
    pub second: &'a dyn Preconditioner,
}

impl Preconditioner for BlockDiagonal<'_> {
    fn dim(&self) -> usize {
        self.first.dim() + self.second.dim()
    }

    fn apply(&self, r: &[f64], z: &mut [f64]) {
        let n = self.first.dim();
        let (ru, rp) = r.split_at(n);
        let (zu, zp) = z.split_at_mut(n);
        self.first.apply(ru, zu);
        self.second.apply(rp, zp);
    }
}
