//! Solid cylinders and pucks: a square grid mapped onto the disk, extruded along z.

use super::lattice::Lattice;
use super::{cells_along, positive, resolution, Wall};
use crate::{MeshError, TetMesh, Vec3};

/// Largest accepted `res` and number of layers.
const MAX_RES: usize = 1024;

/// The elliptical-grid map of the square `[-1, 1]^2` onto the unit disk,
/// `(x, y) -> (x sqrt(1 - y^2/2), y sqrt(1 - x^2/2))` (Fong, "Analytical methods for squaring
/// the disc", 2014): smooth inside, and the square's boundary lands exactly on the circle.
pub(crate) fn square_to_disk(x: f64, y: f64) -> (f64, f64) {
    (
        x * (1.0 - 0.5 * y * y).sqrt(),
        y * (1.0 - 0.5 * x * x).sqrt(),
    )
}

/// A solid cylinder of `radius` with axis z from 0 to `height`.
///
/// The cross-section is a `2 res x 2 res` square grid mapped onto the disk (cells about
/// `radius / res` wide), with the Kuhn split mirrored in each quadrant so that the diagonals
/// point away from the axis; there are `round(res height / radius)` (at least 1) layers, so
/// `24 res^2 layers` tets (res 4 with height = 2 radius: 3072).
pub fn cylinder(radius: f64, height: f64, res: usize) -> Result<TetMesh, MeshError> {
    let radius = positive("radius", radius)?;
    let height = positive("height", height)?;
    let res = resolution(res, MAX_RES)?;
    let layers = cells_along("height", height, radius / res as f64, MAX_RES)?;
    extruded_disk(radius, height, res, layers)
}

/// A puck (a short cylinder that is indented from the top, Sheen et al. 2021, Figs. 6 and 9):
/// the same mesh as [`cylinder`], with at least `res` layers through its height so that the
/// compression under an indenter is resolved: `24 res^2 max(res, round(res height / radius))`
/// tets.
pub fn puck(radius: f64, height: f64, res: usize) -> Result<TetMesh, MeshError> {
    let radius = positive("radius", radius)?;
    let height = positive("height", height)?;
    let res = resolution(res, MAX_RES)?;
    let layers = cells_along("height", height, radius / res as f64, MAX_RES)?.max(res);
    extruded_disk(radius, height, res, layers)
}

/// The true surface of a [`cylinder`] or [`puck`] of `radius` for
/// [`crate::ElementMesh::quadratic_on_surface`]: the mid-edge node of an edge with both ends
/// on the side wall goes to the radial projection of its midpoint onto the wall.
pub fn cylinder_surface(radius: f64) -> impl Fn(&Vec3, &Vec3) -> Option<Vec3> + Copy + Send + Sync {
    move |a, b| Wall::Cylinder(radius).midpoint(a, b)
}

fn extruded_disk(
    radius: f64,
    height: f64,
    res: usize,
    layers: usize,
) -> Result<TetMesh, MeshError> {
    let lattice = Lattice {
        cells: [2 * res, 2 * res, layers],
        periodic: [false; 3],
        mirror: [Some(res), Some(res), None],
    };
    let r = res as f64;
    let positions = lattice
        .points()
        .into_iter()
        .map(|[i, j, k]| {
            let (u, v) = square_to_disk((i as f64 - r) / r, (j as f64 - r) / r);
            Vec3::new(radius * u, radius * v, height * k as f64 / layers as f64)
        })
        .collect();
    TetMesh::new(positions, lattice.tets())
}

/// The vertex and tet counts of [`cylinder`] (or, if `puck`, of [`puck`]), without
/// generating it; NaN for parameters the generator refuses.
pub fn cylinder_counts(radius: f64, height: f64, res: usize, puck: bool) -> (f64, f64) {
    let r = res as f64;
    let mut layers = (r * height / radius).round().max(1.0);
    if puck {
        layers = layers.max(r);
    }
    (
        (2.0 * r + 1.0).powi(2) * (layers + 1.0),
        24.0 * r * r * layers,
    )
}
