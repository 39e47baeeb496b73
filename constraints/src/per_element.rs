//! Per-element (P0) volume constraints: one pressure per element (sec. 4.6 of Francu et al. 2021).

use crate::measured::{check_len, inverse_bulk_moduli, MeasuredElements};
use crate::{Compliance, ConstraintError, ConstraintSet, Measure, RowShape};
use isochor_mesh::element::TetQuadrature;
use isochor_mesh::{ElementMesh, TetMesh, Vec3};
use rayon::prelude::*;

/// One constraint per element, `phi_e = integral_e Phi(J) dV = sum_q W_q Phi(J_q)` (`v_e - V_e`
/// for the linear measure), with compliance `C_e = V_e / kappa` (sec. 4.6; eq. 18 with
/// `N_p = 1`).
///
/// Row `e` is element `e`. The Jacobian pattern holds `3n` entries per element of `n` nodes
/// (row `e`, the element's DOFs node-major) and the geometric stiffness pattern one
/// `3n x 3n` block per element.
///
/// With as many constraints as tets, about `5n` on a 4-node tet mesh against `3n` DOFs, this
/// discretization violates the counting condition (eq. 1) and locks (Appendix A).
#[derive(Debug, Clone)]
pub struct PerElementConstraints {
    elements: MeasuredElements,
    /// `1 / kappa_e` per element.
    inverse_kappa: Vec<f64>,
}

impl PerElementConstraints {
    /// Per-element constraints on the 4-node tets of `mesh` (the one-point rule, exact) with the
    /// given measure and bulk modulus `kappa` (`f64::INFINITY` for an incompressible
    /// material: `C = 0` exactly).
    ///
    /// Errors: [`ConstraintError::InvalidParameter`] unless `kappa > 0`.
    pub fn new(mesh: &TetMesh, measure: Measure, kappa: f64) -> Result<Self, ConstraintError> {
        let linear = ElementMesh::linear(mesh.clone());
        Self::on_elements(&linear, TetQuadrature::Degree1, measure, kappa)
    }

    /// Per-element constraints on the elements of `mesh`, integrated with `rule` (see
    /// [`crate::exact_rule`]).
    ///
    /// Errors: [`ConstraintError::InvalidParameter`] unless `kappa > 0`.
    pub fn on_elements(
        mesh: &ElementMesh,
        rule: TetQuadrature,
        measure: Measure,
        kappa: f64,
    ) -> Result<Self, ConstraintError> {
        Self::on_regions(mesh, rule, measure, &vec![kappa; mesh.num_elements()])
    }

    /// As [`PerElementConstraints::on_elements`] with one bulk modulus per element (a body of
    /// several materials): `C_e = V_e / kappa_e`.
    ///
    /// Errors: [`ConstraintError::InvalidParameter`] unless every `kappa > 0`;
    /// [`ConstraintError::DimensionMismatch`] unless there is one per element.
    pub fn on_regions(
        mesh: &ElementMesh,
        rule: TetQuadrature,
        measure: Measure,
        kappa: &[f64],
    ) -> Result<Self, ConstraintError> {
        let elements = MeasuredElements::new(mesh, rule, measure)?;
        Ok(PerElementConstraints {
            inverse_kappa: inverse_bulk_moduli(kappa, &elements)?,
            elements,
        })
    }

    /// The measure of the constraints.
    pub fn measure(&self) -> Measure {
        self.elements.measure()
    }
}

impl ConstraintSet for PerElementConstraints {
    fn name(&self) -> &'static str {
        match self.measure() {
            Measure::Linear => "element",
            Measure::Logarithmic => "element-log",
        }
    }

    fn num_constraints(&self) -> usize {
        self.elements.len()
    }

    fn values(&self, x: &[Vec3], out: &mut [f64]) -> Result<(), ConstraintError> {
        self.elements.check_positions(x)?;
        self.elements.fill_values(x, RowShape::One, out)
    }

    fn jacobian_pattern(&self) -> Vec<(usize, usize)> {
        (0..self.elements.len())
            .flat_map(|e| self.elements.dofs(e).map(move |dof| (e, dof)))
            .collect()
    }

    fn jacobian_values(&self, x: &[Vec3], out: &mut [f64]) -> Result<(), ConstraintError> {
        self.elements.check_positions(x)?;
        self.elements
            .fill_gradients(x, RowShape::One, out, self.elements.len(), |e| e)
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
        check_len("multipliers", self.elements.len(), multipliers.len())?;
        self.elements
            .fill_hessians(x, out, self.elements.len(), |e| e, |e, _| multipliers[e])
    }

    fn admits_inversion(&self) -> bool {
        self.measure() == Measure::Linear
    }

    fn compliance(&self) -> Compliance {
        Compliance::Diagonal(
            (0..self.elements.len())
                .map(|e| self.elements.rest_volume(e) * self.inverse_kappa[e])
                .collect(),
        )
    }

    /// The element's last corner: each element pressure is ordered after one of its vertices.
    fn anchor_vertex(&self, row: usize) -> Option<usize> {
        (row < self.elements.len()).then(|| self.elements.corners(row)[3])
    }

    /// The element multiplier itself (linear measure) or divided by the element's mean `J`
    /// (logarithmic).
    fn tet_pressures(&self, x: &[Vec3], multipliers: &[f64]) -> Vec<f64> {
        if self.elements.check_positions(x).is_err() {
            return Vec::new();
        }
        if multipliers.len() != self.elements.len() {
            return Vec::new();
        }
        (0..self.elements.len())
            .into_par_iter()
            .map(|e| self.elements.true_pressure(e, x, multipliers[e]))
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::measured::test_meshes::{moved, two_tets};

    #[test]
    fn values_compliance_and_pressures() {
        let mesh = two_tets();
        let set = PerElementConstraints::new(&mesh, Measure::Linear, 2.0).unwrap();
        assert_eq!(set.num_constraints(), 2);
        let x = moved(&mesh, 3, Vec3::new(0.0, 0.0, 0.5));
        let mut phi = [0.0; 2];
        set.values(&x, &mut phi).unwrap();
        // Lifting the apex by 0.5 over the unit right triangle adds 0.5 * 0.5 / 3.
        assert!((phi[0] - 0.5 / 6.0).abs() < 1e-15);
        assert_eq!(phi[1], 0.0);
        let v = mesh.rest_volumes();
        assert_eq!(
            set.compliance(),
            Compliance::Diagonal(vec![v[0] / 2.0, v[1] / 2.0])
        );
        assert_eq!(set.tet_pressures(&x, &[3.0, -1.0]), vec![3.0, -1.0]);
        assert_eq!(set.anchor_vertex(1), Some(4));
        assert_eq!(set.anchor_vertex(2), None);

        let log = PerElementConstraints::new(&mesh, Measure::Logarithmic, 2.0).unwrap();
        let p = log.tet_pressures(&x, &[3.0, -1.0]);
        let j0 = mesh.volume_at(0, &x) / v[0];
        assert!((p[0] - 3.0 / j0).abs() < 1e-15);
        assert_eq!(p[1], -1.0);
    }

    #[test]
    fn incompressible_compliance_is_exactly_zero() {
        let mesh = two_tets();
        let set = PerElementConstraints::new(&mesh, Measure::Linear, f64::INFINITY).unwrap();
        assert_eq!(set.compliance(), Compliance::Diagonal(vec![0.0, 0.0]));
        assert!(PerElementConstraints::new(&mesh, Measure::Linear, f64::NAN).is_err());
    }

    #[test]
    fn bad_inputs_are_errors() {
        let mesh = two_tets();
        let set = PerElementConstraints::new(&mesh, Measure::Logarithmic, 1.0).unwrap();
        // Push apex 4 through the shared face: tet 1 inverts.
        let x = moved(&mesh, 4, Vec3::new(0.0, 0.0, 1.6));
        let mut phi = [0.0; 2];
        assert!(matches!(
            set.values(&x, &mut phi),
            Err(ConstraintError::NonPositiveVolumeRatio { element: 1, .. })
        ));
        let mut g = vec![0.0; 24];
        assert!(set.jacobian_values(&x, &mut g).is_err());
        let rest = mesh.positions();
        assert!(matches!(
            set.values(&rest[..4], &mut phi),
            Err(ConstraintError::DimensionMismatch {
                expected: 5,
                actual: 4,
                ..
            })
        ));
        assert!(set.jacobian_values(rest, &mut g[..12]).is_err());
        assert!(set.tet_pressures(rest, &[1.0]).is_empty());
        let mut k = vec![0.0; 288];
        assert!(set
            .geometric_stiffness_values(rest, &[1.0, 2.0, 3.0], &mut k)
            .is_err());
    }
}
