//! Cavities held at a volume: one hard constraint row per volume-controlled pressure load,
//! `phi_k(x) = V_k(x) + (1 + (R_k - 1) s_k) V_k^rest`, where `V_k` is the cone volume of the
//! load's faces about its origin with the body-outward orientation ([`EnclosedVolume`]: minus
//! the volume the faces enclose), `R_k` the load's volume ratio and `s_k` its load scale. With
//! the Lagrangian `E + p^T phi` the stationarity `grad E + p_k grad V_k = 0` is that of a
//! follower pressure `p_k` ([`crate::terms::FollowerPressure`]), so the multiplier is the
//! cavity's pressure, positive when it inflates.

use crate::error::SolverError;
use crate::problem::schedule::{Curve, LoadLevel};
use crate::terms::EnclosedVolume;
use isochor_constraints::{Compliance, ConstraintError, ConstraintSet};
use isochor_mesh::Vec3;
use std::sync::RwLock;

/// One volume-controlled cavity.
#[derive(Debug)]
pub struct Cavity {
    volume: EnclosedVolume,
    ratio: f64,
    curve: Option<Curve>,
    rest: f64,
}

impl Cavity {
    /// The cavity lined by the faces of `volume` (body-outward orientation), held at `ratio`
    /// times its rest volume at full load, ramped by `curve` (`None`: the default ramp).
    ///
    /// Errors: [`SolverError::InvalidProblem`] unless `ratio` is positive and finite and the
    /// faces enclose a positive volume about their origin at rest (`rest`).
    pub fn new(
        volume: EnclosedVolume,
        ratio: f64,
        curve: Option<Curve>,
        rest: &[Vec3],
    ) -> Result<Self, SolverError> {
        if !(ratio > 0.0 && ratio.is_finite()) {
            return Err(SolverError::InvalidProblem(format!(
                "volume_ratio = {ratio} must be positive and finite"
            )));
        }
        let enclosed = -volume.value(rest);
        if enclosed.is_nan() || enclosed <= 0.0 {
            return Err(SolverError::InvalidProblem(format!(
                "volume_ratio: the faces enclose no volume about the origin (rest volume {enclosed:e}; \
                 the faces must line a closed cavity, or one closed by symmetry planes through the origin)"
            )));
        }
        Ok(Cavity {
            volume,
            ratio,
            curve,
            rest: enclosed,
        })
    }

    /// The volume enclosed at rest.
    pub fn rest_volume(&self) -> f64 {
        self.rest
    }
}

/// The constraint rows of every volume-controlled cavity, their targets at the load level
/// last set ([`Cavities::set_level`]).
#[derive(Debug)]
pub struct Cavities {
    cavities: Vec<Cavity>,
    targets: RwLock<Vec<f64>>,
    num_tets: usize,
}

impl Cavities {
    /// The rows of `cavities` on a mesh of `num_tets` elements, at their rest targets.
    pub fn new(cavities: Vec<Cavity>, num_tets: usize) -> Self {
        let targets = cavities.iter().map(|c| c.rest).collect();
        Cavities {
            cavities,
            targets: RwLock::new(targets),
            num_tets,
        }
    }

    /// The cavities.
    pub fn cavities(&self) -> &[Cavity] {
        &self.cavities
    }

    /// Sets the target volumes `(1 + (R_k - 1) s_k) V_k^rest` at `level`.
    pub fn set_level(&self, level: &LoadLevel) {
        let mut targets = self.targets.write().unwrap_or_else(|e| e.into_inner());
        for (t, c) in targets.iter_mut().zip(&self.cavities) {
            *t = (1.0 + (c.ratio - 1.0) * level.load_scale(c.curve.as_ref())) * c.rest;
        }
    }

    fn check(&self, x: &[Vec3]) -> Result<(), ConstraintError> {
        let needed = self
            .cavities
            .iter()
            .flat_map(|c| c.volume.faces().iter().flatten())
            .max()
            .map_or(0, |v| v + 1);
        if x.len() < needed {
            return Err(ConstraintError::DimensionMismatch {
                what: "positions",
                expected: needed,
                actual: x.len(),
            });
        }
        Ok(())
    }
}

impl ConstraintSet for Cavities {
    fn name(&self) -> &'static str {
        "cavity volume"
    }

    fn num_constraints(&self) -> usize {
        self.cavities.len()
    }

    /// An enclosed volume is a surface integral, defined whatever the tets inside do.
    fn admits_inversion(&self) -> bool {
        true
    }

    fn values(&self, x: &[Vec3], out: &mut [f64]) -> Result<(), ConstraintError> {
        self.check(x)?;
        let targets = self.targets.read().unwrap_or_else(|e| e.into_inner());
        for ((o, c), t) in out.iter_mut().zip(&self.cavities).zip(targets.iter()) {
            *o = c.volume.value(x) + t;
        }
        Ok(())
    }

    fn jacobian_pattern(&self) -> Vec<(usize, usize)> {
        self.cavities
            .iter()
            .enumerate()
            .flat_map(|(k, c)| c.volume.gradient_dofs().into_iter().map(move |d| (k, d)))
            .collect()
    }

    fn jacobian_values(&self, x: &[Vec3], out: &mut [f64]) -> Result<(), ConstraintError> {
        self.check(x)?;
        let mut start = 0;
        for c in &self.cavities {
            let len = c.volume.gradient_len();
            let block = &mut out[start..start + len];
            block.fill(0.0);
            c.volume.evaluate(x, 1.0, Some(block), None);
            start += len;
        }
        Ok(())
    }

    fn geometric_stiffness_pattern(&self) -> Vec<(usize, usize)> {
        self.cavities
            .iter()
            .flat_map(|c| c.volume.hessian_pattern())
            .collect()
    }

    fn geometric_stiffness_values(
        &self,
        x: &[Vec3],
        multipliers: &[f64],
        out: &mut [f64],
    ) -> Result<(), ConstraintError> {
        self.check(x)?;
        let mut start = 0;
        for (c, p) in self.cavities.iter().zip(multipliers) {
            let len = c.volume.hessian_len();
            c.volume
                .evaluate(x, *p, None, Some(&mut out[start..start + len]));
            start += len;
        }
        Ok(())
    }

    fn compliance(&self) -> Compliance {
        Compliance::Diagonal(vec![0.0; self.cavities.len()])
    }

    /// No pressure inside the material: zeros (the cavity's pressure acts on its wall).
    fn tet_pressures(&self, x: &[Vec3], multipliers: &[f64]) -> Vec<f64> {
        if self.check(x).is_err() || multipliers.len() != self.cavities.len() {
            return Vec::new();
        }
        vec![0.0; self.num_tets]
    }
}
