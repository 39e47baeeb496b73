//! Nodal (P1) volume constraints: one pressure per vertex, linear pressure shape functions
//! (eq. 27 of Francu et al. 2021), with consistent or lumped compliance (eq. 18).

use crate::tets::{check_len, inverse_bulk_modulus, MeasuredTets};
use crate::{Compliance, ConstraintError, ConstraintSet, Measure};
use isochor_mesh::{TetMesh, Vec3};
use rayon::prelude::*;

/// How the nodal compliance `C = (1/kappa) int N^T N dV` (eq. 18) is integrated.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum NodalCompliance {
    /// The exact mass-matrix-like integral: `V_e (1 + delta_ij) / (20 kappa)` for the 4x4
    /// node pairs of every tet ([`Compliance::Sparse`]).
    Consistent,
    /// Row sums of the consistent matrix: `sum_e V_e / (4 kappa)` over the tets incident to
    /// each vertex ([`Compliance::Diagonal`]).
    #[default]
    Lumped,
}

/// One constraint per vertex `j`: `phi_j = sum_{e incident to j} m_e / 4` with
/// `m_e = V_e Phi(J_e)` (eq. 27; sec. 6 for the logarithmic form).
///
/// Row `j` is vertex `j` of the mesh; a vertex in no tet gives an empty row `0 = 0` (clean
/// such meshes before solving with zero compliance). The Jacobian pattern holds 48 entries
/// per tet: for each of its 4 vertices (in the tet's order) a row of 12 entries over the
/// tet's DOFs. The geometric stiffness of tet `e` is `((p_a + p_b + p_c + p_d) / 4)` times
/// the Hessian of `m_e`, one 12x12 block per tet.
///
/// With `n` constraints against `3n` DOFs the counting condition (eq. 1) holds with room to
/// spare; on structured boxes `G` has 3 zero singular values (spurious pressure modes).
#[derive(Debug, Clone)]
pub struct NodalConstraints {
    tets: MeasuredTets,
    inverse_kappa: f64,
    compliance: NodalCompliance,
}

impl NodalConstraints {
    /// Nodal constraints on `mesh` with the given measure, bulk modulus `kappa`
    /// (`f64::INFINITY` for an incompressible material: `C = 0` exactly) and compliance
    /// integration.
    ///
    /// Errors: [`ConstraintError::InvalidParameter`] unless `kappa > 0`.
    pub fn new(
        mesh: &TetMesh,
        measure: Measure,
        kappa: f64,
        compliance: NodalCompliance,
    ) -> Result<Self, ConstraintError> {
        Ok(NodalConstraints {
            tets: MeasuredTets::new(mesh, measure),
            inverse_kappa: inverse_bulk_modulus(kappa)?,
            compliance,
        })
    }

    /// The measure of the constraints.
    pub fn measure(&self) -> Measure {
        self.tets.measure()
    }

    /// The average `(p_a + p_b + p_c + p_d) / 4` of the multipliers of tet `e`'s vertices.
    fn tet_multiplier(&self, e: usize, multipliers: &[f64]) -> f64 {
        self.tets
            .tet(e)
            .iter()
            .map(|&v| multipliers[v])
            .sum::<f64>()
            / 4.0
    }
}

impl ConstraintSet for NodalConstraints {
    fn name(&self) -> &'static str {
        match self.measure() {
            Measure::Linear => "nodal",
            Measure::Logarithmic => "nodal-log",
        }
    }

    fn num_constraints(&self) -> usize {
        self.tets.num_vertices()
    }

    fn values(&self, x: &[Vec3], out: &mut [f64]) -> Result<(), ConstraintError> {
        self.tets.check_positions(x)?;
        check_len("constraint values", self.num_constraints(), out.len())?;
        let mut m = vec![0.0; self.tets.len()];
        self.tets.fill_values(x, &mut m)?;
        out.fill(0.0);
        for (e, m_e) in m.into_iter().enumerate() {
            for v in self.tets.tet(e) {
                out[v] += m_e / 4.0;
            }
        }
        Ok(())
    }

    fn jacobian_pattern(&self) -> Vec<(usize, usize)> {
        (0..self.tets.len())
            .flat_map(|e| {
                let dofs = self.tets.dofs(e);
                self.tets
                    .tet(e)
                    .into_iter()
                    .flat_map(move |row| dofs.map(|dof| (row, dof)))
            })
            .collect()
    }

    fn jacobian_values(&self, x: &[Vec3], out: &mut [f64]) -> Result<(), ConstraintError> {
        self.tets.check_positions(x)?;
        self.tets
            .fill_gradients(x, out, self.tets.len(), 4, 0.25, |e| e)
    }

    fn geometric_stiffness_pattern(&self) -> Vec<(usize, usize)> {
        self.tets.hessian_pattern(0..self.tets.len())
    }

    fn geometric_stiffness_values(
        &self,
        x: &[Vec3],
        multipliers: &[f64],
        out: &mut [f64],
    ) -> Result<(), ConstraintError> {
        self.tets.check_positions(x)?;
        check_len("multipliers", self.num_constraints(), multipliers.len())?;
        self.tets.fill_hessians(
            x,
            out,
            self.tets.len(),
            |e| e,
            |e| self.tet_multiplier(e, multipliers),
        )
    }

    fn compliance(&self) -> Compliance {
        let scale = self.inverse_kappa;
        match self.compliance {
            NodalCompliance::Lumped => {
                let mut diagonal = vec![0.0; self.num_constraints()];
                for e in 0..self.tets.len() {
                    for v in self.tets.tet(e) {
                        diagonal[v] += self.tets.rest_volume(e) * scale / 4.0;
                    }
                }
                Compliance::Diagonal(diagonal)
            }
            NodalCompliance::Consistent => Compliance::Sparse(
                (0..self.tets.len())
                    .flat_map(|e| {
                        let t = self.tets.tet(e);
                        let c = self.tets.rest_volume(e) * scale / 20.0;
                        (0..4).flat_map(move |a| {
                            (0..4).map(move |b| (t[a], t[b], if a == b { 2.0 * c } else { c }))
                        })
                    })
                    .collect(),
            ),
        }
    }

    /// Row `j` belongs to vertex `j`.
    fn anchor_vertex(&self, row: usize) -> Option<usize> {
        (row < self.num_constraints()).then_some(row)
    }

    /// The average of the tet's 4 nodal multipliers, divided by `J_e` for the logarithmic
    /// measure.
    fn tet_pressures(&self, x: &[Vec3], multipliers: &[f64]) -> Vec<f64> {
        if self.tets.check_positions(x).is_err() {
            return Vec::new();
        }
        if multipliers.len() != self.num_constraints() {
            return Vec::new();
        }
        (0..self.tets.len())
            .into_par_iter()
            .map(|e| {
                self.tets
                    .true_pressure(e, x, self.tet_multiplier(e, multipliers))
            })
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::tets::test_meshes::{moved, two_tets};

    fn dense(c: &Compliance, n: usize) -> Vec<Vec<f64>> {
        let mut m = vec![vec![0.0; n]; n];
        match c {
            Compliance::Diagonal(d) => d.iter().enumerate().for_each(|(i, &v)| m[i][i] = v),
            Compliance::Sparse(t) => t.iter().for_each(|&(i, j, v)| m[i][j] += v),
        }
        m
    }

    #[test]
    fn consistent_row_sums_are_the_lumped_diagonal() {
        let mesh = two_tets();
        let kappa = 3.0;
        let lumped = NodalConstraints::new(&mesh, Measure::Linear, kappa, NodalCompliance::Lumped)
            .unwrap()
            .compliance();
        let consistent =
            NodalConstraints::new(&mesh, Measure::Linear, kappa, NodalCompliance::Consistent)
                .unwrap()
                .compliance();
        let (l, c) = (dense(&lumped, 5), dense(&consistent, 5));
        for (i, row) in c.iter().enumerate() {
            let sum: f64 = row.iter().sum();
            assert!((sum - l[i][i]).abs() < 1e-15 * l[i][i].max(1.0));
            for (j, &entry) in row.iter().enumerate() {
                assert_eq!(entry, c[j][i]);
            }
        }
        // Vertex 0 touches both tets: (V_0 + V_1) / (4 kappa).
        let v = mesh.rest_volumes();
        assert!((l[0][0] - (v[0] + v[1]) / (4.0 * kappa)).abs() < 1e-16);
        // Vertex 3 touches tet 0 only: diagonal 2 V_0 / (20 kappa).
        assert!((c[3][3] - v[0] / (10.0 * kappa)).abs() < 1e-16);
    }

    #[test]
    fn incompressible_compliance_is_exactly_zero() {
        let mesh = two_tets();
        for kind in [NodalCompliance::Lumped, NodalCompliance::Consistent] {
            let set =
                NodalConstraints::new(&mesh, Measure::Logarithmic, f64::INFINITY, kind).unwrap();
            match set.compliance() {
                Compliance::Diagonal(d) => assert!(d.iter().all(|&c| c == 0.0)),
                Compliance::Sparse(t) => assert!(t.iter().all(|&(_, _, c)| c == 0.0)),
            }
        }
    }

    #[test]
    fn nodal_values_distribute_element_values() {
        let mesh = two_tets();
        let set =
            NodalConstraints::new(&mesh, Measure::Linear, 1.0, NodalCompliance::Lumped).unwrap();
        let x = moved(&mesh, 3, Vec3::new(0.1, -0.2, 0.4));
        let mut phi = [0.0; 5];
        set.values(&x, &mut phi).unwrap();
        let dv = mesh.volume_at(0, &x) - mesh.rest_volumes()[0];
        assert!((phi.iter().sum::<f64>() - dv).abs() < 1e-15);
        assert!((phi[3] - dv / 4.0).abs() < 1e-16);
        assert_eq!(phi[4], 0.0);
        assert_eq!(set.jacobian_pattern().len(), 2 * 48);
        let p = set.tet_pressures(&x, &[1.0, 2.0, 3.0, 4.0, 8.0]);
        assert_eq!(set.anchor_vertex(4), Some(4));
        assert_eq!(p, vec![2.5, 3.5]);
    }
}
