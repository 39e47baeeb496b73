//! # isochor-constraints
//!
//! Volume constraint sets seen by the solvers only through [`ConstraintSet`]: values
//! `phi(x)`, Jacobian `G`, geometric stiffness `sum_i p_i Hess(phi_i)` and compliance `C`
//! (Francu et al. 2021, eq. 15-19 and 23; Sheen et al. 2021, eq. 6-8), on meshes of 4- or
//! 10-node tetrahedra ([`isochor_mesh::ElementMesh`]).
//!
//! - [`Measure`]: linear `J - 1` or logarithmic `log J` (sec. 6), a density of `F` whose
//!   integrals over the elements, by quadrature, make every constraint row; its derivatives
//!   come from the quadrature kernel of `isochor-energies`, the one chain rule of both crates.
//! - [`PerElementConstraints`] (P0, sec. 4.6), [`NodalConstraints`] (P1 on the corners, eq. 27,
//!   consistent or lumped compliance; Taylor-Hood P2-P1 on 10-node tets) and
//!   [`ZonalConstraints`] (Sheen et al. eq. 6-9). Each has a constructor on a linear
//!   [`isochor_mesh::TetMesh`] (the one-point rule) and one on an element mesh with a
//!   quadrature rule ([`exact_rule`] is the recommended one).
//! - [`jacobian_matrix`] and [`geometric_stiffness_matrix`] for analysis.
//!
//! Sign convention: the Lagrangian is `L = E + p^T phi` with `phi_e = v_e - V_e`, so the
//! multipliers are tension-positive pressures (`p = kappa (J - 1)` at equilibrium
//! `phi = C p` for the linear measure).

#![deny(missing_docs)]

mod constraint_set;
mod error;
mod matrix;
mod measure;
mod measured;
mod nodal;
mod per_element;
mod zonal;

pub use constraint_set::{Compliance, ConstraintSet};
pub use per_element::PerElementConstraints;

/// The per-element (P0) constraint set under its old name.
#[deprecated(note = "renamed to `PerElementConstraints`")]
pub type ElementConstraints = PerElementConstraints;
pub use error::ConstraintError;
pub use matrix::{geometric_stiffness_matrix, jacobian_matrix, SparseMatrix};
pub use measure::Measure;
pub use nodal::{NodalCompliance, NodalConstraints};
pub use zonal::ZonalConstraints;

use isochor_mesh::element::{TetElement, TetQuadrature};

/// The shape `c` that weighs the measure in a constraint row (`integral_e c Phi(J) dV`).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum RowShape {
    /// `c = 1`: one row per element (P0) or per zone.
    One,
    /// `c = L_j`, the linear shape function of corner `j`: four rows per element, one per
    /// corner (P1, Taylor-Hood P2-P1 on 10-node tets).
    Corners,
}

impl RowShape {
    /// Rows per element.
    pub fn rows(self) -> usize {
        match self {
            RowShape::One => 1,
            RowShape::Corners => 4,
        }
    }
}

/// The cheapest rule that integrates the linear measure exactly in rows of `shape` on elements
/// of `kind`: `W_q (J_q - 1) c(xi_q) = w_q (det(dx/dxi) - det(dX/dxi)) c(xi_q)`, a polynomial
/// of degree `3 (p - 1) + deg c` in `xi` for elements of order `p`, curved or not. That is the
/// one-point rule on 4-node tets; on 10-node tets the degree-3 rule for element (P0) and zonal
/// rows and the degree-5 rule for nodal (P1) rows. It also makes zone volumes and the total
/// volume change (the sum of the nodal rows) exact.
pub fn exact_rule(kind: TetElement, shape: RowShape) -> TetQuadrature {
    match (kind, shape) {
        (TetElement::Tet4, _) => TetQuadrature::Degree1,
        (TetElement::Tet10, RowShape::One) => TetQuadrature::Degree3,
        (TetElement::Tet10, RowShape::Corners) => TetQuadrature::Degree5,
    }
}
