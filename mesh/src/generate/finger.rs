//! The "finger" of Francu et al. 2021 (Fig. 6, Table 1): a PneuNet-style bending actuator, a
//! row of chambers joined by a channel above a thicker strain-limiting base. Shape and
//! dimensions ours (the paper gives none).

use super::carved::{carve, graded_lines, segment_indices, Cell};
use super::resolution;
use crate::{MeshError, PhysicalGroups, TetMesh};

/// What a slab of the finger across x holds.
#[derive(Clone, Copy, PartialEq)]
enum Slab {
    /// The solid block at the clamped end.
    End,
    /// A chamber.
    Chamber,
    /// A wall between a chamber and a gap, or the tip's wall.
    Wall,
    /// The gap between two chambers' walls, open above the channel's roof.
    Gap,
}

/// Number of chambers.
const CHAMBERS: usize = 5;

/// Along y: a 2 mm wall, the 6 mm wide chambers and channel, a 2 mm wall; along z: the 4 mm
/// strain-limiting base, the 2 mm channel, its 2 mm roof, 6 mm of chamber above it, the 2 mm
/// top wall (metres, cells at res 1).
const Y_SEGMENTS: [(f64, usize); 3] = [(0.002, 1), (0.006, 1), (0.002, 1)];
const Z_SEGMENTS: [(f64, usize); 5] = [(0.004, 1), (0.002, 1), (0.002, 1), (0.006, 1), (0.002, 1)];

/// Outer size of the finger (x, y, z), in metres.
pub const FINGER_SIZE: [f64; 3] = [0.064, 0.01, 0.016];

/// The slabs along x with their `(length, cells at res 1)`: the 8 mm end block, then the
/// chambers (6 mm) separated by wall (2 mm), gap (2 mm), wall; the tip's wall last.
fn x_slabs() -> Vec<(Slab, (f64, usize))> {
    let mut slabs = vec![(Slab::End, (0.008, 2)), (Slab::Chamber, (0.006, 1))];
    for _ in 1..CHAMBERS {
        slabs.extend([
            (Slab::Wall, (0.002, 1)),
            (Slab::Gap, (0.002, 1)),
            (Slab::Wall, (0.002, 1)),
            (Slab::Chamber, (0.006, 1)),
        ]);
    }
    slabs.push((Slab::Wall, (0.002, 1)));
    slabs
}

/// The finger: a `64 x 10 x 16` mm body along x (`[0, 0.064] x [0, 0.01] x [0, 0.016]` m),
/// clamped at x = 0, with five `6 x 6 x 10` mm chambers (z from 4 to 14 mm) joined by a
/// `6 x 2` mm channel (z from 4 to 6 mm) running from the first chamber to the last, above a
/// 4 mm strain-limiting base; the 2 mm walls of neighbouring chambers face each other across
/// 2 mm gaps open from z = 8 mm to the top. The chambers and channel form one cavity closed
/// inside the body, so that a follower pressure on its walls is exactly balanced (an open
/// inlet would leave a net force). Inflated, the chambers push their walls apart above the
/// base: the finger bends towards its base (-z).
///
/// A box grid of `20 res x 3 res x 5 res` hexes, Kuhn-split, without the cavity's and the
/// gaps' hexes: `1494 res^3` tets (res 2: 11,952); the flattest hexes, `2 x 6 x 2` mm (the
/// walls across the channel) and `6 x 2 x 2` mm at res 1, give the worst tet quality (0.12,
/// see [`TetMesh::quality`]).
///
/// Groups (surfaces): `base` (the clamped end, x = 0), `chamber` (the cavity's walls, a
/// closed surface whose outward faces point into the cavity), `tip` (the free end,
/// x = 64 mm).
///
/// Errors: `res` outside `1..=8`.
pub fn finger(res: usize) -> Result<(TetMesh, PhysicalGroups), MeshError> {
    let res = resolution(res, 8)?;
    let slabs = x_slabs();
    let x_segments: Vec<(f64, usize)> = slabs.iter().map(|s| s.1).collect();
    let lines = [
        graded_lines(&x_segments, res),
        graded_lines(&Y_SEGMENTS, res),
        graded_lines(&Z_SEGMENTS, res),
    ];
    // The slab or segment index of every hex along each axis.
    let (along_x, along_y, along_z) = (
        segment_indices(&x_segments, res),
        segment_indices(&Y_SEGMENTS, res),
        segment_indices(&Z_SEGMENTS, res),
    );
    let last_chamber = slabs.len() - 2;
    let inside = |c: Cell| (0..3).all(|a| c[a] >= 0 && (c[a] as usize) < lines[a].len() - 1);
    let cavity = |c: Cell| {
        if !inside(c) {
            return false;
        }
        let (slab, y, z) = (
            along_x[c[0] as usize],
            along_y[c[1] as usize],
            along_z[c[2] as usize],
        );
        let in_chamber = slabs[slab].0 == Slab::Chamber && (1..=3).contains(&z);
        let in_channel = (1..=last_chamber).contains(&slab) && z == 1;
        y == 1 && (in_chamber || in_channel)
    };
    let gap = |c: Cell| {
        inside(c) && slabs[along_x[c[0] as usize]].0 == Slab::Gap && along_z[c[2] as usize] >= 3
    };
    let carved = carve(&lines, |c| !cavity(c) && !gap(c))?;
    let nx = lines[0].len() as isize - 1;
    let groups = vec![
        carved.group("base", 1, |c| c[0] < 0),
        carved.group("chamber", 2, cavity),
        carved.group("tip", 3, |c| c[0] == nx),
    ];
    Ok((carved.mesh, PhysicalGroups::new(groups)))
}

/// The vertex (of the uncarved grid: an upper bound) and tet counts of [`finger`] at `res`,
/// without generating it.
pub fn finger_counts(res: usize) -> (f64, f64) {
    let r = res as f64;
    (
        (20.0 * r + 1.0) * (3.0 * r + 1.0) * (5.0 * r + 1.0),
        1494.0 * r.powi(3),
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::generate::tests::{check_generated, kuhn_quality};

    /// Volume, surface area and cavity volume are exact; the base and tip are the end faces.
    #[test]
    fn finger_has_closed_chambers_joined_by_a_channel() {
        for res in [1, 2] {
            let (mesh, groups) = finger(res).unwrap();
            assert_eq!(mesh.num_tets(), 1494 * res.pow(3));
            let [length, width, height] = FINGER_SIZE;
            let chambers = 5.0 * 0.006 * 0.006 * 0.010;
            let channel = 4.0 * 0.006 * 0.006 * 0.002;
            let gaps = 4.0 * 0.002 * width * 0.008;
            let cavity = chambers + channel;
            // The box's faces, each gap trading its top for its floor and its two side
            // openings for its two walls; the chambers' walls, each channel segment's top,
            // bottom and sides less the openings it makes in two chambers.
            let outer = 2.0 * (length * width + length * height + width * height)
                + 4.0 * 2.0 * (0.008 * width - 0.002 * 0.008);
            let inner = 5.0 * (2.0 * 0.006 * 0.006 + 4.0 * 0.006 * 0.010)
                + 4.0 * 2.0 * (0.006 * 0.006 + 0.002 * 0.006)
                - 8.0 * 0.006 * 0.002;
            let worst = kuhn_quality(2.0, 6.0, 2.0);
            assert!(
                (mesh.worst_quality() - worst).abs() < 1e-12,
                "{}",
                mesh.worst_quality()
            );
            check_generated(
                &mesh,
                &groups,
                length * width * height - cavity - gaps,
                outer + inner,
                Some(cavity),
            );
            let faces = |k: &str| groups.get(k).unwrap().faces.len();
            assert_eq!(
                (faces("base"), faces("tip")),
                (30 * res * res, 30 * res * res)
            );
        }
    }
}
