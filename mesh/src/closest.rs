//! Closest triangle to a point: the exact point-triangle closest point (Ericson, "Real-Time
//! Collision Detection", sec. 5.1.5) and a bounding-volume hierarchy over the triangles.
//! Used to carry surface labels to tets (Sheen et al. 2021, sec. 6).

use crate::Vec3;

/// The point of triangle `(a, b, c)` closest to `p`, by Voronoi regions of its vertices,
/// edges and interior. Exact for degenerate triangles too (they reduce to segments).
pub fn closest_point_on_triangle(p: &Vec3, a: &Vec3, b: &Vec3, c: &Vec3) -> Vec3 {
    let ab = b - a;
    let ac = c - a;
    let ap = p - a;
    let d1 = ab.dot(&ap);
    let d2 = ac.dot(&ap);
    if d1 <= 0.0 && d2 <= 0.0 {
        return *a;
    }
    let bp = p - b;
    let d3 = ab.dot(&bp);
    let d4 = ac.dot(&bp);
    if d3 >= 0.0 && d4 <= d3 {
        return *b;
    }
    let vc = d1 * d4 - d3 * d2;
    if vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0 {
        return a + ab * (d1 / (d1 - d3));
    }
    let cp = p - c;
    let d5 = ab.dot(&cp);
    let d6 = ac.dot(&cp);
    if d6 >= 0.0 && d5 <= d6 {
        return *c;
    }
    let vb = d5 * d2 - d1 * d6;
    if vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0 {
        return a + ac * (d2 / (d2 - d6));
    }
    let va = d3 * d6 - d5 * d4;
    if va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0 {
        return b + (c - b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6)));
    }
    let denom = 1.0 / (va + vb + vc);
    a + ab * (vb * denom) + ac * (vc * denom)
}

/// Leaf size of the hierarchy.
const LEAF: usize = 4;

#[derive(Debug, Clone)]
struct Node {
    min: Vec3,
    max: Vec3,
    /// Leaf: triangles `order[start..start + count]`; inner: children `start` and `start + 1`
    /// (`count == 0`).
    start: usize,
    count: usize,
}

/// A bounding-volume hierarchy over triangles for closest-triangle queries.
#[derive(Debug, Clone)]
pub struct TriangleBvh {
    corners: Vec<[Vec3; 3]>,
    order: Vec<usize>,
    nodes: Vec<Node>,
}

impl TriangleBvh {
    /// Builds the hierarchy over `triangles` (vertex indices into `x`) by median splits along
    /// the longest axis of the centroids' bounding box.
    pub fn new(triangles: &[[usize; 3]], x: &[Vec3]) -> Self {
        let corners: Vec<[Vec3; 3]> = triangles.iter().map(|t| t.map(|v| x[v])).collect();
        let mut bvh = TriangleBvh {
            order: (0..corners.len()).collect(),
            corners,
            nodes: Vec::new(),
        };
        if !bvh.corners.is_empty() {
            bvh.nodes.push(bvh.leaf(0, bvh.corners.len()));
            bvh.split(0);
        }
        bvh
    }

    fn leaf(&self, start: usize, count: usize) -> Node {
        let mut min = Vec3::repeat(f64::INFINITY);
        let mut max = Vec3::repeat(f64::NEG_INFINITY);
        for &t in &self.order[start..start + count] {
            for p in &self.corners[t] {
                min = min.inf(p);
                max = max.sup(p);
            }
        }
        Node {
            min,
            max,
            start,
            count,
        }
    }

    fn split(&mut self, node: usize) {
        let Node { start, count, .. } = self.nodes[node];
        if count <= LEAF {
            return;
        }
        let centroid = |t: usize| self.corners[t].iter().sum::<Vec3>() / 3.0;
        let (mut lo, mut hi) = (Vec3::repeat(f64::INFINITY), Vec3::repeat(f64::NEG_INFINITY));
        for &t in &self.order[start..start + count] {
            lo = lo.inf(&centroid(t));
            hi = hi.sup(&centroid(t));
        }
        let axis = (hi - lo).iamax();
        let half = count / 2;
        let key = |t: &usize| centroid(*t)[axis];
        let mut slice = self.order[start..start + count].to_vec();
        slice.select_nth_unstable_by(half, |a, b| key(a).total_cmp(&key(b)));
        self.order[start..start + count].copy_from_slice(&slice);
        let children = self.nodes.len();
        let left = self.leaf(start, half);
        let right = self.leaf(start + half, count - half);
        self.nodes.push(left);
        self.nodes.push(right);
        self.nodes[node].start = children;
        self.nodes[node].count = 0;
        self.split(children);
        self.split(children + 1);
    }

    /// The triangle closest to `p` and its squared distance, or `None` if there are no
    /// triangles. Ties go to whichever triangle the traversal meets first (deterministic).
    pub fn closest(&self, p: &Vec3) -> Option<(usize, f64)> {
        let box_distance = |n: &Node| {
            let d = (n.min - p).sup(&(p - n.max)).sup(&Vec3::zeros());
            d.norm_squared()
        };
        if self.nodes.is_empty() {
            return None;
        }
        let mut best: Option<(usize, f64)> = None;
        let mut stack = vec![0];
        while let Some(i) = stack.pop() {
            let node = &self.nodes[i];
            if best.is_some_and(|(_, d)| box_distance(node) >= d) {
                continue;
            }
            if node.count > 0 {
                for &t in &self.order[node.start..node.start + node.count] {
                    let [a, b, c] = &self.corners[t];
                    let d = (closest_point_on_triangle(p, a, b, c) - p).norm_squared();
                    if best.is_none_or(|(_, bd)| d < bd) {
                        best = Some((t, d));
                    }
                }
            } else {
                let (l, r) = (node.start, node.start + 1);
                // Visit the nearer child first: push it last.
                if box_distance(&self.nodes[l]) <= box_distance(&self.nodes[r]) {
                    stack.extend([r, l]);
                } else {
                    stack.extend([l, r]);
                }
            }
        }
        best
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn closest_points_in_every_voronoi_region() {
        let (a, b, c) = (Vec3::zeros(), Vec3::x(), Vec3::y());
        let q = |x: f64, y: f64, z: f64| closest_point_on_triangle(&Vec3::new(x, y, z), &a, &b, &c);
        assert!((q(0.2, 0.3, 5.0) - Vec3::new(0.2, 0.3, 0.0)).norm() < 1e-15);
        assert_eq!(q(-1.0, -1.0, 1.0), a);
        assert_eq!(q(2.0, -0.5, 0.0), b);
        assert_eq!(q(-0.1, 3.0, 0.0), c);
        assert_eq!(q(0.5, -2.0, 1.0), Vec3::new(0.5, 0.0, 0.0));
        assert_eq!(q(-2.0, 0.25, 0.0), Vec3::new(0.0, 0.25, 0.0));
        let on_hypotenuse = q(1.0, 1.0, 0.0);
        assert!((on_hypotenuse - Vec3::new(0.5, 0.5, 0.0)).norm() < 1e-15);
    }

    #[test]
    fn hierarchy_agrees_with_brute_force() {
        // A bumpy grid of triangles.
        let n = 12;
        let x: Vec<Vec3> = (0..=n)
            .flat_map(|j| (0..=n).map(move |i| (i, j)))
            .map(|(i, j)| {
                let (u, v) = (i as f64 / n as f64, j as f64 / n as f64);
                Vec3::new(u, v, 0.2 * (7.0 * u).sin() * (5.0 * v).cos())
            })
            .collect();
        let id = |i: usize, j: usize| i + (n + 1) * j;
        let tris: Vec<[usize; 3]> = (0..n)
            .flat_map(|j| (0..n).map(move |i| (i, j)))
            .flat_map(|(i, j)| {
                [
                    [id(i, j), id(i + 1, j), id(i + 1, j + 1)],
                    [id(i, j), id(i + 1, j + 1), id(i, j + 1)],
                ]
            })
            .collect();
        let bvh = TriangleBvh::new(&tris, &x);
        for s in 0..200 {
            let t = s as f64;
            let p = Vec3::new((t * 0.37).sin(), (t * 0.73).cos(), (t * 0.11).sin() * 0.5) * 1.3;
            let brute = tris
                .iter()
                .map(|&[a, b, c]| {
                    (closest_point_on_triangle(&p, &x[a], &x[b], &x[c]) - p).norm_squared()
                })
                .fold(f64::INFINITY, f64::min);
            let (_, d) = bvh.closest(&p).unwrap();
            assert_eq!(d, brute, "query {s}");
        }
        assert!(TriangleBvh::new(&[], &x).closest(&Vec3::zeros()).is_none());
    }
}
