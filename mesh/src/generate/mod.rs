//! Mesh generators. Every generator takes a resolution, returns positively oriented tets
//! (the constructor re-orients none) and places boundary vertices on the analytic surface.
//! The disk and ball maps are singular at the corners of the square or cube they map, so the
//! worst tet there flattens as `res` grows (normalized volume `V / l_max^3` relative to the
//! regular tet, [`crate::TetMesh::quality`]: Kuhn box 0.27; cylinder 0.20 at res 4, 0.11 at
//! res 8; ball 0.19 at res 4, 0.07 at res 8). The spine arm, the pneumatic actuators and the
//! creature are box grids with hexes removed, graded per axis so that thin walls get whole
//! cells: their worst tet is that of their flattest hex, the same at every `res`. They name
//! their own groups of boundary faces ([`crate::PhysicalGroups`]: a chamber's walls, a
//! clamped end, the feet), which scenes select by name as a Gmsh file's.
//!
//! | generator | tets | worst quality |
//! |---|---|---|
//! | [`box_grid`] `[nx, ny, nz]` | `6 nx ny nz` | 0.27 (cubic cells) |
//! | [`cylinder`] / [`puck`] `res` | `24 res^2 layers` (res 4, height = 2 radius: 3072) | 0.20 at res 4 |
//! | [`tube`] `res` | `6 res n_theta n_z`, cells about `(r_o - r_i) / res` wide (radii 0.8 and 1, height 0.5: res 2: 3420, res 4: 27120) | 0.26 at res 2 |
//! | [`band`] `res` | a triangle surface, not tets: `2 res n_theta` triangles (cloth) | |
//! | [`ball`] `res` | `48 res^3` (res 4: 3072, res 8: 24576) | 0.19 at res 4 |
//! | [`hemisphere`] `res`, `grading` | `24 res^3` (the lower half of the ball, graded towards its pole) | 0.19 at res 4, grading 1 |
//! | [`spine_arm`] `res` | `1260 res^3` (a bar with five through-holes) | 0.27 |
//! | [`cushion`] `res` | `768 res^3` (res 2: 6,144; a pad with a flat chamber) | 0.18 |
//! | [`bubble`] `res` | `552 res^3` (res 2: 4,416; a chamber under a membrane) | 0.18 |
//! | [`finger`] `res` | `1494 res^3` (res 2: 11,952; five chambers joined by a channel) | 0.12 |
//! | [`torso`] `res` | `2016 res^3` (res 2: 16,128; a torso on the tops of two legs, mapped like the cylinder) | 0.040 at res 1, 0.033 at res 2 |
//! | [`creature`] `res` | `942 res^3` (res 2: 7,536; a torso on four legs, a neck, a head) | 0.19 |
//!
//! Each generator also gives its vertex and tet counts without generating (`NAME_counts`, in
//! `f64`), so that a scene's memory is checked before anything is allocated; the tet counts
//! are exact, the vertex counts exact or (for the carved grids) the uncarved grid's.
//!
//! The curved generators also give their true surface for
//! [`crate::ElementMesh::quadratic_on_surface`]: [`cylinder_surface`] (cylinder and puck),
//! [`tube_surface`] and [`ball_surface`] place the mid-edge node of a boundary edge whose
//! ends both lie on a curved wall at the projection of the edge's midpoint onto that wall
//! (radially, about the z axis or the origin); other boundary edges (on the flat caps and
//! rings) stay straight. Rims are edges of both a wall and a cap, and so follow the wall.

mod ball;
mod band;
mod bubble;
mod carved;
mod creature;
mod cushion;
mod cylinder;
mod finger;
mod grid;
mod lattice;
mod shell;
mod spine;
mod torso;
mod tube;

pub use ball::{ball, ball_counts, ball_surface, hemisphere, hemisphere_counts};
pub use band::{band, band_counts};
pub use bubble::{bubble, bubble_counts, BUBBLE_SIZE};
pub use creature::{creature, creature_counts, CREATURE_SIZE};
pub use cushion::{cushion, cushion_counts, CUSHION_SIZE};
pub use cylinder::{cylinder, cylinder_counts, cylinder_surface, puck};
pub use finger::{finger, finger_counts, FINGER_SIZE};
pub use grid::{box_grid, box_grid_counts};
pub use shell::{shell_octant, shell_octant_counts, shell_octant_quadratic};
pub use spine::{spine_arm, spine_arm_counts, SPINE_SIZE};
pub use torso::{torso, torso_counts, TORSO_CROTCH, TORSO_HEIGHT, TORSO_WAIST};
pub use tube::{tube, tube_counts, tube_surface, TubeMesh};

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

/// The two triangles `[a, b, c]`, `[a, c, d]` of every quad of a `columns x rows` grid whose
/// corner `(i, j)` is `corner(i, j)` (quad `(i, j)` has corners `(i, j)`, `(i + 1, j)`,
/// `(i + 1, j + 1)`, `(i, j + 1)`; a periodic grid wraps `i` in `corner`). The corners are
/// vertex indices for a surface mesh or points for a drawn shape.
pub fn split_quads<T: Copy>(
    columns: usize,
    rows: usize,
    corner: impl Fn(usize, usize) -> T,
) -> Vec<[T; 3]> {
    (0..rows)
        .flat_map(|j| (0..columns).map(move |i| (i, j)))
        .flat_map(|(i, j)| {
            let [a, b, c, d] = [
                corner(i, j),
                corner(i + 1, j),
                corner(i + 1, j + 1),
                corner(i, j + 1),
            ];
            [[a, b, c], [a, c, d]]
        })
        .collect()
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

#[cfg(test)]
pub(crate) mod tests {
    use crate::{check_closed_manifold, PhysicalGroups, TetMesh};
    use std::collections::HashSet;

    /// The quality of the Kuhn tets of an `a x b x c` hex: volume `a b c / 6`, longest edge
    /// the hex's diagonal.
    pub fn kuhn_quality(a: f64, b: f64, c: f64) -> f64 {
        6.0 * std::f64::consts::SQRT_2 * (a * b * c / 6.0) / (a * a + b * b + c * c).powf(1.5)
    }

    /// Checks a generated mesh with groups: positive tets (none re-oriented), a closed
    /// manifold surface, and groups made of boundary faces, none empty, and disjoint.
    pub fn check_groups(mesh: &TetMesh, groups: &PhysicalGroups) {
        assert_eq!(mesh.reoriented(), 0);
        let boundary = mesh.boundary().unwrap();
        check_closed_manifold(boundary.triangles()).unwrap();
        let faces: HashSet<[usize; 3]> = boundary.triangles().iter().copied().collect();
        let mut seen = HashSet::new();
        for (key, group) in groups.iter() {
            assert!(!group.faces.is_empty(), "{key} is empty");
            for f in &group.faces {
                assert!(faces.contains(f), "{key}: {f:?} is no boundary face");
                assert!(seen.insert(*f), "{key}: {f:?} is in two groups");
            }
        }
    }

    /// Checks a generated mesh with groups: positive tets, a closed manifold surface of area
    /// `area` enclosing `volume`, groups made of boundary faces and disjoint, and, if
    /// `chamber` is given, a closed `chamber` group enclosing it with its faces pointing into
    /// the cavity (the divergence theorem gives minus its volume). Exact up to rounding.
    pub fn check_generated(
        mesh: &TetMesh,
        groups: &PhysicalGroups,
        volume: f64,
        area: f64,
        chamber: Option<f64>,
    ) {
        check_groups(mesh, groups);
        let boundary = mesh.boundary().unwrap();
        let x = mesh.positions();
        assert!((mesh.rest_volume() - volume).abs() < 1e-12 * volume);
        assert!((boundary.enclosed_volume(x) - volume).abs() < 1e-12 * volume);
        assert!(
            (boundary.rest_area() - area).abs() < 1e-12 * area,
            "area {} != {area}",
            boundary.rest_area()
        );
        let Some(chamber) = chamber else {
            return;
        };
        let walls = &groups.get("chamber").unwrap().faces;
        check_closed_manifold(walls).unwrap();
        let enclosed: f64 = walls
            .iter()
            .map(|&[a, b, c]| x[a].dot(&x[b].cross(&x[c])) / 6.0)
            .sum();
        assert!(
            (enclosed + chamber).abs() < 1e-12 * chamber,
            "chamber encloses {enclosed}, expected -{chamber}"
        );
    }

    /// Each generator's counts, computed without generating, are its mesh's: the tets
    /// exactly, the vertices exactly or (the carved grids) from above by the removed cells'.
    #[test]
    fn counts_are_those_of_the_generated_meshes() {
        use super::*;
        let exact = |(v, t): (f64, f64), mesh: &TetMesh| {
            assert_eq!((v, t), (mesh.num_vertices() as f64, mesh.num_tets() as f64));
        };
        let bound = |(v, t): (f64, f64), mesh: &TetMesh| {
            let n = mesh.num_vertices() as f64;
            assert_eq!(t, mesh.num_tets() as f64);
            assert!(v >= n && v <= 1.3 * n, "{v} for {n} vertices");
        };
        let corner = crate::Vec3::new(1.0, 2.0, 0.5);
        exact(
            box_grid_counts([3.0, 2.0, 1.0]),
            &box_grid(crate::Vec3::zeros(), corner, [3, 2, 1]).unwrap(),
        );
        for res in [1, 2] {
            exact(
                cylinder_counts(0.5, 1.3, res, false),
                &cylinder(0.5, 1.3, res).unwrap(),
            );
            exact(
                cylinder_counts(0.5, 0.2, res, true),
                &puck(0.5, 0.2, res).unwrap(),
            );
            exact(
                tube_counts(0.8, 1.0, 0.5, res),
                &tube(0.8, 1.0, 0.5, res).unwrap().mesh,
            );
            exact(ball_counts(res), &ball(1.0, res).unwrap());
            exact(hemisphere_counts(res), &hemisphere(1.0, res, 2.0).unwrap());
            exact(creature_counts(res), &creature(res).unwrap().0);
            bound(spine_arm_counts(res), &spine_arm(res).unwrap().0);
            bound(cushion_counts(res), &cushion(res).unwrap().0);
            bound(bubble_counts(res), &bubble(res).unwrap().0);
            bound(finger_counts(res), &finger(res).unwrap().0);
            bound(torso_counts(res), &torso(res).unwrap().0);
        }
    }
}
