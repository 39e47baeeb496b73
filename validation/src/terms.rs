//! An energy term evaluated densely, for comparing its derivatives with finite differences.

use isochor_mesh::Vec3;
use isochor_solvers::terms::EnergyTerm;
use isochor_solvers::LoadLevel;
use nalgebra::DMatrix;

/// `(energy, gradient, dense Hessian)` of `term` at `x` and `level`: the Hessian's entries
/// summed from the term's pattern. Panics if the term refuses `x` (a test's bug).
pub fn evaluate_dense(
    term: &dyn EnergyTerm,
    x: &[Vec3],
    level: &LoadLevel,
) -> (f64, Vec<f64>, DMatrix<f64>) {
    let n = 3 * x.len();
    let pattern = term.hessian_pattern();
    let mut gradient = vec![0.0; n];
    let mut values = vec![0.0; pattern.len()];
    let energy = term
        .evaluate(x, level, Some(&mut gradient), Some(&mut values))
        .unwrap();
    let mut hessian = DMatrix::zeros(n, n);
    for (&(r, c), v) in pattern.iter().zip(&values) {
        hessian[(r, c)] += v;
    }
    (energy, gradient, hessian)
}
