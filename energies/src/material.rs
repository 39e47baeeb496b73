//! The two traits every material of the energy layer implements.

use crate::{Matrix9, OutOfDomain};
use nalgebra::Matrix3;

/// An isotropic hyperelastic energy density `Psi(F)` with its PK1 stress and tangent.
///
/// Implementations return [`OutOfDomain`] instead of NaN when `F` is outside their domain
/// (`det F <= 0` for energies with `log J`).
///
/// ```
/// use isochor_energies::{standard_neo_hookean, Hyperelastic, Lame};
/// use nalgebra::Matrix3;
///
/// let material = standard_neo_hookean(Lame::from_young_poisson(1e5, 0.45)?)?;
/// // At rest the stress vanishes; under a 1 % uniaxial stretch it pulls along x.
/// assert!(material.pk1(&Matrix3::identity())?.norm() < 1e-9);
/// let p = material.pk1(&Matrix3::from_diagonal(&[1.01, 1.0, 1.0].into()))?;
/// assert!(p[(0, 0)] > 0.0 && p[(0, 1)] == 0.0);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub trait Hyperelastic: Send + Sync + std::fmt::Debug {
    /// Short name for reports and errors.
    fn name(&self) -> &'static str;

    /// Energy density `Psi(F)` per unit rest volume.
    fn energy_density(&self, f: &Matrix3<f64>) -> Result<f64, OutOfDomain>;

    /// First Piola-Kirchhoff stress `P = dPsi/dF`.
    fn pk1(&self, f: &Matrix3<f64>) -> Result<Matrix3<f64>, OutOfDomain>;

    /// Tangent `dP/dF` as a 9x9 matrix in column-major flattening.
    fn pk1_derivative(&self, f: &Matrix3<f64>) -> Result<Matrix9, OutOfDomain>;

    /// Whether the density is defined at `J = det F` (true everywhere for invertible energies).
    fn is_defined_at(&self, j: f64) -> bool {
        j > 0.0
    }
}

/// A volumetric penalty `U(J)` with `U(1) = U'(1) = 0`, scaled by `lambda` by its user.
pub trait VolumetricPenalty: Send + Sync + std::fmt::Debug {
    /// Short name for reports and errors.
    fn name(&self) -> &'static str;
    /// `U(J)`.
    fn value(&self, j: f64) -> Result<f64, OutOfDomain>;
    /// `U'(J)`.
    fn first_derivative(&self, j: f64) -> Result<f64, OutOfDomain>;
    /// `U''(J)`.
    fn second_derivative(&self, j: f64) -> Result<f64, OutOfDomain>;
    /// Whether `U` is defined at `J`.
    fn is_defined_at(&self, j: f64) -> bool {
        j > 0.0
    }
}
