//! Octants of spherical shells: the part `x, y, z >= 0` of the shell between two spheres
//! about the origin, for inflation with symmetry conditions on the three coordinate planes.

use super::{positive, resolution};
use crate::element::TetElement;
use crate::{ElementMesh, MeshError, TetMesh, Vec3};

/// Largest accepted `res` and `layers`.
const MAX_RES: usize = 256;

/// The octant `x, y, z >= 0` of the shell between the spheres of radii `inner < outer`
/// about the origin.
///
/// The flat triangle with corners on the three axes is split into `res^2` triangles (`res`
/// per edge), projected radially onto the spheres of `layers + 1` radii spaced evenly from
/// `inner` to `outer`; each of the `res^2 layers` prisms between two of them is split into
/// 3 tets, the diagonal of each side face running from the higher-numbered bottom vertex
/// to the lower-numbered top one, so that neighbouring prisms agree: `3 res^2 layers` tets.
/// The faces on the coordinate planes are flat; those on the spheres are polygons
/// ([`shell_octant_quadratic`] curves them).
pub fn shell_octant(
    inner: f64,
    outer: f64,
    res: usize,
    layers: usize,
) -> Result<TetMesh, MeshError> {
    let inner = positive("inner_radius", inner)?;
    let outer = positive("outer_radius", outer)?;
    if outer <= inner {
        return Err(MeshError::parameter(
            "outer_radius",
            outer,
            "must exceed the inner radius",
        ));
    }
    let res = resolution(res, MAX_RES)?;
    let layers = resolution(layers, MAX_RES)?;
    // Points (i, j) of the flat triangle, i + j <= res: corner i along x, j along y.
    let per_layer = (res + 1) * (res + 2) / 2;
    let index = |i: usize, j: usize| -> usize {
        // Rows of constant i hold res + 1 - i points.
        i * (res + 1) - i * i.saturating_sub(1) / 2 + j
    };
    let mut flat = Vec::with_capacity(per_layer);
    for i in 0..=res {
        for j in 0..=res - i {
            // Integers first, so that the points on a coordinate plane lie on it exactly.
            let c = [i, j, res - i - j].map(|k| k as f64 / res as f64);
            flat.push(Vec3::from(c).normalize());
        }
    }
    debug_assert_eq!(flat.len(), per_layer);
    let mut positions = Vec::with_capacity(per_layer * (layers + 1));
    for l in 0..=layers {
        let r = inner + (outer - inner) * l as f64 / layers as f64;
        positions.extend(flat.iter().map(|p| r * p));
    }
    let mut triangles = Vec::with_capacity(res * res);
    for i in 0..res {
        for j in 0..res - i {
            triangles.push([index(i, j), index(i + 1, j), index(i, j + 1)]);
            if i + j + 1 < res {
                triangles.push([index(i + 1, j), index(i + 1, j + 1), index(i, j + 1)]);
            }
        }
    }
    let mut tets = Vec::with_capacity(3 * triangles.len() * layers);
    for l in 0..layers {
        let (bottom, top) = (l * per_layer, (l + 1) * per_layer);
        for t in &triangles {
            let mut v = t.map(|k| k + bottom);
            v.sort_unstable();
            let up = |k: usize| k - bottom + top;
            let [a, b, c] = v;
            for tet in [
                [a, b, c, up(a)],
                [b, c, up(a), up(b)],
                [c, up(a), up(b), up(c)],
            ] {
                tets.push(positively_oriented(&positions, tet));
            }
        }
    }
    TetMesh::new(positions, tets)
}

/// `tet` with two vertices swapped if it is negatively oriented.
fn positively_oriented(x: &[Vec3], tet: [usize; 4]) -> [usize; 4] {
    let [a, b, c, d] = tet.map(|v| x[v]);
    if (b - a).cross(&(c - a)).dot(&(d - a)) < 0.0 {
        [tet[1], tet[0], tet[2], tet[3]]
    } else {
        tet
    }
}

/// The 10-node [`shell_octant`]: every mid-edge node `[a, b]` placed by the shell's own
/// spherical map, at the mean radius of `a` and `b` in the direction of the sum of their
/// directions. Boundary edges on a sphere get their mid-edge node on it, edges on a
/// coordinate plane keep it there, and the interior edges are curved alike, so no element
/// folds (moving only the boundary's mid-edge nodes folds the flat tets of a thin wall).
pub fn shell_octant_quadratic(
    inner: f64,
    outer: f64,
    res: usize,
    layers: usize,
) -> Result<ElementMesh, MeshError> {
    let straight = ElementMesh::quadratic(shell_octant(inner, outer, res, layers)?);
    let mut nodes = straight.nodes().to_vec();
    let first = straight.num_vertices();
    for (k, &[a, b]) in straight.mid_edges().iter().enumerate() {
        let (xa, xb) = (nodes[a], nodes[b]);
        let radius = 0.5 * (xa.norm() + xb.norm());
        nodes[first + k] = radius * (xa.normalize() + xb.normalize()).normalize();
    }
    ElementMesh::from_nodes(TetElement::Tet10, nodes, straight.connectivity().to_vec())
}

/// The vertex and tet counts of [`shell_octant`] at `res` and `layers`, without generating it.
pub fn shell_octant_counts(res: usize, layers: usize) -> (f64, f64) {
    let (r, l) = (res as f64, layers as f64);
    ((r + 1.0) * (r + 2.0) / 2.0 * (l + 1.0), 3.0 * r * r * l)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_octant_has_the_shell_volume_in_the_limit_and_its_counts() {
        let volume = |res| shell_octant(1.0, 1.2, res, 2).unwrap().rest_volume();
        let exact = std::f64::consts::PI / 6.0 * (1.2f64.powi(3) - 1.0);
        let (coarse, fine) = (volume(4), volume(16));
        assert!(coarse < fine && fine < exact, "{coarse} {fine} {exact}");
        assert!((exact - fine) / exact < 0.01, "{fine} {exact}");
        let mesh = shell_octant(1.0, 1.2, 3, 2).unwrap();
        let (v, t) = shell_octant_counts(3, 2);
        assert_eq!((mesh.num_vertices() as f64, mesh.num_tets() as f64), (v, t));
        assert!(mesh.rest_volumes().iter().all(|v| *v > 0.0));
        assert!(shell_octant(1.2, 1.0, 3, 2).is_err());
        for p in mesh.positions() {
            let on_planes = p.iter().filter(|c| **c == 0.0).count();
            let near_planes = p.iter().filter(|c| c.abs() < 1e-9).count();
            assert_eq!(on_planes, near_planes, "{p}");
        }
        let curved = shell_octant_quadratic(1.0, 1.2, 4, 2).unwrap();
        let on_spheres = curved
            .nodes()
            .iter()
            .filter(|p| (p.norm() - 1.0).abs() < 1e-12 || (p.norm() - 1.2).abs() < 1e-12)
            .count();
        // Per sphere: 15 vertices and 30 mid-edge nodes of its 16 faces.
        assert_eq!(on_spheres, 2 * (15 + 30));
    }
}
