//! A creature-like body with limbs and a thin part, standing in for the armadillo that Sheen
//! et al. 2021 (sec. 8.7, Table 1) squeeze between two cylinders: a torso on four legs with a
//! thin neck and a head. Shape and dimensions ours.

use super::carved::{carve, graded_lines, segment_indices, Cell};
use super::resolution;
use crate::{MeshError, PhysicalGroups, TetMesh};

/// Along x: the hind legs (40 mm), the belly between the legs (80 mm), the front legs
/// (40 mm), the neck (60 mm), the head (40 mm); along y: a leg (20 mm), 10 mm, the neck
/// (20 mm), 10 mm, a leg (20 mm); along z: the legs (40 mm), the torso's lower 20 mm, 10 mm
/// where the head starts, 20 mm at the neck's height, the 10 mm of the head above the torso
/// (metres, cells at res 1).
const X_SEGMENTS: [(f64, usize); 5] = [(0.04, 2), (0.08, 4), (0.04, 2), (0.06, 3), (0.04, 2)];
const Y_SEGMENTS: [(f64, usize); 5] = [(0.02, 1), (0.01, 1), (0.02, 1), (0.01, 1), (0.02, 1)];
const Z_SEGMENTS: [(f64, usize); 5] = [(0.04, 2), (0.02, 1), (0.01, 1), (0.02, 1), (0.01, 1)];

/// Outer size of the creature (x, y, z), in metres.
pub const CREATURE_SIZE: [f64; 3] = [0.26, 0.08, 0.10];

/// Whether the hex in segments `[x, y, z]` (indices into the segment tables) is solid.
fn solid(s: [usize; 3]) -> bool {
    let [x, y, z] = s;
    let leg = (x == 0 || x == 2) && (y == 0 || y == 4) && z == 0;
    let torso = x <= 2 && (1..=3).contains(&z);
    let neck = x == 3 && y == 2 && z == 3;
    let head = x == 4 && (1..=3).contains(&y) && (2..=4).contains(&z);
    leg || torso || neck || head
}

/// The creature: a `160 x 80 x 50` mm torso (`[0, 0.16] x [0, 0.08] x [0.04, 0.09]` m) on four
/// `40 x 20 x 40` mm legs at its corners (feet at z = 0), a thin `60 x 20 x 20` mm neck
/// (`[0.16, 0.22] x [0.03, 0.05] x [0.07, 0.09]`) and a 40 mm cubic head
/// (`[0.22, 0.26] x [0.02, 0.06] x [0.06, 0.10]`). The legs stand 80 mm apart along x, so a
/// cylinder fits under the belly.
///
/// A box grid of `13 res x 5 res x 6 res` hexes graded per axis, Kuhn-split, with the hexes
/// outside the body removed: `942 res^3` tets (res 1: 942; res 2: 7,536); the flattest hexes,
/// `20 x 10 x 10` mm at res 1, give the worst tet quality (0.19, see [`TetMesh::quality`]),
/// the same at every `res`. The neck is `res` cells thick.
///
/// Groups (surfaces): `feet` (the legs' bottom faces, z = 0).
///
/// Errors: `res` outside `1..=16`.
pub fn creature(res: usize) -> Result<(TetMesh, PhysicalGroups), MeshError> {
    let res = resolution(res, 16)?;
    let segments = [X_SEGMENTS, Y_SEGMENTS, Z_SEGMENTS];
    let lines = segments.map(|s| graded_lines(&s, res));
    let owner = segments.map(|s| segment_indices(&s, res));
    let inside = |c: Cell| (0..3).all(|a| c[a] >= 0 && (c[a] as usize) < owner[a].len());
    let carved = carve(&lines, |c| {
        inside(c) && solid([0, 1, 2].map(|a| owner[a][c[a] as usize]))
    })?;
    let groups = vec![carved.group("feet", 1, |c| c[2] < 0)];
    Ok((carved.mesh, PhysicalGroups::new(groups)))
}

/// The vertex and tet counts of [`creature`] at `res`, without generating it. Exact: the
/// torso's grid, the legs' and neck's without the layers they share with the torso and
/// head, the head's.
pub fn creature_counts(res: usize) -> (f64, f64) {
    let r = res as f64;
    let torso = (8.0 * r + 1.0) * (5.0 * r + 1.0) * (3.0 * r + 1.0);
    let legs = 4.0 * (2.0 * r + 1.0) * (r + 1.0) * 2.0 * r;
    let neck = (3.0 * r - 1.0) * (r + 1.0).powi(2);
    let head = (2.0 * r + 1.0) * (3.0 * r + 1.0).powi(2);
    (torso + legs + neck + head, 942.0 * r.powi(3))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::generate::tests::{check_generated, kuhn_quality};
    use crate::Vec3;

    /// Volume and surface area are exact (boxes: torso, legs, neck, head); the feet are the
    /// four legs' bottom faces; the neck is a thin part of the body.
    #[test]
    fn creature_is_a_torso_on_four_legs_with_a_neck_and_a_head() {
        for res in [1, 2] {
            let (mesh, groups) = creature(res).unwrap();
            assert_eq!(mesh.num_tets(), 942 * res.pow(3));
            let (torso, leg, neck, head) = (
                [0.16, 0.08, 0.05],
                [0.04, 0.02, 0.04],
                [0.06, 0.02, 0.02],
                [0.04, 0.04, 0.04],
            );
            let volume = |[a, b, c]: [f64; 3]| a * b * c;
            let area = |[a, b, c]: [f64; 3]| 2.0 * (a * b + b * c + c * a);
            // The legs' tops and the neck's ends are openings into the torso and head; each
            // leg's opening in the torso's bottom is replaced by its foot.
            let openings = 4.0 * 0.04 * 0.02 + 2.0 * 0.02 * 0.02;
            let total_area =
                area(torso) + 4.0 * area(leg) + area(neck) + area(head) - 2.0 * openings;
            let total_volume = volume(torso) + 4.0 * volume(leg) + volume(neck) + volume(head);
            check_generated(&mesh, &groups, total_volume, total_area, None);
            let worst = kuhn_quality(2.0, 1.0, 1.0);
            assert!(
                (mesh.worst_quality() - worst).abs() < 1e-12,
                "{}",
                mesh.worst_quality()
            );
            let feet = &groups.get("feet").unwrap().faces;
            assert_eq!(feet.len(), 4 * 2 * (2 * res) * res);
            let x = mesh.positions();
            assert!(feet.iter().flatten().all(|&v| x[v].z == 0.0));
            // The neck's middle is inside the body, a neck-width beside it is not.
            let near = |p: Vec3| (0..mesh.num_tets()).any(|e| (mesh.centroid(e) - p).norm() < 0.01);
            assert!(near(Vec3::new(0.19, 0.04, 0.08)));
            assert!(!near(Vec3::new(0.19, 0.04, 0.055)));
        }
        assert!(creature(0).is_err());
    }
}
