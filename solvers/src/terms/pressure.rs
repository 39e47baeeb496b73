//! Follower pressure on a surface: potential `load p V_f(x)` with
//! `V_f(x) = sum_faces x0 . (x1 x x2) / 6`, the signed volume of the cones from the origin
//! to the faces. Its gradient is the follower force `-p n dA` (lumped to vertices) and its
//! Hessian the consistent, symmetric load stiffness. For a closed surface, or an open one
//! whose rim is held by Dirichlet conditions (the inflated tube), this is exactly the
//! pressure load; faces are oriented with the body's outward normal, so a positive pressure
//! pushes into the body (into the wall of a chamber: the chamber inflates).

use super::{block_pattern, scatter, EnergyTerm};
use crate::SolverError;
use isochor_mesh::Vec3;
use nalgebra::{Matrix3, SMatrix};

/// Follower pressure on a set of faces.
#[derive(Debug, Clone)]
pub struct FollowerPressure {
    faces: Vec<[usize; 3]>,
    pressure: f64,
}

impl FollowerPressure {
    /// Pressure `pressure` on `faces` (body-outward orientation).
    pub fn new(faces: Vec<[usize; 3]>, pressure: f64) -> Self {
        FollowerPressure { faces, pressure }
    }
}

/// The skew matrix `[a]x` with `[a]x b = a x b`.
fn skew(a: &Vec3) -> Matrix3<f64> {
    a.cross_matrix()
}

impl EnergyTerm for FollowerPressure {
    fn name(&self) -> &'static str {
        "pressure"
    }

    fn hessian_pattern(&self) -> Vec<(usize, usize)> {
        self.faces.iter().flat_map(block_pattern).collect()
    }

    fn evaluate(
        &self,
        x: &[Vec3],
        load: f64,
        mut gradient: Option<&mut [f64]>,
        mut hessian: Option<&mut [f64]>,
    ) -> Result<f64, SolverError> {
        let s = load * self.pressure / 6.0;
        let mut energy = 0.0;
        for (f, face) in self.faces.iter().enumerate() {
            let [a, b, c] = face.map(|v| x[v]);
            energy += s * a.dot(&b.cross(&c));
            if let Some(g) = gradient.as_deref_mut() {
                let mut local = [0.0; 9];
                for (k, v) in [b.cross(&c), c.cross(&a), a.cross(&b)].iter().enumerate() {
                    local[3 * k..3 * k + 3].copy_from_slice((v * s).as_slice());
                }
                scatter(face, &local, g);
            }
            if let Some(h) = hessian.as_deref_mut() {
                // d2/dxa dxb of a . (b x c) = -[c]x for (a, b), cyclic.
                let mut block = SMatrix::<f64, 9, 9>::zeros();
                let pairs = [(0, 1, c), (1, 2, a), (2, 0, b)];
                for (i, j, w) in pairs {
                    let m = -skew(&w) * s;
                    block.fixed_view_mut::<3, 3>(3 * i, 3 * j).copy_from(&m);
                    block
                        .fixed_view_mut::<3, 3>(3 * j, 3 * i)
                        .copy_from(&m.transpose());
                }
                h[81 * f..81 * (f + 1)].copy_from_slice(block.as_slice());
            }
        }
        Ok(energy)
    }

    fn is_external(&self) -> bool {
        true
    }
}
