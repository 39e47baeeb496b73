//! Assembled sparse matrices of a [`ConstraintSet`], for analysis and tests (solvers keep
//! the fixed patterns and fill values instead).

use crate::{ConstraintError, ConstraintSet};
use faer::sparse::{SparseColMat, Triplet};
use isochor_mesh::Vec3;

/// A sparse matrix in faer's compressed-column form, the type the solvers use.
pub type SparseMatrix = SparseColMat<usize, f64>;

/// The constraint Jacobian `G` (`m x 3n`) at positions `x`, duplicates summed.
///
/// Errors: those of [`ConstraintSet::jacobian_values`].
pub fn jacobian_matrix(
    set: &dyn ConstraintSet,
    x: &[Vec3],
) -> Result<SparseMatrix, ConstraintError> {
    let pattern = set.jacobian_pattern();
    let mut values = vec![0.0; pattern.len()];
    set.jacobian_values(x, &mut values)?;
    assemble((set.num_constraints(), 3 * x.len()), &pattern, &values)
}

/// The geometric stiffness `K_g = sum_i p_i Hess(phi_i)` (`3n x 3n`, eq. 23) at
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
    assemble((3 * x.len(), 3 * x.len()), &pattern, &values)
}

/// The matrix of `shape` from an entry pattern and its values, duplicates summed.
fn assemble(
    shape: (usize, usize),
    pattern: &[(usize, usize)],
    values: &[f64],
) -> Result<SparseMatrix, ConstraintError> {
    let triplets: Vec<Triplet<usize, usize, f64>> = pattern
        .iter()
        .zip(values)
        .map(|(&(row, col), &value)| Triplet::new(row, col, value))
        .collect();
    SparseColMat::try_new_from_triplets(shape.0, shape.1, &triplets).map_err(|e| {
        ConstraintError::InvalidMesh {
            reason: format!("the constraint pattern does not fit a {shape:?} matrix: {e:?}"),
        }
    })
}
