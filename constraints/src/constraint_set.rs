//! The interface between constraints and solvers.

use crate::ConstraintError;
use isochor_mesh::Vec3;

/// The compliance matrix `C` of a constraint set (eq. 18 of Francu et al. 2021).
#[derive(Debug, Clone, PartialEq)]
pub enum Compliance {
    /// Diagonal `C` (per-element constraints, lumped nodal constraints, hard constraints as zeros).
    Diagonal(Vec<f64>),
    /// General symmetric `C` as `(row, col, value)` triplets, both triangles present,
    /// duplicates summed (consistent nodal compliance).
    Sparse(Vec<(usize, usize, f64)>),
}

impl Compliance {
    /// The non-zero entries as `(row, col, value)` triplets (a diagonal one's on the
    /// diagonal; a sparse one's as stored, both triangles): empty for hard constraints.
    pub fn nonzero_entries(self) -> Vec<(usize, usize, f64)> {
        match self {
            Compliance::Diagonal(d) => d
                .into_iter()
                .enumerate()
                .filter(|e| e.1 != 0.0)
                .map(|(i, v)| (i, i, v))
                .collect(),
            Compliance::Sparse(t) => t.into_iter().filter(|e| e.2 != 0.0).collect(),
        }
    }
}

/// A set of `m` scalar constraints `phi(x) = C p` on the `3n` position DOFs
/// (DOF `3 * vertex + axis`).
///
/// Sparse structure is split from values so that solvers build sparsity patterns once:
/// the `*_pattern` methods return the index list of every entry (duplicates allowed; they
/// are summed), fixed for the life of the set, and the `*_values` methods fill a buffer of
/// the same length and order.
pub trait ConstraintSet: Send + Sync + std::fmt::Debug {
    /// Short name for reports (`"nodal"`, `"element"`, `"zonal"`, ...).
    fn name(&self) -> &'static str;

    /// Number of constraints `m` (rows of `G`).
    fn num_constraints(&self) -> usize;

    /// Constraint values `phi(x)`, written into `out` (length `m`).
    fn values(&self, x: &[Vec3], out: &mut [f64]) -> Result<(), ConstraintError>;

    /// `(row, dof)` of every Jacobian entry.
    fn jacobian_pattern(&self) -> Vec<(usize, usize)>;

    /// Jacobian entries `G = d phi / dx` in the order of [`ConstraintSet::jacobian_pattern`].
    fn jacobian_values(&self, x: &[Vec3], out: &mut [f64]) -> Result<(), ConstraintError>;

    /// `(dof, dof)` of every geometric stiffness entry (both triangles).
    fn geometric_stiffness_pattern(&self) -> Vec<(usize, usize)>;

    /// The geometric stiffness pattern as dense element blocks when it is one: the elements'
    /// flat node list and the nodes per element, each block row-major over the element's
    /// DOFs (3 per node, node-major), the entries and order of
    /// [`ConstraintSet::geometric_stiffness_pattern`]. The solvers then lay it out per node
    /// pair; `None` (the default) for other patterns.
    fn geometric_stiffness_blocks(&self) -> Option<(&[usize], usize)> {
        None
    }

    /// Geometric stiffness `K_g = sum_i p_i Hess(phi_i)` (eq. 23) for multipliers `p`
    /// (length `m`), in the order of [`ConstraintSet::geometric_stiffness_pattern`].
    fn geometric_stiffness_values(
        &self,
        x: &[Vec3],
        multipliers: &[f64],
        out: &mut [f64],
    ) -> Result<(), ConstraintError>;

    /// The compliance `C` (constant under Assumption 2 of Francu et al. 2021).
    fn compliance(&self) -> Compliance;

    /// Whether the constraints have a meaning at inverted elements (`J <= 0`): true for
    /// volumes (the linear measure), false for the logarithmic measure.
    fn admits_inversion(&self) -> bool;

    /// Per-tet pressure for visualization, from the multipliers at positions `x` (one value
    /// per tet, tension positive). Empty when `x` or `multipliers` has the wrong length, so
    /// callers that check the length against the tet count reject it.
    fn tet_pressures(&self, x: &[Vec3], multipliers: &[f64]) -> Vec<f64>;

    /// The vertex that constraint `row` is attached to, if any: solvers order each such
    /// row right after that vertex's DOFs in the KKT system, which keeps the `C = 0`
    /// factorization pivot-safe (see docs/toolchain.md). `None` (the default) for rows
    /// spread over many vertices, such as zonal constraints.
    fn anchor_vertex(&self, row: usize) -> Option<usize> {
        let _ = row;
        None
    }
}
