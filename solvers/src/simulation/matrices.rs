//! The sparse matrices of a linearization for a user: `K`, `G`, `C` and the KKT matrix as
//! `sprs::CsMat`, the crate's interchange type (faer stays the solvers' own type), with
//! MatrixMarket export.

use super::linearize::{Linearizer, Sparse};
use super::state::State;
use super::Simulation;
use crate::error::SolverError;
use crate::problem::schedule::LoadLevel;
use sprs::{CsMat, TriMat};
use std::path::Path;

/// The matrices of one Newton linearization at a state, over the free DOFs (Dirichlet DOFs
/// eliminated) and the multipliers; every matrix is stored in full (both triangles of a
/// symmetric one), duplicates summed.
///
/// - `K` ([`Matrices::stiffness`], `n x n` with `n = free.len()`): the Hessian of the
///   energy over the free DOFs (elastic, epidermis, pressure loads, contact), plus the
///   constraints' geometric stiffness `sum_i p_i Hess(phi_i)` (eq. 23 of Francu et al.
///   2021) for the saddle-point methods, plus the augmented terms for `condensed` and
///   `dual`; with `M / dt^2` added in implicit Euler.
/// - `G` ([`Matrices::jacobian`], `m x n`): the constraint Jacobian over the free DOFs.
/// - `C` ([`Matrices::compliance`], `m x m`).
/// - [`Matrices::kkt`]: `[[K, G^T], [G, -C]]` (eq. 24) for the saddle-point methods
///   (`mixed-*`, `zonal`), `K` otherwise: the matrix Newton factorizes.
#[derive(Debug, Clone, PartialEq)]
pub struct Matrices {
    /// The free DOFs (indices `3 v + axis` into the positions), in row order of `K`.
    pub free: Vec<usize>,
    /// `K` over the free DOFs.
    pub stiffness: CsMat<f64>,
    /// `G` over the free DOFs (saddle-point methods only).
    pub jacobian: Option<CsMat<f64>>,
    /// `C` (saddle-point methods only; an empty `m x m` matrix when `C = 0`).
    pub compliance: Option<CsMat<f64>>,
    /// The matrix of the Newton step.
    pub kkt: CsMat<f64>,
}

impl Matrices {
    /// Writes every matrix present to `folder` as a MatrixMarket coordinate file:
    /// `stiffness.mtx`, `kkt.mtx`, and for the saddle-point methods `jacobian.mtx` and
    /// `compliance.mtx` (read by SciPy's `scipy.io.mmread`, MATLAB or Julia).
    pub fn write_matrix_market(&self, folder: impl AsRef<Path>) -> std::io::Result<()> {
        let folder = folder.as_ref();
        let named = [
            ("stiffness", Some(&self.stiffness)),
            ("kkt", Some(&self.kkt)),
            ("jacobian", self.jacobian.as_ref()),
            ("compliance", self.compliance.as_ref()),
        ];
        for (name, matrix) in named {
            if let Some(matrix) = matrix {
                sprs::io::write_matrix_market(folder.join(format!("{name}.mtx")), matrix)?;
            }
        }
        Ok(())
    }
}

impl Linearizer<'_> {
    /// The matrices of the linear system [`Self::newton_system`] builds at `trial`, sparse.
    pub fn matrices(&mut self, trial: &State) -> Result<Matrices, SolverError> {
        let linear = self.linearize(trial)?;
        let (n, free) = (linear.k.ncols(), self.system.model.dofs.free().to_vec());
        let m = linear.kkt.as_ref().map_or(0, |(g, _)| g.nrows());
        let mut stiffness = TriMat::new((n, n));
        add_block(&mut stiffness, &linear.k, (0, 0), 1.0, true);
        let mut kkt = TriMat::new((n + m, n + m));
        add_block(&mut kkt, &linear.k, (0, 0), 1.0, true);
        let (mut jacobian, mut compliance) = (None, None);
        if let Some((g, c)) = &linear.kkt {
            add_block(&mut kkt, g, (n, 0), 1.0, true);
            let mut gm = TriMat::new((m, n));
            add_block(&mut gm, g, (0, 0), 1.0, false);
            let mut cm = TriMat::new((m, m));
            if let Some(c) = c {
                add_block(&mut kkt, c, (n, n), -1.0, false);
                add_block(&mut cm, c, (0, 0), 1.0, false);
            }
            jacobian = Some(gm.to_csr());
            compliance = Some(cm.to_csr());
        }
        Ok(Matrices {
            free,
            stiffness: stiffness.to_csr(),
            jacobian,
            compliance,
            kkt: kkt.to_csr(),
        })
    }
}

impl Simulation {
    /// The matrices of the quasi-static Newton step at `state` (loads, prescribed motions
    /// and obstacles at its load parameter `state.t`, no inertia): see [`Matrices`]. For
    /// implicit Euler, take them from [`Self::linearizer`] with [`Linearizer::matrices`].
    ///
    /// ```
    /// use isochor_mesh::generate::box_grid;
    /// use isochor_solvers::{Problem, Settings, Simulation, Vec3};
    ///
    /// let mesh = box_grid(Vec3::zeros(), Vec3::repeat(0.01), [1, 1, 1])?;
    /// let floor: Vec<usize> = (0..4).collect();
    /// let problem = Problem::builder(mesh).clamp(floor).build()?;
    /// let mut simulation = Simulation::new(problem, Settings::default())?;
    /// let state = simulation.state().clone();
    /// let m = simulation.matrices(&state)?;
    /// let (n, rows) = (m.free.len(), simulation.constraint_volumes().len());
    /// assert_eq!(m.kkt.shape(), (n + rows, n + rows));
    /// assert_eq!(m.kkt.to_csc(), m.kkt.transpose_view().to_owned().to_csc());
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn matrices(&mut self, state: &State) -> Result<Matrices, SolverError> {
        self.linearizer_at(LoadLevel::quasi_static(state.t), None)?
            .matrices(state)
    }
}

/// Adds `scale * a` to `out` with its `(0, 0)` entry at `at`; with `mirror`, also its
/// transpose at the transposed offset (a diagonal block's diagonal once): the one place a
/// faer matrix becomes `sprs` entries.
fn add_block(out: &mut TriMat<f64>, a: &Sparse, at: (usize, usize), scale: f64, mirror: bool) {
    let a = a.as_ref();
    for c in 0..a.ncols() {
        for (r, v) in a.row_idx_of_col(c).zip(a.val_of_col(c)) {
            out.add_triplet(at.0 + r, at.1 + c, scale * v);
            if mirror && (at.0 + r != at.1 + c) {
                out.add_triplet(at.1 + c, at.0 + r, scale * v);
            }
        }
    }
}
