//! A band: an open cylindrical triangle surface about the z axis (a cloth waistband or
//! sleeve), a structured `(theta, z)` grid periodic in theta.

use super::{cells_along, positive, resolution, split_quads};
use crate::io::TriangleSurface;
use crate::{MeshError, Vec3};
use std::f64::consts::PI;

/// Largest accepted `res` and cell count around.
const MAX_CELLS: usize = 4096;

/// A band of `radius` about the z axis from `z = 0` to `width`, with `res` cells across its
/// width (size `h = width / res`) and `n_theta = max(6, round(2 pi radius / h))` around:
/// `(res + 1) n_theta` vertices on the circle (ring `j`, vertex `i` at index
/// `j n_theta + i`, angle `2 pi i / n_theta`) and `2 res n_theta` triangles whose normals
/// point away from the axis.
pub fn band(radius: f64, width: f64, res: usize) -> Result<TriangleSurface, MeshError> {
    let radius = positive("radius", radius)?;
    let width = positive("width", width)?;
    let res = resolution(res, MAX_CELLS)?;
    let around = cells_along("radius", 2.0 * PI * radius, width / res as f64, MAX_CELLS)?.max(6);
    let vertices = (0..=res)
        .flat_map(|j| {
            let z = width * j as f64 / res as f64;
            (0..around).map(move |i| {
                let angle = 2.0 * PI * i as f64 / around as f64;
                Vec3::new(radius * angle.cos(), radius * angle.sin(), z)
            })
        })
        .collect();
    let index = |i: usize, j: usize| j * around + i % around;
    let triangles = split_quads(around, res, index);
    Ok(TriangleSurface {
        vertices,
        triangles,
    })
}

/// The vertex and triangle counts of [`band`] without generating it.
pub fn band_counts(radius: f64, width: f64, res: usize) -> (f64, f64) {
    let around = (2.0 * PI * radius * res as f64 / width).round().max(6.0);
    ((res as f64 + 1.0) * around, 2.0 * res as f64 * around)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn band_lies_on_its_circle_with_outward_normals() {
        let surface = band(0.1, 0.05, 2).unwrap();
        let (vertices, triangles) = band_counts(0.1, 0.05, 2);
        assert_eq!(surface.vertices.len() as f64, vertices);
        assert_eq!(surface.triangles.len() as f64, triangles);
        for p in &surface.vertices {
            assert!((p.xy().norm() - 0.1).abs() < 1e-15);
        }
        for t in &surface.triangles {
            let [a, b, c] = t.map(|v| surface.vertices[v]);
            let normal = (b - a).cross(&(c - a));
            let centroid = (a + b + c) / 3.0;
            assert!(
                normal.xy().dot(&centroid.xy()) > 0.0,
                "{t:?} faces the axis"
            );
        }
        assert!(band(0.1, 0.0, 2).is_err());
        assert!(band(0.1, 0.05, 0).is_err());
    }
}
