//! The spine robot arm of Francu et al. 2021 (Fig. 4, Table 2): a bar with a row of square
//! through-holes, so that it bends like a chain of vertebrae joined above and below.

use super::carved::{carve, Cell};
use crate::{MeshError, PhysicalGroups, TetMesh, Vec3};

/// Length (x), width (y) and height (z) of the spine arm, in metres.
pub const SPINE_SIZE: [f64; 3] = [0.25, 0.03, 0.03];

/// The spine arm: a `0.25 x 0.03 x 0.03` m bar along x (the clamped end at `x = 0`) with five
/// square through-holes along y, `0.01 x 0.01` m, centred in z, at `x = 0.025 + 0.05 k`.
/// Built from a box grid of `25 res x 3 res x 3 res` hexes split by Kuhn's rule with the hexes
/// of the holes removed: `6 * 210 res^3` tets (res 1: 1,260; res 2: 10,080), every one a Kuhn
/// tet of a cube (quality 0.27, see [`TetMesh::quality`]).
///
/// Groups (surfaces): `clamped` (the end face x = 0) and `free_end` (x = 0.25 m).
///
/// Errors: `res = 0`.
pub fn spine_arm(res: usize) -> Result<(TetMesh, PhysicalGroups), MeshError> {
    if res == 0 {
        return Err(MeshError::parameter("res", res, "at least 1"));
    }
    let cells = [25 * res, 3 * res, 3 * res];
    let lines = [0, 1, 2].map(|a| {
        (0..=cells[a])
            .map(|i| SPINE_SIZE[a] * (i as f64 / cells[a] as f64))
            .collect::<Vec<f64>>()
    });
    let hole = |c: &Vec3| {
        let k = ((c.x - 0.02) / 0.05).floor();
        let dx = c.x - (0.02 + 0.05 * k);
        (0.0..5.0).contains(&k) && dx > 0.0 && dx < 0.01 && c.z > 0.01 && c.z < 0.02
    };
    let centre = |c: Cell| {
        Vec3::from_fn(|a, _| {
            let i = c[a] as usize;
            0.5 * (lines[a][i] + lines[a][i + 1])
        })
    };
    let carved = carve(&lines, |c| !hole(&centre(c)))?;
    let nx = cells[0] as isize;
    let groups = vec![
        carved.group("clamped", 1, |c| c[0] < 0),
        carved.group("free_end", 2, |c| c[0] == nx),
    ];
    Ok((carved.mesh, PhysicalGroups::new(groups)))
}

/// The vertex (of the grid before the holes: an upper bound) and tet counts of
/// [`spine_arm`] at `res`, without generating it.
pub fn spine_arm_counts(res: usize) -> (f64, f64) {
    let r = res as f64;
    (
        (25.0 * r + 1.0) * (3.0 * r + 1.0).powi(2),
        1260.0 * r.powi(3),
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn spine_has_five_holes_and_exact_volume() {
        for res in [1, 2] {
            let (mesh, groups) = spine_arm(res).unwrap();
            assert_eq!(mesh.num_tets(), 6 * 210 * res * res * res);
            assert_eq!(mesh.reoriented(), 0);
            let volume = 0.25 * 0.03 * 0.03 - 5.0 * 0.01 * 0.03 * 0.01;
            assert!((mesh.rest_volume() - volume).abs() < 1e-12 * volume);
            // The surface is closed, and its area is the bar's plus the holes' walls minus
            // their openings; the holes' centres are outside the body.
            let boundary = mesh.boundary().unwrap();
            crate::check_closed_manifold(boundary.triangles()).unwrap();
            let area = 2.0 * (0.25 * 0.03 * 2.0 + 0.03 * 0.03) + 5.0 * 4.0 * 0.01 * 0.03
                - 5.0 * 2.0 * 0.01 * 0.01;
            assert!(
                (boundary.rest_area() - area).abs() < 1e-12 * area,
                "{}",
                boundary.rest_area()
            );
            let faces = |k: &str| groups.get(k).unwrap().faces.len();
            assert_eq!(faces("clamped"), 18 * res * res);
            assert_eq!(faces("free_end"), 18 * res * res);
            for k in 0..5 {
                let c = Vec3::new(0.025 + 0.05 * k as f64, 0.015, 0.015);
                assert!((0..mesh.num_tets()).all(|e| (mesh.centroid(e) - c).norm() > 0.004));
            }
        }
        assert!(spine_arm(0).is_err());
    }
}
