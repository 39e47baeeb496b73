//! The preconditioners of the iterative path: zero-fill incomplete Cholesky against exact
//! Cholesky, its diagonal-shift retry, and the block-diagonal saddle-point preconditioner.

mod common;

use common::Rng;
use faer::sparse::SparseColMat;
use isochor_solvers::linear::{
    cg, diagonal, minres, BlockDiagonal, CholeskySolver, IncompleteCholesky, IterativeOptions,
    Jacobi, Preconditioner, SaddlePoint, SparsityPattern, SymmetricLower, Triangle,
};

/// A symmetric matrix from its lower-triangle entries `(row, col, value)`, both triangles
/// stored.
fn symmetric(n: usize, lower: &[(usize, usize, f64)]) -> SparseColMat<usize, f64> {
    let mut pairs = Vec::new();
    let mut values = Vec::new();
    for &(i, j, v) in lower {
        pairs.push((i, j));
        values.push(v);
        if i != j {
            pairs.push((j, i));
            values.push(v);
        }
    }
    SparsityPattern::new(n, n, &pairs, Triangle::Full)
        .unwrap()
        .assemble(&values)
        .unwrap()
}

/// The weighted Laplacian of a tree plus a positive diagonal: vertex `j` is joined to
/// `parent[j] > j`, so eliminating in index order creates no fill.
fn tree_matrix(parent: &[usize], rng: &mut Rng) -> SparseColMat<usize, f64> {
    let n = parent.len() + 1;
    let mut diag = vec![0.0; n];
    let mut lower = Vec::new();
    for (j, &p) in parent.iter().enumerate() {
        let w = 1.5 + rng.uniform();
        lower.push((p, j, -w));
        diag[j] += w;
        diag[p] += w;
    }
    for (j, d) in diag.iter().enumerate() {
        lower.push((j, j, d + 0.1 + 0.05 * rng.uniform()));
    }
    symmetric(n, &lower)
}

fn relative_difference(a: &[f64], b: &[f64]) -> f64 {
    let diff: f64 = a.iter().zip(b).map(|(x, y)| (x - y).powi(2)).sum();
    let norm: f64 = b.iter().map(|y| y * y).sum();
    (diff / norm).sqrt()
}

/// `M^-1 b` by IC(0) against the exact Cholesky solve of the same matrix.
fn ic_against_cholesky(a: &SparseColMat<usize, f64>, rng: &mut Rng) -> (f64, f64) {
    let n = a.nrows();
    let b: Vec<f64> = (0..n).map(|_| rng.uniform()).collect();
    let ic = IncompleteCholesky::new(a.as_ref()).unwrap();
    let mut z = vec![0.0; n];
    ic.apply(&b, &mut z);
    let mut chol = CholeskySolver::new(a.symbolic()).unwrap();
    chol.factorize(a.as_ref(), 0.0).unwrap();
    let exact = chol.solve(&b).unwrap();
    (relative_difference(&z, &exact), ic.shift())
}

/// Where elimination creates no fill (a tridiagonal matrix, a random tree numbered leaves
/// first), IC(0) is the exact Cholesky factorization: `M^-1 b = A^-1 b` to rounding (the
/// matrices are diagonally dominant, condition number below 100, so 1e-12 leaves a factor
/// 100 over `cond * eps * n`-sized rounding).
#[test]
fn incomplete_cholesky_is_exact_without_fill() {
    let mut rng = Rng(11);
    let n = 200;
    let chain: Vec<usize> = (1..n).collect();
    let tree: Vec<usize> = (0..n - 1)
        .map(|j| j + 1 + ((rng.uniform() + 1.0) * 1e6) as usize % (n - 1 - j))
        .collect();
    for (name, parent) in [("tridiagonal", chain), ("tree", tree)] {
        let a = tree_matrix(&parent, &mut rng);
        let (d, shift) = ic_against_cholesky(&a, &mut rng);
        assert_eq!(shift, 0.0, "{name}");
        assert!(d < 1e-12, "{name}: IC(0) differs from Cholesky by {d:e}");
    }
}

/// On a 2D grid Laplacian elimination fills in, so IC(0) is not exact (the test above can
/// tell the two apart), yet it preconditions CG better than the diagonal: fewer iterations.
#[test]
fn incomplete_cholesky_drops_fill_and_beats_jacobi() {
    let mut rng = Rng(5);
    let side = 30;
    let n = side * side;
    let mut lower = Vec::new();
    for y in 0..side {
        for x in 0..side {
            let i = y * side + x;
            lower.push((i, i, 4.0 + 1e-3));
            if x + 1 < side {
                lower.push((i + 1, i, -1.0));
            }
            if y + 1 < side {
                lower.push((i + side, i, -1.0));
            }
        }
    }
    let a = symmetric(n, &lower);
    let (d, _) = ic_against_cholesky(&a, &mut rng);
    assert!(d > 1e-3, "IC(0) of a grid Laplacian cannot be exact: {d:e}");
    let b: Vec<f64> = (0..n).map(|_| rng.uniform()).collect();
    let options = IterativeOptions {
        tolerance: 1e-8,
        max_iterations: 10 * n,
    };
    let op = SymmetricLower(a.as_ref());
    let mut x = vec![0.0; n];
    let jacobi = Jacobi::from_diagonal(&diagonal(a.as_ref()));
    let with_jacobi = cg(&op, &jacobi, &b, &mut x, options).unwrap().iterations;
    let mut x = vec![0.0; n];
    let ic = IncompleteCholesky::new(a.as_ref()).unwrap();
    let with_ic = cg(&op, &ic, &b, &mut x, options).unwrap().iterations;
    assert!(with_ic < with_jacobi, "IC {with_ic}, Jacobi {with_jacobi}");
}

/// A non-positive pivot triggers Manteuffel's shift: `[[1, 2], [2, 1]]` (indefinite, full
/// pattern) factors only once `(1 + alpha)^2 > 4`, i.e. `alpha > 1`; the shifted factor
/// is SPD. A non-positive diagonal entry is an error no shift can fix.
#[test]
fn incomplete_cholesky_shifts_on_breakdown() {
    let a = symmetric(2, &[(0, 0, 1.0), (1, 0, 2.0), (1, 1, 1.0)]);
    let ic = IncompleteCholesky::new(a.as_ref()).unwrap();
    assert!(
        ic.shift() > 1.0 && ic.shift() <= 2.0,
        "shift {}",
        ic.shift()
    );
    let mut z = [0.0; 2];
    for r in [[1.0, 0.0], [0.0, 1.0], [1.0, -1.0], [1.0, 1.0]] {
        ic.apply(&r, &mut z);
        assert!(r[0] * z[0] + r[1] * z[1] > 0.0, "M^-1 not SPD at {r:?}");
    }
    let bad = symmetric(2, &[(0, 0, 1.0), (1, 1, -1.0)]);
    assert!(IncompleteCholesky::new(bad.as_ref()).is_err());
}

/// MINRES with `diag(IC(K), S)` solves a saddle point `[[K, G^T], [G, -C]]` (a grid
/// chain `K`, a random `G`, `C = I`) to its tolerance (MINRES also checks that the
/// preconditioner is SPD).
#[test]
fn block_diagonal_preconditioner_solves_a_saddle_point() {
    let mut rng = Rng(9);
    let n = 40;
    let m = 10;
    let parent: Vec<usize> = (1..n).collect();
    let k = tree_matrix(&parent, &mut rng);
    let g_entries: Vec<(usize, usize)> = (0..m)
        .flat_map(|i| [(i, 4 * i), (i, 4 * i + 1), (i, 4 * i + 3)])
        .collect();
    let g_values: Vec<f64> = g_entries.iter().map(|_| rng.uniform()).collect();
    let g = SparsityPattern::new(m, n, &g_entries, Triangle::Full)
        .unwrap()
        .assemble(&g_values)
        .unwrap();
    let c = symmetric(m, &(0..m).map(|i| (i, i, 1.0)).collect::<Vec<_>>());
    let k_op = SymmetricLower(k.as_ref());
    let c_op = SymmetricLower(c.as_ref());
    let op = SaddlePoint {
        k: &k_op,
        g: g.as_ref(),
        c: Some(&c_op),
    };
    let ic = IncompleteCholesky::new(k.as_ref()).unwrap();
    let schur = Jacobi::from_diagonal(&vec![1.0; m]);
    let pre = BlockDiagonal {
        first: &ic,
        second: &schur,
    };
    let b: Vec<f64> = (0..n + m).map(|_| rng.uniform()).collect();
    let mut x = vec![0.0; n + m];
    let options = IterativeOptions {
        tolerance: 1e-10,
        max_iterations: 500,
    };
    let report = minres(&op, &pre, &b, &mut x, options).unwrap();
    assert!(report.residual <= 1e-10, "{report:?}");
}
