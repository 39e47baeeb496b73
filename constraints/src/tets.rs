//! What every constraint set shares: the tets with their rest volumes and measure, the DOF
//! layout of element blocks, argument checks, and the parallel fill of Jacobian rows and
//! geometric stiffness blocks into caller-owned buffers.

use crate::{ConstraintError, Measure};
use isochor_energies::{Matrix12, Vector12};
use isochor_mesh::{TetMesh, Vec3};
use rayon::prelude::*;

/// Entries of one 12x12 element block in a geometric stiffness pattern.
pub(crate) const BLOCK: usize = 144;

/// Smallest number of tets a rayon task handles (per-tet work is well under a microsecond,
/// so finer splitting costs more than it gains).
const TETS_PER_TASK: usize = 256;

/// The tets of a mesh with their rest volumes `V_e` and the measure `m_e = V_e Phi(J_e)`
/// every constraint row is assembled from.
#[derive(Debug, Clone)]
pub(crate) struct MeasuredTets {
    measure: Measure,
    tets: Vec<[usize; 4]>,
    rest_volumes: Vec<f64>,
    num_vertices: usize,
}

impl MeasuredTets {
    pub(crate) fn new(mesh: &TetMesh, measure: Measure) -> Self {
        MeasuredTets {
            measure,
            tets: mesh.tets().to_vec(),
            rest_volumes: mesh.rest_volumes().to_vec(),
            num_vertices: mesh.num_vertices(),
        }
    }

    pub(crate) fn measure(&self) -> Measure {
        self.measure
    }

    pub(crate) fn len(&self) -> usize {
        self.tets.len()
    }

    pub(crate) fn num_vertices(&self) -> usize {
        self.num_vertices
    }

    pub(crate) fn tet(&self, e: usize) -> [usize; 4] {
        self.tets[e]
    }

    pub(crate) fn rest_volume(&self, e: usize) -> f64 {
        self.rest_volumes[e]
    }

    /// The 12 global DOFs `3 * vertex + axis` of tet `e`, vertex-major.
    pub(crate) fn dofs(&self, e: usize) -> [usize; 12] {
        let t = self.tets[e];
        std::array::from_fn(|i| 3 * t[i / 3] + i % 3)
    }

    /// Checks that `x` holds one position per mesh vertex.
    pub(crate) fn check_positions(&self, x: &[Vec3]) -> Result<(), ConstraintError> {
        check_len("positions", self.num_vertices, x.len())
    }

    fn positions(&self, e: usize, x: &[Vec3]) -> [Vec3; 4] {
        self.tets[e].map(|i| x[i])
    }

    /// Volume ratio `J_e = v_e / V_e`.
    pub(crate) fn volume_ratio(&self, e: usize, x: &[Vec3]) -> f64 {
        crate::volume::tet_volume(&self.positions(e, x)) / self.rest_volumes[e]
    }

    /// The true pressure of tet `e` from its interpolated multiplier `p` (see
    /// [`Measure::true_pressure`]).
    pub(crate) fn true_pressure(&self, e: usize, x: &[Vec3], p: f64) -> f64 {
        self.measure.true_pressure(p, self.volume_ratio(e, x))
    }

    /// Writes `m_e(x)` of every tet into `out`, in parallel. `x` must have been checked.
    pub(crate) fn fill_values(&self, x: &[Vec3], out: &mut [f64]) -> Result<(), ConstraintError> {
        check_len("element values", self.len(), out.len())?;
        out.par_iter_mut()
            .with_min_len(TETS_PER_TASK)
            .enumerate()
            .try_for_each(|(e, m)| {
                *m = self
                    .measure
                    .value(e, &self.positions(e, x), self.rest_volumes[e])?;
                Ok(())
            })
    }

    fn gradient(&self, e: usize, x: &[Vec3]) -> Result<Vector12, ConstraintError> {
        self.measure
            .gradient(e, &self.positions(e, x), self.rest_volumes[e])
    }

    fn hessian(&self, e: usize, x: &[Vec3]) -> Result<Matrix12, ConstraintError> {
        self.measure
            .hessian(e, &self.positions(e, x), self.rest_volumes[e])
    }

    /// Fills `out` with Jacobian entries in blocks of `copies` rows of 12: block `b` holds
    /// `copies` copies of `scale * dm_e/dx` for `e = tet_of_block(b)`, in the order of
    /// [`MeasuredTets::dofs`]. `x` must have been checked.
    pub(crate) fn fill_gradients(
        &self,
        x: &[Vec3],
        out: &mut [f64],
        blocks: usize,
        copies: usize,
        scale: f64,
        tet_of_block: impl Fn(usize) -> usize + Sync,
    ) -> Result<(), ConstraintError> {
        check_len("jacobian buffer", blocks * copies * 12, out.len())?;
        out.par_chunks_mut(copies * 12)
            .with_min_len(TETS_PER_TASK)
            .enumerate()
            .try_for_each(|(b, chunk)| {
                let g = self.gradient(tet_of_block(b), x)? * scale;
                for row in chunk.chunks_exact_mut(12) {
                    row.copy_from_slice(g.as_slice());
                }
                Ok(())
            })
    }

    /// `(dof_i, dof_j)` of the 12x12 block of every tet in `tets`, row-major per block.
    pub(crate) fn hessian_pattern(&self, tets: impl Iterator<Item = usize>) -> Vec<(usize, usize)> {
        tets.flat_map(|e| {
            let dofs = self.dofs(e);
            dofs.into_iter()
                .flat_map(move |r| dofs.into_iter().map(move |c| (r, c)))
        })
        .collect()
    }

    /// Fills `out` with geometric stiffness blocks: block `b` is `weight(e) * d^2 m_e/dx^2`
    /// for `e = tet_of_block(b)`, row-major in the order of [`MeasuredTets::hessian_pattern`].
    /// `x` must have been checked.
    pub(crate) fn fill_hessians(
        &self,
        x: &[Vec3],
        out: &mut [f64],
        blocks: usize,
        tet_of_block: impl Fn(usize) -> usize + Sync,
        weight: impl Fn(usize) -> f64 + Sync,
    ) -> Result<(), ConstraintError> {
        check_len("geometric stiffness buffer", blocks * BLOCK, out.len())?;
        out.par_chunks_mut(BLOCK)
            .with_min_len(TETS_PER_TASK / 4)
            .enumerate()
            .try_for_each(|(b, chunk)| {
                let e = tet_of_block(b);
                let h = self.hessian(e, x)? * weight(e);
                for (i, row) in chunk.chunks_exact_mut(12).enumerate() {
                    for (j, entry) in row.iter_mut().enumerate() {
                        *entry = h[(i, j)];
                    }
                }
                Ok(())
            })
    }
}

/// [`ConstraintError::DimensionMismatch`] unless `actual == expected`.
pub(crate) fn check_len(
    what: &'static str,
    expected: usize,
    actual: usize,
) -> Result<(), ConstraintError> {
    if actual == expected {
        Ok(())
    } else {
        Err(ConstraintError::DimensionMismatch {
            what,
            expected,
            actual,
        })
    }
}

/// `1 / kappa` for a bulk modulus `kappa > 0` (`f64::INFINITY` allowed: incompressible,
/// giving exactly zero compliance).
pub(crate) fn inverse_bulk_modulus(kappa: f64) -> Result<f64, ConstraintError> {
    if kappa > 0.0 {
        Ok(1.0 / kappa)
    } else {
        Err(ConstraintError::InvalidParameter {
            name: "kappa",
            value: kappa,
            reason: "the bulk modulus must be positive (f64::INFINITY for incompressible)",
        })
    }
}

/// Meshes for the unit tests of the constraint sets.
#[cfg(test)]
pub(crate) mod test_meshes {
    use isochor_mesh::{TetMesh, Vec3};

    /// Two tets sharing the face `(0, 1, 2)`, apexes 3 (above) and 4 (below).
    pub(crate) fn two_tets() -> TetMesh {
        let positions = vec![
            Vec3::new(0.0, 0.0, 0.0),
            Vec3::new(1.0, 0.0, 0.0),
            Vec3::new(0.0, 1.0, 0.0),
            Vec3::new(0.3, 0.3, 1.0),
            Vec3::new(0.2, 0.3, -0.8),
        ];
        TetMesh::new(positions, vec![[0, 1, 2, 3], [0, 2, 1, 4]]).expect("valid mesh")
    }

    /// `x` with vertex `v` moved by `d`.
    pub(crate) fn moved(mesh: &TetMesh, v: usize, d: Vec3) -> Vec<Vec3> {
        let mut x = mesh.positions().to_vec();
        x[v] += d;
        x
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn dofs_are_vertex_major() {
        let mesh = test_meshes::two_tets();
        let tets = MeasuredTets::new(&mesh, Measure::Linear);
        assert_eq!(tets.dofs(1), [0, 1, 2, 6, 7, 8, 3, 4, 5, 12, 13, 14]);
        let pattern = tets.hessian_pattern([1].into_iter());
        assert_eq!(pattern.len(), BLOCK);
        // Entry (i, j) of the block sits at 12 i + j: (dofs[1], dofs[3]).
        assert_eq!(pattern[12 + 3], (1, 6));
    }

    #[test]
    fn bulk_modulus_must_be_positive() {
        assert_eq!(inverse_bulk_modulus(f64::INFINITY), Ok(0.0));
        assert_eq!(inverse_bulk_modulus(4.0), Ok(0.25));
        for bad in [0.0, -1.0, f64::NAN, f64::NEG_INFINITY] {
            assert!(matches!(
                inverse_bulk_modulus(bad),
                Err(ConstraintError::InvalidParameter { name: "kappa", .. })
            ));
        }
    }
}
