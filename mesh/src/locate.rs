//! Which points lie inside a tet mesh: a uniform grid of the tets' bounding boxes, then
//! barycentric coordinates in the few tets of a point's cell, and the distance to the
//! boundary surface for the points on it.

use crate::{MeshError, TetMesh, TriangleBvh, Vec3};
use nalgebra::Matrix3;
use std::collections::HashMap;

/// Barycentric slack of the closed tets (a point on an internal face is in both tets).
const SLACK: f64 = 1e-12;

/// Points closer than this fraction of the mesh's bounding-box diagonal to its boundary are
/// on it, not inside: bodies that only touch (a shared plane, a vertex on a face) are not
/// inside each other.
const ON_BOUNDARY: f64 = 1e-9;

/// A point-in-mesh query structure over the tets of a mesh.
#[derive(Debug, Clone)]
pub struct TetLocator<'a> {
    mesh: &'a TetMesh,
    origin: Vec3,
    cell: f64,
    cells: HashMap<[i64; 3], Vec<usize>>,
    inverse: Vec<Option<Matrix3<f64>>>,
    boundary: TriangleBvh,
    on_boundary: f64,
}

impl<'a> TetLocator<'a> {
    /// The grid of `mesh`'s tets, with a cell about the size of a mean tet's bounding box
    /// (each tet is listed in every cell its box meets, so memory is linear in the mesh),
    /// and a bounding-volume hierarchy of its boundary.
    pub fn new(mesh: &'a TetMesh) -> Result<Self, MeshError> {
        let x = mesh.positions();
        let boxes: Vec<(Vec3, Vec3)> = mesh
            .tets()
            .iter()
            .map(|t| {
                let (mut lo, mut hi) = (x[t[0]], x[t[0]]);
                for &v in &t[1..] {
                    lo = lo.inf(&x[v]);
                    hi = hi.sup(&x[v]);
                }
                (lo, hi)
            })
            .collect();
        let (lo, hi) = mesh.bounding_box();
        let mean =
            boxes.iter().map(|(l, h)| (h - l).max()).sum::<f64>() / boxes.len().max(1) as f64;
        let cell = if mean > 0.0 { mean } else { 1.0 };
        let key = |p: &Vec3| -> [i64; 3] {
            let q = (p - lo) / cell;
            [q.x.floor() as i64, q.y.floor() as i64, q.z.floor() as i64]
        };
        let mut cells: HashMap<[i64; 3], Vec<usize>> = HashMap::new();
        for (e, (l, h)) in boxes.iter().enumerate() {
            let (a, b) = (key(l), key(h));
            for i in a[0]..=b[0] {
                for j in a[1]..=b[1] {
                    for k in a[2]..=b[2] {
                        cells.entry([i, j, k]).or_default().push(e);
                    }
                }
            }
        }
        let inverse = mesh
            .tets()
            .iter()
            .map(|t| {
                Matrix3::from_columns(&[x[t[1]] - x[t[0]], x[t[2]] - x[t[0]], x[t[3]] - x[t[0]]])
                    .try_inverse()
            })
            .collect();
        let boundary = TriangleBvh::new(mesh.boundary()?.triangles(), x);
        Ok(TetLocator {
            mesh,
            origin: lo,
            cell,
            cells,
            inverse,
            boundary,
            on_boundary: ON_BOUNDARY * (hi - lo).norm(),
        })
    }

    /// Whether `p` lies inside the mesh and not on its boundary (within `1e-9` of the
    /// bounding-box diagonal).
    pub fn contains(&self, p: &Vec3) -> bool {
        self.in_some_tet(p)
            && self
                .boundary
                .closest(p)
                .is_none_or(|(_, d2)| d2 > self.on_boundary * self.on_boundary)
    }

    /// Whether `p` lies in some closed tet.
    fn in_some_tet(&self, p: &Vec3) -> bool {
        let q = (p - self.origin) / self.cell;
        let key = [q.x.floor() as i64, q.y.floor() as i64, q.z.floor() as i64];
        let Some(tets) = self.cells.get(&key) else {
            return false;
        };
        tets.iter().any(|&e| {
            let Some(inverse) = &self.inverse[e] else {
                return false;
            };
            let b = inverse * (p - self.mesh.positions()[self.mesh.tets()[e][0]]);
            b.iter().all(|&c| c >= -SLACK) && 1.0 - b.sum() >= -SLACK
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::generate::box_grid;

    #[test]
    fn inside_outside_and_on_the_boundary() {
        let cube = box_grid(Vec3::zeros(), Vec3::new(1.0, 1.0, 1.0), [3, 3, 3]).unwrap();
        let locator = TetLocator::new(&cube).unwrap();
        assert!(locator.contains(&Vec3::new(0.5, 0.4, 0.3)));
        // On a grid point and on internal faces: inside.
        assert!(locator.contains(&Vec3::new(1.0 / 3.0, 2.0 / 3.0, 1.0 / 3.0)));
        assert!(locator.contains(&Vec3::new(0.5, 0.5, 0.5)));
        assert!(locator.contains(&Vec3::new(0.01, 0.99, 0.5)));
        assert!(!locator.contains(&Vec3::new(1.5, 0.5, 0.5)));
        assert!(!locator.contains(&Vec3::new(-0.01, 0.5, 0.5)));
        // On a face of the cube: touching, not inside.
        assert!(!locator.contains(&Vec3::new(1.0, 0.5, 0.5)));
    }
}
