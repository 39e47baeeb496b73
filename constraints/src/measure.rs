//! The volume measure `Phi(J)` behind a constraint: linear `J - 1` (sec. 4.6 of Francu et al.
//! 2021) or logarithmic `log J` (sec. 6), integrated over the rest element.

use isochor_energies::kinematics::{add_volumetric_tangent, cofactor};
use isochor_energies::{Hyperelastic, Matrix9, OutOfDomain};
use nalgebra::Matrix3;

/// How the volume ratio `J = det F` enters a constraint: every row is an integral
/// `integral_e c Phi(J) dV` over rest elements (`c = 1` for element (P0) and zonal rows, the
/// corner shape function for nodal (P1) rows, eq. 27).
///
/// `Phi(det F)` is a density of `F`: as a [`Hyperelastic`] its "stress" is
/// `Phi'(J) cof F` and its tangent `Phi''(J) vec(cof F) vec(cof F)^T + Phi'(J) d2J/dF2`, so
/// the quadrature kernel of `isochor-energies` integrates it and its derivatives.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Measure {
    /// `Phi = J - 1`, so a 4-node tet contributes `v_e - V_e` (sec. 4.6). Defined for every
    /// `J`, inverted elements included.
    #[default]
    Linear,
    /// `Phi = log J` (sec. 6), with `Phi' = 1/J` and `Phi'' = -1/J^2`. Defined only for
    /// `J > 0`; the multipliers absorb a factor `J`, the true pressure is `p / J`.
    Logarithmic,
}

impl Measure {
    /// The true (Cauchy) pressure from a multiplier `p` of this measure at volume ratio `j`:
    /// `p` itself for the linear measure, `p / J` for the logarithmic one (sec. 6).
    pub fn true_pressure(self, p: f64, j: f64) -> f64 {
        match self {
            Measure::Linear => p,
            Measure::Logarithmic => p / j,
        }
    }

    /// `(Phi(J), Phi'(J), Phi''(J))` at `J = det F`, or [`OutOfDomain`].
    fn derivatives(self, f: &Matrix3<f64>) -> Result<(f64, f64, f64), OutOfDomain> {
        let j = f.determinant();
        match self {
            Measure::Linear => Ok((j - 1.0, 1.0, 0.0)),
            Measure::Logarithmic if j > 0.0 => Ok((j.ln(), 1.0 / j, -1.0 / (j * j))),
            Measure::Logarithmic => Err(OutOfDomain {
                energy: self.name(),
                j,
            }),
        }
    }
}

impl Hyperelastic for Measure {
    fn name(&self) -> &'static str {
        match self {
            Measure::Linear => "the linear volume measure",
            Measure::Logarithmic => "the logarithmic volume measure",
        }
    }

    fn energy_density(&self, f: &Matrix3<f64>) -> Result<f64, OutOfDomain> {
        Ok(self.derivatives(f)?.0)
    }

    fn pk1(&self, f: &Matrix3<f64>) -> Result<Matrix3<f64>, OutOfDomain> {
        Ok(cofactor(f) * self.derivatives(f)?.1)
    }

    fn pk1_derivative(&self, f: &Matrix3<f64>) -> Result<Matrix9, OutOfDomain> {
        let (_, d1, d2) = self.derivatives(f)?;
        let mut h = Matrix9::zeros();
        add_volumetric_tangent(&mut h, f, d1, d2);
        Ok(h)
    }

    fn is_defined_at(&self, j: f64) -> bool {
        *self == Measure::Linear || j > 0.0
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::Vector3;

    #[test]
    fn values_at_rest_and_under_uniform_scaling() {
        let identity = Matrix3::identity();
        for m in [Measure::Linear, Measure::Logarithmic] {
            assert_eq!(m.energy_density(&identity).unwrap(), 0.0);
        }
        // Doubling every length gives J = 8.
        let f = identity * 2.0;
        assert_eq!(Measure::Linear.energy_density(&f).unwrap(), 7.0);
        let log = Measure::Logarithmic.energy_density(&f).unwrap();
        assert!((log - 8f64.ln()).abs() < 1e-15);
        assert_eq!(Measure::Logarithmic.true_pressure(4.0, 8.0), 0.5);
        assert_eq!(Measure::Linear.true_pressure(4.0, 8.0), 4.0);
    }

    #[test]
    fn logarithmic_measure_rejects_inverted_and_flat_elements() {
        let inverted = Matrix3::from_diagonal(&Vector3::new(1.0, 1.0, -1.0));
        let err = Measure::Logarithmic.energy_density(&inverted).unwrap_err();
        assert_eq!(err.j, -1.0);
        let flat = Matrix3::from_diagonal(&Vector3::new(1.0, 1.0, 0.0));
        assert!(Measure::Logarithmic.pk1(&flat).is_err());
        assert!(Measure::Logarithmic.pk1_derivative(&flat).is_err());
        assert!(!Measure::Logarithmic.is_defined_at(0.0));
        // The linear measure is defined everywhere.
        assert!(Measure::Linear.pk1_derivative(&flat).is_ok());
        assert!(Measure::Linear.is_defined_at(-1.0));
    }

    #[test]
    fn derivatives_match_central_differences() {
        let f = Matrix3::new(1.1, 0.2, -0.3, 0.05, 0.9, 0.4, -0.2, 0.1, 1.3);
        let step = 1e-6;
        for m in [Measure::Linear, Measure::Logarithmic] {
            let p = m.pk1(&f).unwrap();
            let a = m.pk1_derivative(&f).unwrap();
            for k in 0..9 {
                let shifted = |s: f64| {
                    let mut g = f;
                    g[k] += s;
                    g
                };
                let fd = (m.energy_density(&shifted(step)).unwrap()
                    - m.energy_density(&shifted(-step)).unwrap())
                    / (2.0 * step);
                assert!((fd - p[k]).abs() < 1e-8, "{m:?} P[{k}]");
                let fd_p = (m.pk1(&shifted(step)).unwrap() - m.pk1(&shifted(-step)).unwrap())
                    / (2.0 * step);
                let column = Matrix3::from_column_slice(a.column(k).as_slice());
                assert!((fd_p - column).amax() < 1e-8, "{m:?} dP/dF column {k}");
            }
            assert!((a - a.transpose()).amax() < 1e-14);
        }
    }
}
