//! Linear tetrahedron kernels: `F = D_s D_m^-1`, `dF/dx`, and the element energy
//! `V_e Psi(F)` (eq. 2 of Sheen et al. 2021) with its gradient and Hessian.
//!
//! A 4-node tet is the one-point case of the quadrature kernel
//! ([`crate::kernel::evaluate`]): one point of weight `V_e` where the shape gradients are
//! the constant `grad N_a` of [`shape_gradients`]. Every function here is that kernel with
//! fixed-size arguments and results.

use crate::kernel::{self, RestPoints};
use crate::{Hyperelastic, Matrix12, OutOfDomain, Vector12};
use nalgebra::{Matrix3, SMatrix, Vector3};

/// The 9x12 matrix `d vec(F) / dx` (column-major `vec`, vertex-major `x`).
pub type DeformationJacobian = SMatrix<f64, 9, 12>;

/// The local node indices of a tet's own four positions.
const NODES: [usize; 4] = [0, 1, 2, 3];

/// Energy, gradient and Hessian of one element.
#[derive(Debug, Clone, PartialEq)]
pub struct ElementTerms {
    /// `V_e Psi(F)`.
    pub energy: f64,
    /// `V_e dF/dx^T vec(P)`.
    pub gradient: Vector12,
    /// `V_e dF/dx^T dP/dF dF/dx` (exactly symmetric).
    pub hessian: Matrix12,
}

/// Shape-function gradients `grad N_a` (a = 0..3) of a linear tet with inverse rest shape
/// matrix `D_m^-1`: rows of `D_m^-1` for vertices 1..3, minus their sum for vertex 0.
#[inline]
pub fn shape_gradients(dm_inv: &Matrix3<f64>) -> [Vector3<f64>; 4] {
    let r = |k: usize| -> Vector3<f64> { dm_inv.row(k).transpose() };
    let (g1, g2, g3) = (r(0), r(1), r(2));
    [-(g1 + g2 + g3), g1, g2, g3]
}

/// Deformation gradient `F = sum_a x_a (grad N_a)^T = [x1-x0, x2-x0, x3-x0] D_m^-1`.
#[inline]
pub fn deformation_gradient(x: &[Vector3<f64>; 4], dm_inv: &Matrix3<f64>) -> Matrix3<f64> {
    isochor_mesh::element::deformation_gradient(x, &NODES, &shape_gradients(dm_inv))
}

/// `d vec(F) / dx` as a dense 9x12 matrix (for reference; the kernels do not form it).
pub fn deformation_jacobian(dm_inv: &Matrix3<f64>) -> DeformationJacobian {
    let grads = shape_gradients(dm_inv);
    let mut d = DeformationJacobian::zeros();
    for (a, g) in grads.iter().enumerate() {
        for k in 0..3 {
            for j in 0..3 {
                d[(3 * j + k, 3 * a + k)] = g[j];
            }
        }
    }
    d
}

/// The quadrature kernel on one tet: one point of weight `volume`.
fn evaluate<M: Hyperelastic + ?Sized>(
    material: &M,
    x: &[Vector3<f64>; 4],
    dm_inv: &Matrix3<f64>,
    volume: f64,
    gradient: Option<&mut Vector12>,
    hessian: Option<&mut Matrix12>,
) -> Result<f64, OutOfDomain> {
    let rest = RestPoints {
        weights: &[volume],
        gradients: &shape_gradients(dm_inv),
    };
    kernel::evaluate(
        material,
        x,
        &NODES,
        rest,
        gradient.map(|g| g.as_mut_slice()),
        hessian.map(|h| h.as_mut_slice()),
    )
}

/// Element energy `V_e Psi(F)`.
pub fn energy<M: Hyperelastic + ?Sized>(
    material: &M,
    x: &[Vector3<f64>; 4],
    dm_inv: &Matrix3<f64>,
    volume: f64,
) -> Result<f64, OutOfDomain> {
    evaluate(material, x, dm_inv, volume, None, None)
}

/// Element gradient `V_e dF/dx^T vec(P)`.
pub fn gradient<M: Hyperelastic + ?Sized>(
    material: &M,
    x: &[Vector3<f64>; 4],
    dm_inv: &Matrix3<f64>,
    volume: f64,
) -> Result<Vector12, OutOfDomain> {
    let mut g = Vector12::zeros();
    evaluate(material, x, dm_inv, volume, Some(&mut g), None)?;
    Ok(g)
}

/// Element Hessian `V_e dF/dx^T dP/dF dF/dx`.
pub fn hessian<M: Hyperelastic + ?Sized>(
    material: &M,
    x: &[Vector3<f64>; 4],
    dm_inv: &Matrix3<f64>,
    volume: f64,
) -> Result<Matrix12, OutOfDomain> {
    let mut h = Matrix12::zeros();
    evaluate(material, x, dm_inv, volume, None, Some(&mut h))?;
    Ok(h)
}

/// Energy, gradient and Hessian together (the assembly entry point).
pub fn energy_gradient_hessian<M: Hyperelastic + ?Sized>(
    material: &M,
    x: &[Vector3<f64>; 4],
    dm_inv: &Matrix3<f64>,
    volume: f64,
) -> Result<ElementTerms, OutOfDomain> {
    let mut gradient = Vector12::zeros();
    let mut hessian = Matrix12::zeros();
    let energy = evaluate(
        material,
        x,
        dm_inv,
        volume,
        Some(&mut gradient),
        Some(&mut hessian),
    )?;
    Ok(ElementTerms {
        energy,
        gradient,
        hessian,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::kinematics::flatten;
    use approx::assert_relative_eq;

    fn rest() -> [Vector3<f64>; 4] {
        [
            Vector3::new(0.1, 0.0, -0.2),
            Vector3::new(1.0, 0.2, 0.0),
            Vector3::new(0.3, 0.9, 0.1),
            Vector3::new(0.2, 0.1, 1.1),
        ]
    }

    fn dm_inv(x: &[Vector3<f64>; 4]) -> Matrix3<f64> {
        Matrix3::from_columns(&[x[1] - x[0], x[2] - x[0], x[3] - x[0]])
            .try_inverse()
            .unwrap()
    }

    fn deformed() -> [Vector3<f64>; 4] {
        let d = [
            [0.1, -0.05, 0.02],
            [0.0, 0.13, -0.1],
            [-0.07, 0.0, 0.2],
            [0.05, 0.1, 0.0],
        ];
        let mut x = rest();
        for (xi, di) in x.iter_mut().zip(d) {
            *xi += Vector3::from(di);
        }
        x
    }

    #[test]
    fn rest_deformation_is_identity_and_jacobian_is_linear() {
        let x = rest();
        let b = dm_inv(&x);
        assert_relative_eq!(
            deformation_gradient(&x, &b),
            Matrix3::identity(),
            epsilon = 1e-14
        );
        let y = deformed();
        let flat = Vector12::from_iterator(y.iter().flat_map(|v| v.iter().copied()));
        assert_relative_eq!(
            deformation_jacobian(&b) * flat,
            flatten(&deformation_gradient(&y, &b)),
            epsilon = 1e-14
        );
    }

    #[test]
    fn sparse_chain_rule_matches_dense_product() {
        let (x, y) = (rest(), deformed());
        let b = dm_inv(&x);
        let m = crate::constrained_neo_hookean(1.3, 4.0, 2.0, 0.1).unwrap();
        let terms = energy_gradient_hessian(&m, &y, &b, 0.7).unwrap();
        let d = deformation_jacobian(&b);
        let f = deformation_gradient(&y, &b);
        let g = d.transpose() * flatten(&m.pk1(&f).unwrap()) * 0.7;
        let h = d.transpose() * m.pk1_derivative(&f).unwrap() * d * 0.7;
        assert_relative_eq!(terms.gradient, g, max_relative = 1e-12, epsilon = 1e-13);
        assert_relative_eq!(terms.hessian, h, max_relative = 1e-12, epsilon = 1e-13);
        assert_eq!(terms.hessian, terms.hessian.transpose());
        let dynamic: &dyn Hyperelastic = &m;
        assert_eq!(hessian(dynamic, &y, &b, 0.7).unwrap(), terms.hessian);
    }
}
