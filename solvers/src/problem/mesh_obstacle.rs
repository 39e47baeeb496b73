//! Meshed rigid obstacles: a triangle surface (open or closed) that the bodies' surfaces meet
//! in barrier contact ([`crate::terms::SurfaceContact`]), moved rigidly over the run.

use super::schedule::{Curve, LoadLevel};
use crate::error::SolverError;
use isochor_mesh::Vec3;
use nalgebra::{Rotation3, Unit};

/// A rotation by `angle` (radians) about `axis` through `center`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AxisRotation {
    /// A point of the axis.
    pub center: Vec3,
    /// The axis' direction (any length but zero).
    pub axis: Vec3,
    /// The angle, right-handed about `axis`, in radians.
    pub angle: f64,
}

/// A rigid triangle surface whose vertices are positions, not degrees of freedom: at motion
/// parameter `s` (the load parameter, `time / duration` or its curve's value, as for
/// [`super::obstacle::Obstacle`]) a vertex at `x` is at `c + R(s angle) (x - c) + s
/// translate`: the rotation and the translation are those reached at `s = 1`.
#[derive(Debug, Clone, PartialEq)]
pub struct MeshObstacle {
    /// Its name, for messages and output columns.
    pub name: String,
    /// The vertices at `s = 0` (already placed).
    pub vertices: Vec<Vec3>,
    /// The triangles, as indices into `vertices`.
    pub triangles: Vec<[usize; 3]>,
    /// The displacement reached at `s = 1`.
    pub translate: Vec3,
    /// The rotation reached at `s = 1`, if any.
    pub rotate: Option<AxisRotation>,
    /// The motion's parameter as a function of the load parameter or time (`None`: the
    /// fraction of the run).
    pub curve: Option<Curve>,
}

impl MeshObstacle {
    /// Checks the data: some triangles, indices in range and three distinct vertices in
    /// each, finite coordinates and motion, a non-zero rotation axis.
    pub fn validate(&self) -> Result<(), SolverError> {
        let bad = |what: String| {
            Err(SolverError::InvalidProblem(format!(
                "meshed obstacle '{}': {what}",
                self.name
            )))
        };
        let finite = |v: &Vec3| v.iter().all(|c| c.is_finite());
        if self.triangles.is_empty() {
            return bad("it has no triangles".into());
        }
        if let Some(v) = self.vertices.iter().position(|v| !finite(v)) {
            return bad(format!("vertex {v} is not finite"));
        }
        let n = self.vertices.len();
        if let Some(t) = self
            .triangles
            .iter()
            .position(|t| t.iter().any(|&v| v >= n) || t[0] == t[1] || t[1] == t[2] || t[0] == t[2])
        {
            return bad(format!(
                "triangle {t} ({:?}) needs three distinct vertices of the {n}",
                self.triangles[t]
            ));
        }
        if !finite(&self.translate) {
            return bad("the translation must be finite".into());
        }
        if let Some(r) = &self.rotate {
            if !(finite(&r.center) && finite(&r.axis) && r.axis.norm() > 0.0 && r.angle.is_finite())
            {
                return bad(
                    "the rotation needs a finite center and angle and a non-zero axis".into(),
                );
            }
        }
        Ok(())
    }

    /// The vertices at `level`.
    pub fn placed(&self, level: &LoadLevel) -> Vec<Vec3> {
        let s = level.motion_parameter(self.curve.as_ref());
        let rotation = self.rotate.map(|r| {
            (
                r.center,
                Rotation3::from_axis_angle(&Unit::new_normalize(r.axis), s * r.angle),
            )
        });
        let shift = s * self.translate;
        self.vertices
            .iter()
            .map(|x| {
                let turned = match &rotation {
                    Some((c, r)) => c + r * (x - c),
                    None => *x,
                };
                turned + shift
            })
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_motion_is_reached_at_the_end() {
        let obstacle = MeshObstacle {
            name: "plate".into(),
            vertices: vec![Vec3::new(1.0, 0.0, 0.0), Vec3::zeros(), Vec3::y()],
            triangles: vec![[0, 1, 2]],
            translate: Vec3::new(0.0, 0.0, 2.0),
            rotate: Some(AxisRotation {
                center: Vec3::zeros(),
                axis: Vec3::z(),
                angle: std::f64::consts::FRAC_PI_2,
            }),
            curve: None,
        };
        obstacle.validate().unwrap();
        let end = obstacle.placed(&LoadLevel::FULL);
        assert!((end[0] - Vec3::new(0.0, 1.0, 2.0)).norm() < 1e-15);
        let start = obstacle.placed(&LoadLevel::quasi_static(0.0));
        assert_eq!(start, obstacle.vertices);
        let bad = MeshObstacle {
            triangles: vec![[0, 1, 3]],
            ..obstacle
        };
        assert!(bad.validate().unwrap_err().to_string().contains("plate"));
    }
}
