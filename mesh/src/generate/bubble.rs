//! The "bubble" of Francu et al. 2021 (Fig. 6, Fig. 7, Table 1): a closed chamber under a
//! thin membrane that bulges. Shape and dimensions ours (the paper gives none; its bubble has
//! 5,193 tets).

use super::carved::{chambered_box, within};
use super::resolution;
use crate::{MeshError, PhysicalGroups, TetMesh};

/// Along x and y: a 5 mm wall, the 30 mm chamber, a 5 mm wall; along z: a 6 mm base, the
/// 6 mm chamber, the 3 mm membrane (metres, cells at res 1).
const SEGMENTS: [[(f64, usize); 3]; 3] = [
    [(0.005, 1), (0.030, 4), (0.005, 1)],
    [(0.005, 1), (0.030, 4), (0.005, 1)],
    [(0.006, 1), (0.006, 1), (0.003, 1)],
];

/// Outer size of the bubble (x, y, z), in metres.
pub const BUBBLE_SIZE: [f64; 3] = [0.04, 0.04, 0.015];

/// The bubble: a `40 x 40 x 15` mm block (`[0, 0.04]^2 x [0, 0.015]` m) with a closed
/// `30 x 30 x 6` mm chamber from z = 6 to 12 mm under a 3 mm membrane, its walls 5 mm thick.
/// A box grid of `6 res x 6 res x 3 res` hexes, Kuhn-split, without the chamber's
/// `4 res x 4 res x res`: `552 res^3` tets (res 2: 4,416, the paper's 5,193 lie between res 2
/// and 3); the membrane's hexes, `7.5 x 7.5 x 3` mm at res 1, give the worst tet quality
/// (0.18, see [`TetMesh::quality`]). The membrane's centre, the apex, is a vertex.
///
/// Groups (surfaces): `base` (the bottom face, z = 0), `chamber` (the chamber's walls, a
/// closed surface whose outward faces point into the cavity), `membrane` (the top face over
/// the chamber, where the bulge is read).
///
/// Errors: `res` outside `1..=16`.
pub fn bubble(res: usize) -> Result<(TetMesh, PhysicalGroups), MeshError> {
    let res = resolution(res, 16)?;
    let (carved, chamber) = chambered_box(&SEGMENTS, res)?;
    let nz = 3 * res as isize;
    let over = |c: [isize; 3]| chamber[0].contains(&c[0]) && chamber[1].contains(&c[1]);
    let groups = vec![
        carved.group("base", 1, |c| c[2] < 0),
        carved.group("chamber", 2, |c| within(c, &chamber)),
        carved.group("membrane", 3, |c| c[2] == nz && over(c)),
    ];
    Ok((carved.mesh, PhysicalGroups::new(groups)))
}

/// The vertex (of the uncarved grid: at most a few percent more) and tet counts of
/// [`bubble`] at `res`, without generating it.
pub fn bubble_counts(res: usize) -> (f64, f64) {
    let r = res as f64;
    ((6.0 * r + 1.0).powi(2) * (3.0 * r + 1.0), 552.0 * r.powi(3))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::generate::tests::{check_generated, kuhn_quality};
    use crate::Vec3;

    /// Volume, surface area and chamber volume are exact; the membrane is the top over the
    /// chamber, and its centre is a vertex.
    #[test]
    fn bubble_is_a_chamber_under_a_membrane() {
        for res in [1, 2] {
            let (mesh, groups) = bubble(res).unwrap();
            assert_eq!(mesh.num_tets(), 552 * res.pow(3));
            let chamber = 0.03 * 0.03 * 0.006;
            let area =
                2.0 * 0.04 * 0.04 + 4.0 * 0.04 * 0.015 + 2.0 * (0.03 * 0.03 + 2.0 * 0.03 * 0.006);
            let worst = kuhn_quality(7.5, 7.5, 3.0);
            assert!(
                (mesh.worst_quality() - worst).abs() < 1e-12,
                "{}",
                mesh.worst_quality()
            );
            check_generated(
                &mesh,
                &groups,
                0.04 * 0.04 * 0.015 - chamber,
                area,
                Some(chamber),
            );
            let membrane = &groups.get("membrane").unwrap().faces;
            assert_eq!(membrane.len(), 32 * res * res);
            let x = mesh.positions();
            let apex = Vec3::new(0.02, 0.02, 0.015);
            assert!(membrane
                .iter()
                .flatten()
                .any(|&v| (x[v] - apex).norm() < 1e-12));
            assert!(membrane
                .iter()
                .flatten()
                .all(|&v| x[v].z == 0.015 && (x[v].x - 0.02).abs() <= 0.015 + 1e-12));
        }
    }
}
