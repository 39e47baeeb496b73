//! The per-element volume measure `Phi(J)` behind a constraint: linear `J - 1` (sec. 4.6 of
//! Francu et al. 2021) or logarithmic `log J` (sec. 6), integrated over the rest element.

use crate::volume::{tet_volume, volume_gradient, volume_hessian};
use crate::ConstraintError;
use isochor_energies::{Matrix12, Vector12};
use isochor_mesh::Vec3;

/// How the volume change `J_e = v_e / V_e` of a tet enters its constraint: the element
/// quantity is `m_e(x) = V_e Phi(J_e)`, from which element (P0), nodal (P1, eq. 27) and
/// zonal constraints are assembled.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Measure {
    /// `Phi = J - 1`, so `m_e = v_e - V_e` (sec. 4.6). Defined for every `v_e`, inverted
    /// tets included.
    #[default]
    Linear,
    /// `Phi = log J`, so `m_e = V_e (log v_e - log V_e)` (sec. 6), with gradient
    /// `(V_e / v_e) dv_e/dx` and Hessian `V_e (H_v / v_e - g g^T / v_e^2)`. Defined only for
    /// `v_e > 0`; the multipliers absorb a factor `J`, the true pressure is `p / J`.
    Logarithmic,
}

impl Measure {
    /// `m_e = V_e Phi(v_e / V_e)` for tet `tet` with positions `x` and rest volume `rest`.
    pub fn value(self, tet: usize, x: &[Vec3; 4], rest: f64) -> Result<f64, ConstraintError> {
        let v = tet_volume(x);
        match self {
            Measure::Linear => Ok(v - rest),
            // log(v / V) through ln_1p keeps full relative accuracy near J = 1.
            Measure::Logarithmic => Ok(rest * ((positive(tet, v)? - rest) / rest).ln_1p()),
        }
    }

    /// Gradient `d m_e / dx` (12 entries, vertex-major).
    pub fn gradient(
        self,
        tet: usize,
        x: &[Vec3; 4],
        rest: f64,
    ) -> Result<Vector12, ConstraintError> {
        let g = volume_gradient(x);
        match self {
            Measure::Linear => Ok(g),
            Measure::Logarithmic => Ok(g * (rest / positive(tet, tet_volume(x))?)),
        }
    }

    /// Hessian `d^2 m_e / dx^2` (12x12, symmetric).
    pub fn hessian(
        self,
        tet: usize,
        x: &[Vec3; 4],
        rest: f64,
    ) -> Result<Matrix12, ConstraintError> {
        let h = volume_hessian(x);
        match self {
            Measure::Linear => Ok(h),
            Measure::Logarithmic => {
                let v = positive(tet, tet_volume(x))?;
                let g = volume_gradient(x);
                Ok((h / v - g * g.transpose() / (v * v)) * rest)
            }
        }
    }

    /// The true (Cauchy) pressure from a multiplier `p` of this measure at volume ratio `j`:
    /// `p` itself for the linear measure, `p / J` for the logarithmic one (sec. 6).
    pub fn true_pressure(self, p: f64, j: f64) -> f64 {
        match self {
            Measure::Linear => p,
            Measure::Logarithmic => p / j,
        }
    }
}

/// `v` if it is positive, else [`ConstraintError::NonPositiveVolume`] (NaN included).
fn positive(tet: usize, v: f64) -> Result<f64, ConstraintError> {
    if v > 0.0 {
        Ok(v)
    } else {
        Err(ConstraintError::NonPositiveVolume { tet, volume: v })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn tet(scale: f64) -> [Vec3; 4] {
        [Vec3::zeros(), Vec3::x(), Vec3::y(), Vec3::z()].map(|p| p * scale)
    }

    #[test]
    fn values_at_rest_and_under_uniform_scaling() {
        let rest = 1.0 / 6.0;
        for m in [Measure::Linear, Measure::Logarithmic] {
            assert_eq!(m.value(0, &tet(1.0), rest).unwrap(), 0.0);
        }
        // Doubling every edge gives J = 8.
        let x = tet(2.0);
        assert!((Measure::Linear.value(0, &x, rest).unwrap() - 7.0 * rest).abs() < 1e-15);
        let log = Measure::Logarithmic.value(0, &x, rest).unwrap();
        assert!((log - rest * 8f64.ln()).abs() < 1e-15);
        assert_eq!(Measure::Logarithmic.true_pressure(4.0, 8.0), 0.5);
        assert_eq!(Measure::Linear.true_pressure(4.0, 8.0), 4.0);
    }

    #[test]
    fn logarithmic_measure_rejects_inverted_and_flat_tets() {
        let mut x = tet(1.0);
        x.swap(2, 3);
        let err = Measure::Logarithmic.value(7, &x, 1.0 / 6.0).unwrap_err();
        assert_eq!(
            err,
            ConstraintError::NonPositiveVolume {
                tet: 7,
                volume: -1.0 / 6.0
            }
        );
        x[3] = Vec3::new(0.5, 0.5, 0.0);
        assert!(Measure::Logarithmic.gradient(3, &x, 1.0).is_err());
        assert!(Measure::Logarithmic.hessian(3, &x, 1.0).is_err());
        // The linear measure is defined everywhere.
        assert!(Measure::Linear.hessian(3, &x, 1.0).is_ok());
    }

    #[test]
    fn logarithmic_derivatives_match_central_differences() {
        let x = [
            Vec3::new(0.1, -0.2, 0.05),
            Vec3::new(1.2, 0.1, -0.1),
            Vec3::new(0.2, 0.9, 0.3),
            Vec3::new(-0.1, 0.3, 1.1),
        ];
        let rest = 0.13;
        let m = Measure::Logarithmic;
        let g = m.gradient(0, &x, rest).unwrap();
        let h = m.hessian(0, &x, rest).unwrap();
        let step = 1e-6;
        for dof in 0..12 {
            let shifted = |s: f64| {
                let mut y = x;
                y[dof / 3][dof % 3] += s;
                y
            };
            let fd = (m.value(0, &shifted(step), rest).unwrap()
                - m.value(0, &shifted(-step), rest).unwrap())
                / (2.0 * step);
            assert!((fd - g[dof]).abs() < 1e-8 * g.amax());
            let fd_g = (m.gradient(0, &shifted(step), rest).unwrap()
                - m.gradient(0, &shifted(-step), rest).unwrap())
                / (2.0 * step);
            assert!((fd_g - h.column(dof)).amax() < 1e-7 * h.amax());
        }
    }
}
