//! The discretization and solver of the volumetric response, by the names scenes and the
//! command line use.

use crate::error::SolverError;
use std::fmt;
use std::str::FromStr;

/// The discretization and solver of the volumetric response, as named on the command line.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Method {
    /// Displacement-only coupled neo-Hookean (eq. 6 of Francu et al. 2021), Newton with line search.
    Standard,
    /// Mixed FEM, nodal (P1) pressures, linear measure `J - 1` (eq. 24/27), saddle-point Newton.
    MixedP1,
    /// Mixed FEM, element (P0) pressures, linear measure (sec. 4.6), saddle-point Newton.
    MixedP0,
    /// Mixed FEM, nodal pressures, logarithmic measure `log J` (sec. 6).
    MixedP1Log,
    /// Mixed FEM, element pressures, logarithmic measure. With `kappa = lambda` its static
    /// condensation is exactly the standard neo-Hookean energy.
    MixedP0Log,
    /// Static condensation of the nodal mixed system (eq. 37) with a lumped `C^-1`.
    Condensed,
    /// Dual ascent / nonlinear Uzawa on the nodal constraints (eq. 39-41), optionally
    /// augmented with a base Poisson ratio (sec. 8.3).
    Dual,
    /// Constrained neo-Hookean of Sheen et al. 2021: F-bar deviatoric energy plus
    /// `lambda U(J; beta)`, subject to zonal volume constraints (eq. 6-15).
    Zonal,
}

impl Method {
    /// Every method, in the order tables list them.
    pub const ALL: [Method; 8] = [
        Method::Standard,
        Method::MixedP1,
        Method::MixedP0,
        Method::MixedP1Log,
        Method::MixedP0Log,
        Method::Condensed,
        Method::Dual,
        Method::Zonal,
    ];

    /// The name used by scenes and the command line.
    pub fn name(self) -> &'static str {
        match self {
            Method::Standard => "standard",
            Method::MixedP1 => "mixed-p1",
            Method::MixedP0 => "mixed-p0",
            Method::MixedP1Log => "mixed-p1-log",
            Method::MixedP0Log => "mixed-p0-log",
            Method::Condensed => "condensed",
            Method::Dual => "dual",
            Method::Zonal => "zonal",
        }
    }

    /// Whether the method carries pressure unknowns or multipliers.
    pub fn has_constraints(self) -> bool {
        self != Method::Standard
    }
}

impl fmt::Display for Method {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

impl FromStr for Method {
    type Err = SolverError;
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        Method::ALL
            .into_iter()
            .find(|m| m.name() == s)
            .ok_or_else(|| SolverError::UnknownMethod {
                name: s.to_string(),
                valid: Method::ALL
                    .iter()
                    .map(|m| m.name())
                    .collect::<Vec<_>>()
                    .join(", "),
            })
    }
}
