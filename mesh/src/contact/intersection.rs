//! An independent check that a surface does not intersect itself: every pair of triangles
//! sharing no node, found by the broad phase, is tested for intersection (one triangle's
//! edge crossing the other triangle, with floating-point orientation tests; coplanar pairs
//! in the plane). For tests of contact: an accepted state must have none.

use super::aabb::Aabb;
use super::hash_grid::overlapping_pairs;
use super::surface::ContactSurface;
use crate::Vec3;

/// `(b - a) x (c - a) . (d - a)`: six times the signed volume of `(a, b, c, d)`.
fn orient3d(a: &Vec3, b: &Vec3, c: &Vec3, d: &Vec3) -> f64 {
    (b - a).cross(&(c - a)).dot(&(d - a))
}

/// `(b - a) x (c - a)` in the plane.
fn orient2d(a: [f64; 2], b: [f64; 2], c: [f64; 2]) -> f64 {
    (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0])
}

/// Whether the closed segments `pq` and `ab` of a plane meet.
fn segments_meet(p: [f64; 2], q: [f64; 2], a: [f64; 2], b: [f64; 2]) -> bool {
    let (d1, d2) = (orient2d(a, b, p), orient2d(a, b, q));
    let (d3, d4) = (orient2d(p, q, a), orient2d(p, q, b));
    if d1 * d2 < 0.0 && d3 * d4 < 0.0 {
        return true;
    }
    let on = |s: [f64; 2], e: [f64; 2], r: [f64; 2], o: f64| {
        o == 0.0 && (0..2).all(|k| s[k].min(e[k]) <= r[k] && r[k] <= s[k].max(e[k]))
    };
    on(a, b, p, d1) || on(a, b, q, d2) || on(p, q, a, d3) || on(p, q, b, d4)
}

/// Whether the closed segment `pq` meets the closed triangle `abc` when all lie in a plane.
fn coplanar_segment_meets_triangle(p: &Vec3, q: &Vec3, t: [&Vec3; 3]) -> bool {
    let n = (t[1] - t[0]).cross(&(t[2] - t[0]));
    let drop = n.iamax();
    let [i, j] = [(drop + 1) % 3, (drop + 2) % 3];
    let flat = |v: &Vec3| [v[i], v[j]];
    let [a, b, c] = t.map(flat);
    let (p2, q2) = (flat(p), flat(q));
    let inside = |r: [f64; 2]| {
        let s = [orient2d(a, b, r), orient2d(b, c, r), orient2d(c, a, r)];
        s.iter().all(|&v| v >= 0.0) || s.iter().all(|&v| v <= 0.0)
    };
    inside(p2)
        || [(a, b), (b, c), (c, a)]
            .iter()
            .any(|&(u, v)| segments_meet(p2, q2, u, v))
}

/// Whether the closed segment `pq` meets the closed triangle `t`.
fn segment_meets_triangle(p: &Vec3, q: &Vec3, t: [&Vec3; 3]) -> bool {
    let (sp, sq) = (orient3d(t[0], t[1], t[2], p), orient3d(t[0], t[1], t[2], q));
    if (sp > 0.0 && sq > 0.0) || (sp < 0.0 && sq < 0.0) {
        return false;
    }
    if sp == 0.0 && sq == 0.0 {
        return coplanar_segment_meets_triangle(p, q, t);
    }
    let s = [
        orient3d(p, q, t[0], t[1]),
        orient3d(p, q, t[1], t[2]),
        orient3d(p, q, t[2], t[0]),
    ];
    s.iter().all(|&v| v >= 0.0) || s.iter().all(|&v| v <= 0.0)
}

/// Whether the closed triangles `s` and `t` meet: an edge of one meets the other.
pub fn triangles_intersect(s: [&Vec3; 3], t: [&Vec3; 3]) -> bool {
    let crosses = |a: [&Vec3; 3], b: [&Vec3; 3]| {
        (0..3).any(|k| segment_meets_triangle(a[k], a[(k + 1) % 3], b))
    };
    crosses(s, t) || crosses(t, s)
}

/// The pairs `[i, j]` (`i < j`, indices into [`ContactSurface::triangles`]) of triangles
/// that share no node and intersect at node positions `x`, sorted; empty for a valid state.
pub fn intersecting_triangles(surface: &ContactSurface, x: &[Vec3]) -> Vec<[usize; 2]> {
    let triangles = surface.triangles();
    let boxes: Vec<Aabb> = triangles
        .iter()
        .map(|t| Aabb::of_nodes(t, x, None, 0.0))
        .collect();
    overlapping_pairs(&boxes, None)
        .into_iter()
        .filter(|&[i, j]| {
            let (s, t) = (&triangles[i], &triangles[j]);
            !s.iter().any(|n| t.contains(n))
                && triangles_intersect(s.map(|n| &x[n]), t.map(|n| &x[n]))
        })
        .collect()
}
