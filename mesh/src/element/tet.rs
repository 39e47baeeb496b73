//! The reference tetrahedra: 4-node (linear) and 10-node (quadratic) Lagrange elements on the
//! unit tetrahedron `{xi, eta, zeta >= 0, xi + eta + zeta <= 1}`, with Gmsh's node order.

use super::{lagrange, TriElement};
use crate::{Vec3, TET_FACES};

/// The corner pairs of the six edges, in Gmsh's order (the "Tetrahedron10" diagram of the Gmsh
/// reference manual, section "Node ordering"): the mid-edge node of edge `k` is local node
/// `4 + k`.
pub const TET_EDGES: [[usize; 2]; 6] = [[0, 1], [1, 2], [0, 2], [0, 3], [2, 3], [1, 3]];

/// The six local nodes of each face of a 10-node tet: the three corners of [`TET_FACES`] (face
/// `f` opposite corner `f`, outward right-hand normal), then the mid-edge nodes of the face's
/// edges `(c0, c1)`, `(c1, c2)`, `(c2, c0)`, which is the node order of the 6-node triangle.
const TET10_FACES: [[usize; 6]; 4] = [
    [1, 2, 3, 5, 8, 9],
    [0, 3, 2, 7, 8, 6],
    [0, 1, 3, 4, 9, 7],
    [0, 2, 1, 6, 5, 4],
];

/// Local node `k` of a VTK quadratic tetra (cell type 24) is local node `TET10_VTK_ORDER[k]`
/// of ours, and conversely (the permutation is its own inverse). VTK's mid-edge nodes lie on
/// the edges `(0,1), (1,2), (2,0), (0,3), (1,3), (2,3)` (`vtkQuadraticTetra`): the last two are
/// Gmsh's in swapped order.
const TET10_VTK_ORDER: [usize; 10] = [0, 1, 2, 3, 4, 5, 6, 7, 9, 8];

/// The linear element's reference nodes: the corners of the unit tetrahedron.
const TET4_NODES: [Vec3; 4] = [
    Vec3::new(0.0, 0.0, 0.0),
    Vec3::new(1.0, 0.0, 0.0),
    Vec3::new(0.0, 1.0, 0.0),
    Vec3::new(0.0, 0.0, 1.0),
];

/// The quadratic element's reference nodes: the corners, then the midpoints of [`TET_EDGES`].
const TET10_NODES: [Vec3; 10] = [
    Vec3::new(0.0, 0.0, 0.0),
    Vec3::new(1.0, 0.0, 0.0),
    Vec3::new(0.0, 1.0, 0.0),
    Vec3::new(0.0, 0.0, 1.0),
    Vec3::new(0.5, 0.0, 0.0),
    Vec3::new(0.5, 0.5, 0.0),
    Vec3::new(0.0, 0.5, 0.0),
    Vec3::new(0.0, 0.0, 0.5),
    Vec3::new(0.0, 0.5, 0.5),
    Vec3::new(0.5, 0.0, 0.5),
];

/// Gradients `d lambda_a / d xi` of the barycentric coordinates
/// `lambda = (1 - xi - eta - zeta, xi, eta, zeta)`.
const BARYCENTRIC_GRADIENTS: [Vec3; 4] = [
    Vec3::new(-1.0, -1.0, -1.0),
    Vec3::new(1.0, 0.0, 0.0),
    Vec3::new(0.0, 1.0, 0.0),
    Vec3::new(0.0, 0.0, 1.0),
];

/// A reference tetrahedron. Kernels take the kind at run time, so a 4-node tet is the
/// 4-node case of the same code path as the 10-node one.
///
/// Local nodes are the corners `0..4` (at `(0,0,0)`, `(1,0,0)`, `(0,1,0)`, `(0,0,1)`), then for
/// [`TetElement::Tet10`] the mid-edge nodes `4..10` on [`TET_EDGES`] in Gmsh's order (element
/// type 11): on the edges `(0,1), (1,2), (0,2), (0,3), (2,3), (1,3)`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum TetElement {
    /// The 4-node linear tet: `N_a = lambda_a`.
    Tet4,
    /// The 10-node quadratic tet: `N_a = lambda_a (2 lambda_a - 1)` at the corners and
    /// `N = 4 lambda_i lambda_j` on the edge `(i, j)`, the standard quadratic tetrahedron
    /// (Zienkiewicz, Taylor and Zhu, "The Finite Element Method: Its Basis and Fundamentals",
    /// 6th ed., 2005).
    Tet10,
}

impl TetElement {
    /// Both elements, linear first.
    pub const ALL: [TetElement; 2] = [TetElement::Tet4, TetElement::Tet10];

    /// The name used by scenes and the command line: `"tet4"` or `"tet10"`.
    pub const fn name(self) -> &'static str {
        match self {
            TetElement::Tet4 => "tet4",
            TetElement::Tet10 => "tet10",
        }
    }

    /// The element named `name` (see [`TetElement::name`]).
    pub fn from_name(name: &str) -> Option<Self> {
        Self::ALL.into_iter().find(|e| e.name() == name)
    }

    /// The reference points where an element map's `det(dX/dxi)` is checked for folding or
    /// inversion: the element's nodes and the points of every [`super::TetQuadrature`] rule.
    pub fn check_points(self) -> Vec<Vec3> {
        self.node_coordinates()
            .iter()
            .chain(
                super::TetQuadrature::ALL
                    .iter()
                    .flat_map(|rule| rule.points()),
            )
            .copied()
            .collect()
    }

    /// Number of nodes: 4 or 10.
    pub const fn num_nodes(self) -> usize {
        match self {
            TetElement::Tet4 => 4,
            TetElement::Tet10 => 10,
        }
    }

    /// Polynomial degree of the shape functions: 1 or 2.
    pub const fn order(self) -> usize {
        match self {
            TetElement::Tet4 => 1,
            TetElement::Tet10 => 2,
        }
    }

    /// The element of the same order on each face: [`TriElement::Tri3`] or
    /// [`TriElement::Tri6`].
    pub const fn face_element(self) -> TriElement {
        match self {
            TetElement::Tet4 => TriElement::Tri3,
            TetElement::Tet10 => TriElement::Tri6,
        }
    }

    /// Reference coordinates `xi` of the local nodes.
    pub fn node_coordinates(self) -> &'static [Vec3] {
        match self {
            TetElement::Tet4 => &TET4_NODES,
            TetElement::Tet10 => &TET10_NODES,
        }
    }

    /// The local nodes of face `f` (`0..4`, opposite corner `f`), in the node order of
    /// [`TetElement::face_element`] and with the outward right-hand normal of [`TET_FACES`].
    pub fn face_nodes(self, f: usize) -> &'static [usize] {
        match self {
            TetElement::Tet4 => &TET_FACES[f],
            TetElement::Tet10 => &TET10_FACES[f],
        }
    }

    /// VTK's node order (cell type 10 or 24): VTK local node `k` is our local node
    /// `vtk_order()[k]`, and conversely.
    pub fn vtk_order(self) -> &'static [usize] {
        match self {
            TetElement::Tet4 => &TET10_VTK_ORDER[..4],
            TetElement::Tet10 => &TET10_VTK_ORDER,
        }
    }

    /// Writes the shape functions `N_a(xi)` into `n[..num_nodes]`.
    pub fn shape_values(self, xi: &Vec3, n: &mut [f64]) {
        lagrange::values(self.order(), &barycentric(xi), &TET_EDGES, n);
    }

    /// Writes the reference gradients `dN_a/dxi (xi)` into `dn[..num_nodes]`:
    /// `grad lambda_a` (4 nodes), or `(4 lambda_a - 1) grad lambda_a` at the corners and
    /// `4 (lambda_j grad lambda_i + lambda_i grad lambda_j)` on the edges (10 nodes).
    pub fn shape_gradients(self, xi: &Vec3, dn: &mut [Vec3]) {
        let l = barycentric(xi);
        lagrange::gradients(self.order(), &l, &BARYCENTRIC_GRADIENTS, &TET_EDGES, dn);
    }
}

/// Barycentric coordinates `(1 - xi - eta - zeta, xi, eta, zeta)` of reference point `xi`.
fn barycentric(xi: &Vec3) -> [f64; 4] {
    [1.0 - xi.x - xi.y - xi.z, xi.x, xi.y, xi.z]
}
