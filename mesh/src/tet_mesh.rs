//! The tetrahedral mesh: rest positions, tets, rest volumes and inverse rest shape matrices.

use crate::{MeshError, Vec3};
use nalgebra::Matrix3;

/// What to do with negatively oriented tets when building a mesh.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Orientation {
    /// Swap two vertices of every negatively oriented tet and count it.
    #[default]
    Reorient,
    /// Reject the first negatively oriented tet with [`MeshError::Inverted`].
    Strict,
}

/// A tet is degenerate when `|V| < DEGENERACY * l_max^3`, with `l_max` its longest edge.
/// A regular tet has `V / l^3 = 0.118`; this threshold only rejects slivers that are flat to
/// within about nine digits, which no solver can use.
pub const DEGENERACY: f64 = 1e-10;

/// Signed volume of the tet `(x0, x1, x2, x3)`: `(x1-x0) . ((x2-x0) x (x3-x0)) / 6`
/// (eq. 25 of Francu et al. 2021).
pub fn signed_volume(x0: &Vec3, x1: &Vec3, x2: &Vec3, x3: &Vec3) -> f64 {
    (x1 - x0).dot(&(x2 - x0).cross(&(x3 - x0))) / 6.0
}

/// Edge matrix `[x1-x0, x2-x0, x3-x0]` (the shape matrix `D_s` or `D_m`).
pub fn shape_matrix(x: [&Vec3; 4]) -> Matrix3<f64> {
    Matrix3::from_columns(&[x[1] - x[0], x[2] - x[0], x[3] - x[0]])
}

/// A linear tetrahedral mesh in its rest configuration.
///
/// Every tet is positively oriented, non-degenerate and references four distinct vertices
/// in range; constructors guarantee it. Per-tet rest data (volume `V_e`, inverse rest shape
/// matrix `D_m^-1`) is computed once here and shared by every later layer.
#[derive(Debug, Clone)]
pub struct TetMesh {
    positions: Vec<Vec3>,
    tets: Vec<[usize; 4]>,
    rest_volumes: Vec<f64>,
    inverse_rest_shapes: Vec<Matrix3<f64>>,
    reoriented: usize,
}

impl TetMesh {
    /// Builds a mesh, re-orienting negatively oriented tets (see [`TetMesh::reoriented`]).
    pub fn new(positions: Vec<Vec3>, tets: Vec<[usize; 4]>) -> Result<Self, MeshError> {
        Self::with_orientation(positions, tets, Orientation::Reorient)
    }

    /// Builds a mesh, choosing what happens to negatively oriented tets.
    pub fn with_orientation(
        positions: Vec<Vec3>,
        mut tets: Vec<[usize; 4]>,
        orientation: Orientation,
    ) -> Result<Self, MeshError> {
        if tets.is_empty() {
            return Err(MeshError::Empty);
        }
        for (vertex, p) in positions.iter().enumerate() {
            if !p.iter().all(|c| c.is_finite()) {
                return Err(MeshError::NonFiniteVertex {
                    vertex,
                    coords: [p.x, p.y, p.z],
                });
            }
        }
        let n = positions.len();
        let mut reoriented = 0;
        let mut rest_volumes = Vec::with_capacity(tets.len());
        let mut inverse_rest_shapes = Vec::with_capacity(tets.len());
        for (tet, t) in tets.iter_mut().enumerate() {
            for (a, &index) in t.iter().enumerate() {
                if index >= n {
                    return Err(MeshError::IndexOutOfRange {
                        tet,
                        index,
                        vertices: n,
                    });
                }
                if t[..a].contains(&index) {
                    return Err(MeshError::RepeatedVertex {
                        tet,
                        vertex: index,
                        indices: *t,
                    });
                }
            }
            let x = t.map(|i| &positions[i]);
            let mut volume = signed_volume(x[0], x[1], x[2], x[3]);
            let longest = (0..4)
                .flat_map(|a| (a + 1..4).map(move |b| (a, b)))
                .map(|(a, b)| (x[a] - x[b]).norm())
                .fold(0.0, f64::max);
            let threshold = DEGENERACY * longest.powi(3);
            if volume.abs() <= threshold {
                return Err(MeshError::Degenerate {
                    tet,
                    volume,
                    threshold,
                });
            }
            if volume < 0.0 {
                if orientation == Orientation::Strict {
                    return Err(MeshError::Inverted { tet, volume });
                }
                t.swap(2, 3);
                volume = -volume;
                reoriented += 1;
            }
            let dm = shape_matrix(t.map(|i| &positions[i]));
            // Non-degenerate, so the inverse exists.
            let inverse = dm.try_inverse().ok_or(MeshError::Degenerate {
                tet,
                volume,
                threshold,
            })?;
            rest_volumes.push(volume);
            inverse_rest_shapes.push(inverse);
        }
        Ok(TetMesh {
            positions,
            tets,
            rest_volumes,
            inverse_rest_shapes,
            reoriented,
        })
    }

    /// Rest positions of the vertices.
    pub fn positions(&self) -> &[Vec3] {
        &self.positions
    }

    /// Tets as four vertex indices, positively oriented in the rest configuration.
    pub fn tets(&self) -> &[[usize; 4]] {
        &self.tets
    }

    /// Number of vertices.
    pub fn num_vertices(&self) -> usize {
        self.positions.len()
    }

    /// Number of tets.
    pub fn num_tets(&self) -> usize {
        self.tets.len()
    }

    /// Rest volume `V_e` of every tet (all positive).
    pub fn rest_volumes(&self) -> &[f64] {
        &self.rest_volumes
    }

    /// Inverse rest shape matrix `D_m^-1` of every tet, so that `F = D_s D_m^-1`.
    pub fn inverse_rest_shapes(&self) -> &[Matrix3<f64>] {
        &self.inverse_rest_shapes
    }

    /// Total rest volume.
    pub fn rest_volume(&self) -> f64 {
        self.rest_volumes.iter().sum()
    }

    /// How many tets the constructor re-oriented.
    pub fn reoriented(&self) -> usize {
        self.reoriented
    }

    /// Signed volume of tet `e` at positions `x`.
    pub fn volume_at(&self, e: usize, x: &[Vec3]) -> f64 {
        let [a, b, c, d] = self.tets[e];
        signed_volume(&x[a], &x[b], &x[c], &x[d])
    }

    /// Total signed volume at positions `x`.
    pub fn total_volume_at(&self, x: &[Vec3]) -> f64 {
        (0..self.num_tets()).map(|e| self.volume_at(e, x)).sum()
    }

    /// Number of tets with non-positive volume at positions `x`.
    pub fn count_inverted(&self, x: &[Vec3]) -> usize {
        (0..self.num_tets())
            .filter(|&e| self.volume_at(e, x) <= 0.0)
            .count()
    }

    /// Shape quality of tet `e` at rest: its volume over the cube of its longest edge,
    /// relative to the regular tet's `1 / (6 sqrt 2)`: 1 for the regular tet, 0.27 for a Kuhn
    /// tet of a cube, towards 0 for a flat one.
    pub fn quality(&self, e: usize) -> f64 {
        let t = self.tets[e];
        let x = &self.positions;
        let longest = (0..4)
            .flat_map(|a| (a + 1..4).map(move |b| (a, b)))
            .map(|(a, b)| (x[t[a]] - x[t[b]]).norm())
            .fold(0.0, f64::max);
        6.0 * std::f64::consts::SQRT_2 * self.rest_volumes[e] / longest.powi(3)
    }

    /// The lowest [`TetMesh::quality`] of any tet.
    pub fn worst_quality(&self) -> f64 {
        (0..self.num_tets())
            .map(|e| self.quality(e))
            .fold(f64::INFINITY, f64::min)
    }

    /// Centroid of tet `e` in the rest configuration.
    pub fn centroid(&self, e: usize) -> Vec3 {
        self.tets[e]
            .iter()
            .map(|&i| self.positions[i])
            .sum::<Vec3>()
            / 4.0
    }

    /// Axis-aligned bounding box `(min, max)` of the rest positions.
    pub fn bounding_box(&self) -> (Vec3, Vec3) {
        let mut lo = Vec3::repeat(f64::INFINITY);
        let mut hi = Vec3::repeat(f64::NEG_INFINITY);
        for p in &self.positions {
            lo = lo.inf(p);
            hi = hi.sup(p);
        }
        (lo, hi)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn unit_tet() -> Vec<Vec3> {
        vec![
            Vec3::new(0.0, 0.0, 0.0),
            Vec3::new(1.0, 0.0, 0.0),
            Vec3::new(0.0, 1.0, 0.0),
            Vec3::new(0.0, 0.0, 1.0),
        ]
    }

    /// The regular tet has quality 1, a Kuhn tet of a cube 0.27 (`sqrt 2 / 3^1.5`), a flat
    /// one almost none.
    #[test]
    fn quality_is_one_for_the_regular_tet() {
        let s = 1.0 / 2f64.sqrt();
        let regular = [
            Vec3::new(1.0, 0.0, -s),
            Vec3::new(-1.0, 0.0, -s),
            Vec3::new(0.0, 1.0, s),
            Vec3::new(0.0, -1.0, s),
        ];
        let mesh = TetMesh::new(regular.to_vec(), vec![[0, 1, 2, 3]]).unwrap();
        assert!((mesh.quality(0) - 1.0).abs() < 1e-14, "{}", mesh.quality(0));
        let cube = crate::generate::box_grid(Vec3::zeros(), Vec3::repeat(1.0), [1, 1, 1]).unwrap();
        let kuhn = 2f64.sqrt() / 3f64.powf(1.5);
        assert!((cube.worst_quality() - kuhn).abs() < 1e-14);
        // The same tet squashed to a thousandth of its height: a sliver.
        let flat = regular
            .iter()
            .map(|p| Vec3::new(p.x, p.y, 1e-3 * p.z))
            .collect();
        let flat = TetMesh::new(flat, vec![[0, 1, 2, 3]]).unwrap();
        assert!(flat.quality(0) < 1e-2);
    }

    #[test]
    fn rest_data_of_the_unit_tet() {
        let mesh = TetMesh::new(unit_tet(), vec![[0, 1, 2, 3]]).unwrap();
        assert!((mesh.rest_volume() - 1.0 / 6.0).abs() < 1e-15);
        assert_eq!(mesh.inverse_rest_shapes()[0], Matrix3::identity());
        assert_eq!(mesh.reoriented(), 0);
    }

    #[test]
    fn negative_tets_are_reoriented_or_rejected() {
        let mesh = TetMesh::new(unit_tet(), vec![[0, 2, 1, 3]]).unwrap();
        assert_eq!(mesh.reoriented(), 1);
        assert!(mesh.rest_volumes()[0] > 0.0);
        let err = TetMesh::with_orientation(unit_tet(), vec![[0, 2, 1, 3]], Orientation::Strict);
        assert!(matches!(err, Err(MeshError::Inverted { tet: 0, .. })));
    }

    #[test]
    fn bad_tets_are_named() {
        let e = TetMesh::new(unit_tet(), vec![[0, 1, 2, 3], [0, 1, 2, 7]]).unwrap_err();
        assert!(matches!(
            e,
            MeshError::IndexOutOfRange {
                tet: 1,
                index: 7,
                ..
            }
        ));
        let e = TetMesh::new(unit_tet(), vec![[0, 1, 1, 3]]).unwrap_err();
        assert!(matches!(
            e,
            MeshError::RepeatedVertex {
                tet: 0,
                vertex: 1,
                ..
            }
        ));
        let mut flat = unit_tet();
        flat[3] = Vec3::new(0.3, 0.3, 0.0);
        let e = TetMesh::new(flat, vec![[0, 1, 2, 3]]).unwrap_err();
        assert!(matches!(e, MeshError::Degenerate { tet: 0, .. }));
        let mut nan = unit_tet();
        nan[2].y = f64::NAN;
        let e = TetMesh::new(nan, vec![[0, 1, 2, 3]]).unwrap_err();
        assert!(matches!(e, MeshError::NonFiniteVertex { vertex: 2, .. }));
        assert!(e.to_string().contains("vertex 2"));
    }
}
