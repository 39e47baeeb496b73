//! Face elements of the surface terms (traction, follower pressure, epidermis): 3- or 6-node
//! triangles with the quadrature rule they are integrated with and its reference shape
//! functions.

use crate::error::SolverError;
use isochor_mesh::element::{TriElement, TriQuadrature};
use isochor_mesh::{ElementMesh, Vec3};
use nalgebra::Vector2;

/// Face elements and their quadrature: the one-point rule on 3-node triangles (exact for
/// their constant area element), the degree-4 rule on 6-node ones (exact for the enclosed
/// volume of a curved face, whose integrand has degree 4, and for `integral N_a dA` on a
/// flat one).
#[derive(Debug, Clone)]
pub struct Faces {
    kind: TriElement,
    nodes: Vec<usize>,
    rule: TriQuadrature,
    values: Vec<f64>,
    gradients: Vec<Vector2<f64>>,
}

impl Faces {
    /// The face elements of the corner triangles `triangles` of `mesh` (see
    /// [`ElementMesh::face_elements`]).
    pub fn new(mesh: &ElementMesh, triangles: &[[usize; 3]]) -> Result<Self, SolverError> {
        let kind = mesh.kind().face_element();
        let nodes = mesh.face_elements(triangles)?;
        Ok(Self::from_nodes(kind, nodes))
    }

    /// Face elements of `kind` with `kind.num_nodes()` nodes each in `nodes`.
    pub fn from_nodes(kind: TriElement, nodes: Vec<usize>) -> Self {
        let rule = match kind {
            TriElement::Tri3 => TriQuadrature::Degree1,
            TriElement::Tri6 => TriQuadrature::Degree4,
        };
        let n = kind.num_nodes();
        let mut values = vec![0.0; rule.num_points() * n];
        let mut gradients = vec![Vector2::zeros(); rule.num_points() * n];
        for (q, xi) in rule.points().iter().enumerate() {
            kind.shape_values(xi, &mut values[q * n..(q + 1) * n]);
            kind.shape_gradients(xi, &mut gradients[q * n..(q + 1) * n]);
        }
        Faces {
            kind,
            nodes,
            rule,
            values,
            gradients,
        }
    }

    /// Number of faces.
    pub fn len(&self) -> usize {
        self.nodes.len() / self.kind.num_nodes()
    }

    /// Whether there are no faces.
    pub fn is_empty(&self) -> bool {
        self.nodes.is_empty()
    }

    /// Nodes per face.
    pub fn nodes_per_face(&self) -> usize {
        self.kind.num_nodes()
    }

    /// The nodes of face `f`.
    pub fn face(&self, f: usize) -> &[usize] {
        let n = self.kind.num_nodes();
        &self.nodes[f * n..(f + 1) * n]
    }

    /// Every face's nodes, in order.
    pub fn iter(&self) -> impl Iterator<Item = &[usize]> {
        self.nodes.chunks_exact(self.kind.num_nodes())
    }

    /// The rule's weights `w_q` (adding up to 1/2).
    pub fn weights(&self) -> &[f64] {
        self.rule.weights()
    }

    /// Shape values `N_a(xi_q)` at point `q`.
    pub fn values(&self, q: usize) -> &[f64] {
        let n = self.kind.num_nodes();
        &self.values[q * n..(q + 1) * n]
    }

    /// Reference shape gradients `dN_a/dxi` at point `q`.
    pub fn gradients(&self, q: usize) -> &[Vector2<f64>] {
        let n = self.kind.num_nodes();
        &self.gradients[q * n..(q + 1) * n]
    }

    /// Reference shape gradients of every point, point-major.
    pub fn all_gradients(&self) -> &[Vector2<f64>] {
        &self.gradients
    }

    /// `integral N_a dA` over every face at positions `x`, as `(node, value)` pairs.
    pub fn node_areas(&self, x: &[Vec3]) -> Vec<(usize, f64)> {
        let mut out = Vec::with_capacity(self.nodes.len());
        for face in self.iter() {
            let start = out.len();
            out.extend(face.iter().map(|&a| (a, 0.0)));
            for (q, w) in self.weights().iter().enumerate() {
                let area = isochor_energies::triangle::area_element(x, face, self.gradients(q));
                for (slot, n) in out[start..].iter_mut().zip(self.values(q)) {
                    slot.1 += w * area * n;
                }
            }
        }
        out
    }
}
