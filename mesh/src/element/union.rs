//! Several meshes as one: the disjoint union of element meshes of one kind (the bodies of a
//! scene), with where each part's vertices, mid-edge nodes and elements went.

use super::ElementMesh;
use crate::{MeshError, Vec3};
use std::ops::Range;

/// Where one part of a [`ElementMesh::disjoint_union`] lies in the union.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Part {
    /// Its vertices (corner nodes), a range of the union's vertices.
    pub vertices: Range<usize>,
    /// Its mid-edge nodes (empty for 4-node meshes), a range of the union's nodes.
    pub mid_edge_nodes: Range<usize>,
    /// Its elements.
    pub elements: Range<usize>,
}

impl Part {
    /// Whether node `node` of the union belongs to this part.
    pub fn has_node(&self, node: usize) -> bool {
        self.vertices.contains(&node) || self.mid_edge_nodes.contains(&node)
    }

    /// Every node of the part: its vertices, then its mid-edge nodes.
    pub fn nodes(&self) -> impl Iterator<Item = usize> + '_ {
        self.vertices.clone().chain(self.mid_edge_nodes.clone())
    }
}

impl ElementMesh {
    /// The same mesh with every node moved by `map` (a rigid placement keeps every element's
    /// orientation; a map that folds an element is the constructor's error).
    pub fn mapped(&self, map: impl Fn(&Vec3) -> Vec3) -> Result<ElementMesh, MeshError> {
        ElementMesh::from_nodes(
            self.kind(),
            self.nodes().iter().map(map).collect(),
            self.connectivity().to_vec(),
        )
    }

    /// The disjoint union of `parts` (all of one kind; none shares a node with another):
    /// the vertices of every part in order, then the mid-edge nodes of every part in order,
    /// then the elements in order; with each part's ranges in the union. A single part is
    /// returned as it is.
    pub fn disjoint_union(parts: Vec<ElementMesh>) -> Result<(ElementMesh, Vec<Part>), MeshError> {
        let Some(kind) = parts.first().map(ElementMesh::kind) else {
            return Err(MeshError::Empty);
        };
        if let Some(other) = parts.iter().find(|p| p.kind() != kind) {
            return Err(MeshError::parameter(
                "parts",
                other.kind().num_nodes(),
                format!("every part must be of {}-node tets", kind.num_nodes()),
            ));
        }
        let num_vertices: usize = parts.iter().map(ElementMesh::num_vertices).sum();
        let (mut vertex, mut mid, mut element) = (0, num_vertices, 0);
        let layout: Vec<Part> = parts
            .iter()
            .map(|p| {
                let mids = p.num_nodes() - p.num_vertices();
                let part = Part {
                    vertices: vertex..vertex + p.num_vertices(),
                    mid_edge_nodes: mid..mid + mids,
                    elements: element..element + p.num_elements(),
                };
                (vertex, mid, element) = (
                    part.vertices.end,
                    part.mid_edge_nodes.end,
                    part.elements.end,
                );
                part
            })
            .collect();
        if parts.len() == 1 {
            let only = parts.into_iter().next().expect("one part");
            return Ok((only, layout));
        }
        // `from_nodes` numbers the corners first in input order, then the mid-edge nodes in
        // input order: the parts' nodes concatenated land exactly on the ranges above.
        let mut nodes = Vec::new();
        let mut connectivity = Vec::new();
        for p in &parts {
            let offset = nodes.len();
            nodes.extend_from_slice(p.nodes());
            connectivity.extend(p.connectivity().iter().map(|&n| n + offset));
        }
        let union = ElementMesh::from_nodes(kind, nodes, connectivity)?;
        debug_assert_eq!(union.num_vertices(), num_vertices);
        Ok((union, layout))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::element::TetElement;
    use crate::generate::box_grid;

    fn cube(offset: f64, kind: TetElement) -> ElementMesh {
        let grid = box_grid(
            Vec3::new(offset, 0.0, 0.0),
            Vec3::new(offset + 1.0, 1.0, 1.0),
            [1, 1, 1],
        )
        .unwrap();
        match kind {
            TetElement::Tet4 => ElementMesh::linear(grid),
            TetElement::Tet10 => ElementMesh::quadratic(grid),
        }
    }

    #[test]
    fn the_union_keeps_each_part_in_its_ranges() {
        for kind in [TetElement::Tet4, TetElement::Tet10] {
            let (a, b) = (cube(0.0, kind), cube(2.0, kind));
            let (union, parts) = ElementMesh::disjoint_union(vec![a.clone(), b.clone()]).unwrap();
            assert_eq!(union.num_nodes(), a.num_nodes() + b.num_nodes());
            assert_eq!(union.num_elements(), a.num_elements() + b.num_elements());
            for (part, mesh) in parts.iter().zip([&a, &b]) {
                for (local, e) in part.elements.clone().enumerate() {
                    let nodes: Vec<Vec3> =
                        union.element(e).iter().map(|&n| union.nodes()[n]).collect();
                    let expected: Vec<Vec3> = mesh
                        .element(local)
                        .iter()
                        .map(|&n| mesh.nodes()[n])
                        .collect();
                    assert_eq!(nodes, expected);
                    assert!(union.element(e).iter().all(|&n| part.has_node(n)));
                }
            }
            assert!((union.rest_volume() - 2.0).abs() < 1e-12);
        }
    }

    #[test]
    fn a_rigid_map_keeps_the_volume_and_a_mixed_union_is_refused() {
        let a = cube(0.0, TetElement::Tet10);
        let turned = a
            .mapped(|x| Vec3::new(-x.y, x.x, x.z) + Vec3::new(5.0, 0.0, 0.0))
            .unwrap();
        assert!((turned.rest_volume() - 1.0).abs() < 1e-12);
        assert!(ElementMesh::disjoint_union(vec![a, cube(3.0, TetElement::Tet4)]).is_err());
        assert!(ElementMesh::disjoint_union(Vec::new()).is_err());
    }
}
