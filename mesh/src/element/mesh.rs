//! A mesh of 4- or 10-node tetrahedra over a linear corner mesh: the corners keep their
//! vertex indices and the mid-edge nodes are numbered after them.

use super::gradient::{deformation_gradient, inverse_jacobian};
use super::{ElementSurface, RestGeometry, TetElement, TetQuadrature, TET_EDGES};
use crate::{MeshError, TetMesh, Vec3};

/// A mesh of [`TetElement`]s in its rest configuration.
///
/// `corners` is the linear mesh of the element corners, with all its rest data; node `i <
/// num_vertices` is its vertex `i` (so P1 fields live on the first `num_vertices` nodes) and
/// the mid-edge nodes of a 10-node mesh come after, one per edge shared by all the elements
/// around it. Element `e` lists `kind.num_nodes()` nodes in the local order of
/// [`TetElement`]; its first four are `corners.tets()[e]`.
///
/// Constructors guarantee that `det(dX/dxi)` is positive in every element at its nodes and
/// at the points of every [`TetQuadrature`] rule (a folded curved element is
/// [`MeshError::FoldedElement`]), so [`RestGeometry::new`] never fails on such a mesh.
#[derive(Debug, Clone)]
pub struct ElementMesh {
    kind: TetElement,
    corners: TetMesh,
    nodes: Vec<Vec3>,
    connectivity: Vec<usize>,
    edges: Vec<[usize; 2]>,
}

/// How errors of [`ElementMesh::from_nodes`] number nodes and elements: by the caller's labels
/// (a file's node and element tags), or else by their index in the input.
#[derive(Debug, Clone, Copy, Default)]
pub(crate) struct Labels<'a> {
    /// The label of each input node.
    pub nodes: Option<&'a [usize]>,
    /// The label of each input element.
    pub elements: Option<&'a [usize]>,
}

impl Labels<'_> {
    fn node(&self, i: usize) -> usize {
        self.nodes.and_then(|l| l.get(i).copied()).unwrap_or(i)
    }

    fn element(&self, e: usize) -> usize {
        self.elements.and_then(|l| l.get(e).copied()).unwrap_or(e)
    }
}

/// `[a, b]` sorted.
fn sorted([a, b]: [usize; 2]) -> [usize; 2] {
    if a < b {
        [a, b]
    } else {
        [b, a]
    }
}

/// What a node of the input of [`ElementMesh::from_nodes`] is used as.
#[derive(Clone, Copy, PartialEq, Eq)]
enum Role {
    Unused,
    Corner,
    Mid,
}

impl ElementMesh {
    /// The 4-node mesh of `mesh` (nodes are its vertices, elements its tets).
    pub fn linear(mesh: TetMesh) -> Self {
        ElementMesh {
            kind: TetElement::Tet4,
            nodes: mesh.positions().to_vec(),
            connectivity: mesh.tets().as_flattened().to_vec(),
            edges: Vec::new(),
            corners: mesh,
        }
    }

    /// The 10-node mesh of `mesh` with straight edges: one mid-edge node at the midpoint of
    /// every edge, numbered after the vertices in the order of the sorted edge `[a, b]`, `a <
    /// b`. The element maps are affine (those of `mesh`).
    pub fn quadratic(mesh: TetMesh) -> Self {
        let nv = mesh.num_vertices();
        let mut connectivity = Vec::with_capacity(10 * mesh.num_tets());
        // (sorted edge, slot of its mid-edge node in `connectivity`)
        let mut slots = Vec::with_capacity(6 * mesh.num_tets());
        for t in mesh.tets() {
            let start = connectivity.len();
            connectivity.extend_from_slice(t);
            connectivity.extend([0; 6]);
            for (k, [a, b]) in TET_EDGES.into_iter().enumerate() {
                slots.push((sorted([t[a], t[b]]), start + 4 + k));
            }
        }
        slots.sort_unstable();
        let mut edges = Vec::new();
        for run in slots.chunk_by(|a, b| a.0 == b.0) {
            run.iter()
                .for_each(|&(_, slot)| connectivity[slot] = nv + edges.len());
            edges.push(run[0].0);
        }
        let x = mesh.positions();
        let mut nodes = x.to_vec();
        nodes.extend(edges.iter().map(|&[a, b]| 0.5 * (x[a] + x[b])));
        ElementMesh {
            kind: TetElement::Tet10,
            corners: mesh,
            nodes,
            connectivity,
            edges,
        }
    }

    /// The 10-node mesh of `mesh` with its boundary on a curved surface: as
    /// [`ElementMesh::quadratic`], then the mid-edge node of every boundary edge `[a, b]` goes
    /// to `midpoint(x_a, x_b)` where that is `Some` (the generators' surfaces, such as
    /// [`crate::generate::cylinder_surface`], return the projection of the midpoint onto the
    /// curved surface when both ends lie on it). Interior mid-edge nodes stay at midpoints.
    ///
    /// Fails with [`MeshError::NonManifoldFace`] if the boundary is not a surface, or
    /// [`MeshError::FoldedElement`] if moving the nodes folds an element.
    pub fn quadratic_on_surface(
        mesh: TetMesh,
        midpoint: impl Fn(&Vec3, &Vec3) -> Option<Vec3>,
    ) -> Result<Self, MeshError> {
        let mut curved = Self::quadratic(mesh);
        let surface = ElementSurface::new(&curved)?;
        for f in 0..surface.len() {
            let face = surface.face(f);
            for k in 0..3 {
                let (a, b) = (face[k], face[(k + 1) % 3]);
                let x = &curved.nodes;
                if let Some(p) = midpoint(&x[a], &x[b]) {
                    curved.nodes[face[3 + k]] = p;
                }
            }
        }
        curved.check_jacobians()?;
        Ok(curved)
    }

    /// A mesh of `kind` elements from raw data (a file): `connectivity` lists
    /// `kind.num_nodes()` indices into `nodes` per element, in [`TetElement`]'s local order.
    ///
    /// Nodes are renumbered: the corners first, in input order, then the mid-edge nodes in
    /// input order; nodes no element uses are dropped. Negatively oriented elements are
    /// re-oriented like [`TetMesh::new`] does (corners 2 and 3 swapped), with their mid-edge
    /// nodes moved to the matching edges. Fails, naming the element, on an index out of range,
    /// a corner repeated or degenerate ([`TetMesh::new`]'s errors), a node that is a corner in
    /// one element and a mid-edge node in another, a mid-edge node on two different edges or
    /// two mid-edge nodes on one edge ([`MeshError::MidEdgeNode`]), or a folded element
    /// ([`MeshError::FoldedElement`]). Errors number nodes and elements as the input does
    /// (not as renumbered).
    pub fn from_nodes(
        kind: TetElement,
        nodes: Vec<Vec3>,
        connectivity: Vec<usize>,
    ) -> Result<Self, MeshError> {
        Self::from_labelled_nodes(kind, nodes, connectivity, Labels::default())
    }

    /// [`ElementMesh::from_nodes`] with errors that name nodes and elements by `labels`.
    pub(crate) fn from_labelled_nodes(
        kind: TetElement,
        nodes: Vec<Vec3>,
        connectivity: Vec<usize>,
        labels: Labels,
    ) -> Result<Self, MeshError> {
        let n = kind.num_nodes();
        if connectivity.is_empty() {
            return Err(MeshError::Empty);
        }
        if connectivity.len() % n != 0 {
            return Err(MeshError::parameter(
                "connectivity",
                connectivity.len(),
                format!("must hold {n} nodes per element"),
            ));
        }
        let mut role = vec![Role::Unused; nodes.len()];
        let mut first_use = vec![0; nodes.len()];
        for (e, element) in connectivity.chunks_exact(n).enumerate() {
            for (a, &index) in element.iter().enumerate() {
                let wanted = if a < 4 { Role::Corner } else { Role::Mid };
                let Some(r) = role.get_mut(index) else {
                    return Err(MeshError::IndexOutOfRange {
                        tet: labels.element(e),
                        index,
                        vertices: nodes.len(),
                    });
                };
                match *r {
                    Role::Unused => {
                        *r = wanted;
                        first_use[index] = e;
                    }
                    r if r != wanted => {
                        let (corner_in, mid_in) = if wanted == Role::Mid {
                            (first_use[index], e)
                        } else {
                            (e, first_use[index])
                        };
                        return Err(MeshError::MidEdgeNode {
                            element: labels.element(mid_in),
                            node: labels.node(index),
                            reason: format!(
                                "is a mid-edge node here and a corner of element {}",
                                labels.element(corner_in)
                            ),
                        });
                    }
                    _ => {}
                }
            }
        }
        // New index of every node: corners first, then mid-edge nodes, each in input order.
        let mut new_index = vec![usize::MAX; nodes.len()];
        let mut old_index = Vec::new();
        let mut positions = Vec::new();
        for pass in [Role::Corner, Role::Mid] {
            for (i, p) in nodes.iter().enumerate() {
                if role[i] == pass {
                    new_index[i] = positions.len();
                    old_index.push(i);
                    positions.push(*p);
                }
            }
        }
        // The label of a renumbered node.
        let label = |new: usize| labels.node(old_index[new]);
        let nv = role.iter().filter(|&&r| r == Role::Corner).count();
        let input: Vec<usize> = connectivity.iter().map(|&i| new_index[i]).collect();
        let tets: Vec<[usize; 4]> = input
            .chunks_exact(n)
            .map(|c| [c[0], c[1], c[2], c[3]])
            .collect();
        let corners = TetMesh::new(positions[..nv].to_vec(), tets).map_err(|e| match e {
            MeshError::RepeatedVertex {
                tet,
                vertex,
                indices,
            } => MeshError::RepeatedVertex {
                tet: labels.element(tet),
                vertex: label(vertex),
                indices: indices.map(label),
            },
            MeshError::Degenerate {
                tet,
                volume,
                threshold,
            } => MeshError::Degenerate {
                tet: labels.element(tet),
                volume,
                threshold,
            },
            MeshError::NonFiniteVertex { vertex, coords } => MeshError::NonFiniteVertex {
                vertex: label(vertex),
                coords,
            },
            other => other,
        })?;
        if kind == TetElement::Tet4 {
            return Ok(Self::linear(corners));
        }
        if let Some(vertex) = positions[nv..]
            .iter()
            .position(|p| !p.iter().all(|c| c.is_finite()))
        {
            let p = positions[nv + vertex];
            return Err(MeshError::NonFiniteVertex {
                vertex: label(nv + vertex),
                coords: [p.x, p.y, p.z],
            });
        }
        let mut edge_of = vec![None; positions.len() - nv];
        let mut mid_of = std::collections::HashMap::new();
        let mut connectivity = Vec::with_capacity(input.len());
        for (e, (given, t)) in input.chunks_exact(n).zip(corners.tets()).enumerate() {
            connectivity.extend_from_slice(t);
            for [a, b] in TET_EDGES {
                let edge = sorted([t[a], t[b]]);
                // The input's mid-edge node on the same two corners: re-orientation permuted
                // the corners, so `t` and `given[..4]` hold the same four distinct nodes and
                // the search always succeeds.
                let k = TET_EDGES
                    .iter()
                    .position(|&[i, j]| sorted([given[i], given[j]]) == edge)
                    .unwrap_or_default();
                let mid = given[4 + k];
                let mismatch = |reason: String| MeshError::MidEdgeNode {
                    element: labels.element(e),
                    node: label(mid),
                    reason,
                };
                match edge_of[mid - nv] {
                    None => edge_of[mid - nv] = Some((edge, e)),
                    Some((other, f)) if other != edge => {
                        return Err(mismatch(format!(
                            "lies on edge {:?} here but on edge {:?} in element {}",
                            edge.map(label),
                            other.map(label),
                            labels.element(f)
                        )))
                    }
                    _ => {}
                }
                match mid_of.insert(edge, (mid, e)) {
                    Some((other, f)) if other != mid => {
                        let (edge, f, other) = (edge.map(label), labels.element(f), label(other));
                        return Err(mismatch(format!(
                            "is a second mid-edge node of edge {edge:?}, whose node in element \
                             {f} is {other}"
                        )));
                    }
                    _ => {}
                }
                connectivity.push(mid);
            }
        }
        // Every mid-edge node is used by some element, so every entry is set.
        let edges = edge_of
            .into_iter()
            .map(|edge| edge.map_or([0, 0], |(edge, _)| edge))
            .collect();
        let mesh = ElementMesh {
            kind,
            corners,
            nodes: positions,
            connectivity,
            edges,
        };
        mesh.check_jacobians().map_err(|e| match e {
            MeshError::FoldedElement {
                element,
                point,
                determinant,
            } => MeshError::FoldedElement {
                element: labels.element(element),
                point,
                determinant,
            },
            other => other,
        })?;
        Ok(mesh)
    }

    /// Checks `det(dX/dxi) > 0` in every element at its nodes and at the points of every
    /// [`TetQuadrature`] rule.
    fn check_jacobians(&self) -> Result<(), MeshError> {
        let n = self.kind.num_nodes();
        let points = self.kind.check_points();
        let mut reference = vec![Vec3::zeros(); points.len() * n];
        for (xi, dn) in points.iter().zip(reference.chunks_exact_mut(n)) {
            self.kind.shape_gradients(xi, dn);
        }
        for e in 0..self.num_elements() {
            for (xi, dn) in points.iter().zip(reference.chunks_exact(n)) {
                inverse_jacobian(e, &self.nodes, self.element(e), xi, dn)?;
            }
        }
        Ok(())
    }

    /// The kind of every element.
    pub fn kind(&self) -> TetElement {
        self.kind
    }

    /// The linear mesh of the element corners, with its rest data and topology.
    pub fn corners(&self) -> &TetMesh {
        &self.corners
    }

    /// The linear mesh of the element corners, by value.
    pub fn into_corners(self) -> TetMesh {
        self.corners
    }

    /// Rest positions of all nodes: the corner vertices, then the mid-edge nodes.
    pub fn nodes(&self) -> &[Vec3] {
        &self.nodes
    }

    /// Number of nodes.
    pub fn num_nodes(&self) -> usize {
        self.nodes.len()
    }

    /// Number of corner vertices (the nodes of a P1 field).
    pub fn num_vertices(&self) -> usize {
        self.corners.num_vertices()
    }

    /// Number of elements.
    pub fn num_elements(&self) -> usize {
        self.corners.num_tets()
    }

    /// The nodes of every element, `kind.num_nodes()` per element.
    pub fn connectivity(&self) -> &[usize] {
        &self.connectivity
    }

    /// The nodes of element `e`.
    pub fn element(&self, e: usize) -> &[usize] {
        let n = self.kind.num_nodes();
        &self.connectivity[e * n..(e + 1) * n]
    }

    /// The corner pair `[a, b]`, `a < b`, of every mid-edge node: node `num_vertices + i` lies
    /// on edge `mid_edges()[i]` (empty for 4-node meshes).
    pub fn mid_edges(&self) -> &[[usize; 2]] {
        &self.edges
    }

    /// The rest geometry at the points of `rule`; see [`RestGeometry::new`].
    pub fn rest_geometry(&self, rule: TetQuadrature) -> Result<RestGeometry, MeshError> {
        RestGeometry::new(self, rule)
    }

    /// Total rest volume `sum_e sum_q w_q det(dX/dxi)(xi_q)` by the degree-5 rule: exact for
    /// the isoparametric geometry, whose `det(dX/dxi)` is a polynomial of degree at most 3
    /// (for 4-node tets, the corner mesh's volume).
    pub fn rest_volume(&self) -> f64 {
        if self.kind == TetElement::Tet4 {
            return self.corners.rest_volume();
        }
        let rule = TetQuadrature::Degree5;
        let n = self.kind.num_nodes();
        let mut dn = vec![Vec3::zeros(); n];
        let mut volume = 0.0;
        for (xi, w) in rule.points().iter().zip(rule.weights()) {
            self.kind.shape_gradients(xi, &mut dn);
            volume += w
                * (0..self.num_elements())
                    .map(|e| deformation_gradient(&self.nodes, self.element(e), &dn).determinant())
                    .sum::<f64>();
        }
        volume
    }

    /// The boundary surface of the mesh as 3- or 6-node triangles; see [`ElementSurface`].
    pub fn boundary(&self) -> Result<ElementSurface, MeshError> {
        ElementSurface::new(self)
    }
}

impl From<TetMesh> for ElementMesh {
    /// The 4-node mesh of `mesh` ([`ElementMesh::linear`]).
    fn from(mesh: TetMesh) -> Self {
        ElementMesh::linear(mesh)
    }
}
