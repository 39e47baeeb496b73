//! The reference triangles: 3-node (linear) and 6-node (quadratic) Lagrange elements on the
//! unit triangle `{xi, eta >= 0, xi + eta <= 1}`, with Gmsh's node order. They are the faces
//! of the reference tetrahedra.

use super::lagrange;
use nalgebra::Vector2;

/// The corner pairs of the three edges, in Gmsh's order (the "Triangle6" diagram of the Gmsh
/// reference manual, section "Node ordering"; VTK's quadratic triangle, cell type 22, is the
/// same): the mid-edge node of edge `k` is local node `3 + k`.
pub const TRI_EDGES: [[usize; 2]; 3] = [[0, 1], [1, 2], [2, 0]];

/// The linear element's reference nodes.
const TRI3_NODES: [Vector2<f64>; 3] = [
    Vector2::new(0.0, 0.0),
    Vector2::new(1.0, 0.0),
    Vector2::new(0.0, 1.0),
];

/// The quadratic element's reference nodes: the corners, then the midpoints of [`TRI_EDGES`].
const TRI6_NODES: [Vector2<f64>; 6] = [
    Vector2::new(0.0, 0.0),
    Vector2::new(1.0, 0.0),
    Vector2::new(0.0, 1.0),
    Vector2::new(0.5, 0.0),
    Vector2::new(0.5, 0.5),
    Vector2::new(0.0, 0.5),
];

/// Gradients `d lambda_a / d xi` of the barycentric coordinates `(1 - xi - eta, xi, eta)`.
const BARYCENTRIC_GRADIENTS: [Vector2<f64>; 3] = [
    Vector2::new(-1.0, -1.0),
    Vector2::new(1.0, 0.0),
    Vector2::new(0.0, 1.0),
];

/// A reference triangle: corners `0..3` at `(0,0)`, `(1,0)`, `(0,1)`, then for
/// [`TriElement::Tri6`] the mid-edge nodes `3..6` on the edges `(0,1), (1,2), (2,0)` (Gmsh
/// element type 9).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum TriElement {
    /// The 3-node linear triangle: `N_a = lambda_a`.
    Tri3,
    /// The 6-node quadratic triangle: `N_a = lambda_a (2 lambda_a - 1)` at the corners and
    /// `N = 4 lambda_i lambda_j` on the edge `(i, j)`.
    Tri6,
}

impl TriElement {
    /// Number of nodes: 3 or 6.
    pub const fn num_nodes(self) -> usize {
        match self {
            TriElement::Tri3 => 3,
            TriElement::Tri6 => 6,
        }
    }

    /// Polynomial degree of the shape functions: 1 or 2.
    pub const fn order(self) -> usize {
        match self {
            TriElement::Tri3 => 1,
            TriElement::Tri6 => 2,
        }
    }

    /// Reference coordinates `xi` of the local nodes.
    pub fn node_coordinates(self) -> &'static [Vector2<f64>] {
        match self {
            TriElement::Tri3 => &TRI3_NODES,
            TriElement::Tri6 => &TRI6_NODES,
        }
    }

    /// Writes the shape functions `N_a(xi)` into `n[..num_nodes]`.
    pub fn shape_values(self, xi: &Vector2<f64>, n: &mut [f64]) {
        lagrange::values(self.order(), &barycentric(xi), &TRI_EDGES, n);
    }

    /// Writes the reference gradients `dN_a/dxi (xi)` into `dn[..num_nodes]` (the formulas of
    /// [`super::TetElement::shape_gradients`] with three barycentric coordinates).
    pub fn shape_gradients(self, xi: &Vector2<f64>, dn: &mut [Vector2<f64>]) {
        let l = barycentric(xi);
        lagrange::gradients(self.order(), &l, &BARYCENTRIC_GRADIENTS, &TRI_EDGES, dn);
    }
}

/// Barycentric coordinates `(1 - xi - eta, xi, eta)` of reference point `xi`.
fn barycentric(xi: &Vector2<f64>) -> [f64; 3] {
    [1.0 - xi.x - xi.y, xi.x, xi.y]
}
