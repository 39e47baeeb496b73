//! Projection of symmetric Hessians onto the positive semidefinite cone for Newton's method.

use nalgebra::allocator::Allocator;
use nalgebra::{DefaultAllocator, Dim, DimDiff, DimSub, OMatrix, SymmetricEigen, U1};

/// Eigenvalues above `-PSD_TOLERANCE * max |eigenvalue|` count as non-negative.
const PSD_TOLERANCE: f64 = 1e-12;

/// The nearest (Frobenius) positive semidefinite matrix to the symmetric `m`: eigenvalues below
/// zero are clamped to zero, `V max(Lambda, 0) V^T`.
///
/// If every eigenvalue is above `-1e-12 max |eigenvalue|` (PSD up to rounding, e.g. the rigid
/// modes of an element Hessian), `m` is returned unchanged, bit for bit. Only the lower triangle of `m` is read by the
/// eigensolver; a matrix with non-finite entries is returned unchanged.
pub fn project_to_psd<D>(m: &OMatrix<f64, D, D>) -> OMatrix<f64, D, D>
where
    D: Dim + DimSub<U1>,
    DefaultAllocator: Allocator<D, D> + Allocator<D> + Allocator<DimDiff<D, U1>>,
{
    if !m.iter().all(|v| v.is_finite()) {
        return m.clone();
    }
    let eigen = SymmetricEigen::new(m.clone());
    let tolerance = PSD_TOLERANCE * eigen.eigenvalues.amax();
    if eigen.eigenvalues.iter().all(|&l| l >= -tolerance) {
        return m.clone();
    }
    let SymmetricEigen {
        eigenvectors: v,
        eigenvalues,
    } = eigen;
    let clamped = eigenvalues.map(|l| l.max(0.0));
    let mut vd = v.clone();
    for (mut col, l) in vd.column_iter_mut().zip(clamped.iter()) {
        col *= *l;
    }
    let out = vd * v.transpose();
    // Symmetrize away rounding so downstream code may read either triangle.
    (&out + out.transpose()) * 0.5
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::Matrix12;
    use nalgebra::{DMatrix, Matrix3};

    #[test]
    fn clamps_an_indefinite_matrix() {
        let m = Matrix3::new(2.0, 0.0, 0.0, 0.0, -1.0, 0.0, 0.0, 0.0, 0.5);
        let p = project_to_psd(&m);
        assert_eq!(p, Matrix3::new(2.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.5));
        let d = DMatrix::from_row_slice(2, 2, &[0.0, 1.0, 1.0, 0.0]);
        let pd = project_to_psd(&d);
        approx::assert_relative_eq!(pd, DMatrix::from_element(2, 2, 0.5), epsilon = 1e-15);
    }

    #[test]
    fn keeps_a_psd_matrix() {
        let a = Matrix12::from_fn(|i, j| ((i * 7 + j * 3) % 5) as f64 - 2.0);
        let m = a * a.transpose();
        assert_eq!(project_to_psd(&m), m);
    }
}
