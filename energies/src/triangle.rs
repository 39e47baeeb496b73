//! Surface triangle kernels for 3- and 6-node faces: the area element
//! `s = |dx/dxi x dx/deta|` at a point of the reference triangle and the area ratio
//! `J~ = s / S`, `S` its rest value (eq. 16 of Sheen et al. 2021: `J~ = sqrt(det(F~^T F~))`),
//! with derivatives with respect to the node positions (node-major, `3n` DOFs).
//!
//! The tangents `t_i = sum_a x_a dN_a/dxi_i` are linear in `x` with two nonzeros per column
//! (`dt_i / dx_{a,k} = (dN_a/dxi)_i e_k`), so the kernel works in the six tangent coordinates
//! and pulls back node pair by node pair. A 3-node triangle with the one-point rule is the case
//! `n = 3` of the same code ([`RestTriangle`]).

use crate::{Matrix9, Vector9};
use isochor_mesh::element::{deformation_gradient, TriElement, TriQuadrature};
use isochor_mesh::Vec3;
use nalgebra::{Matrix2, Matrix3, Matrix3x2, SMatrix, Vector2, Vector3};

/// Rest data of a 3-node triangle: `D_m^-1` in an orthonormal frame of its plane, and its area
/// `A_0`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RestTriangle {
    dm_inv: Matrix2<f64>,
    area: f64,
}

impl RestTriangle {
    /// From the rest positions; `None` if the triangle is degenerate (zero or non-finite area).
    pub fn new(rest: &[Vector3<f64>; 3]) -> Option<Self> {
        let (e1, e2) = (rest[1] - rest[0], rest[2] - rest[0]);
        let n = e1.cross(&e2);
        let area = 0.5 * n.norm();
        if !(area > 0.0 && area.is_finite()) {
            return None;
        }
        let t1 = e1.normalize();
        let t2 = n.normalize().cross(&t1);
        let dm = Matrix2::new(e1.norm(), e2.dot(&t1), 0.0, e2.dot(&t2));
        Some(RestTriangle {
            dm_inv: dm.try_inverse()?,
            area,
        })
    }

    /// The same triangle with every rest length times `scale` (positive): `D_m^-1 / scale`,
    /// area `scale^2 A_0`.
    pub fn scaled(&self, scale: f64) -> Self {
        RestTriangle {
            dm_inv: self.dm_inv / scale,
            area: self.area * scale * scale,
        }
    }

    /// Rest area `A_0`.
    pub fn area(&self) -> f64 {
        self.area
    }

    /// Inverse of the 2x2 rest edge matrix in the triangle's own frame.
    pub fn dm_inv(&self) -> &Matrix2<f64> {
        &self.dm_inv
    }

    /// The one-point rule on this triangle: the rest area element `S = 2 A_0` and the
    /// (constant) reference gradients of [`TriElement::Tri3`], for [`RestFacePoints`] with the
    /// weights of [`TriQuadrature::Degree1`].
    pub(crate) fn one_point(&self) -> ([f64; 1], [Vector2<f64>; 3]) {
        let mut gradients = [Vector2::zeros(); 3];
        TriElement::Tri3.shape_gradients(&TriQuadrature::Degree1.points()[0], &mut gradients);
        ([2.0 * self.area], gradients)
    }
}

/// The rest data of one face at the points of a quadrature rule on the reference triangle.
#[derive(Debug, Clone, Copy)]
pub struct RestFacePoints<'a> {
    /// The rule's weights `w_q` (adding up to 1/2, the reference area).
    pub weights: &'a [f64],
    /// The rest area element `S_q = |dX/dxi x dX/deta|(xi_q)` of every point (see
    /// [`area_element`]), so that the rest area is `sum_q w_q S_q`.
    pub areas: &'a [f64],
    /// The reference shape gradients `dN_a/dxi`: `n` per point, point-major.
    pub gradients: &'a [Vector2<f64>],
}

/// Reduced deformation gradient `F~ = [x1-x0, x2-x0] D_m^-1` (3x2) of a 3-node triangle.
pub fn reduced_deformation_gradient(x: &[Vector3<f64>; 3], rest: &RestTriangle) -> Matrix3x2<f64> {
    Matrix3x2::from_columns(&[x[1] - x[0], x[2] - x[0]]) * rest.dm_inv
}

/// The area element `s = |dx/dxi x dx/deta|` of the face with nodes `nodes` (indices into `x`)
/// at a point where the reference shape gradients are `gradients`: `s dxi deta` is the area
/// of the deformed face element. At rest positions it is the `S_q` of [`RestFacePoints`].
pub fn area_element(x: &[Vec3], nodes: &[usize], gradients: &[Vector2<f64>]) -> f64 {
    let t = deformation_gradient(x, nodes, gradients);
    t.column(0).cross(&t.column(1)).norm()
}

/// Area ratio `J~ = |(x1-x0) x (x2-x0)| / (2 A_0)` of a 3-node triangle; always `>= 0`.
pub fn area_ratio(x: &[Vector3<f64>; 3], rest: &RestTriangle) -> f64 {
    let (areas, gradients) = rest.one_point();
    area_element(x, &[0, 1, 2], &gradients) / areas[0]
}

/// `J~` with its gradient and Hessian with respect to the 9 vertex coordinates.
#[derive(Debug, Clone, PartialEq)]
pub struct AreaRatio {
    /// `J~`.
    pub value: f64,
    /// `dJ~/dx`.
    pub gradient: Vector9,
    /// `d2J~/dx2` (exactly symmetric).
    pub hessian: Matrix9,
}

/// `J~ = s / (2 A_0)` of a 3-node triangle and its derivatives: the one-point case of the
/// kernel behind [`crate::Epidermis::evaluate`]. Where the deformed triangle is degenerate
/// (`s = 0`), `J~ = 0` is not differentiable and the derivatives returned are zero.
pub fn area_ratio_derivatives(x: &[Vector3<f64>; 3], rest: &RestTriangle) -> AreaRatio {
    let (areas, gradients) = rest.one_point();
    let mut gradient = Vector9::zeros();
    let mut hessian = Matrix9::zeros();
    let s = add_area_terms(
        x,
        &[0, 1, 2],
        &gradients,
        |_| (1.0 / areas[0], 0.0),
        Some(gradient.as_mut_slice()),
        Some(hessian.as_mut_slice()),
    );
    crate::kernel::mirror_lower(hessian.as_mut_slice(), 9);
    AreaRatio {
        value: s / areas[0],
        gradient,
        hessian,
    }
}

/// The kernel of every triangle term: the area element `s` at one point of a face (see
/// [`area_element`]) and, with `(c1, c2) = coefficients(s)`, adds `c1 ds/dx` to `gradient`
/// (`3n`) and `c2 ds/dx ds/dx^T + c1 d2s/dx2` to the lower triangle of the column-major
/// `hessian` (`3n x 3n`). Nothing is added where `s = 0` (not differentiable).
///
/// In the tangents `t1, t2`, with `n = t1 x t2` and `n^ = n / s`: `ds/dt1 = t2 x n^`,
/// `ds/dt2 = n^ x t1` and `d2s/dt2 = N^T (I - n^ n^T) N / s + [[0, -[n^]x], [[n^]x, 0]]`
/// with `N = [-[t2]x, [t1]x]`; then `ds/dx_a = sum_i (dN_a/dxi)_i ds/dt_i` and block `(a, b)`
/// of `d2s/dx2` is `sum_{i,j} (dN_a/dxi)_i (dN_b/dxi)_j d2s/dt_i dt_j`.
pub(crate) fn add_area_terms(
    x: &[Vec3],
    nodes: &[usize],
    gradients: &[Vector2<f64>],
    coefficients: impl FnOnce(f64) -> (f64, f64),
    gradient: Option<&mut [f64]>,
    hessian: Option<&mut [f64]>,
) -> f64 {
    let tangents = deformation_gradient(x, nodes, gradients);
    let (t1, t2): (Vec3, Vec3) = (tangents.column(0).into(), tangents.column(1).into());
    let normal = t1.cross(&t2);
    let s = normal.norm();
    if s == 0.0 || (gradient.is_none() && hessian.is_none()) {
        return s;
    }
    let (c1, c2) = coefficients(s);
    let nh = normal / s;
    let ds = [t2.cross(&nh), nh.cross(&t1)];
    let node_ds = |g: &Vector2<f64>| ds[0] * g.x + ds[1] * g.y;
    if let Some(out) = gradient {
        for (o, g) in out.chunks_exact_mut(3).zip(gradients) {
            let d = node_ds(g) * c1;
            o.iter_mut().zip(d.iter()).for_each(|(o, d)| *o += d);
        }
    }
    if let Some(h) = hessian {
        let mut dn = SMatrix::<f64, 3, 6>::zeros();
        dn.fixed_view_mut::<3, 3>(0, 0)
            .copy_from(&(-t2.cross_matrix()));
        dn.fixed_view_mut::<3, 3>(0, 3)
            .copy_from(&t1.cross_matrix());
        let projection = Matrix3::identity() - nh * nh.transpose();
        let mut he = dn.transpose() * projection * dn / s;
        let nx = nh.cross_matrix();
        let mut block = he.fixed_view_mut::<3, 3>(0, 3);
        block -= nx;
        let mut block = he.fixed_view_mut::<3, 3>(3, 0);
        block += nx;
        let dim = 3 * nodes.len();
        for (b, gb) in gradients.iter().enumerate() {
            let dsb = node_ds(gb) * c2;
            for (a, ga) in gradients.iter().enumerate().skip(b) {
                let mut hab = node_ds(ga) * dsb.transpose();
                for i in 0..2 {
                    for j in 0..2 {
                        hab += he.fixed_view::<3, 3>(3 * i, 3 * j) * (c1 * ga[i] * gb[j]);
                    }
                }
                for k in 0..3 {
                    let col = 3 * b + k;
                    for i in 0..3 {
                        let row = 3 * a + i;
                        if row >= col {
                            h[col * dim + row] += hab[(i, k)];
                        }
                    }
                }
            }
        }
    }
    s
}
#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;

    #[test]
    fn area_ratio_is_sqrt_det_of_metric() {
        let rest = [
            Vector3::new(0.0, 0.1, 0.0),
            Vector3::new(1.2, 0.0, 0.3),
            Vector3::new(0.2, 0.8, -0.1),
        ];
        let t = RestTriangle::new(&rest).unwrap();
        let ft = reduced_deformation_gradient(&rest, &t);
        assert_relative_eq!(ft.transpose() * ft, Matrix2::identity(), epsilon = 1e-14);
        let x = [
            Vector3::new(0.1, 0.0, 0.2),
            Vector3::new(1.5, 0.4, 0.1),
            Vector3::new(-0.2, 1.1, 0.3),
        ];
        let ft = reduced_deformation_gradient(&x, &t);
        let j = (ft.transpose() * ft).determinant().sqrt();
        assert_relative_eq!(area_ratio(&x, &t), j, max_relative = 1e-13);
        assert_relative_eq!(
            area_ratio_derivatives(&x, &t).value,
            j,
            max_relative = 1e-13
        );
        assert!(RestTriangle::new(&[rest[0], rest[1], rest[1]]).is_none());
    }
}
