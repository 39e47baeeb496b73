//! What a problem asks of friction: lagged smoothed Coulomb friction (Li et al. 2020, sec. 5)
//! against the analytic obstacles, between surfaces and against meshed obstacles, with one
//! slip length `epsv`.
//!
//! `epsv` is a length: the slip of a step below which friction is static (smoothed). IPC
//! states it as a velocity `epsv_v`; over an implicit Euler step `h` the slip is the
//! velocity times `h`, so `epsv = epsv_v h` gives the same friction force. Quasi-static
//! steps slip by their displacement increment.

use crate::error::SolverError;

/// Friction between the surfaces of bodies (and of a surface with itself), and against the
/// meshed obstacles; the body of every node is the surface contact's
/// ([`crate::terms::SurfaceContact::friction_lag`]).
#[derive(Debug, Clone, PartialEq)]
pub struct SurfaceFrictionSpec {
    /// The coefficient of every pair of surfaces without an override.
    pub friction: f64,
    /// Overrides per pair of bodies `([a, b], mu)` (in either order); the `k`-th meshed
    /// obstacle after the `B` bodies is body `B + k`.
    pub pairs: Vec<([usize; 2], f64)>,
}

/// Friction of a problem: coefficients against the obstacles, between surfaces, and the
/// slip length.
#[derive(Debug, Clone, PartialEq)]
pub struct FrictionSpec {
    /// The slip (m) over a step below which friction is static (smoothed).
    pub epsv: f64,
    /// The coefficient against each analytic obstacle, in the problem's order.
    pub obstacles: Vec<f64>,
    /// Between surfaces (only with surface contact on).
    pub surfaces: Option<SurfaceFrictionSpec>,
}

impl SurfaceFrictionSpec {
    /// The coefficient between bodies `a` and `b`.
    pub fn coefficient(&self, a: usize, b: usize) -> f64 {
        self.pairs
            .iter()
            .rev()
            .find(|(p, _)| *p == [a, b] || *p == [b, a])
            .map_or(self.friction, |&(_, mu)| mu)
    }
}

impl FrictionSpec {
    /// Checks the values: a positive finite `epsv`, finite non-negative coefficients.
    pub fn validate(&self) -> Result<(), SolverError> {
        let bad = |what: String| Err(SolverError::InvalidProblem(format!("friction: {what}")));
        if !(self.epsv.is_finite() && self.epsv > 0.0) {
            return bad(format!(
                "epsv must be finite and positive, not {}",
                self.epsv
            ));
        }
        let coefficients =
            self.obstacles
                .iter()
                .chain(self.surfaces.iter().flat_map(|s| {
                    std::iter::once(&s.friction).chain(s.pairs.iter().map(|(_, mu)| mu))
                }));
        for &mu in coefficients {
            if !(mu.is_finite() && mu >= 0.0) {
                return bad(format!(
                    "a coefficient must be finite and non-negative, not {mu}"
                ));
            }
        }
        Ok(())
    }
}
