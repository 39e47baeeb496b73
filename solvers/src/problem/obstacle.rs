//! Rigid obstacles: their shapes, motions and signed distances.

use super::schedule::Curve;
use crate::error::SolverError;
use isochor_mesh::Vec3;

/// The shape of a rigid obstacle in its reference position. Each has a signed distance
/// `d(x)`, positive outside, that the contact constraints `d(x_i) >= 0` act on (sec. 8.2-8.3
/// of Francu et al. 2021).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Shape {
    /// The half-space below the plane through `point` with (outward) `normal`:
    /// `d = n . (x - p)`.
    HalfSpace {
        /// A point of the boundary plane.
        point: Vec3,
        /// The outward normal (any length but zero).
        normal: Vec3,
    },
    /// A solid sphere: `d = |x - c| - R`.
    Sphere {
        /// The centre.
        center: Vec3,
        /// The radius.
        radius: f64,
    },
    /// An infinite solid cylinder around the line through `point` along `axis`:
    /// `d = dist(x, axis) - R`.
    Cylinder {
        /// A point of the axis.
        point: Vec3,
        /// The axis' direction (any length but zero).
        axis: Vec3,
        /// The radius.
        radius: f64,
    },
    /// A solid torus, a ring whose hole a body passes through (a tight band around a waist):
    /// the tube of radius `r` around the circle of radius `R` about `center` in the plane
    /// normal to `axis`. With `q = x - c - R rho_hat` (`rho_hat` the unit direction from the
    /// axis to `x` in that plane), `d = |q| - r`, gradient `n = q / |q|` and Hessian
    /// `(I - n n^T - (R / rho) P) / |q|`, `rho` the distance from the axis and
    /// `P = I - a a^T - rho_hat rho_hat^T` the projection onto the circle's tangent. The
    /// hole's radius is `R - r`.
    Ring {
        /// The centre of the ring (a point of the axis).
        center: Vec3,
        /// The axis' direction (any length but zero).
        axis: Vec3,
        /// The major radius `R`, from the axis to the tube's centre circle.
        radius: f64,
        /// The tube's radius `r` (less than `R`).
        tube: f64,
    },
}

/// A rigid obstacle: a shape translated by `t * translate` and with its radius changed by
/// `t * radius_change`, with `t` the load parameter (quasi-static), `time / duration`
/// (dynamics) or the value of its curve, like a [`Motion::Translate`](crate::Motion::Translate) condition.
#[derive(Debug, Clone, PartialEq)]
pub struct Obstacle {
    /// The shape at `t = 0`.
    pub shape: Shape,
    /// Displacement at `t = 1`.
    pub translate: Vec3,
    /// Change of the radius at `t = 1`: a sphere's or cylinder's radius, a ring's major
    /// radius `R` (a negative change tightens the ring's hole); a half-space has none (it
    /// must be 0).
    pub radius_change: f64,
    /// The motion's parameter as a function of the load parameter or time (`None`: the
    /// fraction of the run).
    pub curve: Option<Curve>,
}

impl Obstacle {
    /// A fixed obstacle.
    pub fn fixed(shape: Shape) -> Self {
        Obstacle {
            shape,
            translate: Vec3::zeros(),
            radius_change: 0.0,
            curve: None,
        }
    }

    /// Checks the shape: finite data, a non-zero normal or axis, a positive radius at `t = 0`
    /// and at `t = 1` (after the radius change), a ring's tube thinner than its major radius
    /// at both (so that its hole stays open), no radius change for a half-space.
    pub fn validate(&self) -> Result<(), SolverError> {
        let bad = |what: &str| Err(SolverError::InvalidProblem(format!("obstacle: {what}")));
        let finite = |v: &Vec3| v.iter().all(|c| c.is_finite());
        let positive = |r: f64| r.is_finite() && r > 0.0;
        if !finite(&self.translate) {
            return bad("the translation must be finite");
        }
        let change = self.radius_change;
        if !change.is_finite() {
            return bad("the radius change must be finite");
        }
        // The radius at t = 0 and at t = 1.
        let both = |radius: f64, above: f64| radius > above && radius + change > above;
        match self.shape {
            Shape::HalfSpace { point, normal } => {
                if !finite(&point) || !finite(&normal) || normal.norm() == 0.0 {
                    return bad("a half-space needs a finite point and a non-zero normal");
                }
                if change != 0.0 {
                    return bad("a half-space has no radius to change");
                }
            }
            Shape::Sphere { center, radius } => {
                if !(finite(&center) && positive(radius) && both(radius, 0.0)) {
                    return bad("a sphere needs a finite center and a positive radius, also after its radius change");
                }
            }
            Shape::Cylinder {
                point,
                axis,
                radius,
            } => {
                if !(finite(&point)
                    && finite(&axis)
                    && axis.norm() > 0.0
                    && positive(radius)
                    && both(radius, 0.0))
                {
                    return bad(
                        "a cylinder needs a finite point, a non-zero axis and a positive radius, also after its radius change",
                    );
                }
            }
            Shape::Ring {
                center,
                axis,
                radius,
                tube,
            } => {
                if !(finite(&center)
                    && finite(&axis)
                    && axis.norm() > 0.0
                    && positive(tube)
                    && positive(radius)
                    && both(radius, tube))
                {
                    return bad(
                        "a ring needs a finite center, a non-zero axis, a positive tube radius and a major radius above it, also after its radius change",
                    );
                }
            }
        }
        Ok(())
    }

    /// Signed distance `d`, its gradient `n` and Hessian at `x`, with the obstacle moved to
    /// parameter `t`.
    pub fn distance(&self, x: &Vec3, t: f64) -> (f64, Vec3, nalgebra::Matrix3<f64>) {
        let shift = t * self.translate;
        let grown = |radius: f64| radius + t * self.radius_change;
        let zero = nalgebra::Matrix3::zeros();
        match self.shape {
            Shape::HalfSpace { point, normal } => {
                let n = normal.normalize();
                (n.dot(&(x - point - shift)), n, zero)
            }
            Shape::Sphere { center, radius } => radial(x - center - shift, grown(radius), None),
            Shape::Cylinder {
                point,
                axis,
                radius,
            } => {
                let a = axis.normalize();
                let r = x - point - shift;
                radial(r - a * a.dot(&r), grown(radius), Some(a))
            }
            Shape::Ring {
                center,
                axis,
                radius,
                tube,
            } => ring(x - center - shift, axis.normalize(), grown(radius), tube),
        }
    }
}

/// The signed distance to the ring of [`Shape::Ring`] at `r = x - c`, with unit `axis`,
/// major radius `big` and tube radius `tube`. On the axis (`rho = 0`, where `d` has a
/// ridge and no gradient) any radial direction is taken, with no curvature along the
/// circle; on the tube's centre circle (`q = 0`, deep inside) `n` points towards the axis,
/// with no curvature: neither is met by a body inside the hole and clear of the tube's core.
fn ring(r: Vec3, axis: Vec3, big: f64, tube: f64) -> (f64, Vec3, nalgebra::Matrix3<f64>) {
    let tiny = f64::MIN_POSITIVE.sqrt();
    let height = axis.dot(&r);
    let w = r - axis * height;
    let rho = w.norm();
    let (rho_hat, bend) = if rho <= tiny * big {
        (
            axis.cross(&Vec3::x())
                .try_normalize(tiny)
                .unwrap_or_else(|| axis.cross(&Vec3::y()).normalize()),
            0.0,
        )
    } else {
        (w / rho, big / rho)
    };
    // `q = r - big rho_hat` from its two coordinates: near the axis `rho_hat` carries the
    // rounding of `w` divided by `rho`, which would otherwise reach `d` itself.
    let radial = rho - big;
    let len = radial.hypot(height);
    if len <= tiny * tube {
        return (-tube, -rho_hat, nalgebra::Matrix3::zeros());
    }
    let n = (radial * rho_hat + height * axis) / len;
    let identity = nalgebra::Matrix3::identity();
    let tangent = identity - axis * axis.transpose() - rho_hat * rho_hat.transpose();
    let h = (identity - n * n.transpose() - bend * tangent) / len;
    (len - tube, n, h)
}

/// `d = |r| - R` with gradient `u = r / |r|` and Hessian `(I - u u^T - a a^T) / |r|` (`a` the
/// cylinder axis). At `r = 0` (a vertex on the centre, far inside) the direction is
/// undefined: `+z` is taken, with no curvature.
fn radial(r: Vec3, radius: f64, axis: Option<Vec3>) -> (f64, Vec3, nalgebra::Matrix3<f64>) {
    let len = r.norm();
    if len <= f64::MIN_POSITIVE.sqrt() {
        return (-radius, Vec3::z(), nalgebra::Matrix3::zeros());
    }
    let u = r / len;
    let mut h = nalgebra::Matrix3::identity() - u * u.transpose();
    if let Some(a) = axis {
        h -= a * a.transpose();
    }
    (len - radius, u, h / len)
}
