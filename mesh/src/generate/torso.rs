//! A soft body shaped like a human torso (Sheen et al. 2021, Figs. 1 and 4, where a full body
//! is squeezed by a garment): the tops of two legs, hips, a belly bulging forward, a narrower
//! waist and a chest. Shape and dimensions ours.
//!
//! A box grid with the crotch gap carved out between the legs, its vertices then mapped so
//! that square cross-sections become rounded ones: the body's by the elliptical-grid map of
//! the square onto the disk scaled to a half-width `a(z)` and half-depth `b(z)` that vary
//! smoothly with height (narrowest at the waist), the belly pushed forward (+y); each leg's
//! square onto its own disk, blended smoothly into the body's section up to the crotch. The
//! surface has no staircase: a ring squeezing the waist meets a smooth wall.

use super::carved::{carve_flipped, graded_lines, Cell};
use super::cylinder::square_to_disk;
use super::resolution;
use crate::{MeshError, PhysicalGroups, TetMesh, Vec3};

/// Height of the torso, from the legs' cut (z = 0) to the top cut (m).
pub const TORSO_HEIGHT: f64 = 0.45;

/// Height of the crotch (m): below it the legs are separate.
pub const TORSO_CROTCH: f64 = 0.12;

/// Height of the waist (m), the narrowest section (a grid line at every `res`).
pub const TORSO_WAIST: f64 = 0.34;

/// Each leg's radius at the cut and the distance of its axis from the body's (m).
const LEG_RADIUS: f64 = 0.075;
const LEG_OFFSET: f64 = 0.09;

/// Along the grid's x in `[-1, 1]`: left leg, crotch gap, right leg (cells at res 1); the
/// leg's square is `[g, 1]` with `g = 0.25`.
const X_SEGMENTS: [(f64, usize); 3] = [(0.75, 3), (0.5, 2), (0.75, 3)];
const GAP: f64 = 0.25;

/// Along the grid's y in `[-1, 1]` (back to front).
const Y_SEGMENTS: [(f64, usize); 1] = [(2.0, 4)];

/// Along z (m, cells at res 1): the legs up to the crotch, hips and belly up to 0.3 m, the
/// waist finer (2 cm cells from 0.3 to 0.38 m: a ring squeezing it meets several rows of
/// vertices, which contact holds, and cannot slip between them), the chest.
const Z_SEGMENTS: [(f64, usize); 4] = [(TORSO_CROTCH, 2), (0.18, 3), (0.08, 4), (0.07, 2)];

/// A horizontal section of the body: half-width `a` (x), half-depth `b` (y), and how far the
/// belly bulges forward of the ellipse at the front centre (all m).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Section {
    pub a: f64,
    pub b: f64,
    pub belly: f64,
}

/// `(z, section)` from the crotch to the top: hips, belly, waist, chest.
const KNOTS: [(f64, Section); 5] = [
    (
        TORSO_CROTCH,
        Section {
            a: 0.165,
            b: 0.105,
            belly: 0.0,
        },
    ),
    (
        0.20,
        Section {
            a: 0.17,
            b: 0.11,
            belly: 0.01,
        },
    ),
    (
        0.27,
        Section {
            a: 0.15,
            b: 0.105,
            belly: 0.035,
        },
    ),
    (
        TORSO_WAIST,
        Section {
            a: 0.12,
            b: 0.105,
            belly: 0.01,
        },
    ),
    (
        TORSO_HEIGHT,
        Section {
            a: 0.145,
            b: 0.11,
            belly: 0.0,
        },
    ),
];

/// The body's section at height `z` (clamped to the knots): cosine easing between knots, so
/// the profile is C1 with a level tangent at every knot.
pub(crate) fn section(z: f64) -> Section {
    let i = KNOTS[1..]
        .iter()
        .position(|k| z <= k.0)
        .unwrap_or(KNOTS.len() - 2);
    let ((z0, s0), (z1, s1)) = (KNOTS[i], KNOTS[i + 1]);
    let t = ((z - z0) / (z1 - z0)).clamp(0.0, 1.0);
    let w = 0.5 - 0.5 * (std::f64::consts::PI * t).cos();
    let mix = |p: f64, q: f64| p + w * (q - p);
    Section {
        a: mix(s0.a, s1.a),
        b: mix(s0.b, s1.b),
        belly: mix(s0.belly, s1.belly),
    }
}

/// The point `(p, q)` of the unit disk placed in section `s`: `x = a p`,
/// `y = b q + belly max(q, 0)^2 (1 - p^2)` (the bulge largest at the front centre; `y`
/// increases with `q`, so the map keeps orientation).
pub(crate) fn in_section(s: Section, p: f64, q: f64) -> (f64, f64) {
    let front = q.max(0.0);
    (s.a * p, s.b * q + s.belly * front * front * (1.0 - p * p))
}

/// Where grid point `(u, v, z)` (`u, v` in `[-1, 1]`) goes.
fn place(u: f64, v: f64, z: f64) -> Vec3 {
    let body = |z: f64| {
        let (p, q) = square_to_disk(u, v);
        in_section(section(z), p, q)
    };
    if z >= TORSO_CROTCH {
        let (x, y) = body(z);
        return Vec3::new(x, y, z);
    }
    // A leg vertex (|u| >= g): its leg's square [g, 1] onto the leg's disk, blended into the
    // body's section at the crotch with a smoothstep (level at both ends).
    let side = u.signum();
    let centre = 0.5 * (1.0 + GAP);
    let (p, q) = square_to_disk((u.abs() - centre) / (1.0 - centre), v);
    let leg = (side * (LEG_OFFSET + LEG_RADIUS * p), LEG_RADIUS * q);
    let t = z / TORSO_CROTCH;
    let s = t * t * (3.0 - 2.0 * t);
    let top = body(TORSO_CROTCH);
    Vec3::new(leg.0 + s * (top.0 - leg.0), leg.1 + s * (top.1 - leg.1), z)
}

/// A torso `0.34 m` wide at the hips and `0.45 m` tall, standing on the cut tops of two legs
/// (z = 0, each of radius 75 mm) with a crotch at z = 0.12 m, the widest hips at 0.2 m, the
/// belly (bulging 35 mm forward, +y) at 0.27 m, the waist (0.24 x 0.22 m, its section nearly
/// round) at [`TORSO_WAIST`], cut at the chest (z = 0.45 m). The body's axis is z through the
/// origin; x is left to right.
///
/// A grid of `8 res x 4 res x 11 res` hexes (cells about 4 cm across at res 1, 2 cm high
/// around the waist), Kuhn-split with the split reflected so that every mapped corner hex has
/// its diagonal through the corner, without the `2 res x 4 res x 2 res` hexes of the crotch
/// gap: `2016 res^3` tets (res 1: 2,016; res 2: 16,128; res 3: 54,432),
/// worst quality 0.040 at res 1, 0.033 at res 2 and 0.019 at res 3 (see [`TetMesh::quality`]:
/// the corner hexes of the mapped squares flatten as `res` grows, as in [`super::cylinder`];
/// with an unreflected split they would carry tets of 0.015, 0.003 and 0.001).
///
/// Groups (surfaces): `legs` (both legs' cut faces, z = 0), `top` (the cut at the chest).
///
/// Errors: `res` outside `1..=16`.
pub fn torso(res: usize) -> Result<(TetMesh, PhysicalGroups), MeshError> {
    let res = resolution(res, 16)?;
    let lines = [
        graded_lines(&X_SEGMENTS, res)
            .into_iter()
            .map(|u| u - 1.0)
            .collect::<Vec<_>>(),
        graded_lines(&Y_SEGMENTS, res)
            .into_iter()
            .map(|v| v - 1.0)
            .collect(),
        graded_lines(&Z_SEGMENTS, res),
    ];
    let centre = |axis: usize, i: usize| 0.5 * (lines[axis][i] + lines[axis][i + 1]);
    // Diagonals towards the nearest corner of each mapped square: the body's at u = +-1,
    // v = +-1, and each leg's, whose inner side is at |u| = g.
    let leg_centre = 0.5 * (1.0 + GAP);
    let flip = |axis: usize, i: usize| {
        let c = centre(axis, i);
        match axis {
            0 => c < -leg_centre || (c > 0.0 && c < leg_centre),
            1 => c < 0.0,
            _ => false,
        }
    };
    let crotch = (2 * res) as isize;
    let gap = (3 * res) as isize..(5 * res) as isize;
    let solid = |c: Cell| !(c[2] < crotch && gap.contains(&c[0]));
    let carved = carve_flipped(&lines, flip, solid)?;
    let positions = carved
        .mesh
        .positions()
        .iter()
        .map(|g| place(g.x, g.y, g.z))
        .collect();
    let nz = 11 * res as isize;
    let groups = vec![
        carved.group("legs", 1, |c| c[2] < 0),
        carved.group("top", 2, |c| c[2] == nz),
    ];
    let mesh = TetMesh::new(positions, carved.mesh.tets().to_vec())?;
    Ok((mesh, PhysicalGroups::new(groups)))
}

/// The vertex (of the uncarved grid: an upper bound) and tet counts of [`torso`] at `res`,
/// without generating it.
pub fn torso_counts(res: usize) -> (f64, f64) {
    let r = res as f64;
    (
        (8.0 * r + 1.0) * (4.0 * r + 1.0) * (11.0 * r + 1.0),
        2016.0 * r.powi(3),
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::generate::tests::check_groups;

    /// The torso: tets positive without re-orientation, a closed surface enclosing the mesh's
    /// volume, the groups on its cut planes, its side wall on the analytic surface (every
    /// side vertex above the crotch lies on its section's curve), the waist narrower than
    /// hips and chest, and no flat tet at the mapped corners: the reflected split gives 0.040
    /// at res 1 and 0.033 at res 2, the plain Kuhn split 0.015 and 0.003 (measured).
    #[test]
    fn torso_is_a_rounded_body_on_two_legs() {
        for res in [1, 2] {
            let (mesh, groups) = torso(res).unwrap();
            assert_eq!(mesh.num_tets(), 2016 * res.pow(3));
            check_groups(&mesh, &groups);
            let quality = mesh.worst_quality();
            assert!(quality > 0.025, "res {res}: {quality}");
            let x = mesh.positions();
            let boundary = mesh.boundary().unwrap();
            assert!(
                (boundary.enclosed_volume(x) - mesh.rest_volume()).abs()
                    < 1e-12 * mesh.rest_volume()
            );
            for (name, z) in [("legs", 0.0), ("top", TORSO_HEIGHT)] {
                let faces = &groups.get(name).unwrap().faces;
                assert!(faces.iter().flatten().all(|&v| x[v].z == z), "{name}");
            }
            // The legs' cut is two disks: no face crosses the gap.
            let legs = &groups.get("legs").unwrap().faces;
            assert!(legs.iter().all(|f| f
                .iter()
                .all(|&v| x[v].x.abs() >= LEG_OFFSET - LEG_RADIUS - 1e-12)));
            let mut side = 0;
            for &v in boundary.vertices() {
                let p = x[v];
                if p.z <= TORSO_CROTCH || p.z == TORSO_HEIGHT {
                    continue;
                }
                // Above the crotch and below the top cut the surface is the side wall, where
                // p^2 + q^2 = 1.
                let s = section(p.z);
                let u = p.x / s.a;
                let q = if p.y <= 0.0 {
                    p.y / s.b
                } else {
                    // Solve b q + c q^2 = y for q >= 0, c = belly (1 - u^2).
                    let c = s.belly * (1.0 - u * u);
                    if c == 0.0 {
                        p.y / s.b
                    } else {
                        (-s.b + (s.b * s.b + 4.0 * c * p.y).sqrt()) / (2.0 * c)
                    }
                };
                assert!((u * u + q * q - 1.0).abs() < 1e-9, "{p}: {}", u * u + q * q);
                side += 1;
            }
            assert!(side > 0);
            let width = |z: f64| 2.0 * section(z).a;
            assert!(width(TORSO_WAIST) < width(0.2) && width(TORSO_WAIST) < width(TORSO_HEIGHT));
        }
    }

    #[test]
    fn res_zero_is_an_error() {
        assert!(torso(0).is_err());
    }
}
