//! Rest geometry at the quadrature points of every element: the volume weights
//! `w_q det(dX/dxi)` and the rest-space shape gradients `dN_a/dX` of the isoparametric map.

use super::gradient::inverse_jacobian;
use super::{ElementMesh, TetElement, TetQuadrature};
use crate::{MeshError, Vec3};

/// The isoparametric rest geometry of an [`ElementMesh`] at the points of one quadrature rule.
///
/// The element map is `X(xi) = sum_a X_a N_a(xi)` over the element's nodes, so that
/// `dX/dxi = sum_a X_a (dN_a/dxi)^T`, the volume element is `dV = det(dX/dxi) dxi` and
/// `dN_a/dX = (dX/dxi)^-T dN_a/dxi`. On a straight-sided element (every mid-edge node at its
/// edge's midpoint) the map is affine: `det(dX/dxi) = 6 V_e` and `dN_a/dX` of a 4-node tet
/// is constant, the columns of `D_m^-T [-1 -1 -1; I]`.
#[derive(Debug, Clone)]
pub struct RestGeometry {
    kind: TetElement,
    rule: TetQuadrature,
    values: Vec<f64>,
    weights: Vec<f64>,
    gradients: Vec<Vec3>,
}

impl RestGeometry {
    /// Evaluates the rest geometry of every element at the points of `rule`. An element whose
    /// `det(dX/dxi)` is not positive at a point is [`MeshError::FoldedElement`] (cannot happen
    /// for a mesh built by an [`ElementMesh`] constructor, which checks every rule's points).
    pub fn new(mesh: &ElementMesh, rule: TetQuadrature) -> Result<Self, MeshError> {
        let kind = mesh.kind();
        let n = kind.num_nodes();
        let q_count = rule.num_points();
        let mut values = vec![0.0; q_count * n];
        let mut reference = vec![Vec3::zeros(); q_count * n];
        for (q, xi) in rule.points().iter().enumerate() {
            kind.shape_values(xi, &mut values[q * n..]);
            kind.shape_gradients(xi, &mut reference[q * n..]);
        }
        let mut weights = Vec::with_capacity(mesh.num_elements() * q_count);
        let mut gradients = Vec::with_capacity(mesh.num_elements() * q_count * n);
        for e in 0..mesh.num_elements() {
            let nodes = mesh.element(e);
            for (q, (xi, w)) in rule.points().iter().zip(rule.weights()).enumerate() {
                let dn = &reference[q * n..(q + 1) * n];
                let (det, inverse) = inverse_jacobian(e, mesh.nodes(), nodes, xi, dn)?;
                weights.push(w * det);
                gradients.extend(dn.iter().map(|g| inverse.tr_mul(g)));
            }
        }
        Ok(RestGeometry {
            kind,
            rule,
            values,
            weights,
            gradients,
        })
    }

    /// The rule whose points these are.
    pub fn rule(&self) -> TetQuadrature {
        self.rule
    }

    /// Number of quadrature points per element.
    pub fn num_points(&self) -> usize {
        self.rule.num_points()
    }

    /// The shape functions `N_a(xi_q)` at point `q` (the same in every element).
    pub fn shape_values(&self, q: usize) -> &[f64] {
        let n = self.kind.num_nodes();
        &self.values[q * n..(q + 1) * n]
    }

    /// The rest volume weight `w_q det(dX/dxi)(xi_q)` of point `q` of element `e`.
    pub fn weight(&self, e: usize, q: usize) -> f64 {
        self.weights[e * self.num_points() + q]
    }

    /// The rest-space shape gradients `dN_a/dX` at point `q` of element `e`, one per node of
    /// the element, for [`super::deformation_gradient`].
    pub fn gradients(&self, e: usize, q: usize) -> &[Vec3] {
        let n = self.kind.num_nodes();
        let start = (e * self.num_points() + q) * n;
        &self.gradients[start..start + n]
    }

    /// The weights of every point of element `e`, [`RestGeometry::weight`] for `q` in order.
    pub fn element_weights(&self, e: usize) -> &[f64] {
        let nq = self.num_points();
        &self.weights[e * nq..(e + 1) * nq]
    }

    /// The shape gradients of every point of element `e`, [`RestGeometry::gradients`] for `q`
    /// in order (point-major, `kind.num_nodes()` per point).
    pub fn element_gradients(&self, e: usize) -> &[Vec3] {
        let n = self.kind.num_nodes() * self.num_points();
        &self.gradients[e * n..(e + 1) * n]
    }

    /// Rest volume of element `e` by this rule: `sum_q w_q det(dX/dxi)(xi_q)`.
    pub fn element_volume(&self, e: usize) -> f64 {
        self.element_weights(e).iter().sum()
    }

    /// Total rest volume by this rule.
    pub fn volume(&self) -> f64 {
        self.weights.iter().sum()
    }
}
