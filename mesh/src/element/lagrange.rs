//! Lagrange shape functions of degree 1 and 2 on a simplex, in barycentric coordinates
//! `lambda`: the one kernel behind the reference tetrahedra and triangles.

use nalgebra::SVector;

/// Writes the shape functions of degree `order` (1 or 2) at barycentric coordinates `l` into
/// `n`: `N_a = lambda_a` (degree 1); `N_a = lambda_a (2 lambda_a - 1)` at the corners and
/// `N = 4 lambda_i lambda_j` at the node of edge `(i, j)` of `edges`, numbered after the
/// corners (degree 2).
pub(super) fn values(order: usize, l: &[f64], edges: &[[usize; 2]], n: &mut [f64]) {
    let corners = l.len();
    if order == 1 {
        n[..corners].copy_from_slice(l);
        return;
    }
    for a in 0..corners {
        n[a] = l[a] * (2.0 * l[a] - 1.0);
    }
    for (k, &[i, j]) in edges.iter().enumerate() {
        n[corners + k] = 4.0 * l[i] * l[j];
    }
}

/// Writes the reference gradients of [`values`] into `dn`, given the constant gradients `g`
/// of the barycentric coordinates: `grad lambda_a` (degree 1); `(4 lambda_a - 1) grad
/// lambda_a` at the corners and `4 (lambda_j grad lambda_i + lambda_i grad lambda_j)` on the
/// edges (degree 2).
pub(super) fn gradients<const D: usize>(
    order: usize,
    l: &[f64],
    g: &[SVector<f64, D>],
    edges: &[[usize; 2]],
    dn: &mut [SVector<f64, D>],
) {
    let corners = l.len();
    if order == 1 {
        dn[..corners].copy_from_slice(g);
        return;
    }
    for a in 0..corners {
        dn[a] = (4.0 * l[a] - 1.0) * g[a];
    }
    for (k, &[i, j]) in edges.iter().enumerate() {
        dn[corners + k] = 4.0 * (l[j] * g[i] + l[i] * g[j]);
    }
}
