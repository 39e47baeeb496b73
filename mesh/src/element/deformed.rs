//! An element mesh at deformed node positions: element volumes, the sign of the element
//! map's Jacobian (inversion) and the face elements of corner triangles, for loads, probes
//! and output.

use super::gradient::deformation_gradient;
use super::{ElementMesh, TetElement, TetQuadrature, TRI_EDGES};
use crate::{MeshError, Vec3};
use std::collections::HashMap;

/// Reference shape gradients of `kind` at `points`, `kind.num_nodes()` per point.
fn reference_gradients(kind: TetElement, points: &[Vec3]) -> Vec<Vec3> {
    let n = kind.num_nodes();
    let mut dn = vec![Vec3::zeros(); points.len() * n];
    for (xi, g) in points.iter().zip(dn.chunks_exact_mut(n)) {
        kind.shape_gradients(xi, g);
    }
    dn
}

impl ElementMesh {
    /// Volume of every element at node positions `x`: `integral det(dx/dxi) dxi` by the
    /// degree-5 rule, exact since `det(dx/dxi)` is a polynomial of degree at most 3 (for a
    /// 4-node tet, the signed volume of its corners).
    pub fn volumes_at(&self, x: &[Vec3]) -> Vec<f64> {
        if self.kind() == TetElement::Tet4 {
            let corners = self.corners();
            return (0..self.num_elements())
                .map(|e| corners.volume_at(e, x))
                .collect();
        }
        let rule = TetQuadrature::Degree5;
        let n = self.kind().num_nodes();
        let dn = reference_gradients(self.kind(), rule.points());
        (0..self.num_elements())
            .map(|e| {
                let nodes = self.element(e);
                dn.chunks_exact(n)
                    .zip(rule.weights())
                    .map(|(g, w)| w * deformation_gradient(x, nodes, g).determinant())
                    .sum()
            })
            .collect()
    }

    /// Total volume at node positions `x` (see [`ElementMesh::volumes_at`]).
    pub fn total_volume_at(&self, x: &[Vec3]) -> f64 {
        self.volumes_at(x).iter().sum()
    }

    /// Number of elements whose map `dx/dxi` at node positions `x` has a non-positive
    /// determinant at one of its nodes or at a point of any [`TetQuadrature`] rule (the
    /// points where the constructors check the rest geometry; for a 4-node tet, a
    /// non-positive volume).
    pub fn count_inverted(&self, x: &[Vec3]) -> usize {
        if self.kind() == TetElement::Tet4 {
            return self.corners().count_inverted(x);
        }
        let n = self.kind().num_nodes();
        let dn = reference_gradients(self.kind(), &self.kind().check_points());
        (0..self.num_elements())
            .filter(|&e| {
                let nodes = self.element(e);
                dn.chunks_exact(n)
                    .any(|g| deformation_gradient(x, nodes, g).determinant() <= 0.0)
            })
            .count()
    }

    /// Whether every mid-edge node sits at its edge's midpoint (to rounding), so that every
    /// element map is affine (true for 4-node meshes).
    pub fn is_affine(&self) -> bool {
        let x = self.nodes();
        let nv = self.num_vertices();
        self.mid_edges().iter().enumerate().all(|(i, &[a, b])| {
            let length = (x[b] - x[a]).norm();
            (x[nv + i] - 0.5 * (x[a] + x[b])).norm() <= 1e-12 * length
        })
    }

    /// The face elements of corner triangles of the mesh (for example a selection of boundary
    /// faces): for each, its corners, then for a 10-node mesh the mid-edge nodes of its edges
    /// `(0,1), (1,2), (2,0)` (the order of [`super::TriElement`]). Fails with
    /// [`MeshError::MidEdgeNode`] naming the face if one of its edges is not an edge of the
    /// mesh.
    pub fn face_elements(&self, triangles: &[[usize; 3]]) -> Result<Vec<usize>, MeshError> {
        if self.kind() == TetElement::Tet4 {
            return Ok(triangles.as_flattened().to_vec());
        }
        let nv = self.num_vertices();
        let mid: HashMap<[usize; 2], usize> = self
            .mid_edges()
            .iter()
            .enumerate()
            .map(|(i, &edge)| (edge, nv + i))
            .collect();
        let mut faces = Vec::with_capacity(6 * triangles.len());
        for (f, t) in triangles.iter().enumerate() {
            faces.extend_from_slice(t);
            for [a, b] in TRI_EDGES {
                let edge = [t[a].min(t[b]), t[a].max(t[b])];
                let node = mid.get(&edge).ok_or_else(|| MeshError::MidEdgeNode {
                    element: f,
                    node: edge[0],
                    reason: format!("face {t:?}: edge {edge:?} is not an edge of the mesh"),
                })?;
                faces.push(*node);
            }
        }
        Ok(faces)
    }
}
