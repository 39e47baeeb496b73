//! The F-bar deviatoric neo-Hookean energy with a C2 extension, eq. 10-12 of Sheen et al. 2021.

use crate::kinematics::{cofactor, first_invariant, flatten, unflatten, VolumeFactor};
use crate::parameters::{require, require_mu};
use crate::{Hyperelastic, Matrix9, OutOfDomain, ParameterError};
use nalgebra::Matrix3;

/// `Psi = mu/2 (alpha~(J)^2 I_C - 3)` (eq. 12), the neo-Hookean energy of `F-bar = alpha~ F`
/// (eq. 10 with `J-bar = 1`), where (eq. 11)
///
/// `alpha~(J) = J^-1/3` for `J > epsilon`, and below `epsilon` its second-order Taylor
/// expansion at `epsilon`:
/// `epsilon^-1/3 - 1/3 epsilon^-4/3 (J - epsilon) + 2/9 epsilon^-7/3 (J - epsilon)^2`.
///
/// The extension matches value, slope and curvature at `epsilon` (C2) and stays positive, so
/// the energy is defined for every `J`, inverted elements included. Above `epsilon` it equals
/// Bonet-Wood (eq. 30 of Francu et al. 2021). Shear modulus `mu` (the initial shear
/// modulus); rest stable for `epsilon < 1`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FbarNeoHookean {
    mu: f64,
    epsilon: f64,
}

impl FbarNeoHookean {
    /// The paper's suggested threshold (`~0.1`, sec. 4.1).
    pub const DEFAULT_EPSILON: f64 = 0.1;

    /// `mu` finite and positive, `epsilon` in `(0, 1)`.
    pub fn new(mu: f64, epsilon: f64) -> Result<Self, ParameterError> {
        let epsilon = require(
            "epsilon",
            epsilon,
            epsilon > 0.0 && epsilon < 1.0,
            "the extension threshold must lie in (0, 1)",
        )?;
        Ok(FbarNeoHookean {
            mu: require_mu(mu)?,
            epsilon,
        })
    }

    /// Shear modulus.
    pub fn mu(&self) -> f64 {
        self.mu
    }

    /// Extension threshold `epsilon`.
    pub fn epsilon(&self) -> f64 {
        self.epsilon
    }

    /// `(alpha~, alpha~', alpha~'')` at `J` (eq. 11).
    pub fn alpha(&self, j: f64) -> (f64, f64, f64) {
        let (x, t) = if j > self.epsilon {
            (j, 0.0)
        } else {
            (self.epsilon, j - self.epsilon)
        };
        let a = x.cbrt().recip();
        let d1 = -a / (3.0 * x);
        let d2 = 4.0 * a / (9.0 * x * x);
        // Taylor expansion about x (exact when t = 0, i.e. above epsilon).
        (a + d1 * t + 0.5 * d2 * t * t, d1 + d2 * t, d2)
    }

    /// `a = alpha~^2`, `a' = 2 alpha~ alpha~'`, `a'' = 2 (alpha~'^2 + alpha~ alpha~'')`.
    fn factor(&self, f: &Matrix3<f64>) -> VolumeFactor {
        let (al, d1, d2) = self.alpha(f.determinant());
        VolumeFactor {
            a: al * al,
            da: 2.0 * al * d1,
            dda: 2.0 * (d1 * d1 + al * d2),
        }
    }
}

impl Hyperelastic for FbarNeoHookean {
    fn name(&self) -> &'static str {
        "F-bar deviatoric neo-Hookean"
    }

    fn energy_density(&self, f: &Matrix3<f64>) -> Result<f64, OutOfDomain> {
        Ok(0.5 * self.mu * (self.factor(f).a * first_invariant(f) - 3.0))
    }

    /// `P = mu/2 d(a I_C)/dF = mu/2 (2 a F + a' I_C cof F)`, `a = alpha~^2`.
    fn pk1(&self, f: &Matrix3<f64>) -> Result<Matrix3<f64>, OutOfDomain> {
        let g = flatten(&cofactor(f));
        let p = self
            .factor(f)
            .scaled_gradient(first_invariant(f), &(flatten(f) * 2.0), &g);
        Ok(unflatten(&(p * (0.5 * self.mu))))
    }

    /// `dP/dF = mu/2 d2(a I_C)/dF2` ([`VolumeFactor::scaled_hessian`] with `d2I_C = 2 I`).
    fn pk1_derivative(&self, f: &Matrix3<f64>) -> Result<Matrix9, OutOfDomain> {
        let g = flatten(&cofactor(f));
        let h = self.factor(f).scaled_hessian(
            f,
            first_invariant(f),
            &(flatten(f) * 2.0),
            &Matrix9::from_diagonal_element(2.0),
            &g,
        );
        Ok(h * (0.5 * self.mu))
    }

    fn is_defined_at(&self, _j: f64) -> bool {
        true
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;

    #[test]
    fn extension_is_c2_at_epsilon() {
        let m = FbarNeoHookean::new(1.0, 0.1).unwrap();
        let (below, above) = (m.alpha(0.1 - 1e-12), m.alpha(0.1 + 1e-12));
        assert_relative_eq!(below.0, above.0, max_relative = 1e-9);
        assert_relative_eq!(below.1, above.1, max_relative = 1e-9);
        assert_relative_eq!(below.2, above.2, max_relative = 1e-9);
        // Written out as in eq. 11.
        let (e, j) = (0.1f64, -0.7f64);
        let eq11 = e.powf(-1.0 / 3.0) - e.powf(-4.0 / 3.0) * (j - e) / 3.0
            + 2.0 / 9.0 * e.powf(-7.0 / 3.0) * (j - e).powi(2);
        assert_relative_eq!(m.alpha(j).0, eq11, max_relative = 1e-14);
    }

    #[test]
    fn validates_epsilon() {
        for e in [0.0, 1.0, -0.1, f64::NAN] {
            assert_eq!(FbarNeoHookean::new(1.0, e).unwrap_err().name, "epsilon");
        }
    }
}
