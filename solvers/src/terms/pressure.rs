//! Follower pressure on a surface: potential `s p V_f(x)` (`s` the load ramp or the load's
//! curve) with
//! `V_f(x) = (1/3) integral x . n da = (1/3) sum_faces sum_q w_q x . (dx/dxi x dx/deta)`, the
//! signed volume of the cones from the origin to the faces (on a 3-node face the one-point
//! rule gives `x0 . (x1 x x2) / 6`; on a 6-node face the degree-4 rule is exact). Its gradient
//! is the follower force `-p n da` and its Hessian the consistent, symmetric load stiffness.
//! For a closed surface, or an open one whose rim is held by Dirichlet conditions (the
//! inflated tube), this is exactly the pressure load; faces are oriented with the body's
//! outward normal, so a positive pressure pushes into the body (into the wall of a chamber:
//! the chamber inflates).

use super::{block_pattern, scatter, EnergyTerm, Faces};
use crate::error::SolverError;
use crate::problem::schedule::{Curve, LoadLevel};
use isochor_mesh::Vec3;
use nalgebra::{DMatrix, Matrix3};

/// Follower pressure on a set of faces.
#[derive(Debug, Clone)]
pub struct FollowerPressure {
    faces: Faces,
    pressure: f64,
    curve: Option<Curve>,
}

impl FollowerPressure {
    /// Pressure `pressure` on `faces` (body-outward orientation).
    pub fn new(faces: Faces, pressure: f64) -> Self {
        FollowerPressure {
            faces,
            pressure,
            curve: None,
        }
    }

    /// The same pressure scaled by `curve` (`None`: the default ramp).
    pub fn following(self, curve: Option<Curve>) -> Self {
        FollowerPressure { curve, ..self }
    }
}

impl EnergyTerm for FollowerPressure {
    fn name(&self) -> &'static str {
        "pressure"
    }

    fn hessian_pattern(&self) -> Vec<(usize, usize)> {
        self.faces.iter().flat_map(block_pattern).collect()
    }

    /// At a point with position `x`, tangents `a = dx/dxi`, `b = dx/deta` and shape values
    /// `N`, `G1 = dN/dxi`, `G2 = dN/deta`, the integrand `T = x . (a x b)` has gradient
    /// `N_c (a x b) + G1_c (b x x) + G2_c (x x a)` for node `c`, and (`T` being trilinear)
    /// Hessian block `(c, d)`
    /// `(G1_c N_d - N_c G1_d)[b]x + (G2_c G1_d - G1_c G2_d)[x]x + (N_c G2_d - G2_c N_d)[a]x`.
    fn evaluate(
        &self,
        x: &[Vec3],
        level: &LoadLevel,
        mut gradient: Option<&mut [f64]>,
        mut hessian: Option<&mut [f64]>,
    ) -> Result<f64, SolverError> {
        let s = level.load_scale(self.curve.as_ref()) * self.pressure / 3.0;
        let n = self.faces.nodes_per_face();
        let mut local = vec![0.0; 3 * n];
        let mut block = DMatrix::<f64>::zeros(3 * n, 3 * n);
        let mut energy = 0.0;
        for (f, face) in self.faces.iter().enumerate() {
            local.fill(0.0);
            block.fill(0.0);
            for (q, w) in self.faces.weights().iter().enumerate() {
                let (values, grads) = (self.faces.values(q), self.faces.gradients(q));
                let mut p = Vec3::zeros();
                let (mut a, mut b) = (Vec3::zeros(), Vec3::zeros());
                for ((&i, v), g) in face.iter().zip(values).zip(grads) {
                    p += *v * x[i];
                    a += g.x * x[i];
                    b += g.y * x[i];
                }
                let sw = s * w;
                energy += sw * p.dot(&a.cross(&b));
                let (ab, bp, pa) = (a.cross(&b), b.cross(&p), p.cross(&a));
                for c in 0..n {
                    let force = values[c] * ab + grads[c].x * bp + grads[c].y * pa;
                    for k in 0..3 {
                        local[3 * c + k] += sw * force[k];
                    }
                }
                if hessian.is_some() {
                    let (sa, sb, sp): (Matrix3<f64>, Matrix3<f64>, Matrix3<f64>) =
                        (a.cross_matrix(), b.cross_matrix(), p.cross_matrix());
                    for d in 0..n {
                        for c in 0..n {
                            let (nc, g1c, g2c) = (values[c], grads[c].x, grads[c].y);
                            let (nd, g1d, g2d) = (values[d], grads[d].x, grads[d].y);
                            let m = sb * (g1c * nd - nc * g1d)
                                + sp * (g2c * g1d - g1c * g2d)
                                + sa * (nc * g2d - g2c * nd);
                            let mut view = block.fixed_view_mut::<3, 3>(3 * c, 3 * d);
                            view += m * sw;
                        }
                    }
                }
            }
            if let Some(g) = gradient.as_deref_mut() {
                scatter(face, &local, g);
            }
            if let Some(h) = hessian.as_deref_mut() {
                let size = 9 * n * n;
                h[size * f..size * (f + 1)].copy_from_slice(block.as_slice());
            }
        }
        Ok(energy)
    }

    fn is_external(&self) -> bool {
        true
    }
}
