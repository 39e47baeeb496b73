//! The quadrature kernel: the elastic energy of one tetrahedron of `n` = 4 or 10 nodes,
//! `E_e = sum_q w_q Psi(F_q)` (eq. 2 of Sheen et al. 2021 integrated by quadrature), with its
//! gradient and Hessian by the chain rule, for any [`Hyperelastic`] density.
//!
//! At point `q`, `F_q = sum_a x_a (dN_a/dX)^T`, so `dF_ij / dx_{a,k} = delta_ik (dN_a/dX)_j`:
//! `dF/dx` has three nonzeros per column, and the kernel uses that sparsity instead of a dense
//! `9 x 3n` product:
//!
//! - gradient: `dE/dx_a = sum_q w_q P(F_q) dN_a/dX`;
//! - Hessian: block `(a, b)` is `sum_q w_q sum_{j,l} (dN_a/dX)_j (dN_b/dX)_l A_{jl}`, with
//!   `A_{jl}` the 3x3 block of `dP/dF` at columns `j` and `l` of `F`.
//!
//! A 4-node tet with the one-point rule is the case `n = 4`, one point of weight `V_e`
//! ([`crate::tet`]). The code is generic in `n` (fixed-size arrays, so its loops unroll) and
//! compiled for 4 and 10 nodes.

use crate::{Hyperelastic, Matrix9, OutOfDomain};
use isochor_mesh::element::deformation_gradient;
use isochor_mesh::Vec3;

/// The rest data of one element at the points of a quadrature rule, as
/// [`isochor_mesh::element::RestGeometry`] holds it.
#[derive(Debug, Clone, Copy)]
pub struct RestPoints<'a> {
    /// The volume weight `w_q det(dX/dxi)(xi_q)` of every point.
    pub weights: &'a [f64],
    /// The rest-space shape gradients `dN_a/dX`: `n` per point, point-major.
    pub gradients: &'a [Vec3],
}

/// The element energy `sum_q w_q Psi(F_q)` of the element with nodes `nodes` (indices into the
/// positions `x`; 4 or 10 of them), and, when asked for, its gradient (`3n` entries,
/// node-major) and its Hessian (`3n x 3n`, column-major, exactly symmetric), written over
/// `gradient` and `hessian`.
///
/// The shape functions must form a partition of unity (`sum_a dN_a/dX = 0`, as for every
/// Lagrange element): `F` is taken from the differences `x_a - x_0`, and the Hessian rows and
/// columns of node 0 are minus the sums of the others (translation invariance).
///
/// # Panics
///
/// If there are not 4 or 10 nodes, `rest.gradients` does not hold `nodes.len()` gradients per
/// weight, or an output does not have `3n` or `9n^2` entries.
pub fn evaluate<M: Hyperelastic + ?Sized>(
    material: &M,
    x: &[Vec3],
    nodes: &[usize],
    rest: RestPoints<'_>,
    gradient: Option<&mut [f64]>,
    hessian: Option<&mut [f64]>,
) -> Result<f64, OutOfDomain> {
    if let Ok(nodes) = <&[usize; 4]>::try_from(nodes) {
        fixed(material, x, nodes, rest, gradient, hessian)
    } else if let Ok(nodes) = <&[usize; 10]>::try_from(nodes) {
        fixed(material, x, nodes, rest, gradient, hessian)
    } else {
        panic!("elements have 4 or 10 nodes, not {}", nodes.len())
    }
}

/// The Hessian of an `N`-node element by 3x3 blocks, `h[b][k][a][i]` the entry of row `3a + i`
/// and column `3b + k`: the layout of a column-major `3N x 3N` matrix.
type Blocks<const N: usize> = [[[[f64; 3]; N]; 3]; N];

/// [`evaluate`] for elements of `N` nodes: the one implementation, fixed-size so that the
/// compiler unrolls its loops.
fn fixed<M: Hyperelastic + ?Sized, const N: usize>(
    material: &M,
    x: &[Vec3],
    nodes: &[usize; N],
    rest: RestPoints<'_>,
    gradient: Option<&mut [f64]>,
    hessian: Option<&mut [f64]>,
) -> Result<f64, OutOfDomain> {
    assert_eq!(
        rest.gradients.len(),
        N * rest.weights.len(),
        "shape gradients for {} points of a {N}-node element",
        rest.weights.len()
    );
    let mut forces = gradient.as_ref().map(|_| [Vec3::zeros(); N]);
    let mut blocks: Option<Blocks<N>> = hessian.as_ref().map(|_| [[[[0.0; 3]; N]; 3]; N]);
    let mut energy = 0.0;
    for (&w, grads) in rest.weights.iter().zip(rest.gradients.chunks_exact(N)) {
        let grads: &[Vec3; N] = grads.try_into().expect("chunks of N");
        let f = deformation_gradient(x, nodes, grads);
        energy += w * material.energy_density(&f)?;
        if let Some(forces) = forces.as_mut() {
            let pw = material.pk1(&f)? * w;
            for (force, g) in forces.iter_mut().zip(grads) {
                *force += pw * g;
            }
        }
        if let Some(blocks) = blocks.as_mut() {
            add_tangent(&material.pk1_derivative(&f)?, grads, w, blocks);
        }
    }
    if let (Some(out), Some(forces)) = (gradient, forces.as_ref()) {
        assert_eq!(out.len(), 3 * N, "gradient length");
        for (o, force) in out.chunks_exact_mut(3).zip(forces) {
            o.copy_from_slice(force.as_slice());
        }
    }
    if let (Some(out), Some(blocks)) = (hessian, blocks.as_mut()) {
        complete(blocks);
        out.copy_from_slice(blocks.as_flattened().as_flattened().as_flattened());
    }
    Ok(energy)
}

/// Adds `w dF/dx^T A dF/dx` for a 9x9 `A` in column-major flattening to the blocks `(a, b)`,
/// `a >= b >= 1` (the diagonal blocks' lower triangles): for each node `b`, the three columns
/// `t_k = w sum_l (dN_b/dX)_l A[:, 3l + k]` of `w A dF/dx`, then block `(a, b)` entry `(i, k)`
/// is `sum_j (dN_a/dX)_j t_k[3j + i]`. [`complete`] fills the rest.
fn add_tangent<const N: usize>(a: &Matrix9, grads: &[Vec3; N], w: f64, blocks: &mut Blocks<N>) {
    let a = &a.data.0; // columns of A
    for b in 1..N {
        let gb = grads[b] * w;
        let mut t = [[0.0f64; 9]; 3];
        for (k, column) in t.iter_mut().enumerate() {
            for (l, s) in gb.iter().enumerate() {
                for (c, a_rl) in column.iter_mut().zip(&a[3 * l + k]) {
                    *c += s * a_rl;
                }
            }
        }
        for (k, t) in t.iter().enumerate() {
            let entry = |ga: &Vec3, i: usize| ga[0] * t[i] + ga[1] * t[3 + i] + ga[2] * t[6 + i];
            let rows = blocks[b][k].iter_mut().zip(grads).enumerate().skip(b);
            for (node, (block, ga)) in rows {
                // The diagonal block's lower triangle only.
                let first = if node == b { k } else { 0 };
                for (i, out) in block.iter_mut().enumerate().skip(first) {
                    *out += entry(ga, i);
                }
            }
        }
    }
}

/// Completes the blocks `(a, b)`, `a >= b >= 1`, that [`add_tangent`] accumulated into the full
/// Hessian: the upper triangle mirrors the lower one, and since the shape gradients add up to
/// zero, the rows and columns of node 0 are minus the sums of the others.
// Index loops: every entry is written at (r, c) and (c, r).
#[allow(clippy::needless_range_loop)]
fn complete<const N: usize>(h: &mut Blocks<N>) {
    for b in 1..N {
        for k in 0..3 {
            for i in 0..k {
                h[b][k][b][i] = h[b][i][b][k];
            }
            for a in b + 1..N {
                for i in 0..3 {
                    h[a][i][b][k] = h[b][k][a][i];
                }
            }
        }
    }
    for k in 0..3 {
        for a in 1..N {
            for i in 0..3 {
                h[0][k][a][i] = -(1..N).map(|b| h[b][k][a][i]).sum::<f64>();
                h[a][i][0][k] = h[0][k][a][i];
            }
        }
    }
    for k in 0..3 {
        for i in k..3 {
            h[0][k][0][i] = -(1..N).map(|a| h[0][k][a][i]).sum::<f64>();
            h[0][i][0][k] = h[0][k][0][i];
        }
    }
}

/// Copies the lower triangle of the column-major `dim x dim` matrix `h` onto its upper one.
pub(crate) fn mirror_lower(h: &mut [f64], dim: usize) {
    for col in 0..dim {
        for row in col + 1..dim {
            h[row * dim + col] = h[col * dim + row];
        }
    }
}
