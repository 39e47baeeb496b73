//! Whether the supports of a [`Problem`] hold the body: the rigid motions that its prescribed
//! DOFs leave free. A quasi-static equilibrium is singular along each of them (the stiffness
//! is not positive definite), so a driver can refuse such a problem before any solve.

use super::Problem;
use isochor_mesh::Vec3;
use nalgebra::{Matrix6, Vector6};

/// Singular values of the restricted rigid modes below this fraction of the largest one
/// count as zero. The modes are scaled to unit size (rotations by the body's radius), so a
/// support holds a rotation only with a lever arm above about `1e-8` of the body.
const RANK_TOLERANCE: f64 = 1e-8;

impl Problem {
    /// How many of the six rigid motions (three translations, three rotations about the
    /// centroid of the nodes) the Dirichlet conditions leave free: six minus the numerical
    /// rank of the rigid modes restricted to the prescribed DOFs (nodes x axes). A problem
    /// with an obstacle counts as held (0): contact may hold the body.
    pub fn unremoved_rigid_modes(&self) -> usize {
        if !self.obstacles.is_empty() {
            return 0;
        }
        let prescribed = self
            .dirichlet
            .iter()
            .flat_map(|d| d.nodes.iter().map(move |&node| (node, d.axes)));
        free_rigid_modes(self.mesh.nodes(), prescribed)
    }

    /// [`Problem::unremoved_rigid_modes`] of the part of the mesh made of `nodes` (one body of
    /// several): its rigid motions about its own centroid, held by its prescribed nodes.
    pub fn unremoved_rigid_modes_of(&self, nodes: &[usize]) -> usize {
        if !self.obstacles.is_empty() {
            return 0;
        }
        let all = self.mesh.nodes();
        let mut local = vec![usize::MAX; all.len()];
        for (i, &n) in nodes.iter().enumerate() {
            if let Some(l) = local.get_mut(n) {
                *l = i;
            }
        }
        let positions: Vec<Vec3> = nodes.iter().filter_map(|&n| all.get(n).copied()).collect();
        let prescribed = self.dirichlet.iter().flat_map(|d| {
            let local = &local;
            d.nodes
                .iter()
                .filter_map(move |&node| local.get(node).filter(|&&l| l != usize::MAX))
                .map(move |&l| (l, d.axes))
        });
        free_rigid_modes(&positions, prescribed)
    }
}

/// Six minus the rank of the rigid modes of `nodes` restricted to the `(node, axes)` pairs
/// (indices out of range are ignored). The restricted mode matrix has one row per prescribed
/// component; it is reduced row by row to a 6x6 triangular factor by Givens rotations (its
/// singular values are those of the tall matrix, without squaring them as `A^T A` would).
fn free_rigid_modes(
    nodes: &[Vec3],
    prescribed: impl IntoIterator<Item = (usize, [bool; 3])>,
) -> usize {
    if nodes.is_empty() {
        return 6;
    }
    let centroid = nodes.iter().sum::<Vec3>() / nodes.len() as f64;
    let radius = nodes
        .iter()
        .map(|x| (x - centroid).norm())
        .fold(0.0, f64::max);
    let scale = if radius > 0.0 { 1.0 / radius } else { 1.0 };
    let mut r = Matrix6::<f64>::zeros();
    for (node, axes) in prescribed {
        let Some(x) = nodes.get(node) else { continue };
        let arm = (x - centroid) * scale;
        for (k, _) in axes.iter().enumerate().filter(|(_, &on)| on) {
            // Component k of the three unit translations and of the rotations e_a x arm.
            let mut row = Vector6::zeros();
            row[k] = 1.0;
            for a in 0..3 {
                row[3 + a] = Vec3::ith(a, 1.0).cross(&arm)[k];
            }
            givens_update(&mut r, row);
        }
    }
    let sigma = r.singular_values();
    let largest = sigma.max();
    let rank = sigma
        .iter()
        .filter(|&&s| largest > 0.0 && s > RANK_TOLERANCE * largest)
        .count();
    6 - rank
}

/// Folds one more row into the upper triangular `r` of a QR factorization.
fn givens_update(r: &mut Matrix6<f64>, mut row: Vector6<f64>) {
    for j in 0..6 {
        if row[j] == 0.0 {
            continue;
        }
        let h = r[(j, j)].hypot(row[j]);
        let (c, s) = (r[(j, j)] / h, row[j] / h);
        for k in j..6 {
            let (a, b) = (r[(j, k)], row[k]);
            r[(j, k)] = c * a + s * b;
            row[k] = c * b - s * a;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::problem::material::Material;
    use crate::problem::method::Method;
    use crate::problem::obstacle::{Obstacle, Shape};
    use isochor_mesh::{generate, ElementMesh};

    /// A 3 x 2 x 2 box grid and the vertices on its faces.
    fn grid() -> Vec<Vec3> {
        generate::box_grid(Vec3::zeros(), Vec3::new(3.0, 2.0, 2.0), [3, 2, 2])
            .unwrap()
            .positions()
            .to_vec()
    }

    fn on_plane(nodes: &[Vec3], axis: usize, value: f64) -> Vec<usize> {
        (0..nodes.len())
            .filter(|&i| nodes[i][axis] == value)
            .collect()
    }

    fn held(nodes: &[usize], axes: [bool; 3]) -> Vec<(usize, [bool; 3])> {
        nodes.iter().map(|&n| (n, axes)).collect()
    }

    const XYZ: [bool; 3] = [true; 3];

    #[test]
    fn counts_the_free_rigid_motions() {
        let x = grid();
        assert_eq!(free_rigid_modes(&x, []), 6, "nothing held");
        let face = on_plane(&x, 0, 0.0);
        assert_eq!(free_rigid_modes(&x, held(&face, XYZ)), 0, "clamped face");
        assert_eq!(
            free_rigid_modes(&x, held(&[5], XYZ)),
            3,
            "one node: three rotations about it"
        );
        assert_eq!(
            free_rigid_modes(&x, held(&[0, 1], XYZ)),
            1,
            "two nodes: the rotation about their line"
        );
        assert_eq!(free_rigid_modes(&x, held(&[0, 1, 4], XYZ)), 0);
        // Rollers on the face z = 0 hold z, and the rotations about x and y.
        let bottom = on_plane(&x, 2, 0.0);
        assert_eq!(free_rigid_modes(&x, held(&bottom, [false, false, true])), 3);
        // Rollers on three symmetry planes hold everything.
        let mut symmetric = held(&on_plane(&x, 0, 0.0), [true, false, false]);
        symmetric.extend(held(&on_plane(&x, 1, 0.0), [false, true, false]));
        symmetric.extend(held(&bottom, [false, false, true]));
        assert_eq!(free_rigid_modes(&x, symmetric), 0);
        // A face held sideways only: the normal translation and the tilts stay free.
        assert_eq!(free_rigid_modes(&x, held(&bottom, [true, true, false])), 3);
        // Out-of-range nodes are left to the DOF check.
        assert_eq!(free_rigid_modes(&x, held(&[usize::MAX], XYZ)), 6);
    }

    #[test]
    fn obstacles_count_as_support() {
        let mesh: ElementMesh = generate::box_grid(Vec3::zeros(), Vec3::repeat(1.0), [1, 1, 1])
            .unwrap()
            .into();
        let mut problem = Problem {
            mesh,
            method: Method::Standard,
            material: Material::from_young_poisson(1e3, 0.3, 1.0).unwrap(),
            regions: Vec::new(),
            zones: None,
            dirichlet: Vec::new(),
            loads: Vec::new(),
            obstacles: Vec::new(),
            cloths: Vec::new(),
        };
        assert_eq!(problem.unremoved_rigid_modes(), 6);
        problem.obstacles.push(Obstacle::fixed(Shape::HalfSpace {
            point: Vec3::zeros(),
            normal: Vec3::z(),
        }));
        assert_eq!(problem.unremoved_rigid_modes(), 0);
    }
}
