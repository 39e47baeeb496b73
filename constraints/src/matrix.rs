//! Assembled sparse matrices of a [`ConstraintSet`], for analysis and tests (solvers keep
//! the fixed patterns and fill values instead).

use crate::{ConstraintError, ConstraintSet};
use isochor_mesh::Vec3;
use sprs::{CsMat, TriMat};

/// A sparse matrix handed to users: `sprs`' compressed form (the interchange type of the
/// workspace; the solvers factorize with faer inside).
pub type SparseMatrix = CsMat<f64>;

/// The constraint Jacobian `G` (`m x 3n`, CSR) at positions `x`, duplicates summed.
///
/// Errors: those of [`ConstraintSet::jacobian_values`].
pub fn jacobian_matrix(
    set: &dyn ConstraintSet,
    x: &[Vec3],
) -> Result<SparseMatrix, ConstraintError> {
    let pattern = set.jacobian_pattern();
    let mut values = vec![0.0; pattern.len()];
    set.jacobian_values(x, &mut values)?;
    Ok(assemble(
        (set.num_constraints(), 3 * x.len()),
        &pattern,
        &values,
    ))
}

/// The geometric stiffness `K_g = sum_i p_i Hess(phi_i)` (`3n x 3n`, CSR, eq. 23) at
/// positions `x` and multipliers `p`, duplicates summed.
///
/// Errors: those of [`ConstraintSet::geometric_stiffness_values`].
pub fn geometric_stiffness_matrix(
    set: &dyn ConstraintSet,
    x: &[Vec3],
    multipliers: &[f64],
) -> Result<SparseMatrix, ConstraintError> {
    let pattern = set.geometric_stiffness_pattern();
    let mut values = vec![0.0; pattern.len()];
    set.geometric_stiffness_values(x, multipliers, &mut values)?;
    Ok(assemble((3 * x.len(), 3 * x.len()), &pattern, &values))
}

/// The CSR matrix of `shape` from an entry pattern and its values, duplicates summed. The
/// `*_values` call that produced `values` has checked `x`, so every index is in range.
fn assemble(shape: (usize, usize), pattern: &[(usize, usize)], values: &[f64]) -> SparseMatrix {
    let mut triplets = TriMat::with_capacity(shape, pattern.len());
    for (&(row, col), &value) in pattern.iter().zip(values) {
        triplets.add_triplet(row, col, value);
    }
    triplets.to_csr()
}
