//! # isochor-energies
//!
//! Pure functions of the deformation: hyperelastic energy densities `Psi(F)`, their first
//! Piola-Kirchhoff stress `P = dPsi/dF` and its derivative `dP/dF`, volumetric penalties
//! `U(J)`, and the quadrature kernels that turn them into per-tet and per-triangle energies,
//! gradients and Hessians.
//!
//! Conventions used throughout:
//! - 3x3 matrices are flattened column-major (nalgebra's storage order): `vec(F)[3*j + i] = F[(i, j)]`,
//!   so `dP/dF` is the 9x9 matrix `d vec(P) / d vec(F)`.
//! - Element DOF vectors are node-major: `[x0.x, x0.y, x0.z, x1.x, ...]`; element Hessians are
//!   column-major (the storage of nalgebra's fixed matrices).
//!
//! Contents:
//! - densities ([`Hyperelastic`]): [`Mooney`] (eq. 29 of Francu et al. 2021),
//!   [`DistortionalNeoHookean`] (eq. 32), [`BonetWood`] (eq. 30), [`FbarNeoHookean`]
//!   (eq. 10-12 of Sheen et al. 2021), [`DistortionalStableNeoHookean`] (the distortional part
//!   of Stable neo-Hookean, Smith et al. 2018), and the uncoupled invariant models
//!   [`MooneyRivlin`] `c10 (Ib1 - 3) + c01 (Ib2 - 3)` and [`Yeoh`]
//!   `c10 (Ib1 - 3) + c20 (Ib1 - 3)^2 + c30 (Ib1 - 3)^3`, and the uncoupled N-term [`Ogden`]
//!   model on the isochoric principal stretches;
//! - penalties ([`VolumetricPenalty`]): [`LogPenalty`], [`QuadraticPenalty`], [`SheenPenalty`]
//!   (eq. 13-15 of Sheen et al. 2021), [`Snh2Penalty`] (SNH2 of Fig. 3 of Sheen et al.),
//!   [`StvkPenalty`] (Saint Venant-Kirchhoff under pure dilation: our reading of Fig. 3's
//!   Kikuuwe et al. 2009 curve);
//! - [`Composed`] `Psi_dev + lambda U(J)`: [`standard_neo_hookean`], [`quadratic_neo_hookean`],
//!   [`constrained_neo_hookean`], [`stable_neo_hookean`] and
//!   [`StableNeoHookean::from_linear_lame`] (Smith et al. 2018);
//! - kernels: [`kernel`] (the quadrature kernel: energy `sum_q w_q Psi(F_q)`, gradient
//!   and Hessian of an element of any number of nodes, 4- and 10-node tets), [`tet`] (its
//!   one-point 4-node case with fixed-size types), [`triangle`] (the area element and `J~` of
//!   3- and 6-node faces), [`Epidermis`] (eq. 16 of Sheen et al. 2021), [`project_to_psd`];
//! - [`cloth`]: a fabric sheet's membrane (Saint Venant-Kirchhoff, plane stress) per triangle
//!   and its discrete-shell bending (Grinspun et al. 2003) per hinge;
//! - [`kinematics`]: `vec`, `cof F = dJ/dF`, `d2J/dF2`, shared by every `J`-based term, and
//!   the isochoric invariants `Ib1 = J^-2/3 I_1`, `Ib2 = J^-4/3 I_2` with their gradients,
//!   Hessians and the chain rule of a density `W(Ib1, Ib2)`
//!   ([`kinematics::IsochoricInvariants`]).

#![deny(missing_docs)]

pub mod cloth;
mod composed;
mod epidermis;
mod error;
pub mod kernel;
pub mod kinematics;
mod material;
mod materials;
mod parameters;
mod penalties;
mod psd_projection;
pub mod tet;
pub mod triangle;

pub use composed::{
    constrained_neo_hookean, quadratic_neo_hookean, stable_neo_hookean, standard_neo_hookean,
    Composed, ConstrainedNeoHookean, QuadraticNeoHookean, StableNeoHookean, StandardNeoHookean,
};
pub use epidermis::{Epidermis, TriangleTerms};
pub use error::{OutOfDomain, ParameterError};
pub use material::{Hyperelastic, VolumetricPenalty};
// Every density of `materials/`, one file each: a new one needs no line here.
pub use materials::*;
pub use parameters::{bulk_modulus, Lame};
pub use penalties::{LogPenalty, QuadraticPenalty, SheenPenalty, Snh2Penalty, StvkPenalty};
pub use psd_projection::project_to_psd;

/// The quadrature kernel under its old name.
#[deprecated(
    note = "renamed to `kernel` (the quadrature kernel; `element` is the mesh's reference element)"
)]
pub mod element {
    pub use crate::kernel::{evaluate, RestPoints};
}

/// 9x9 matrix: `dP/dF` in column-major flattening.
pub type Matrix9 = nalgebra::SMatrix<f64, 9, 9>;
/// 9-vector: a flattened 3x3 matrix.
pub type Vector9 = nalgebra::SVector<f64, 9>;
/// 12x12 matrix: a tet element Hessian.
pub type Matrix12 = nalgebra::SMatrix<f64, 12, 12>;
/// 12-vector: a tet element gradient.
pub type Vector12 = nalgebra::SVector<f64, 12>;
