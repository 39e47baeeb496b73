//! Element (P0) volume constraints: one pressure per tet (sec. 4.6 of Francu et al. 2021).

use crate::tets::{check_len, inverse_bulk_modulus, MeasuredTets};
use crate::{Compliance, ConstraintError, ConstraintSet, Measure};
use isochor_mesh::{TetMesh, Vec3};
use rayon::prelude::*;

/// One constraint per tet, `phi_e = V_e Phi(J_e)` (`v_e - V_e` for the linear measure), with
/// compliance `C_e = V_e / kappa` (sec. 4.6; eq. 18 with `N_p = 1`).
///
/// Row `e` is tet `e`. The Jacobian pattern holds 12 entries per tet (row `e`, the tet's DOFs
/// vertex-major) and the geometric stiffness pattern one 12x12 block per tet.
///
/// With as many constraints as tets, about `5n` on a tet mesh against `3n` DOFs, this
/// discretization violates the counting condition (eq. 1) and locks (Appendix A).
#[derive(Debug, Clone)]
pub struct ElementConstraints {
    tets: MeasuredTets,
    inverse_kappa: f64,
}

impl ElementConstraints {
    /// Element constraints on `mesh` with the given measure and bulk modulus `kappa`
    /// (`f64::INFINITY` for an incompressible material: `C = 0` exactly).
    ///
    /// Errors: [`ConstraintError::InvalidParameter`] unless `kappa > 0`.
    pub fn new(mesh: &TetMesh, measure: Measure, kappa: f64) -> Result<Self, ConstraintError> {
        Ok(ElementConstraints {
            tets: MeasuredTets::new(mesh, measure),
            inverse_kappa: inverse_bulk_modulus(kappa)?,
        })
    }

    /// The measure of the constraints.
    pub fn measure(&self) -> Measure {
        self.tets.measure()
    }
}

impl ConstraintSet for ElementConstraints {
    fn name(&self) -> &'static str {
        match self.measure() {
            Measure::Linear => "element",
            Measure::Logarithmic => "element-log",
        }
    }

    fn num_constraints(&self) -> usize {
        self.tets.len()
    }

    fn values(&self, x: &[Vec3], out: &mut [f64]) -> Result<(), ConstraintError> {
        self.tets.check_positions(x)?;
        self.tets.fill_values(x, out)
    }

    fn jacobian_pattern(&self) -> Vec<(usize, usize)> {
        (0..self.tets.len())
            .flat_map(|e| self.tets.dofs(e).map(|dof| (e, dof)))
            .collect()
    }

    fn jacobian_values(&self, x: &[Vec3], out: &mut [f64]) -> Result<(), ConstraintError> {
        self.tets.check_positions(x)?;
        self.tets
            .fill_gradients(x, out, self.tets.len(), 1, 1.0, |e| e)
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
        check_len("multipliers", self.tets.len(), multipliers.len())?;
        self.tets
            .fill_hessians(x, out, self.tets.len(), |e| e, |e| multipliers[e])
    }

    fn compliance(&self) -> Compliance {
        Compliance::Diagonal(
            (0..self.tets.len())
                .map(|e| self.tets.rest_volume(e) * self.inverse_kappa)
                .collect(),
        )
    }

    /// The tet's last vertex: each element pressure is ordered after one of its vertices.
    fn anchor_vertex(&self, row: usize) -> Option<usize> {
        (row < self.tets.len()).then(|| self.tets.tet(row)[3])
    }

    /// The element multiplier itself (linear measure) or divided by `J_e` (logarithmic).
    fn tet_pressures(&self, x: &[Vec3], multipliers: &[f64]) -> Vec<f64> {
        if self.tets.check_positions(x).is_err() {
            return Vec::new();
        }
        if multipliers.len() != self.tets.len() {
            return Vec::new();
        }
        (0..self.tets.len())
            .into_par_iter()
            .map(|e| self.tets.true_pressure(e, x, multipliers[e]))
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::tets::test_meshes::{moved, two_tets};

    #[test]
    fn values_compliance_and_pressures() {
        let mesh = two_tets();
        let set = ElementConstraints::new(&mesh, Measure::Linear, 2.0).unwrap();
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

        let log = ElementConstraints::new(&mesh, Measure::Logarithmic, 2.0).unwrap();
        let p = log.tet_pressures(&x, &[3.0, -1.0]);
        let j0 = mesh.volume_at(0, &x) / v[0];
        assert!((p[0] - 3.0 / j0).abs() < 1e-15);
        assert_eq!(p[1], -1.0);
    }

    #[test]
    fn incompressible_compliance_is_exactly_zero() {
        let mesh = two_tets();
        let set = ElementConstraints::new(&mesh, Measure::Linear, f64::INFINITY).unwrap();
        assert_eq!(set.compliance(), Compliance::Diagonal(vec![0.0, 0.0]));
        assert!(ElementConstraints::new(&mesh, Measure::Linear, f64::NAN).is_err());
    }

    #[test]
    fn bad_inputs_are_errors() {
        let mesh = two_tets();
        let set = ElementConstraints::new(&mesh, Measure::Logarithmic, 1.0).unwrap();
        // Push apex 4 through the shared face: tet 1 inverts.
        let x = moved(&mesh, 4, Vec3::new(0.0, 0.0, 1.6));
        let mut phi = [0.0; 2];
        assert!(matches!(
            set.values(&x, &mut phi),
            Err(ConstraintError::NonPositiveVolume { tet: 1, .. })
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
