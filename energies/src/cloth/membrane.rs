//! The membrane energy of a 3-node cloth triangle: Saint Venant-Kirchhoff under plane stress,
//! `Psi = h (mu tr(E^2) + lambda_s/2 tr(E)^2)` per unit rest area, with the in-plane Green
//! strain `E = (F~^T F~ - I) / 2` of the reduced deformation gradient `F~` (3x2,
//! [`reduced_deformation_gradient`]); the element energy is `A_0 Psi`.
//!
//! Its first Piola-Kirchhoff stress is `P = F~ S` with `S = 2 mu E + lambda_s tr(E) I` (2x2, per
//! unit volume), pulled back to the nodes through `F~ = [x1 - x0, x2 - x0] D_m^-1`. The Hessian
//! is the exact one (indefinite under compression, where a sheet buckles): project it
//! ([`crate::project_to_psd`]) where a solver needs a convex model.

use super::Fabric;
use crate::triangle::{reduced_deformation_gradient, RestTriangle};
use crate::{Matrix9, TriangleTerms, Vector9};
use nalgebra::{Matrix2, Matrix3x2, SMatrix, Vector3};

/// `S = 2 mu E + lambda_s tr(E) I`, the second Piola-Kirchhoff stress (per unit volume) of the
/// membrane at the reduced deformation gradient `f`.
pub fn second_piola_kirchhoff(fabric: &Fabric, f: &Matrix3x2<f64>) -> Matrix2<f64> {
    let strain = green_strain(f);
    strain * (2.0 * fabric.mu()) + Matrix2::identity() * (fabric.lambda_s() * strain.trace())
}

/// `Psi / h = mu tr(E^2) + lambda_s/2 tr(E)^2`, the energy per unit rest volume at `f`.
pub fn energy_density(fabric: &Fabric, f: &Matrix3x2<f64>) -> f64 {
    let strain = green_strain(f);
    fabric.mu() * strain.norm_squared() + 0.5 * fabric.lambda_s() * strain.trace().powi(2)
}

/// Energy `A_0 h Psi`, its gradient with respect to the 9 vertex coordinates and its exact
/// Hessian.
pub fn energy_gradient_hessian(
    fabric: &Fabric,
    x: &[Vector3<f64>; 3],
    rest: &RestTriangle,
) -> TriangleTerms {
    let f = reduced_deformation_gradient(x, rest);
    let scale = rest.area() * fabric.thickness();
    let piola = f * second_piola_kirchhoff(fabric, &f);
    let weights = node_weights(rest);
    let mut gradient = Vector9::zeros();
    for a in 0..3 {
        for i in 0..3 {
            gradient[3 * a + i] =
                scale * (0..2).map(|j| piola[(i, j)] * weights[a][j]).sum::<f64>();
        }
    }
    let tangent = stress_derivative(fabric, &f);
    let mut hessian = Matrix9::zeros();
    for a in 0..3 {
        for b in 0..3 {
            for i in 0..3 {
                for k in 0..3 {
                    let mut sum = 0.0;
                    for j in 0..2 {
                        for l in 0..2 {
                            sum += tangent[(3 * j + i, 3 * l + k)] * weights[a][j] * weights[b][l];
                        }
                    }
                    hessian[(3 * a + i, 3 * b + k)] = scale * sum;
                }
            }
        }
    }
    TriangleTerms {
        energy: scale * energy_density(fabric, &f),
        gradient,
        hessian,
    }
}

/// `E = (F~^T F~ - I) / 2`.
fn green_strain(f: &Matrix3x2<f64>) -> Matrix2<f64> {
    (f.transpose() * f - Matrix2::identity()) * 0.5
}

/// `w[a][j] = dF~_ij / dx_{a,i}`: row `a - 1` of `D_m^-1` for the nodes 1 and 2, minus their
/// sum for node 0.
fn node_weights(rest: &RestTriangle) -> [[f64; 2]; 3] {
    let d = rest.dm_inv();
    let row = |c: usize| [d[(c, 0)], d[(c, 1)]];
    let (w1, w2) = (row(0), row(1));
    [[-w1[0] - w2[0], -w1[1] - w2[1]], w1, w2]
}

/// `d vec(P) / d vec(F~)` (6x6, column-major vec of 3x2 matrices) of `P = F~ S(F~)`:
/// `dP = dF S + F (2 mu dE + lambda_s tr(dE) I)` with `dE = (dF^T F + F^T dF) / 2`.
fn stress_derivative(fabric: &Fabric, f: &Matrix3x2<f64>) -> SMatrix<f64, 6, 6> {
    let stress = second_piola_kirchhoff(fabric, f);
    let mut tangent = SMatrix::<f64, 6, 6>::zeros();
    for column in 0..6 {
        let mut df = Matrix3x2::zeros();
        df[(column % 3, column / 3)] = 1.0;
        let de = (df.transpose() * f + f.transpose() * df) * 0.5;
        let ds = de * (2.0 * fabric.mu()) + Matrix2::identity() * (fabric.lambda_s() * de.trace());
        let dp = df * stress + f * ds;
        tangent.column_mut(column).copy_from_slice(dp.as_slice());
    }
    tangent
}
