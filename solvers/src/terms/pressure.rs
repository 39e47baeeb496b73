//! Follower pressure on a surface: potential `s p V_f(x)` (`s` the load ramp or the load's
//! curve) with `V_f` the cone volume of the faces about the load's origin
//! ([`EnclosedVolume`]). Its gradient is the follower force `-p n da` and its Hessian the
//! consistent, symmetric load stiffness. For a closed surface, an open one whose rim is held
//! by Dirichlet conditions (the inflated tube), or one closed by symmetry planes through the
//! origin, this is exactly the pressure load; faces are oriented with the body's outward
//! normal, so a positive pressure pushes into the body (into the wall of a chamber: the
//! chamber inflates).

use super::{EnclosedVolume, EnergyTerm, Faces};
use crate::error::SolverError;
use crate::problem::schedule::{Curve, LoadLevel};
use isochor_mesh::Vec3;

/// Follower pressure on a set of faces.
#[derive(Debug, Clone)]
pub struct FollowerPressure {
    volume: EnclosedVolume,
    pressure: f64,
    curve: Option<Curve>,
}

impl FollowerPressure {
    /// Pressure `pressure` on `faces` (body-outward orientation), its potential the cone
    /// volume about the origin of coordinates.
    pub fn new(faces: Faces, pressure: f64) -> Self {
        FollowerPressure {
            volume: EnclosedVolume::new(faces, Vec3::zeros()),
            pressure,
            curve: None,
        }
    }

    /// Pressure `pressure` on the faces of `volume`, its potential `-p` times the volume
    /// they enclose (about its origin, capped or not).
    pub fn on(volume: EnclosedVolume, pressure: f64) -> Self {
        FollowerPressure {
            volume,
            pressure,
            curve: None,
        }
    }

    /// The same pressure scaled by `curve` (`None`: the default ramp).
    pub fn following(self, curve: Option<Curve>) -> Self {
        FollowerPressure { curve, ..self }
    }
}

impl EnergyTerm for FollowerPressure {
    fn name(&self) -> &'static str {
        "pressure"
    }

    fn hessian_pattern(&self) -> Vec<(usize, usize)> {
        self.volume.hessian_pattern()
    }

    fn evaluate(
        &self,
        x: &[Vec3],
        level: &LoadLevel,
        gradient: Option<&mut [f64]>,
        hessian: Option<&mut [f64]>,
    ) -> Result<f64, SolverError> {
        let s = level.load_scale(self.curve.as_ref()) * self.pressure;
        Ok(self.volume.accumulate(x, s, gradient, hessian))
    }

    fn is_external(&self) -> bool {
        true
    }
}
