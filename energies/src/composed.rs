//! A distortional density plus a scaled volumetric penalty: `Psi(F) = Psi_dev(F) + lambda U(J)`.
//!
//! The standard neo-Hookean energy (eq. 6 of Francu et al. 2021, eq. 4 of Sheen et al. 2021),
//! its `(J - 1)^2` variant and the constrained neo-Hookean of Sheen et al. 2021 (eq. 12 + 13)
//! are each one value of [`Composed`], and so is Stable neo-Hookean (Smith et al. 2018).

use crate::kinematics::{add_volumetric_tangent, cofactor};
use crate::materials::{DistortionalNeoHookean, DistortionalStableNeoHookean, FbarNeoHookean};
use crate::parameters::{require_lambda, require_mu};
use crate::penalties::{LogPenalty, QuadraticPenalty, SheenPenalty};
use crate::{Hyperelastic, Lame, Matrix9, OutOfDomain, ParameterError, VolumetricPenalty};
use nalgebra::Matrix3;

/// `Psi(F) = Psi_dev(F) + lambda U(det F)`, with `P = P_dev + lambda U'(J) cof F` and
/// `dP/dF = dP_dev/dF + lambda (U''(J) g g^T + U'(J) d2J/dF2)`, `g = vec(cof F) = dJ/dF`.
///
/// Defined where both parts are. Build it with [`Composed::new`] (which validates `lambda`)
/// or a named constructor.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Composed<D, P> {
    /// The distortional part `Psi_dev`.
    pub deviatoric: D,
    /// Volumetric stiffness `lambda >= 0` scaling the penalty.
    pub lambda: f64,
    /// The volumetric penalty `U(J)`.
    pub penalty: P,
    /// Name for reports.
    pub name: &'static str,
}

/// Standard neo-Hookean, eq. 6 of Francu et al. 2021:
/// `mu/2 (I_C - 3) - mu log J + lambda/2 (log J)^2` (distortional eq. 32 + `lambda (log J)^2/2`).
pub type StandardNeoHookean = Composed<DistortionalNeoHookean, LogPenalty>;

/// Neo-Hookean with `lambda/2 (J - 1)^2` in place of `lambda/2 (log J)^2` (Ogden 1997).
pub type QuadraticNeoHookean = Composed<DistortionalNeoHookean, QuadraticPenalty>;

/// Constrained neo-Hookean of Sheen et al. 2021: `mu/2 (alpha~^2 I_C - 3) + lambda U(J; beta)`.
pub type ConstrainedNeoHookean = Composed<FbarNeoHookean, SheenPenalty>;

/// Stable neo-Hookean of Smith, de Goes and Kim 2018 (eq. 14), the invertible energy compared
/// against in sec. 5 of Sheen et al. 2021:
/// `Psi_d + lambda/2 (J - 1)^2` with the distortional part `Psi_d` of
/// [`DistortionalStableNeoHookean`]. Rest stable and defined for every `F`.
///
/// It has the stress and tangent of the paper's
/// `mu/2 (I_C - 3) + lambda/2 (J - alpha)^2 - mu/2 log(I_C + 1)`, `alpha = 1 + 3 mu/(4 lambda)`;
/// its energy is the paper's minus the paper's rest value
/// `lambda/2 (1 - alpha)^2 - mu/2 log 4 = 9 mu^2/(32 lambda) - mu/2 log 4`, so `Psi(I) = 0`.
/// `lambda = 0` is allowed (the paper's `alpha` is then undefined, this form is not).
pub type StableNeoHookean = Composed<DistortionalStableNeoHookean, QuadraticPenalty>;

impl<D: Hyperelastic, P: VolumetricPenalty> Composed<D, P> {
    /// `deviatoric + lambda * penalty`, with `lambda` finite and non-negative.
    pub fn new(
        deviatoric: D,
        lambda: f64,
        penalty: P,
        name: &'static str,
    ) -> Result<Self, ParameterError> {
        Ok(Composed {
            deviatoric,
            lambda: require_lambda(lambda)?,
            penalty,
            name,
        })
    }
}

/// Standard neo-Hookean (eq. 6 of Francu et al. 2021, eq. 4 of Sheen et al. 2021);
/// rest stable, undefined for `J <= 0`.
pub fn standard_neo_hookean(lame: Lame) -> Result<StandardNeoHookean, ParameterError> {
    Composed::new(
        DistortionalNeoHookean::new(lame.mu)?,
        lame.lambda,
        LogPenalty,
        "standard neo-Hookean",
    )
}

/// Neo-Hookean with the `lambda/2 (J - 1)^2` volumetric term; rest stable, undefined for
/// `J <= 0` (its distortional part has `log J`).
pub fn quadratic_neo_hookean(lame: Lame) -> Result<QuadraticNeoHookean, ParameterError> {
    Composed::new(
        DistortionalNeoHookean::new(lame.mu)?,
        lame.lambda,
        QuadraticPenalty,
        "neo-Hookean (J-1)^2",
    )
}

/// Stable neo-Hookean (see [`StableNeoHookean`]) with `(mu, lambda)` used directly in the
/// energy; `mu > 0`, `lambda >= 0`, both finite.
pub fn stable_neo_hookean(lame: Lame) -> Result<StableNeoHookean, ParameterError> {
    Composed::new(
        DistortionalStableNeoHookean::new(lame.mu)?,
        lame.lambda,
        QuadraticPenalty,
        "Stable neo-Hookean",
    )
}

impl StableNeoHookean {
    /// Stable neo-Hookean matching, at small strain, linear elasticity with the given Lame
    /// parameters: the energy uses `mu' = 4/3 mu`, `lambda' = lambda + 5/6 mu` (Smith et al.
    /// 2018, sec. 3.4). `mu > 0` and `lambda' >= 0`, both finite.
    pub fn from_linear_lame(lame: Lame) -> Result<Self, ParameterError> {
        let mu = require_mu(lame.mu)?;
        stable_neo_hookean(Lame {
            mu: 4.0 / 3.0 * mu,
            lambda: lame.lambda + 5.0 / 6.0 * mu,
        })
    }
}

/// Constrained neo-Hookean (Sheen et al. 2021, eq. 12 + eq. 13):
/// `mu/2 (alpha~(J)^2 I_C - 3) + lambda U(J; beta)`; rest stable and defined for every `J`.
pub fn constrained_neo_hookean(
    mu: f64,
    lambda: f64,
    beta: f64,
    epsilon: f64,
) -> Result<ConstrainedNeoHookean, ParameterError> {
    Composed::new(
        FbarNeoHookean::new(mu, epsilon)?,
        lambda,
        SheenPenalty::new(beta)?,
        "constrained neo-Hookean",
    )
}

impl<D: Hyperelastic, P: VolumetricPenalty> Composed<D, P> {
    fn penalty_error(&self, j: f64) -> OutOfDomain {
        OutOfDomain {
            energy: self.penalty.name(),
            j,
        }
    }

    /// `(J, lambda U'(J), lambda U''(J))`, checking the penalty's domain.
    fn volumetric_derivatives(&self, f: &Matrix3<f64>) -> Result<(f64, f64, f64), OutOfDomain> {
        let j = f.determinant();
        if !self.penalty.is_defined_at(j) {
            return Err(self.penalty_error(j));
        }
        Ok((
            j,
            self.lambda * self.penalty.first_derivative(j)?,
            self.lambda * self.penalty.second_derivative(j)?,
        ))
    }
}

impl<D: Hyperelastic, P: VolumetricPenalty> Hyperelastic for Composed<D, P> {
    fn name(&self) -> &'static str {
        self.name
    }

    fn energy_density(&self, f: &Matrix3<f64>) -> Result<f64, OutOfDomain> {
        let j = f.determinant();
        if !self.penalty.is_defined_at(j) {
            return Err(self.penalty_error(j));
        }
        Ok(self.deviatoric.energy_density(f)? + self.lambda * self.penalty.value(j)?)
    }

    fn pk1(&self, f: &Matrix3<f64>) -> Result<Matrix3<f64>, OutOfDomain> {
        let (_, d1, _) = self.volumetric_derivatives(f)?;
        Ok(self.deviatoric.pk1(f)? + cofactor(f) * d1)
    }

    fn pk1_derivative(&self, f: &Matrix3<f64>) -> Result<Matrix9, OutOfDomain> {
        let (_, d1, d2) = self.volumetric_derivatives(f)?;
        let mut h = self.deviatoric.pk1_derivative(f)?;
        add_volumetric_tangent(&mut h, f, d1, d2);
        Ok(h)
    }

    fn is_defined_at(&self, j: f64) -> bool {
        self.deviatoric.is_defined_at(j) && self.penalty.is_defined_at(j)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;

    #[test]
    fn standard_neo_hookean_matches_eq_6() {
        let lame = Lame::new(1.5, 7.0).unwrap();
        let m = standard_neo_hookean(lame).unwrap();
        let f = Matrix3::<f64>::new(1.1, 0.2, 0.0, -0.1, 0.8, 0.3, 0.05, 0.0, 1.2);
        let (ic, lj) = (f.norm_squared(), f.determinant().ln());
        let eq6 = 0.75 * (ic - 3.0) - 1.5 * lj + 3.5 * lj * lj;
        assert_relative_eq!(m.energy_density(&f).unwrap(), eq6, max_relative = 1e-14);
        // P = mu (F - F^-T) + lambda log J F^-T.
        let fit = f.try_inverse().unwrap().transpose();
        let p = (f - fit) * 1.5 + fit * (7.0 * lj);
        assert_relative_eq!(m.pk1(&f).unwrap(), p, max_relative = 1e-13);
    }

    #[test]
    fn stable_neo_hookean_parameters() {
        let m = StableNeoHookean::from_linear_lame(Lame {
            mu: 3.0,
            lambda: 0.0,
        })
        .unwrap();
        assert_eq!((m.deviatoric.mu(), m.lambda), (4.0, 2.5));
        // lambda = 0 is allowed: the distortional part alone is rest stable.
        let m = stable_neo_hookean(Lame::new(1.0, 0.0).unwrap()).unwrap();
        assert_eq!(m.pk1(&Matrix3::identity()).unwrap(), Matrix3::zeros());
        assert_eq!(m.energy_density(&Matrix3::identity()).unwrap(), 0.0);
        let bad = Lame {
            mu: f64::NAN,
            lambda: 1.0,
        };
        assert_eq!(
            StableNeoHookean::from_linear_lame(bad).unwrap_err().name,
            "mu"
        );
    }

    #[test]
    fn domain_is_the_conjunction() {
        let lame = Lame::new(1.0, 1.0).unwrap();
        assert!(!standard_neo_hookean(lame).unwrap().is_defined_at(-0.1));
        assert!(!quadratic_neo_hookean(lame).unwrap().is_defined_at(0.0));
        let cnh = constrained_neo_hookean(1.0, 1.0, 2.0, 0.1).unwrap();
        assert!(cnh.is_defined_at(-3.0));
        let inverted = Matrix3::from_diagonal(&nalgebra::Vector3::new(1.0, 1.0, -0.5));
        let err = standard_neo_hookean(lame)
            .unwrap()
            .pk1(&inverted)
            .unwrap_err();
        assert_eq!(err.j, -0.5);
    }

    #[test]
    fn names_bad_parameters() {
        assert_eq!(
            constrained_neo_hookean(1.0, -1.0, 1.0, 0.1)
                .unwrap_err()
                .name,
            "lambda"
        );
        assert_eq!(
            constrained_neo_hookean(1.0, 1.0, -1.0, 0.1)
                .unwrap_err()
                .name,
            "beta"
        );
        assert_eq!(
            constrained_neo_hookean(f64::NAN, 1.0, 1.0, 0.1)
                .unwrap_err()
                .name,
            "mu"
        );
        assert_eq!(
            constrained_neo_hookean(1.0, 1.0, 1.0, 2.0)
                .unwrap_err()
                .name,
            "epsilon"
        );
    }
}
