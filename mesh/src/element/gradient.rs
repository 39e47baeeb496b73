//! The gradient of a map interpolated from nodal positions: one kernel for the deformation
//! gradient, the Jacobian of an element's reference map and the tangents of a face.

use crate::{MeshError, Vec3};
use nalgebra::{Matrix3, SMatrix, SVector};

/// `sum_a x[nodes[a]] grad_a^T`, the gradient of the interpolated map
/// `x(.) = sum_a x[nodes[a]] N_a(.)` given the gradients `grad_a` of its shape functions
/// (pairs beyond the shorter of `nodes` and `gradients` are ignored). The shape functions
/// form a partition of unity (`sum_a grad_a = 0`), so the sum is taken as
/// `sum_a (x_a - x_0) grad_a^T`, which does not depend on where the origin is. It is
///
/// - with the rest-space gradients `dN_a/dX` at a quadrature point, the deformation gradient
///   `F = dx/dX = sum_a x_a (dN_a/dX)^T` (Bonet and Wood, "Nonlinear Continuum Mechanics for
///   Finite Element Analysis", 2nd ed., "Discretized kinematics");
/// - with rest positions and reference gradients `dN_a/dxi`, the Jacobian `dX/dxi` of the
///   element's isoparametric map;
/// - on a face (`D = 2`), the tangents `[dx/dxi, dx/deta]`, whose cross product is the
///   area-weighted normal `n dA / (dxi deta)`.
pub fn deformation_gradient<const D: usize>(
    x: &[Vec3],
    nodes: &[usize],
    gradients: &[SVector<f64, D>],
) -> SMatrix<f64, 3, D> {
    let Some(&first) = nodes.first() else {
        return SMatrix::zeros();
    };
    let origin = x[first];
    // The first node's difference is zero.
    nodes
        .iter()
        .zip(gradients)
        .skip(1)
        .fold(SMatrix::zeros(), |f, (&i, g)| {
            f + (x[i] - origin) * g.transpose()
        })
}

/// The determinant and inverse of the Jacobian `dX/dxi` of `element` (nodes `nodes` over the
/// positions `x`) at reference point `xi`, where the reference shape gradients are `dn`.
/// A determinant that is not positive is [`MeshError::FoldedElement`].
pub(super) fn inverse_jacobian(
    element: usize,
    x: &[Vec3],
    nodes: &[usize],
    xi: &Vec3,
    dn: &[Vec3],
) -> Result<(f64, Matrix3<f64>), MeshError> {
    let jacobian = deformation_gradient(x, nodes, dn);
    let determinant = jacobian.determinant();
    match jacobian.try_inverse() {
        Some(inverse) if determinant > 0.0 => Ok((determinant, inverse)),
        _ => Err(MeshError::FoldedElement {
            element,
            point: [xi.x, xi.y, xi.z],
            determinant,
        }),
    }
}
