//! # isochor-energies
//!
//! Pure functions of the deformation: hyperelastic energy densities `Psi(F)`, their first
//! Piola-Kirchhoff stress `P = dPsi/dF` and its derivative `dP/dF`, volumetric penalties
//! `U(J)`, and the element kernels that turn them into per-tet and per-triangle energies,
//! gradients and Hessians.
//!
//! Conventions used throughout:
//! - 3x3 matrices are flattened column-major (nalgebra's storage order): `vec(F)[3*j + i] = F[(i, j)]`,
//!   so `dP/dF` is the 9x9 matrix `d vec(P) / d vec(F)`.
//! - Element DOF vectors are vertex-major: `[x0.x, x0.y, x0.z, x1.x, ...]`.

mod error;
mod material;
mod parameters;

pub use error::{OutOfDomain, ParameterError};
pub use material::{Hyperelastic, VolumetricPenalty};
pub use parameters::{bulk_modulus, Lame};

/// 9x9 matrix: `dP/dF` in column-major flattening.
pub type Matrix9 = nalgebra::SMatrix<f64, 9, 9>;
/// 9-vector: a flattened 3x3 matrix.
pub type Vector9 = nalgebra::SVector<f64, 9>;
/// 12x12 matrix: a tet element Hessian.
pub type Matrix12 = nalgebra::SMatrix<f64, 12, 12>;
/// 12-vector: a tet element gradient.
pub type Vector12 = nalgebra::SVector<f64, 12>;
