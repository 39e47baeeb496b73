//! The uncoupled N-term Ogden energy (Ogden 1972) on the isochoric principal stretches.

use crate::kinematics::{cofactor, flatten, positive_determinant, unflatten, VolumeFactor};
use crate::parameters::require;
use crate::{Hyperelastic, Matrix9, OutOfDomain, ParameterError, Vector9};
use nalgebra::{Matrix3, SymmetricEigen, Vector3};

/// `Psi = sum_p mu_p / alpha_p (lb1^alpha_p + lb2^alpha_p + lb3^alpha_p - 3)` on the isochoric
/// principal stretches `lbi = J^-1/3 li` (`li^2` the eigenvalues of `C = F^T F`).
///
/// Parameters: terms `(mu_p, alpha_p)`, `mu_p` in units of stress, `alpha_p` dimensionless and
/// nonzero, each with `mu_p alpha_p > 0` (Ogden's stability condition); the initial shear
/// modulus is `mu = 1/2 sum_p mu_p alpha_p`. One term `(mu, 2)` is
/// [`BonetWood`](crate::BonetWood) with `mu`; `(2 c10, 2), (-2 c01, -2)` is
/// [`MooneyRivlin`](crate::MooneyRivlin). Purely distortional and rest stable (`P(I) = 0`);
/// undefined ([`OutOfDomain`]) for `J <= 0`. For incompressible uniaxial stretch `l` the
/// nominal stress is `sum_p mu_p (l^(alpha_p - 1) - l^(-alpha_p/2 - 1))`.
///
/// Each term is `J^(-alpha/3) tr(C^(alpha/2))`, a [`VolumeFactor`] times the spectral
/// function `I = tr g(C)`, `g(c) = c^q`, `q = alpha/2`, so `dI/dF = 2 F g'(C)`. Its Hessian
/// needs the derivative of the matrix function `g'(C)` (Daleckii-Krein):
/// `D g'(C)[E] = V (G o V^T E V) V^T` with `C = V diag(c) V^T` and the divided differences
/// `G_ij = (g'(c_i) - g'(c_j)) / (c_i - c_j)` (`g''(c_i)` on the diagonal), evaluated as
/// `q c_j^(q-2) expm1((q-1) t) / expm1(t)`, `t = log(c_i / c_j)`, which tends to `g''` without
/// cancellation as `c_i -> c_j`. The tangent is therefore accurate at equal and nearly equal
/// stretches, where the classical formulas in `1 / (l_i^2 - l_j^2)` break down.
#[derive(Debug, Clone, PartialEq)]
pub struct Ogden {
    terms: Vec<(f64, f64)>,
}

impl Ogden {
    /// At least one term `(mu_p, alpha_p)`, all finite, `alpha_p != 0` and `mu_p alpha_p > 0`
    /// (errors name `mu_p` or `alpha_p`).
    pub fn new(terms: &[(f64, f64)]) -> Result<Self, ParameterError> {
        if terms.is_empty() {
            return Err(ParameterError {
                name: "mu_p",
                value: f64::NAN,
                reason: "Ogden needs at least one term (mu_p, alpha_p)",
            });
        }
        for &(mu, alpha) in terms {
            require(
                "alpha_p",
                alpha,
                alpha.is_finite() && alpha != 0.0,
                "every alpha_p must be finite and nonzero",
            )?;
            require(
                "mu_p",
                mu,
                mu.is_finite() && mu * alpha > 0.0,
                "every mu_p must be finite with mu_p alpha_p > 0",
            )?;
        }
        Ok(Ogden {
            terms: terms.to_vec(),
        })
    }

    /// The terms `(mu_p, alpha_p)`.
    pub fn terms(&self) -> &[(f64, f64)] {
        &self.terms
    }

    /// Initial shear modulus `mu = 1/2 sum_p mu_p alpha_p`.
    pub fn mu(&self) -> f64 {
        0.5 * self.terms.iter().map(|(m, a)| m * a).sum::<f64>()
    }

    fn spectrum(&self, f: &Matrix3<f64>) -> Result<Spectrum, OutOfDomain> {
        let j = positive_determinant(self.name(), f)?;
        let eigen = SymmetricEigen::new(f.transpose() * f);
        let c = eigen.eigenvalues;
        if c.min() > 0.0 {
            Ok(Spectrum {
                j,
                c,
                v: eigen.eigenvectors,
            })
        } else {
            Err(OutOfDomain {
                energy: self.name(),
                j,
            })
        }
    }
}

/// `J` and the eigen-decomposition `C = V diag(c) V^T`.
struct Spectrum {
    j: f64,
    c: Vector3<f64>,
    v: Matrix3<f64>,
}

impl Spectrum {
    /// `tr C^q`.
    fn power_trace(&self, q: f64) -> f64 {
        self.c.iter().map(|c| c.powf(q)).sum()
    }

    /// `g'(C) = q C^(q-1)`.
    fn derivative(&self, q: f64) -> Matrix3<f64> {
        let d = self.c.map(|c| q * c.powf(q - 1.0));
        self.v * Matrix3::from_diagonal(&d) * self.v.transpose()
    }

    /// The divided differences `G_ij` of `g'(c) = q c^(q-1)`.
    fn divided_differences(&self, q: f64) -> Matrix3<f64> {
        Matrix3::from_fn(|i, j| {
            let (ci, cj) = (self.c[i], self.c[j]);
            let t = (ci / cj).ln();
            let ratio = if t == 0.0 {
                q - 1.0
            } else {
                ((q - 1.0) * t).exp_m1() / t.exp_m1()
            };
            q * cj.powf(q - 2.0) * ratio
        })
    }
}

impl Hyperelastic for Ogden {
    fn name(&self) -> &'static str {
        "Ogden"
    }

    fn energy_density(&self, f: &Matrix3<f64>) -> Result<f64, OutOfDomain> {
        let s = self.spectrum(f)?;
        Ok(self
            .terms
            .iter()
            .map(|&(mu, alpha)| {
                let a = s.j.powf(-alpha / 3.0);
                mu / alpha * (a * s.power_trace(0.5 * alpha) - 3.0)
            })
            .sum())
    }

    fn pk1(&self, f: &Matrix3<f64>) -> Result<Matrix3<f64>, OutOfDomain> {
        let s = self.spectrum(f)?;
        let g = flatten(&cofactor(f));
        let mut p = Vector9::zeros();
        for &(mu, alpha) in &self.terms {
            let q = 0.5 * alpha;
            let di = flatten(&(f * s.derivative(q) * 2.0));
            let factor = VolumeFactor::power(s.j, -alpha / 3.0);
            p += factor.scaled_gradient(s.power_trace(q), &di, &g) * (mu / alpha);
        }
        Ok(unflatten(&p))
    }

    fn pk1_derivative(&self, f: &Matrix3<f64>) -> Result<Matrix9, OutOfDomain> {
        let s = self.spectrum(f)?;
        let g = flatten(&cofactor(f));
        let fv = f * s.v;
        let mut h = Matrix9::zeros();
        for &(mu, alpha) in &self.terms {
            let q = 0.5 * alpha;
            let dg = s.derivative(q);
            let divided = s.divided_differences(q);
            // d2I/dF2 column by column: the change of dI/dF = 2 F g'(C) along the unit
            // direction E, 2 E g'(C) + 2 F D g'(C)[E^T F + F^T E].
            let mut d2i = Matrix9::zeros();
            for k in 0..9 {
                let mut e = Matrix3::zeros();
                e[(k % 3, k / 3)] = 1.0;
                let dc = s.v.transpose() * (e.transpose() * f + f.transpose() * e) * s.v;
                let column = (e * dg + fv * divided.component_mul(&dc) * s.v.transpose()) * 2.0;
                d2i.set_column(k, &flatten(&column));
            }
            // Symmetric in exact arithmetic; averaging removes the rounding asymmetry.
            let d2i = (d2i + d2i.transpose()) * 0.5;
            let di = flatten(&(f * dg * 2.0));
            let factor = VolumeFactor::power(s.j, -alpha / 3.0);
            h += factor.scaled_hessian(f, s.power_trace(q), &di, &d2i, &g) * (mu / alpha);
        }
        Ok(h)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_bad_parameters() {
        let name = |terms: &[(f64, f64)]| Ogden::new(terms).unwrap_err().name;
        assert_eq!(name(&[]), "mu_p");
        assert_eq!(name(&[(1.0, 0.0)]), "alpha_p");
        assert_eq!(name(&[(1.0, 2.0), (1.0, -2.0)]), "mu_p");
        assert_eq!(name(&[(f64::NAN, 2.0)]), "mu_p");
        let treloar = Ogden::new(&[(0.63, 1.3), (0.0012, 5.0), (-0.01, -2.0)]).unwrap();
        assert!((treloar.mu() - 0.5 * (0.819 + 0.006 + 0.02)).abs() < 1e-15);
    }
}
