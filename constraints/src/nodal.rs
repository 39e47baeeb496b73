//! Nodal (P1) volume constraints: one pressure per corner vertex, linear pressure shape
//! functions (eq. 27 of Francu et al. 2021; on 10-node tets the Taylor-Hood P2-P1 pair), with
//! consistent or lumped compliance (eq. 18).

use crate::measured::{check_len, inverse_bulk_moduli, MeasuredElements};
use crate::{Compliance, ConstraintError, ConstraintSet, Measure, RowShape};
use isochor_mesh::element::TetQuadrature;
use isochor_mesh::{ElementMesh, TetMesh, Vec3};
use rayon::prelude::*;

/// How the nodal compliance `C = (1/kappa) integral L^T L dV` (eq. 18) is integrated.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum NodalCompliance {
    /// The exact mass-matrix-like integral `(1/kappa) integral_e L_i L_j dV` for the 4x4
    /// corner pairs of every element (`V_e (1 + delta_ij) / (20 kappa)` on a straight
    /// element; [`Compliance::Sparse`]).
    Consistent,
    /// Row sums of the consistent matrix: `(1/kappa) sum_e integral_e L_i dV` over the
    /// elements incident to each vertex (`V_e / (4 kappa)` each on a straight element;
    /// [`Compliance::Diagonal`]).
    #[default]
    Lumped,
}

/// One constraint per corner vertex `j`: `phi_j = integral L_j Phi(J) dV`, with `L_j` the
/// linear shape function of corner `j` (on a 10-node tet, the barycentric coordinate of the
/// corner), by quadrature: `sum_e sum_q W_q L_j(xi_q) Phi(J_q)` (eq. 27; sec. 6 for the
/// logarithmic form). On a 4-node tet with the one-point rule, `phi_j = sum_e m_e / 4` with
/// `m_e = V_e Phi(J_e)`.
///
/// Row `j` is vertex `j` of the mesh (node `j`: corners come first); a vertex in no element
/// (a cloth's node) gives the row `-p_j = 0` through a unit compliance, its pressure zero. The
/// Jacobian pattern holds `4 x 3n` entries per element of `n` nodes: for each of its 4
/// corners (in the element's order) a row over the element's DOFs. The geometric stiffness
/// of element `e` is `sum_q W_q p(xi_q) d^2 Phi(J_q)/dx^2`, with `p = sum_j p_j L_j` the
/// pressure field, one `3n x 3n` block per element.
///
/// With `n` constraints against `3n` DOFs the counting condition (eq. 1) holds with room to
/// spare; on structured boxes of 4-node tets `G` has 3 zero singular values (spurious
/// pressure modes).
#[derive(Debug, Clone)]
pub struct NodalConstraints {
    elements: MeasuredElements,
    /// `1 / kappa_e` per element.
    inverse_kappa: Vec<f64>,
    compliance: NodalCompliance,
}

impl NodalConstraints {
    /// Nodal constraints on the 4-node tets of `mesh` (the one-point rule, exact for the
    /// linear measure) with the given measure, bulk modulus `kappa` (`f64::INFINITY` for an
    /// incompressible material: `C = 0` exactly) and compliance integration.
    ///
    /// Errors: [`ConstraintError::InvalidParameter`] unless `kappa > 0`.
    ///
    /// ```
    /// use isochor_constraints::{
    ///     jacobian_matrix, ConstraintSet, Measure, NodalCompliance, NodalConstraints,
    /// };
    /// use isochor_mesh::generate::box_grid;
    /// use isochor_mesh::Vec3;
    ///
    /// let mesh = box_grid(Vec3::zeros(), Vec3::repeat(1.0), [1, 1, 1])?;
    /// let set = NodalConstraints::new(&mesh, Measure::Linear, f64::INFINITY, NodalCompliance::Lumped)?;
    /// assert_eq!(set.num_constraints(), 8); // one per vertex
    /// // Doubling every length multiplies each nodal volume by 8: phi = 7 V_i.
    /// let x: Vec<Vec3> = mesh.positions().iter().map(|p| 2.0 * p).collect();
    /// let mut phi = vec![0.0; 8];
    /// set.values(&x, &mut phi)?;
    /// assert!((phi.iter().sum::<f64>() - 7.0).abs() < 1e-12);
    /// assert_eq!(jacobian_matrix(&set, &x)?.shape(), (8, 24));
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn new(
        mesh: &TetMesh,
        measure: Measure,
        kappa: f64,
        compliance: NodalCompliance,
    ) -> Result<Self, ConstraintError> {
        let linear = ElementMesh::linear(mesh.clone());
        Self::on_elements(&linear, TetQuadrature::Degree1, measure, kappa, compliance)
    }

    /// Nodal constraints on the corners of the elements of `mesh`, integrated with `rule` (see
    /// [`crate::exact_rule`]); the compliance is integrated exactly whatever `rule` is.
    ///
    /// Errors: [`ConstraintError::InvalidParameter`] unless `kappa > 0`.
    pub fn on_elements(
        mesh: &ElementMesh,
        rule: TetQuadrature,
        measure: Measure,
        kappa: f64,
        compliance: NodalCompliance,
    ) -> Result<Self, ConstraintError> {
        Self::on_regions(
            mesh,
            rule,
            measure,
            &vec![kappa; mesh.num_elements()],
            compliance,
        )
    }

    /// As [`NodalConstraints::on_elements`] with one bulk modulus per element (a body of
    /// several materials): `C = integral (1/kappa) L^T L dV`.
    ///
    /// Errors: [`ConstraintError::InvalidParameter`] unless every `kappa > 0`;
    /// [`ConstraintError::DimensionMismatch`] unless there is one per element.
    pub fn on_regions(
        mesh: &ElementMesh,
        rule: TetQuadrature,
        measure: Measure,
        kappa: &[f64],
        compliance: NodalCompliance,
    ) -> Result<Self, ConstraintError> {
        let elements = MeasuredElements::new(mesh, rule, measure)?;
        Ok(NodalConstraints {
            inverse_kappa: inverse_bulk_moduli(kappa, &elements)?,
            elements,
            compliance,
        })
    }

    /// The measure of the constraints.
    pub fn measure(&self) -> Measure {
        self.elements.measure()
    }

    /// The average `(p_a + p_b + p_c + p_d) / 4` of the multipliers of element `e`'s corners:
    /// the pressure at its centroid.
    fn element_multiplier(&self, e: usize, multipliers: &[f64]) -> f64 {
        self.elements
            .corners(e)
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
        self.elements.num_vertices()
    }

    fn values(&self, x: &[Vec3], out: &mut [f64]) -> Result<(), ConstraintError> {
        self.elements.check_positions(x)?;
        check_len("constraint values", self.num_constraints(), out.len())?;
        let mut m = vec![0.0; 4 * self.elements.len()];
        self.elements.fill_values(x, RowShape::Corners, &mut m)?;
        out.fill(0.0);
        for (e, rows) in m.chunks_exact(4).enumerate() {
            for (v, m_j) in self.elements.corners(e).into_iter().zip(rows) {
                out[v] += m_j;
            }
        }
        Ok(())
    }

    fn jacobian_pattern(&self) -> Vec<(usize, usize)> {
        (0..self.elements.len())
            .flat_map(|e| {
                self.elements
                    .corners(e)
                    .into_iter()
                    .flat_map(move |row| self.elements.dofs(e).map(move |dof| (row, dof)))
            })
            .collect()
    }

    fn jacobian_values(&self, x: &[Vec3], out: &mut [f64]) -> Result<(), ConstraintError> {
        self.elements.check_positions(x)?;
        self.elements
            .fill_gradients(x, RowShape::Corners, out, self.elements.len(), |e| e)
    }

    fn geometric_stiffness_pattern(&self) -> Vec<(usize, usize)> {
        self.elements.hessian_pattern(0..self.elements.len())
    }

    fn geometric_stiffness_blocks(&self) -> Option<(&[usize], usize)> {
        Some(self.elements.blocks())
    }

    fn geometric_stiffness_values(
        &self,
        x: &[Vec3],
        multipliers: &[f64],
        out: &mut [f64],
    ) -> Result<(), ConstraintError> {
        self.elements.check_positions(x)?;
        check_len("multipliers", self.num_constraints(), multipliers.len())?;
        self.elements.fill_hessians(
            x,
            out,
            self.elements.len(),
            |e| e,
            |e, q| self.elements.corner_interpolation(e, q, multipliers),
        )
    }

    fn admits_inversion(&self) -> bool {
        self.measure() == Measure::Linear
    }

    /// Eq. 18, plus a unit diagonal on the empty rows of vertices in no element (a cloth's
    /// nodes beside a body): their rows read `-p_j = 0`, which keeps those pressures at zero
    /// instead of leaving the saddle-point matrix singular.
    fn compliance(&self) -> Compliance {
        let scale = &self.inverse_kappa;
        let mut used = vec![false; self.num_constraints()];
        for e in 0..self.elements.len() {
            for v in self.elements.corners(e) {
                used[v] = true;
            }
        }
        let empty = || (0..used.len()).filter(|&v| !used[v]);
        match self.compliance {
            NodalCompliance::Lumped => {
                let mut diagonal = vec![0.0; self.num_constraints()];
                for (e, inverse_kappa) in scale.iter().enumerate() {
                    let products = self.elements.corner_products(e);
                    for (v, row) in self.elements.corners(e).into_iter().zip(products) {
                        diagonal[v] += row.iter().sum::<f64>() * inverse_kappa;
                    }
                }
                for v in empty() {
                    diagonal[v] = 1.0;
                }
                Compliance::Diagonal(diagonal)
            }
            NodalCompliance::Consistent => Compliance::Sparse(
                (0..self.elements.len())
                    .flat_map(|e| {
                        let t = self.elements.corners(e);
                        let products = self.elements.corner_products(e);
                        (0..4).flat_map(move |a| {
                            (0..4).map(move |b| (t[a], t[b], products[a][b] * scale[e]))
                        })
                    })
                    .chain(empty().map(|v| (v, v, 1.0)))
                    .collect(),
            ),
        }
    }

    /// Row `j` belongs to vertex `j`.
    fn anchor_vertex(&self, row: usize) -> Option<usize> {
        (row < self.num_constraints()).then_some(row)
    }

    /// The average of the element's 4 corner multipliers, divided by the element's mean `J`
    /// for the logarithmic measure.
    fn tet_pressures(&self, x: &[Vec3], multipliers: &[f64]) -> Vec<f64> {
        if self.elements.check_positions(x).is_err() {
            return Vec::new();
        }
        if multipliers.len() != self.num_constraints() {
            return Vec::new();
        }
        (0..self.elements.len())
            .into_par_iter()
            .map(|e| {
                self.elements
                    .true_pressure(e, x, self.element_multiplier(e, multipliers))
            })
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::measured::test_meshes::{moved, two_tets};

    fn dense(c: &Compliance, n: usize) -> Vec<Vec<f64>> {
        let mut m = vec![vec![0.0; n]; n];
        match c {
            Compliance::Diagonal(d) => d.iter().enumerate().for_each(|(i, &v)| m[i][i] = v),
            Compliance::Sparse(t) => t.iter().for_each(|&(i, j, v)| m[i][j] += v),
        }
        m
    }

    /// A vertex in no element (a cloth's node) gets the row `-p = 0`: unit compliance on
    /// its diagonal, nothing else, with either integration, even when `C = 0` elsewhere.
    #[test]
    fn a_vertex_in_no_element_has_unit_compliance() {
        let two = two_tets();
        let mut positions = two.positions().to_vec();
        positions.push(Vec3::new(5.0, 5.0, 5.0));
        let mesh = TetMesh::new(positions, two.tets().to_vec()).unwrap();
        for kind in [NodalCompliance::Lumped, NodalCompliance::Consistent] {
            let c = NodalConstraints::new(&mesh, Measure::Linear, f64::INFINITY, kind)
                .unwrap()
                .compliance();
            let m = dense(&c, 6);
            for (i, row) in m.iter().enumerate() {
                for (j, &entry) in row.iter().enumerate() {
                    let expected = if i == 5 && j == 5 { 1.0 } else { 0.0 };
                    assert_eq!(entry, expected, "{kind:?} ({i}, {j})");
                }
            }
        }
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
