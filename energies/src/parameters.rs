//! Material parameters: Lame coefficients from Young's modulus and Poisson's ratio.

use crate::ParameterError;

/// Lame coefficients `mu` (shear modulus) and `lambda`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Lame {
    /// Shear modulus `mu > 0`.
    pub mu: f64,
    /// First Lame parameter `lambda >= 0` (finite).
    pub lambda: f64,
}

impl Lame {
    /// From `(mu, lambda)`; both finite, `mu > 0`, `lambda >= 0`.
    pub fn new(mu: f64, lambda: f64) -> Result<Self, ParameterError> {
        Ok(Lame {
            mu: require_mu(mu)?,
            lambda: require_lambda(lambda)?,
        })
    }

    /// From Young's modulus and Poisson's ratio: `mu = E / (2 (1 + nu))`,
    /// `lambda = E nu / ((1 + nu)(1 - 2 nu))` (eq. 3 of Sheen et al. 2021).
    /// Requires `E > 0` and `nu` in `(-1, 0.5)`: at `nu = 0.5` lambda is infinite, which only
    /// constraint-based methods can represent (use [`bulk_modulus`] there).
    pub fn from_young_poisson(e: f64, nu: f64) -> Result<Self, ParameterError> {
        check_young(e)?;
        check_poisson(nu)?;
        if nu >= 0.5 {
            return Err(ParameterError {
                name: "nu",
                value: nu,
                reason: "nu = 0.5 makes lambda infinite; use a mixed or zonal method",
            });
        }
        Lame::new(
            e / (2.0 * (1.0 + nu)),
            e * nu / ((1.0 + nu) * (1.0 - 2.0 * nu)),
        )
    }

    /// Shear modulus from `(E, nu)`, valid up to and including `nu = 0.5`.
    pub fn shear_modulus(e: f64, nu: f64) -> Result<f64, ParameterError> {
        check_young(e)?;
        check_poisson(nu)?;
        Ok(e / (2.0 * (1.0 + nu)))
    }
}

/// Bulk modulus `kappa = E / (3 (1 - 2 nu))`, `+inf` at `nu = 0.5` (so that compliances
/// `1 / kappa` are exactly zero there).
pub fn bulk_modulus(e: f64, nu: f64) -> Result<f64, ParameterError> {
    check_young(e)?;
    check_poisson(nu)?;
    if nu == 0.5 {
        Ok(f64::INFINITY)
    } else {
        Ok(e / (3.0 * (1.0 - 2.0 * nu)))
    }
}

fn check_young(e: f64) -> Result<(), ParameterError> {
    if e.is_finite() && e > 0.0 {
        Ok(())
    } else {
        Err(ParameterError {
            name: "E",
            value: e,
            reason: "Young's modulus must be finite and positive",
        })
    }
}

fn check_poisson(nu: f64) -> Result<(), ParameterError> {
    if nu > -1.0 && nu <= 0.5 {
        Ok(())
    } else {
        Err(ParameterError {
            name: "nu",
            value: nu,
            reason: "Poisson's ratio must lie in (-1, 0.5]",
        })
    }
}

/// Returns `value` if `ok`, else a [`ParameterError`] naming the parameter. `ok` must be false
/// for NaN (write comparisons so that NaN fails them).
pub(crate) fn require(
    name: &'static str,
    value: f64,
    ok: bool,
    reason: &'static str,
) -> Result<f64, ParameterError> {
    if ok {
        Ok(value)
    } else {
        Err(ParameterError {
            name,
            value,
            reason,
        })
    }
}

/// A finite, positive shear modulus `mu`.
pub(crate) fn require_mu(mu: f64) -> Result<f64, ParameterError> {
    require(
        "mu",
        mu,
        mu.is_finite() && mu > 0.0,
        "the shear modulus must be finite and positive",
    )
}

/// A finite, non-negative `lambda`.
pub(crate) fn require_lambda(lambda: f64) -> Result<f64, ParameterError> {
    require(
        "lambda",
        lambda,
        lambda.is_finite() && lambda >= 0.0,
        "lambda must be finite and non-negative",
    )
}
