//! The broad phase: point-triangle and edge-edge pairs of a contact surface whose boxes
//! overlap, at one state grown by the barrier's reach `dhat` (the pairs the barrier may see)
//! or swept over a step (the pairs the CCD must check), by the spatial hash of
//! [`super::hash_grid`].

use super::aabb::Aabb;
use super::hash_grid::overlapping_pairs;
use super::surface::ContactSurface;
use crate::Vec3;

/// Which pairs of primitives may touch.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum PairFilter<'a> {
    /// Every pair that shares no node: contact between bodies and of a surface with itself.
    All,
    /// Only pairs between different bodies: `bodies[n]` is the body of node `n`.
    BetweenBodies(&'a [usize]),
}

/// Candidate pairs of a contact surface.
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub struct Candidates {
    /// `[node, triangle]`: a surface node and an index into
    /// [`ContactSurface::triangles`], sorted.
    pub point_triangle: Vec<[usize; 2]>,
    /// `[edge, edge]`: two indices into [`ContactSurface::edges`], the first smaller, sorted.
    pub edge_edge: Vec<[usize; 2]>,
}

impl Candidates {
    /// The number of pairs.
    pub fn len(&self) -> usize {
        self.point_triangle.len() + self.edge_edge.len()
    }

    /// Whether there is no pair.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }
}

/// The candidate pairs of `surface` at node positions `x`: the primitives whose boxes,
/// grown by `inflation / 2` each (so pairs closer than `inflation` in every coordinate meet),
/// overlap; with `x1`, the boxes are swept from `x` to `x1`. Pairs sharing a node are left
/// out, and `filter` can keep only pairs between bodies.
pub fn contact_candidates(
    surface: &ContactSurface,
    x: &[Vec3],
    x1: Option<&[Vec3]>,
    inflation: f64,
    filter: PairFilter,
) -> Candidates {
    let margin = 0.5 * inflation;
    let boxes = |nodes: &mut dyn Iterator<Item = &[usize]>| -> Vec<Aabb> {
        nodes.map(|n| Aabb::of_nodes(n, x, x1, margin)).collect()
    };
    let vertices = surface.vertices();
    let point_boxes = boxes(&mut vertices.chunks(1));
    let triangle_boxes = boxes(&mut surface.triangles().iter().map(|t| t.as_slice()));
    let edge_boxes = boxes(&mut surface.edges().iter().map(|e| e.as_slice()));
    let apart = |a: &[usize], b: &[usize]| match filter {
        PairFilter::All => true,
        PairFilter::BetweenBodies(bodies) => bodies[a[0]] != bodies[b[0]],
    };
    let point_triangle = overlapping_pairs(&point_boxes, Some(&triangle_boxes))
        .into_iter()
        .map(|[v, t]| [vertices[v], t])
        .filter(|&[v, t]| {
            let tri = &surface.triangles()[t];
            !tri.contains(&v) && apart(&[v], tri)
        })
        .collect();
    let edges = surface.edges();
    let edge_edge = overlapping_pairs(&edge_boxes, None)
        .into_iter()
        .filter(|&[i, j]| {
            let (a, b) = (&edges[i], &edges[j]);
            !a.iter().any(|n| b.contains(n)) && apart(a, b)
        })
        .collect();
    Candidates {
        point_triangle,
        edge_edge,
    }
}
