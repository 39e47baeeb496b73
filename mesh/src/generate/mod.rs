//! Mesh generators. Every generator takes a resolution, returns positively oriented tets
//! (the constructor re-orients none) and places boundary vertices on the analytic surface.
//! The disk and ball maps are singular at the corners of the square or cube they map, so the
//! worst tet there flattens as `res` grows (normalized volume `V / l_max^3` relative to the
//! regular tet: Kuhn box 0.27; cylinder 0.20 at res 4, 0.11 at res 8; ball 0.19 at res 4,
//! 0.07 at res 8).
//!
//! | generator | tets |
//! |---|---|
//! | [`box_grid`] `[nx, ny, nz]` | `6 nx ny nz` |
//! | [`cylinder`] / [`puck`] `res` | `24 res^2 layers` (res 4, height = 2 radius: 3072) |
//! | [`tube`] `res` | `6 res n_theta n_z`, cells about `(r_o - r_i) / res` wide (radii 0.8 and 1, height 0.5: res 2: 3420, res 4: 27120) |
//! | [`ball`] `res` | `48 res^3` (res 4: 3072, res 8: 24576) |
//! | [`spine_arm`] `res` | `1260 res^3` (a bar with five through-holes) |
//!
//! The curved generators also give their true surface for
//! [`crate::ElementMesh::quadratic_on_surface`]: [`cylinder_surface`] (cylinder and puck),
//! [`tube_surface`] and [`ball_surface`] place the mid-edge node of a boundary edge whose
//! ends both lie on a curved wall at the projection of the edge's midpoint onto that wall
//! (radially, about the z axis or the origin); other boundary edges (on the flat caps and
//! rings) stay straight. Rims are edges of both a wall and a cap, and so follow the wall.

mod ball;
mod cylinder;
mod grid;
mod lattice;
mod spine;
mod tube;

pub use ball::{ball, ball_surface};
pub use cylinder::{cylinder, cylinder_surface, puck};
pub use grid::box_grid;
pub use spine::{spine_arm, SPINE_SIZE};
pub use tube::{tube, tube_surface, TubeMesh};

use crate::{MeshError, Vec3};

/// A point lies on a curved wall when its distance to the axis or centre is within this
/// fraction of the radius (the generators place vertices there to a few ulps).
const ON_WALL: f64 = 1e-9;

/// A round wall: a cylinder about the z axis or a sphere about the origin.
#[derive(Clone, Copy)]
enum Wall {
    Cylinder(f64),
    Sphere(f64),
}

impl Wall {
    /// The part of `p` whose length is the distance to the axis or centre.
    fn radial(self, p: &Vec3) -> Vec3 {
        match self {
            Wall::Cylinder(_) => Vec3::new(p.x, p.y, 0.0),
            Wall::Sphere(_) => *p,
        }
    }

    fn radius(self) -> f64 {
        match self {
            Wall::Cylinder(r) | Wall::Sphere(r) => r,
        }
    }

    /// The projection of the midpoint of `[a, b]` onto the wall, `m + (R / |m_r| - 1) m_r`
    /// with `m_r` the radial part of the midpoint, if both `a` and `b` lie on the wall.
    fn midpoint(self, a: &Vec3, b: &Vec3) -> Option<Vec3> {
        let r = self.radius();
        let on = |p: &Vec3| (self.radial(p).norm() - r).abs() <= ON_WALL * r;
        if !(on(a) && on(b)) {
            return None;
        }
        let m = 0.5 * (a + b);
        let radial = self.radial(&m);
        let length = radial.norm();
        (length > 0.0).then(|| m + (r / length - 1.0) * radial)
    }
}

/// `value` if it is finite and positive, else an [`MeshError::InvalidParameter`] naming it.
fn positive(name: &'static str, value: f64) -> Result<f64, MeshError> {
    if value.is_finite() && value > 0.0 {
        Ok(value)
    } else {
        Err(MeshError::parameter(name, value, "must be finite and > 0"))
    }
}

/// `res` if it is at least 1 and at most `max` (the bound keeps tet counts allocatable).
fn resolution(res: usize, max: usize) -> Result<usize, MeshError> {
    if (1..=max).contains(&res) {
        Ok(res)
    } else {
        Err(MeshError::parameter(
            "res",
            res,
            format!("must be in 1..={max}"),
        ))
    }
}

/// Cells of size about `cell` along a length `length`: at least one, at most `max`.
fn cells_along(name: &'static str, length: f64, cell: f64, max: usize) -> Result<usize, MeshError> {
    let n = (length / cell).round().max(1.0);
    if n > max as f64 {
        return Err(MeshError::parameter(
            name,
            n,
            format!("the aspect ratio needs more than {max} cells along this axis"),
        ));
    }
    Ok(n as usize)
}
