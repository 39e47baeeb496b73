//! Energy terms: everything that contributes to the objective of a solve is a term with a
//! value, a gradient, a Hessian whose sparsity pattern is fixed, and a validity check that
//! line searches use to back off (the "Form" contract of polyfem).

mod augmented;
mod cloth;
mod contact;
mod dead_load;
mod elastic;
mod enclosed_volume;
mod epidermis;
mod faces;
mod inertia;
mod openings;
mod pair_rows;
mod pressure;
mod surface_contact;
mod surface_friction;

pub use augmented::AugmentedConstraints;
pub use cloth::Cloth;
pub use contact::{Contact, ContactState, ContactSummary};
pub use dead_load::DeadLoad;
pub use elastic::{elastic_rule, Elastic};
pub use enclosed_volume::EnclosedVolume;
pub use epidermis::EpidermisTerm;
pub use faces::Faces;
pub use inertia::Inertia;
pub use openings::Openings;
pub use pressure::FollowerPressure;
pub use surface_contact::{SurfaceContact, SurfaceContactSpec, SurfaceContactSummary};
pub use surface_friction::{FrictionLag, SurfaceFriction};

use crate::error::SolverError;
use crate::problem::schedule::LoadLevel;
use isochor_mesh::Vec3;

/// A term of the total energy `E(x)` minimized (or made stationary) by the solvers.
///
/// `level` says where the run's loads stand: external loads scale with it (by their curve or
/// the default ramp), stored energies ignore it.
pub trait EnergyTerm: Send + Sync + std::fmt::Debug {
    /// Short name for reports.
    fn name(&self) -> &'static str;

    /// `(dof, dof)` of every Hessian entry (duplicates summed), fixed for the term's life;
    /// empty for terms linear in `x`.
    fn hessian_pattern(&self) -> Vec<(usize, usize)>;

    /// The Hessian pattern as dense element blocks when it is one (the entries of
    /// [`EnergyTerm::hessian_pattern`] in its order): the assembly then lays it out per node
    /// pair, a ninth of the work. `None` (the default) for other patterns.
    fn hessian_blocks(&self) -> Option<ElementBlocks> {
        None
    }

    /// The energy at `x`; adds the gradient into `gradient` (length `3n`) and writes the
    /// Hessian entries, in pattern order, into `hessian` when asked.
    fn evaluate(
        &self,
        x: &[Vec3],
        level: &LoadLevel,
        gradient: Option<&mut [f64]>,
        hessian: Option<&mut [f64]>,
    ) -> Result<f64, SolverError>;

    /// For terms whose element Hessians can be indefinite and are then PSD-projected (barrier
    /// contact, cloth): makes later evaluations project them (`true`, their default) or keep
    /// them exact (`false`), and returns whether the term now has any such block (without
    /// one there is nothing to choose). The Newton solvers try the exact Hessian first and
    /// project only where it fails to factorize. Other terms: `false`, nothing changes.
    fn project_hessian(&self, _projected: bool) -> bool {
        false
    }

    /// Whether `x` lies in the term's domain (for example no inverted tet under `log J`).
    fn is_valid(&self, _x: &[Vec3]) -> bool {
        true
    }

    /// Whether the term's energy has a meaning at inverted elements (`J <= 0` somewhere), so
    /// that a state with such elements may be accepted (invertible energies such as Stable
    /// neo-Hookean); false for energies undefined there (`log J`, `J^-2/3`).
    fn admits_inversion(&self) -> bool {
        true
    }

    /// Whether the term is an external load (its energy is reported as external work).
    fn is_external(&self) -> bool {
        false
    }

    /// Size of the quantities the term sums into its energy, constant over a run, beyond
    /// the energy itself (e.g. `sum_e V_e` times the material's stiffness for an elastic
    /// energy, whose `mu/2 tr(F^T F)` part does not vanish at rest): energy changes below
    /// about `1e3 eps` times it are rounding noise to the line search.
    fn rounding_scale(&self) -> f64 {
        0.0
    }
}

/// How the entries of a dense element block are listed.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum BlockOrder {
    /// Column by column, as the element matrices of the terms.
    ColumnMajor,
    /// Row by row, as the constraints' geometric stiffness.
    RowMajor,
}

impl BlockOrder {
    /// `(row, col)` of the entry at `(outer, inner)` of the listing.
    pub fn pair(self, outer: usize, inner: usize) -> (usize, usize) {
        match self {
            BlockOrder::ColumnMajor => (inner, outer),
            BlockOrder::RowMajor => (outer, inner),
        }
    }
}

/// A Hessian pattern of dense element blocks: element `e` couples the nodes
/// `nodes[e * per_element..(e + 1) * per_element]` (3 DOFs each, node-major), its
/// `3n x 3n` block listed in `order`, elements one after the other.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct ElementBlocks {
    /// The elements' nodes, `per_element` each.
    pub nodes: Vec<usize>,
    /// Nodes per element.
    pub per_element: usize,
    /// The order of each block's entries.
    pub order: BlockOrder,
}

impl ElementBlocks {
    /// Number of entries: `(3n)^2` per element.
    pub fn entries(&self) -> usize {
        9 * self.per_element * self.nodes.len()
    }

    /// The `(dof, dof)` pairs of every entry, in order.
    pub fn pairs(&self) -> Vec<(usize, usize)> {
        let dim = 3 * self.per_element;
        let mut out = Vec::with_capacity(self.entries());
        for element in self.nodes.chunks_exact(self.per_element) {
            let dof = |local: usize| 3 * element[local / 3] + local % 3;
            for outer in 0..dim {
                for inner in 0..dim {
                    let (r, c) = self.order.pair(outer, inner);
                    out.push((dof(r), dof(c)));
                }
            }
        }
        out
    }
}

/// Dense `(dof, dof)` pattern of the blocks of an element (or face) with the given nodes, in
/// the column-major order of its `3n x 3n` element matrix.
pub(crate) fn block_pattern(nodes: &[usize]) -> impl Iterator<Item = (usize, usize)> + '_ {
    let dof = move |local: usize| 3 * nodes[local / 3] + local % 3;
    let n = 3 * nodes.len();
    (0..n).flat_map(move |c| (0..n).map(move |r| (dof(r), dof(c))))
}

/// Adds an element vector (node-major, 3 per node) into the global gradient.
pub(crate) fn scatter(nodes: &[usize], local: &[f64], global: &mut [f64]) {
    for (a, &v) in nodes.iter().enumerate() {
        for k in 0..3 {
            global[3 * v + k] += local[3 * a + k];
        }
    }
}
