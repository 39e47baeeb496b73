//! Thick-walled tubes: a structured `(r, theta, z)` grid, periodic in theta.

use super::lattice::Lattice;
use super::{cells_along, positive, resolution, Wall};
use crate::{FaceSelection, MeshError, TetMesh, Vec3};
use std::f64::consts::PI;

/// Largest accepted `res` and cell count along theta or z.
const MAX_CELLS: usize = 4096;

/// A tube and its four boundary parts (outward triangles): the inner wall (where the
/// inflation pressure of Francu et al. 2021, Fig. 1 acts), the outer wall, and the end rings.
#[derive(Debug, Clone)]
pub struct TubeMesh {
    /// The tube's tets.
    pub mesh: TetMesh,
    /// The wall at `inner_radius`, named "inner".
    pub inner: FaceSelection,
    /// The wall at `outer_radius`, named "outer".
    pub outer: FaceSelection,
    /// The ring at `z = 0`, named "bottom".
    pub bottom: FaceSelection,
    /// The ring at `z = height`, named "top".
    pub top: FaceSelection,
}

/// A tube with axis z from 0 to `height` and wall between `inner_radius` and `outer_radius`.
///
/// `res` cells through the wall (size `h = (r_o - r_i) / res`), `n_theta = max(6,
/// round(pi (r_i + r_o) / h))` cells around, `n_z = max(1, round(height / h))` along the
/// axis; `6 res n_theta n_z` tets. Wall vertices lie exactly (to rounding) on the circles.
pub fn tube(
    inner_radius: f64,
    outer_radius: f64,
    height: f64,
    res: usize,
) -> Result<TubeMesh, MeshError> {
    let ri = positive("inner_radius", inner_radius)?;
    let ro = positive("outer_radius", outer_radius)?;
    let height = positive("height", height)?;
    if ro <= ri {
        return Err(MeshError::parameter(
            "outer_radius",
            ro,
            format!("must exceed inner_radius = {ri}"),
        ));
    }
    let nr = resolution(res, MAX_CELLS)?;
    let h = (ro - ri) / nr as f64;
    let nt = cells_along("theta", PI * (ri + ro), h, MAX_CELLS)?.max(6);
    let nz = cells_along("height", height, h, MAX_CELLS)?;
    let lattice = Lattice {
        cells: [nr, nt, nz],
        periodic: [false, true, false],
        mirror: [None; 3],
    };
    let points = lattice.points();
    let positions = points
        .iter()
        .map(|&[i, j, k]| {
            let r = if i == nr {
                ro
            } else {
                ri + (ro - ri) * i as f64 / nr as f64
            };
            let theta = 2.0 * PI * j as f64 / nt as f64;
            Vec3::new(
                r * theta.cos(),
                r * theta.sin(),
                height * k as f64 / nz as f64,
            )
        })
        .collect();
    let mesh = TetMesh::new(positions, lattice.tets())?;
    let surface = mesh.boundary()?;
    let part = |name: &str, axis: usize, layer: usize| {
        FaceSelection::from_filter(name, &surface, |t| {
            t.iter().all(|&v| points[v][axis] == layer)
        })
    };
    Ok(TubeMesh {
        inner: part("inner", 0, 0),
        outer: part("outer", 0, nr),
        bottom: part("bottom", 2, 0),
        top: part("top", 2, nz),
        mesh,
    })
}

/// The true surface of a [`tube`] for [`crate::ElementMesh::quadratic_on_surface`]: the
/// mid-edge node of an edge with both ends on the inner (or outer) wall goes to the radial
/// projection of its midpoint onto that wall.
pub fn tube_surface(
    inner_radius: f64,
    outer_radius: f64,
) -> impl Fn(&Vec3, &Vec3) -> Option<Vec3> + Copy + Send + Sync {
    move |a, b| {
        Wall::Cylinder(inner_radius)
            .midpoint(a, b)
            .or_else(|| Wall::Cylinder(outer_radius).midpoint(a, b))
    }
}

/// The vertex and tet counts of [`tube`], without generating it; NaN for parameters the
/// generator refuses.
pub fn tube_counts(inner_radius: f64, outer_radius: f64, height: f64, res: usize) -> (f64, f64) {
    let round = |x: f64| x.round().max(1.0);
    let r = res as f64;
    let h = (outer_radius - inner_radius) / r;
    let around = round(PI * (inner_radius + outer_radius) / h).max(6.0);
    let along = round(height / h);
    ((r + 1.0) * around * (along + 1.0), 6.0 * r * around * along)
}
