//! Solid balls: a cube grid mapped onto the ball.

use super::lattice::Lattice;
use super::{positive, resolution, Wall};
use crate::{MeshError, TetMesh, Vec3};

/// Largest accepted `res`.
const MAX_RES: usize = 256;

/// The cube `[-1, 1]^3` mapped onto the unit ball by
/// `x -> x sqrt(1 - y^2/2 - z^2/2 + y^2 z^2/3)` (and cyclically): smooth inside, and every
/// point of the cube's surface lands exactly on the unit sphere.
fn cube_to_ball(p: [f64; 3]) -> Vec3 {
    let [x2, y2, z2] = p.map(|c| c * c);
    Vec3::new(
        p[0] * (1.0 - 0.5 * (y2 + z2) + y2 * z2 / 3.0).sqrt(),
        p[1] * (1.0 - 0.5 * (z2 + x2) + z2 * x2 / 3.0).sqrt(),
        p[2] * (1.0 - 0.5 * (x2 + y2) + x2 * y2 / 3.0).sqrt(),
    )
}

/// A ball of `radius` centred at the origin.
///
/// A `2 res` per side cube grid (cells about `radius / res` wide) mapped onto the ball, with
/// the Kuhn split mirrored in each octant so that diagonals point away from the centre:
/// `48 res^3` tets (res 4: 3072; res 8: 24576; res 11: 63888, the "64K tets" ball of
/// Sheen et al. 2021, Fig. 10).
pub fn ball(radius: f64, res: usize) -> Result<TetMesh, MeshError> {
    let radius = positive("radius", radius)?;
    let res = resolution(res, MAX_RES)?;
    let lattice = Lattice {
        cells: [2 * res; 3],
        periodic: [false; 3],
        mirror: [Some(res); 3],
    };
    let r = res as f64;
    let positions = lattice
        .points()
        .into_iter()
        .map(|p| radius * cube_to_ball(p.map(|i| (i as f64 - r) / r)))
        .collect();
    TetMesh::new(positions, lattice.tets())
}

/// The true surface of a [`ball`] of `radius` for
/// [`crate::ElementMesh::quadratic_on_surface`]: the mid-edge node of an edge with both ends
/// on the sphere goes to the radial projection of its midpoint onto the sphere.
pub fn ball_surface(radius: f64) -> impl Fn(&Vec3, &Vec3) -> Option<Vec3> + Copy + Send + Sync {
    move |a, b| Wall::Sphere(radius).midpoint(a, b)
}

/// The lower half (`z <= 0`) of a [`ball`] of `radius`, graded towards its south pole
/// `(0, 0, -radius)` for contact studies: the half cube's lattice `[-1, 1]^2 x [-1, 0]`
/// (`2 res` cells wide, `res` deep) is re-spaced about the pole `P = (0, 0, -1)` of the cube
/// by `c -> P + (c - P) s^(grading - 1)`, with `s = |c - P|_inf`, before the cube-to-ball
/// map. The map keeps every ray from `P` and the half cube's faces (`s = 1` there, and the
/// face through `P` maps onto itself), so cells near the pole shrink to about
/// `radius / res^grading` in every direction while the surface stays on the sphere and the
/// equator on `z = 0`; `grading = 1` is the lower half of [`ball`]. `24 res^3` tets.
pub fn hemisphere(radius: f64, res: usize, grading: f64) -> Result<TetMesh, MeshError> {
    let radius = positive("radius", radius)?;
    let res = resolution(res, MAX_RES)?;
    let grading = positive("grading", grading)?;
    let lattice = Lattice {
        cells: [2 * res, 2 * res, res],
        periodic: [false; 3],
        mirror: [Some(res); 3],
    };
    let r = res as f64;
    let graded = |c: [f64; 3]| {
        let q = [c[0], c[1], c[2] + 1.0];
        let s = q.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        let scale = if s > 0.0 { s.powf(grading - 1.0) } else { 0.0 };
        [q[0] * scale, q[1] * scale, q[2] * scale - 1.0]
    };
    let positions = lattice
        .points()
        .into_iter()
        .map(|p| radius * cube_to_ball(graded(p.map(|i| (i as f64 - r) / r))))
        .collect();
    TetMesh::new(positions, lattice.tets())
}

/// The vertex and tet counts of [`hemisphere`] at `res`, without generating it.
pub fn hemisphere_counts(res: usize) -> (f64, f64) {
    let r = res as f64;
    ((2.0 * r + 1.0).powi(2) * (r + 1.0), 24.0 * r.powi(3))
}

/// The vertex and tet counts of [`ball`] at `res`, without generating it.
pub fn ball_counts(res: usize) -> (f64, f64) {
    let r = res as f64;
    ((2.0 * r + 1.0).powi(3), 48.0 * r.powi(3))
}
