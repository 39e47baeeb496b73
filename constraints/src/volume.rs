//! The volume primitives every constraint type is built from: the signed volume of a tet
//! (eq. 25 of Francu et al. 2021), its gradient (eq. 26a-c) and its Hessian.
//!
//! Element DOF vectors are vertex-major, `[x0.x, x0.y, x0.z, x1.x, ...]`, like the element
//! kernels of `isochor-energies`.

use isochor_energies::{Matrix12, Vector12};
use isochor_mesh::{signed_volume, Vec3};

/// Signed volume `v = (x1 - x0) . ((x2 - x0) x (x3 - x0)) / 6` (eq. 25).
pub fn tet_volume(x: &[Vec3; 4]) -> f64 {
    signed_volume(&x[0], &x[1], &x[2], &x[3])
}

/// Gradient `dv/dx` of the signed volume (eq. 26a-c): with edges `e_i = x_i - x0`,
/// `dv/dx1 = e2 x e3 / 6`, `dv/dx2 = e3 x e1 / 6`, `dv/dx3 = e1 x e2 / 6` and
/// `dv/dx0 = -(dv/dx1 + dv/dx2 + dv/dx3)`. Each block is `A_a n_a / 3`, with `A_a` the area
/// of the face opposite vertex `a` and `n_a` its unit normal pointing toward `a`.
pub fn volume_gradient(x: &[Vec3; 4]) -> Vector12 {
    let [e1, e2, e3] = edges(x);
    let g1 = e2.cross(&e3) / 6.0;
    let g2 = e3.cross(&e1) / 6.0;
    let g3 = e1.cross(&e2) / 6.0;
    let g0 = -(g1 + g2 + g3);
    let mut g = Vector12::zeros();
    for (a, ga) in [g0, g1, g2, g3].iter().enumerate() {
        g.fixed_rows_mut::<3>(3 * a).copy_from(ga);
    }
    g
}

/// Hessian `d^2 v / dx^2` of the signed volume: a symmetric 12x12 matrix, linear in `x`,
/// with zero diagonal 3x3 blocks and skew-symmetric off-diagonal blocks
/// `d^2 v / dx_a dx_b = [x_c - x_d]_x / 6` for every even permutation `(a, b, c, d)` of
/// `(0, 1, 2, 3)`, where `[w]_x y = w x y` (differentiate eq. 26a-c once more).
pub fn volume_hessian(x: &[Vec3; 4]) -> Matrix12 {
    let mut h = Matrix12::zeros();
    for (a, row) in OPPOSITE_EDGE.iter().enumerate() {
        for (b, &(c, d)) in row.iter().enumerate().filter(|&(b, _)| b != a) {
            let block = (x[c] - x[d]).cross_matrix() / 6.0;
            h.fixed_view_mut::<3, 3>(3 * a, 3 * b).copy_from(&block);
        }
    }
    h
}

/// `OPPOSITE_EDGE[a][b] = (c, d)` such that `(a, b, c, d)` is an even permutation of
/// `(0, 1, 2, 3)` (the diagonal is unused).
const OPPOSITE_EDGE: [[(usize, usize); 4]; 4] = [
    [(0, 0), (2, 3), (3, 1), (1, 2)],
    [(3, 2), (0, 0), (0, 3), (2, 0)],
    [(1, 3), (3, 0), (0, 0), (0, 1)],
    [(2, 1), (0, 2), (1, 0), (0, 0)],
];

/// The edge vectors `[x1 - x0, x2 - x0, x3 - x0]`.
fn edges(x: &[Vec3; 4]) -> [Vec3; 3] {
    [x[1] - x[0], x[2] - x[0], x[3] - x[0]]
}

#[cfg(test)]
mod tests {
    use super::*;

    fn sample() -> [Vec3; 4] {
        [
            Vec3::new(0.1, -0.2, 0.05),
            Vec3::new(1.2, 0.1, -0.1),
            Vec3::new(0.2, 0.9, 0.3),
            Vec3::new(-0.1, 0.3, 1.1),
        ]
    }

    fn perturbed(x: &[Vec3; 4], dof: usize, h: f64) -> [Vec3; 4] {
        let mut y = *x;
        y[dof / 3][dof % 3] += h;
        y
    }

    #[test]
    fn unit_tet_volume_and_gradient() {
        let x = [Vec3::zeros(), Vec3::x(), Vec3::y(), Vec3::z()];
        assert_eq!(tet_volume(&x), 1.0 / 6.0);
        let g = volume_gradient(&x);
        // dv/dx1 = e_y x e_z / 6 = e_x / 6, and the four sum to zero.
        assert_eq!(g.fixed_rows::<3>(3), (Vec3::x() / 6.0));
        let sum: Vec3 = (0..4).map(|a| g.fixed_rows::<3>(3 * a).into_owned()).sum();
        assert_eq!(sum, Vec3::zeros());
    }

    #[test]
    fn gradient_and_hessian_match_central_differences() {
        let x = sample();
        let g = volume_gradient(&x);
        let h = volume_hessian(&x);
        let step = 1e-6;
        for dof in 0..12 {
            let fd_v = (tet_volume(&perturbed(&x, dof, step))
                - tet_volume(&perturbed(&x, dof, -step)))
                / (2.0 * step);
            assert!((fd_v - g[dof]).abs() < 1e-9, "gradient dof {dof}");
            let fd_g = (volume_gradient(&perturbed(&x, dof, step))
                - volume_gradient(&perturbed(&x, dof, -step)))
                / (2.0 * step);
            assert!((fd_g - h.column(dof)).amax() < 1e-9, "hessian column {dof}");
        }
        assert_eq!(h, h.transpose());
    }

    #[test]
    fn euler_identity_for_a_cubic() {
        // v is homogeneous of degree 3 in x, so x . g = 3 v and x^T H x = 6 v; translations
        // leave every gradient unchanged, so they are in the kernel of H.
        let x = sample();
        let flat = Vector12::from_iterator(x.iter().flat_map(|p| p.iter().copied()));
        let v = tet_volume(&x);
        assert!((flat.dot(&volume_gradient(&x)) - 3.0 * v).abs() < 1e-14);
        let h = volume_hessian(&x);
        assert!(((flat.transpose() * h * flat)[0] - 6.0 * v).abs() < 1e-14);
        let shift = Vector12::from_iterator((0..12).map(|i| if i % 3 == 1 { 1.0 } else { 0.0 }));
        assert!((h * shift).amax() < 1e-15);
    }
}
