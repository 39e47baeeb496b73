//! The boundary of an element mesh, or of a set of its elements, as 3- or 6-node triangles.

use super::gradient::deformation_gradient;
use super::{ElementMesh, TriElement, TriQuadrature};
use crate::{BoundarySurface, MeshError, Vec3};
use nalgebra::Vector2;

/// Outward boundary faces of a set of elements: the corner triangles of a
/// [`BoundarySurface`] (same order, owners and orientation), each with the nodes of its face
/// element ([`TriElement::Tri3`] or [`TriElement::Tri6`]: the corners, then the mid-edge
/// nodes of the edges `(0,1), (1,2), (2,0)`).
#[derive(Debug, Clone, PartialEq)]
pub struct ElementSurface {
    kind: TriElement,
    corners: BoundarySurface,
    faces: Vec<usize>,
}

impl ElementSurface {
    /// The boundary of the whole mesh; fails like [`BoundarySurface::new`].
    pub fn new(mesh: &ElementMesh) -> Result<Self, MeshError> {
        Ok(Self::with_corners(
            mesh,
            BoundarySurface::new(mesh.corners())?,
        ))
    }

    /// The boundary of the elements `elements` (a zone); fails like
    /// [`BoundarySurface::of_tets`].
    pub fn of_elements(mesh: &ElementMesh, elements: &[usize]) -> Result<Self, MeshError> {
        Ok(Self::with_corners(
            mesh,
            BoundarySurface::of_tets(mesh.corners(), elements)?,
        ))
    }

    fn with_corners(mesh: &ElementMesh, corners: BoundarySurface) -> Self {
        let kind = mesh.kind();
        let mut faces = Vec::with_capacity(corners.len() * kind.face_element().num_nodes());
        for (&e, &f) in corners.owner_tets().iter().zip(corners.owner_faces()) {
            let element = mesh.element(e);
            faces.extend(kind.face_nodes(f).iter().map(|&a| element[a]));
        }
        ElementSurface {
            kind: kind.face_element(),
            corners,
            faces,
        }
    }

    /// The kind of every face.
    pub fn kind(&self) -> TriElement {
        self.kind
    }

    /// The corner triangles, with their owners and rest areas.
    pub fn corners(&self) -> &BoundarySurface {
        &self.corners
    }

    /// Number of faces.
    pub fn len(&self) -> usize {
        self.corners.len()
    }

    /// Whether there is no face.
    pub fn is_empty(&self) -> bool {
        self.corners.is_empty()
    }

    /// The nodes of face `f`, in the local order of [`TriElement`].
    pub fn face(&self, f: usize) -> &[usize] {
        let n = self.kind.num_nodes();
        &self.faces[f * n..(f + 1) * n]
    }

    /// The nodes of every face, `kind.num_nodes()` per face.
    pub fn faces(&self) -> &[usize] {
        &self.faces
    }

    /// Sorted, duplicate-free indices of the nodes on the surface (corners and mid-edge
    /// nodes).
    pub fn nodes(&self) -> Vec<usize> {
        let mut nodes = self.faces.clone();
        nodes.sort_unstable();
        nodes.dedup();
        nodes
    }

    /// Volume enclosed by the surface at node positions `x`, by the divergence theorem (see
    /// `faces_enclosed_volume`): on a mesh's own boundary it equals the volume of the
    /// elements ([`super::ElementMesh::rest_volume`] at rest).
    pub fn enclosed_volume(&self, x: &[Vec3]) -> f64 {
        faces_enclosed_volume(self.kind, &self.faces, x)
    }
}

/// `(1/3) sum_f integral of x . n dA` over faces of `kind` (`faces` holds `kind.num_nodes()`
/// nodes per face), with `n dA = (dx/dxi x dx/deta) dxi deta` on the isoparametric face: the
/// volume the faces enclose when they form a closed surface, positive if they point out of
/// it. The integrand has degree `3p - 2` for faces of degree `p`, so the rule of that degree
/// makes this exact.
pub(crate) fn faces_enclosed_volume(kind: TriElement, faces: &[usize], x: &[Vec3]) -> f64 {
    let rule = match kind {
        TriElement::Tri3 => TriQuadrature::Degree1,
        TriElement::Tri6 => TriQuadrature::Degree4,
    };
    let n = kind.num_nodes();
    let mut values = vec![0.0; n];
    let mut gradients = vec![Vector2::zeros(); n];
    let mut volume = 0.0;
    for (xi, w) in rule.points().iter().zip(rule.weights()) {
        kind.shape_values(xi, &mut values);
        kind.shape_gradients(xi, &mut gradients);
        for face in faces.chunks_exact(n) {
            let position: Vec3 = face.iter().zip(&values).map(|(&i, v)| *v * x[i]).sum();
            let tangents = deformation_gradient(x, face, &gradients);
            let normal = tangents.column(0).cross(&tangents.column(1));
            volume += w * position.dot(&normal);
        }
    }
    volume / 3.0
}
