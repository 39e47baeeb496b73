//! The "cushion" of Francu et al. 2021 (Fig. 6, Table 1): a flat pad with an internal
//! chamber, inflated like a pillow. Shape and dimensions ours (the paper gives none).

use super::carved::chambered_box;
use super::resolution;
use crate::{MeshError, PhysicalGroups, TetMesh};

/// Along x and y: a 5 mm wall, the 30 mm chamber, a 5 mm wall; along z: a 3 mm floor, the
/// 4 mm chamber, a 6 mm roof of two cells (metres, cells at res 1). A 3 mm roof balloons at
/// Table 1's 10 kPa and the mixed run stalls there.
const SEGMENTS: [[(f64, usize); 3]; 3] = [
    [(0.005, 1), (0.030, 4), (0.005, 1)],
    [(0.005, 1), (0.030, 4), (0.005, 1)],
    [(0.003, 1), (0.004, 1), (0.006, 2)],
];

/// Outer size of the cushion (x, y, z), in metres.
pub const CUSHION_SIZE: [f64; 3] = [0.04, 0.04, 0.013];

/// The cushion: a `40 x 40 x 13` mm pad (`[0, 0.04]^2 x [0, 0.013]` m) with a closed
/// `30 x 30 x 4` mm chamber (walls 5 mm thick around it, 3 mm below, 6 mm above).
/// A box grid of `6 res x 6 res x 4 res` hexes, Kuhn-split, without the chamber's
/// `4 res x 4 res x res`: `768 res^3` tets (res 2: 6,144); the flattest hexes, `7.5 x 7.5 x 3`
/// mm at res 1, give the worst tet quality (0.18, see [`TetMesh::quality`]).
///
/// Groups (surfaces): `base` (the bottom face, z = 0), `chamber` (the chamber's walls, a
/// closed surface whose outward faces point into the cavity), `top` (the top face).
///
/// Errors: `res` outside `1..=16`.
pub fn cushion(res: usize) -> Result<(TetMesh, PhysicalGroups), MeshError> {
    let res = resolution(res, 16)?;
    let (carved, chamber) = chambered_box(&SEGMENTS, res)?;
    let nz = 4 * res as isize;
    let groups = vec![
        carved.group("base", 1, |c| c[2] < 0),
        carved.group("chamber", 2, |c| super::carved::within(c, &chamber)),
        carved.group("top", 3, |c| c[2] == nz),
    ];
    Ok((carved.mesh, PhysicalGroups::new(groups)))
}

/// The vertex (of the uncarved grid: at most a few percent more) and tet counts of
/// [`cushion`] at `res`, without generating it.
pub fn cushion_counts(res: usize) -> (f64, f64) {
    let r = res as f64;
    ((6.0 * r + 1.0).powi(2) * (4.0 * r + 1.0), 768.0 * r.powi(3))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::generate::tests::{check_generated, kuhn_quality};

    /// Volume, surface area and chamber volume are exact; the groups are where they say.
    #[test]
    fn cushion_is_a_pad_with_a_closed_chamber() {
        for res in [1, 2] {
            let (mesh, groups) = cushion(res).unwrap();
            assert_eq!(mesh.num_tets(), 768 * res.pow(3));
            let chamber = 0.03 * 0.03 * 0.004;
            let area =
                2.0 * 0.04 * 0.04 + 4.0 * 0.04 * 0.013 + 2.0 * (0.03 * 0.03 + 2.0 * 0.03 * 0.004);
            let worst = kuhn_quality(7.5, 7.5, 3.0);
            assert!(
                (mesh.worst_quality() - worst).abs() < 1e-12,
                "{}",
                mesh.worst_quality()
            );
            check_generated(
                &mesh,
                &groups,
                0.04 * 0.04 * 0.013 - chamber,
                area,
                Some(chamber),
            );
            assert_eq!(groups.get("base").unwrap().faces.len(), 72 * res * res);
            assert_eq!(groups.get("top").unwrap().faces.len(), 72 * res * res);
        }
        assert!(cushion(0).is_err());
    }
}
