//! Surface triangle kinematics: the 3x2 reduced deformation gradient `F~` and the area ratio
//! `J~ = sqrt(det(F~^T F~))` (eq. 16 of Sheen et al. 2021), with its gradient and Hessian
//! with respect to the three vertex positions (vertex-major, 9 DOFs).

use crate::{Matrix9, Vector9};
use nalgebra::{Matrix2, Matrix3, Matrix3x2, SMatrix, Vector3};

/// Rest data of a triangle: `D_m^-1` in an orthonormal frame of its plane, and its area `A_0`.
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

    /// Rest area `A_0`.
    pub fn area(&self) -> f64 {
        self.area
    }

    /// Inverse of the 2x2 rest edge matrix in the triangle's own frame.
    pub fn dm_inv(&self) -> &Matrix2<f64> {
        &self.dm_inv
    }
}

/// Reduced deformation gradient `F~ = [x1-x0, x2-x0] D_m^-1` (3x2).
pub fn reduced_deformation_gradient(x: &[Vector3<f64>; 3], rest: &RestTriangle) -> Matrix3x2<f64> {
    Matrix3x2::from_columns(&[x[1] - x[0], x[2] - x[0]]) * rest.dm_inv
}

/// Area ratio `J~ = sqrt(det(F~^T F~)) = |(x1-x0) x (x2-x0)| / (2 A_0)`; always `>= 0`.
pub fn area_ratio(x: &[Vector3<f64>; 3], rest: &RestTriangle) -> f64 {
    (x[1] - x[0]).cross(&(x[2] - x[0])).norm() / (2.0 * rest.area)
}

/// `J~` with its gradient and Hessian with respect to the 9 vertex coordinates.
#[derive(Debug, Clone, PartialEq)]
pub struct AreaRatio {
    /// `J~`.
    pub value: f64,
    /// `dJ~/dx`.
    pub gradient: Vector9,
    /// `d2J~/dx2` (symmetric).
    pub hessian: Matrix9,
}

/// `J~` and its derivatives. With `e1 = x1-x0`, `e2 = x2-x0`, `n = e1 x e2`, `s = |n|`:
/// `ds/de1 = e2 x n^`, `ds/de2 = n^ x e1`, and
/// `d2s/de2 = N^T (I - n^ n^T) N / s + [[0, -[n^]x], [[n^]x, 0]]` with `N = [-[e2]x, [e1]x]`.
/// Where the deformed triangle is degenerate (`s = 0`), `J~ = 0` is not differentiable and the
/// derivatives returned are zero.
pub fn area_ratio_derivatives(x: &[Vector3<f64>; 3], rest: &RestTriangle) -> AreaRatio {
    let (e1, e2) = (x[1] - x[0], x[2] - x[0]);
    let n = e1.cross(&e2);
    let s = n.norm();
    let scale = 1.0 / (2.0 * rest.area);
    if s == 0.0 {
        return AreaRatio {
            value: 0.0,
            gradient: Vector9::zeros(),
            hessian: Matrix9::zeros(),
        };
    }
    let nh = n / s;
    let mut ge = SMatrix::<f64, 6, 1>::zeros();
    ge.fixed_rows_mut::<3>(0).copy_from(&e2.cross(&nh));
    ge.fixed_rows_mut::<3>(3).copy_from(&nh.cross(&e1));

    let mut dn = SMatrix::<f64, 3, 6>::zeros();
    dn.fixed_view_mut::<3, 3>(0, 0)
        .copy_from(&(-e2.cross_matrix()));
    dn.fixed_view_mut::<3, 3>(0, 3)
        .copy_from(&e1.cross_matrix());
    let proj = Matrix3::identity() - nh * nh.transpose();
    let mut he = dn.transpose() * proj * dn / s;
    let nx = nh.cross_matrix();
    let mut off = he.fixed_view_mut::<3, 3>(0, 3);
    off -= nx;
    let mut off = he.fixed_view_mut::<3, 3>(3, 0);
    off += nx;

    // e = A x with A = [[-I, I, 0], [-I, 0, I]].
    let mut a = SMatrix::<f64, 6, 9>::zeros();
    for k in 0..3 {
        a[(k, k)] = -1.0;
        a[(k, 3 + k)] = 1.0;
        a[(3 + k, k)] = -1.0;
        a[(3 + k, 6 + k)] = 1.0;
    }
    AreaRatio {
        value: s * scale,
        gradient: a.transpose() * ge * scale,
        hessian: a.transpose() * he * a * scale,
    }
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
