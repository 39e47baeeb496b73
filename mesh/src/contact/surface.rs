//! The contact surface of a mesh: its boundary triangles, their unique edges and vertices,
//! all in the mesh's node indices. On 10-node tets each 6-node face is split into its four
//! 3-node triangles, whose vertices are all nodes (corners and mid-edge nodes), so contact
//! acts on every surface node.

use crate::element::TriElement;
use crate::{BoundarySurface, ElementSurface};

/// Triangles, edges and vertices on which contact acts; every index is a node of the mesh
/// (an index into the position vector the queries take).
#[derive(Debug, Clone, PartialEq)]
pub struct ContactSurface {
    triangles: Vec<[usize; 3]>,
    edges: Vec<[usize; 2]>,
    vertices: Vec<usize>,
}

impl ContactSurface {
    /// The surface of any triangles (e.g. a rigid obstacle's, open or closed); edges and
    /// vertices are collected sorted and unique, each edge as `[low, high]`.
    pub fn from_triangles(triangles: Vec<[usize; 3]>) -> Self {
        let mut edges: Vec<[usize; 2]> = triangles
            .iter()
            .flat_map(|t| [[t[0], t[1]], [t[1], t[2]], [t[2], t[0]]])
            .map(|[a, b]| [a.min(b), a.max(b)])
            .collect();
        edges.sort_unstable();
        edges.dedup();
        let mut vertices: Vec<usize> = triangles.as_flattened().to_vec();
        vertices.sort_unstable();
        vertices.dedup();
        ContactSurface {
            triangles,
            edges,
            vertices,
        }
    }

    /// The boundary triangles of a linear tet mesh (or of a set of its tets).
    pub fn from_boundary(surface: &BoundarySurface) -> Self {
        Self::from_triangles(surface.triangles().to_vec())
    }

    /// The boundary of an element mesh: its 3-node faces as they are, each 6-node face as
    /// the four triangles `(0, 3, 5), (3, 1, 4), (5, 4, 2), (3, 4, 5)` of its nodes (corners
    /// `0, 1, 2`, mid-edge nodes `3, 4, 5` of edges `(0,1), (1,2), (2,0)`), with the face's
    /// orientation.
    pub fn from_element_surface(surface: &ElementSurface) -> Self {
        let triangles = match surface.kind() {
            TriElement::Tri3 => surface.corners().triangles().to_vec(),
            TriElement::Tri6 => (0..surface.len())
                .flat_map(|f| {
                    let n = surface.face(f);
                    [[0, 3, 5], [3, 1, 4], [5, 4, 2], [3, 4, 5]].map(|t| t.map(|a| n[a]))
                })
                .collect(),
        };
        Self::from_triangles(triangles)
    }

    /// The triangles, as node triples.
    pub fn triangles(&self) -> &[[usize; 3]] {
        &self.triangles
    }

    /// The unique edges of the triangles, `[low, high]`, sorted.
    pub fn edges(&self) -> &[[usize; 2]] {
        &self.edges
    }

    /// The nodes of the triangles, sorted and unique.
    pub fn vertices(&self) -> &[usize] {
        &self.vertices
    }
}
