//! Linear tetrahedron kernels: `F = D_s D_m^-1`, `dF/dx`, and the element energy
//! `V_e Psi(F)` (eq. 2 of Sheen et al. 2021) with its gradient and Hessian by the chain rule.
//!
//! `F = sum_a x_a (grad N_a)^T` with constant shape-function gradients `grad N_a`, so
//! `dF_ij / dx_{a,k} = delta_ik (grad N_a)_j`: `dF/dx` has three nonzeros per column, and the
//! kernels below use that sparsity instead of a dense 9x12 product.

use crate::{Hyperelastic, Matrix12, Matrix9, OutOfDomain, Vector12};
use nalgebra::{Matrix3, SMatrix, Vector3};

/// The 9x12 matrix `d vec(F) / dx` (column-major `vec`, vertex-major `x`).
pub type DeformationJacobian = SMatrix<f64, 9, 12>;

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

/// Deformation gradient `F = [x1-x0, x2-x0, x3-x0] D_m^-1`.
#[inline]
pub fn deformation_gradient(x: &[Vector3<f64>; 4], dm_inv: &Matrix3<f64>) -> Matrix3<f64> {
    Matrix3::from_columns(&[x[1] - x[0], x[2] - x[0], x[3] - x[0]]) * dm_inv
}

/// `d vec(F) / dx` as a dense 9x12 matrix (for reference and for constraint code; the
/// kernels of this module do not form it).
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

/// Element energy `V_e Psi(F)`.
pub fn energy<M: Hyperelastic + ?Sized>(
    material: &M,
    x: &[Vector3<f64>; 4],
    dm_inv: &Matrix3<f64>,
    volume: f64,
) -> Result<f64, OutOfDomain> {
    Ok(volume * material.energy_density(&deformation_gradient(x, dm_inv))?)
}

/// Element gradient `V_e dF/dx^T vec(P)`.
pub fn gradient<M: Hyperelastic + ?Sized>(
    material: &M,
    x: &[Vector3<f64>; 4],
    dm_inv: &Matrix3<f64>,
    volume: f64,
) -> Result<Vector12, OutOfDomain> {
    let p = material.pk1(&deformation_gradient(x, dm_inv))?;
    Ok(pull_back_stress(&p, &shape_gradients(dm_inv), volume))
}

/// Element Hessian `V_e dF/dx^T dP/dF dF/dx`.
pub fn hessian<M: Hyperelastic + ?Sized>(
    material: &M,
    x: &[Vector3<f64>; 4],
    dm_inv: &Matrix3<f64>,
    volume: f64,
) -> Result<Matrix12, OutOfDomain> {
    let dpdf = material.pk1_derivative(&deformation_gradient(x, dm_inv))?;
    Ok(pull_back_tangent(&dpdf, &shape_gradients(dm_inv), volume))
}

/// Energy, gradient and Hessian together (the assembly entry point).
pub fn energy_gradient_hessian<M: Hyperelastic + ?Sized>(
    material: &M,
    x: &[Vector3<f64>; 4],
    dm_inv: &Matrix3<f64>,
    volume: f64,
) -> Result<ElementTerms, OutOfDomain> {
    let f = deformation_gradient(x, dm_inv);
    let grads = shape_gradients(dm_inv);
    Ok(ElementTerms {
        energy: volume * material.energy_density(&f)?,
        gradient: pull_back_stress(&material.pk1(&f)?, &grads, volume),
        hessian: pull_back_tangent(&material.pk1_derivative(&f)?, &grads, volume),
    })
}

/// `V dF/dx^T vec(P)`: the force-like gradient of vertex `a` is `V P grad N_a`.
pub fn pull_back_stress(p: &Matrix3<f64>, grads: &[Vector3<f64>; 4], volume: f64) -> Vector12 {
    let pv = p * volume;
    let mut out = Vector12::zeros();
    for (a, g) in grads.iter().enumerate() {
        out.fixed_rows_mut::<3>(3 * a).copy_from(&(pv * g));
    }
    out
}

/// `V dF/dx^T A dF/dx` for a 9x9 (symmetric) `A` in column-major flattening, using the three
/// nonzeros per column of `dF/dx` and translation invariance (`grad N_0 = -sum grad N_a`):
/// the 9x9 block of vertices 1..3 is computed, and the rows and columns of vertex 0 are minus
/// the sums of the others. The result is exactly symmetric (lower triangles mirrored).
// Index loops: every entry is written at (r, c) and (c, r).
#[allow(clippy::needless_range_loop)]
pub fn pull_back_tangent(a: &Matrix9, grads: &[Vector3<f64>; 4], volume: f64) -> Matrix12 {
    let a = &a.data.0; // columns of A
    let g = [grads[1], grads[2], grads[3]].map(|v| [v.x, v.y, v.z]);
    // t[3b + k] = column (b + 1, k) of A dF/dx: sum_l (grad N_b)_l A[:, 3 l + k].
    let mut t = [[0.0f64; 9]; 9];
    for b in 0..3 {
        for k in 0..3 {
            let col = &mut t[3 * b + k];
            for l in 0..3 {
                let s = g[b][l];
                for (c, a_rl) in col.iter_mut().zip(&a[3 * l + k]) {
                    *c += s * a_rl;
                }
            }
        }
    }
    // Columns of the result; h[c][r] = entry (r, c).
    let mut h = [[0.0f64; 12]; 12];
    // Vertices 1..3: h[(3 + 3a + i), (3 + c)] = V sum_j (grad N_a)_j t[c][3 j + i], lower part.
    for c in 0..9 {
        for r in c..9 {
            let (va, i) = (r / 3, r % 3);
            let v = volume * (g[va][0] * t[c][i] + g[va][1] * t[c][3 + i] + g[va][2] * t[c][6 + i]);
            h[3 + c][3 + r] = v;
            h[3 + r][3 + c] = v;
        }
    }
    // Vertex 0 against the others: minus the sum over vertices 1..3.
    for c in 3..12 {
        for i in 0..3 {
            let v = -(h[c][3 + i] + h[c][6 + i] + h[c][9 + i]);
            h[c][i] = v;
            h[i][c] = v;
        }
    }
    for k in 0..3 {
        for i in k..3 {
            let v = -(h[3 + k][i] + h[6 + k][i] + h[9 + k][i]);
            h[k][i] = v;
            h[i][k] = v;
        }
    }
    Matrix12::from_data(nalgebra::ArrayStorage(h))
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
