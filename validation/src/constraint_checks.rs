//! A constraint set's values, Jacobian and geometric stiffness as dense matrices, and their
//! agreement with central differences: the one harness of the constraint tests on 4- and
//! 10-node meshes.

use crate::fd;
use isochor_constraints::{
    geometric_stiffness_matrix, jacobian_matrix, ConstraintSet, SparseMatrix,
};
use isochor_mesh::Vec3;
use nalgebra::{DMatrix, DVector};

/// Positions as one vector, node-major (`3 * node + axis`).
pub fn flatten(x: &[Vec3]) -> DVector<f64> {
    DVector::from_iterator(3 * x.len(), x.iter().flat_map(|p| p.iter().copied()))
}

/// Inverse of [`flatten`].
pub fn unflatten(q: &DVector<f64>) -> Vec<Vec3> {
    q.as_slice()
        .chunks_exact(3)
        .map(Vec3::from_column_slice)
        .collect()
}

/// A dense matrix of `shape` from sparse `(value, (row, col))` entries, duplicates summed.
fn dense(a: &SparseMatrix) -> DMatrix<f64> {
    let mut d = DMatrix::zeros(a.rows(), a.cols());
    for (v, (r, c)) in a {
        d[(r, c)] += v;
    }
    d
}

/// The constraint values `phi(x)`.
pub fn values(set: &dyn ConstraintSet, x: &[Vec3]) -> DVector<f64> {
    let mut phi = DVector::zeros(set.num_constraints());
    set.values(x, phi.as_mut_slice())
        .expect("constraint values");
    phi
}

/// The Jacobian `G` at `x`, dense.
pub fn jacobian(set: &dyn ConstraintSet, x: &[Vec3]) -> DMatrix<f64> {
    dense(&jacobian_matrix(set, x).expect("constraint Jacobian"))
}

/// The geometric stiffness `K_g` at `x` and multipliers `p`, dense.
pub fn geometric_stiffness(set: &dyn ConstraintSet, x: &[Vec3], p: &[f64]) -> DMatrix<f64> {
    dense(&geometric_stiffness_matrix(set, x, p).expect("geometric stiffness"))
}

/// Relative errors of a set's derivatives at `x` with multipliers `p` (the first
/// `num_constraints` entries).
#[derive(Debug, Clone, Copy)]
pub struct DerivativeErrors {
    /// `G` against central differences of `phi`.
    pub jacobian: f64,
    /// `K_g` against central differences of `G^T p`.
    pub geometric_stiffness: f64,
    /// `max |K_g - K_g^T| / max |K_g|`.
    pub asymmetry: f64,
}

/// `G` against central differences of `phi` and `K_g` against central differences of
/// `G^T p` (both relative, max norm, with the floor `1e-12`), and the asymmetry of `K_g`.
/// The step is [`fd::STEP`] times `scale`, the size of the elements.
pub fn derivative_errors(
    set: &dyn ConstraintSet,
    x: &[Vec3],
    p: &[f64],
    scale: f64,
) -> DerivativeErrors {
    let q = flatten(x);
    let p = &p[..set.num_constraints()];
    let step = fd::STEP * scale;
    let g = jacobian(set, x);
    let g_fd = fd::jacobian(|q| values(set, &unflatten(q)), &q, step);
    let kg = geometric_stiffness(set, x, p);
    // G^T p straight from the pattern: cheaper than assembling G for every evaluation.
    let pattern = set.jacobian_pattern();
    let force = |q: &DVector<f64>| {
        let mut entries = vec![0.0; pattern.len()];
        set.jacobian_values(&unflatten(q), &mut entries)
            .expect("Jacobian values");
        let mut f = DVector::zeros(q.len());
        for (&(row, dof), g) in pattern.iter().zip(entries) {
            f[dof] += g * p[row];
        }
        f
    };
    let kg_fd = fd::jacobian(force, &q, step);
    DerivativeErrors {
        jacobian: fd::relative_error(&g, &g_fd, 1e-12),
        geometric_stiffness: fd::relative_error(&kg, &kg_fd, 1e-12),
        asymmetry: (&kg - kg.transpose()).amax() / kg.amax().max(f64::MIN_POSITIVE),
    }
}
