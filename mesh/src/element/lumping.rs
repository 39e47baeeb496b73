//! Volumes carried by the nodes of an element mesh: the consistent `integral N_a dV`, which
//! body forces need, and the positive lumped volumes of Hinton, Rock and Zienkiewicz (HRZ),
//! which lumped masses need.
//!
//! On a 10-node tet the consistent volumes are `-V/20` at the corners and `V/5` at the
//! mid-edge nodes, so row-sum lumping would give negative corner masses. HRZ lumping keeps
//! the diagonal of the consistent mass matrix, `integral N_a^2 dV`, scaled so that each element
//! carries its volume: `V_e integral N_a^2 / sum_b integral N_b^2`, positive by construction
//! (`V/36` at the corners and `4V/27` at the mid-edge nodes of a straight 10-node tet;
//! `V/4` at each vertex of a 4-node tet, the row sum).

use super::{ElementMesh, TetQuadrature};

impl ElementMesh {
    /// `integral N_a dV` for every node `a` (the element volumes' consistent split), by the
    /// degree-5 rule: exact on straight elements.
    pub fn node_volumes(&self) -> Vec<f64> {
        self.node_masses(&vec![1.0; self.num_elements()])
    }

    /// HRZ-lumped volumes of every node (see the module docs): positive, and adding up to
    /// the mesh volume.
    pub fn lumped_volumes(&self) -> Vec<f64> {
        self.lumped_masses(&vec![1.0; self.num_elements()])
    }

    /// `integral rho N_a dV` for every node `a`, with `density` the constant `rho` of each
    /// element: the consistent split of the element masses (body forces of a body of several
    /// materials).
    ///
    /// # Panics
    /// If `density` does not hold one value per element.
    pub fn node_masses(&self, density: &[f64]) -> Vec<f64> {
        self.split_volumes(density, |values| values.to_vec())
    }

    /// HRZ-lumped masses of every node, with `density` the constant `rho` of each element:
    /// positive, and adding up to the body's mass.
    ///
    /// # Panics
    /// If `density` does not hold one value per element.
    pub fn lumped_masses(&self, density: &[f64]) -> Vec<f64> {
        self.split_volumes(density, |values| values.iter().map(|v| v * v).collect())
    }

    /// Splits every element's volume (by the degree-5 rule), times its `density`, among its
    /// nodes in proportion to `integral f(N)_a dV`, `f` mapping the shape values at a point to
    /// one value per node; `f(N) = N` is the consistent split itself, whose parts add up to
    /// the volume.
    fn split_volumes(&self, density: &[f64], f: impl Fn(&[f64]) -> Vec<f64>) -> Vec<f64> {
        assert_eq!(
            density.len(),
            self.num_elements(),
            "one density per element"
        );
        let rest = self
            .rest_geometry(TetQuadrature::Degree5)
            .expect("constructors check det(dX/dxi) > 0 at the points of every rule");
        let per_point: Vec<Vec<f64>> = (0..rest.num_points())
            .map(|q| f(rest.shape_values(q)))
            .collect();
        let mut out = vec![0.0; self.num_nodes()];
        let mut local = vec![0.0; self.kind().num_nodes()];
        for (e, rho) in density.iter().enumerate() {
            local.fill(0.0);
            for (w, values) in rest.element_weights(e).iter().zip(&per_point) {
                for (l, v) in local.iter_mut().zip(values) {
                    *l += w * v;
                }
            }
            let scale = rho * rest.element_volume(e) / local.iter().sum::<f64>();
            for (&a, l) in self.element(e).iter().zip(&local) {
                out[a] += scale * l;
            }
        }
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::generate::box_grid;
    use crate::Vec3;

    #[test]
    fn quadratic_lumping_is_positive_and_matches_the_closed_forms() {
        let mesh = box_grid(Vec3::zeros(), Vec3::new(1.0, 0.5, 0.25), [1, 1, 1]).unwrap();
        let volumes = mesh.rest_volumes().to_vec();
        let quadratic = ElementMesh::quadratic(mesh);
        let lumped = quadratic.lumped_volumes();
        let consistent = quadratic.node_volumes();
        let mut corner = vec![0.0; quadratic.num_nodes()];
        let mut mid = vec![0.0; quadratic.num_nodes()];
        for (e, v) in volumes.iter().enumerate() {
            for (k, &a) in quadratic.element(e).iter().enumerate() {
                if k < 4 {
                    corner[a] += v;
                } else {
                    mid[a] += v;
                }
            }
        }
        for a in 0..quadratic.num_nodes() {
            let hrz = corner[a] / 36.0 + 4.0 * mid[a] / 27.0;
            let split = -corner[a] / 20.0 + mid[a] / 5.0;
            assert!(
                lumped[a] > 0.0 && (lumped[a] - hrz).abs() < 1e-15,
                "{a}: {}",
                lumped[a]
            );
            assert!(
                (consistent[a] - split).abs() < 1e-15,
                "{a}: {}",
                consistent[a]
            );
        }
        let total: f64 = volumes.iter().sum();
        assert!((lumped.iter().sum::<f64>() - total).abs() < 1e-14);
    }
}
