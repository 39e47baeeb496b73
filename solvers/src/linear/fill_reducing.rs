//! The fill-reducing ordering of a sparse factorization: approximate minimum degree
//! (faer's AMD) or nested dissection (METIS), or chosen by size.

use super::nested_dissection::nested_dissection;
use super::LinearError;
use faer::dyn_stack::{MemBuffer, MemStack};
use faer::sparse::linalg::amd;
use faer::sparse::SymbolicSparseColMatRef;

/// Fill-reducing ordering of the sparse direct solvers.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Ordering {
    /// Approximate minimum degree: cheap to compute, least fill on small meshes.
    Amd,
    /// Nested dissection (METIS): less fill and flops on large 3D meshes.
    NestedDissection,
    /// [`Ordering::Amd`] below [`Ordering::AUTO_THRESHOLD`] graph vertices, nested
    /// dissection from there on.
    #[default]
    Auto,
}

impl Ordering {
    /// Graph vertices (DOFs; for the KKT, DOFs with the constraints merged into their anchors) from
    /// which [`Ordering::Auto`] uses nested dissection. Measured on the cantilever
    /// (docs/performance.md, "Fill-reducing orderings"): nested dissection was slower at 7,776
    /// vertices (`standard`, res 8), even for `mixed-p1` at res 8 (7,776 vertices), about 20%
    /// faster at 24,336 (res 12, both methods) and twice as fast on the fine ball (36k).
    pub const AUTO_THRESHOLD: usize = 20_000;

    /// The algorithm used for a graph of `vertices` vertices (never `Auto`).
    pub fn resolve(self, vertices: usize) -> Ordering {
        match self {
            Ordering::Auto if vertices >= Self::AUTO_THRESHOLD => Ordering::NestedDissection,
            Ordering::Auto => Ordering::Amd,
            other => other,
        }
    }
}

/// Fill-reducing permutation `(fwd, inv)` (`fwd[new] = old`) of the symmetric matrix whose
/// pattern is `graph` (both triangles, or one).
pub(crate) fn fill_reducing(
    graph: SymbolicSparseColMatRef<'_, usize>,
    ordering: Ordering,
) -> Result<(Vec<usize>, Vec<usize>), LinearError> {
    let n = graph.nrows();
    match ordering.resolve(n) {
        Ordering::NestedDissection => nested_dissection(graph),
        _ => {
            let mut fwd = vec![0usize; n];
            let mut inv = vec![0usize; n];
            let nnz = graph.row_idx().len();
            let req = amd::order_maybe_unsorted_scratch::<usize>(n, nnz);
            let mut mem =
                MemBuffer::try_new(req).map_err(|_| LinearError::Faer("out of memory".into()))?;
            amd::order_maybe_unsorted(
                &mut fwd,
                &mut inv,
                graph,
                amd::Control::default(),
                MemStack::new(&mut mem),
            )?;
            Ok((fwd, inv))
        }
    }
}
