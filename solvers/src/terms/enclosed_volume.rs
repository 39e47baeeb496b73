//! The cone volume of a set of faces about a point `o`:
//! `V(x) = (1/3) integral (x - o) . n da = (1/3) sum_faces sum_q w_q (x - o) . (dx/dxi x dx/deta)`,
//! the signed volume of the cones from `o` to the faces, with the faces' own orientation. It
//! is the enclosed volume of a closed surface for any `o`, and of a surface closed by planes
//! through `o` (symmetry cuts: `(x - o) . n = 0` on them). The integrand has degree 1 on a
//! 3-node face (the one-point rule gives `(x0 - o) . ((x1 - o) x (x2 - o)) / 6` exactly) and
//! degree 4 on a 6-node face (the degree-4 rule of [`Faces`] is exact), so value, gradient
//! and Hessian are exact. Used by the follower pressure (its potential) and by the volume
//! control of a cavity (a constraint row, see docs/scene-format.md#loads).

use super::openings::Openings;
use super::Faces;
use crate::error::SolverError;
use isochor_mesh::Vec3;
use nalgebra::{DMatrix, Matrix3};

/// The cone volume of `faces` about `origin`, with its openings capped if asked.
#[derive(Debug, Clone)]
pub struct EnclosedVolume {
    faces: Faces,
    origin: Vec3,
    openings: Openings,
}

impl EnclosedVolume {
    /// The cone volume of `faces` about `origin`.
    pub fn new(faces: Faces, origin: Vec3) -> Self {
        EnclosedVolume {
            faces,
            origin,
            openings: Openings::default(),
        }
    }

    /// The same with every boundary loop of the faces capped by the fan from its centroid
    /// ([`Openings`]): the volume of a chamber with openings, whatever the origin.
    ///
    /// Errors: the faces are not an oriented surface, or a loop cannot be capped.
    pub fn capped(self) -> Result<Self, SolverError> {
        let openings = Openings::of(&self.faces)?;
        Ok(EnclosedVolume { openings, ..self })
    }

    /// Entries of the gradient buffer of [`EnclosedVolume::evaluate`].
    pub fn gradient_len(&self) -> usize {
        3 * self.faces.nodes_per_face() * self.faces.len()
            + self
                .openings
                .loop_nodes()
                .map(|n| 3 * n.len())
                .sum::<usize>()
    }

    /// Entries of the Hessian buffer of [`EnclosedVolume::evaluate`].
    pub fn hessian_len(&self) -> usize {
        let n = self.faces.nodes_per_face();
        9 * n * n * self.faces.len()
            + self
                .openings
                .loop_nodes()
                .map(|l| 9 * l.len() * l.len())
                .sum::<usize>()
    }

    /// The faces.
    pub fn faces(&self) -> &Faces {
        &self.faces
    }

    /// The volume at positions `x`.
    pub fn value(&self, x: &[Vec3]) -> f64 {
        self.evaluate(x, 1.0, None, None)
    }

    /// `(dof, dof)` of the Hessian entries: one dense `3n x 3n` block per face, then one
    /// per capped loop, column-major (the order of [`EnclosedVolume::evaluate`]'s Hessian).
    pub fn hessian_pattern(&self) -> Vec<(usize, usize)> {
        self.faces
            .iter()
            .chain(self.openings.loop_nodes())
            .flat_map(super::block_pattern)
            .collect()
    }

    /// `(node, axis)` DOFs of the gradient, face-major, then loop-major (duplicates where
    /// faces share nodes).
    pub fn gradient_dofs(&self) -> Vec<usize> {
        self.faces
            .iter()
            .chain(self.openings.loop_nodes())
            .flat_map(|nodes| nodes.iter().flat_map(|&v| (0..3).map(move |k| 3 * v + k)))
            .collect()
    }

    /// `s V(x)`; adds `s dV/dx` per face (and capped loop) into `gradient` (the order of
    /// [`EnclosedVolume::gradient_dofs`]) and writes `s` times the Hessian blocks into
    /// `hessian` (the order of [`EnclosedVolume::hessian_pattern`]) when asked.
    ///
    /// At a point with position `y = x - o`, tangents `a = dx/dxi`, `b = dx/deta` and shape
    /// values `N`, `G1 = dN/dxi`, `G2 = dN/deta`, the integrand `T = y . (a x b)` has
    /// gradient `N_c (a x b) + G1_c (b x y) + G2_c (y x a)` for node `c`, and (`T` being
    /// trilinear) Hessian block `(c, d)`
    /// `(G1_c N_d - N_c G1_d)[b]x + (G2_c G1_d - G1_c G2_d)[y]x + (N_c G2_d - G2_c N_d)[a]x`.
    pub fn evaluate(
        &self,
        x: &[Vec3],
        s: f64,
        mut gradient: Option<&mut [f64]>,
        mut hessian: Option<&mut [f64]>,
    ) -> f64 {
        let s = s / 3.0;
        let faces = &self.faces;
        let n = faces.nodes_per_face();
        let mut local = vec![0.0; 3 * n];
        let mut block = DMatrix::<f64>::zeros(3 * n, 3 * n);
        let mut volume = 0.0;
        for (f, face) in faces.iter().enumerate() {
            local.fill(0.0);
            block.fill(0.0);
            for (q, w) in faces.weights().iter().enumerate() {
                let (values, grads) = (faces.values(q), faces.gradients(q));
                let mut y = -self.origin;
                let (mut a, mut b) = (Vec3::zeros(), Vec3::zeros());
                for ((&i, v), g) in face.iter().zip(values).zip(grads) {
                    y += *v * x[i];
                    a += g.x * x[i];
                    b += g.y * x[i];
                }
                let sw = s * w;
                let (ab, by, ya) = (a.cross(&b), b.cross(&y), y.cross(&a));
                volume += sw * y.dot(&ab);
                if gradient.is_some() {
                    for c in 0..n {
                        let force = values[c] * ab + grads[c].x * by + grads[c].y * ya;
                        for k in 0..3 {
                            local[3 * c + k] += sw * force[k];
                        }
                    }
                }
                if hessian.is_some() {
                    let (sa, sb, sy): (Matrix3<f64>, Matrix3<f64>, Matrix3<f64>) =
                        (a.cross_matrix(), b.cross_matrix(), y.cross_matrix());
                    for d in 0..n {
                        for c in 0..n {
                            let (nc, g1c, g2c) = (values[c], grads[c].x, grads[c].y);
                            let (nd, g1d, g2d) = (values[d], grads[d].x, grads[d].y);
                            let m = sb * (g1c * nd - nc * g1d)
                                + sy * (g2c * g1d - g1c * g2d)
                                + sa * (nc * g2d - g2c * nd);
                            let mut view = block.fixed_view_mut::<3, 3>(3 * c, 3 * d);
                            view += m * sw;
                        }
                    }
                }
            }
            if let Some(g) = gradient.as_deref_mut() {
                g[3 * n * f..3 * n * (f + 1)]
                    .iter_mut()
                    .zip(&local)
                    .for_each(|(a, b)| *a += b);
            }
            if let Some(h) = hessian.as_deref_mut() {
                let size = 9 * n * n;
                h[size * f..size * (f + 1)].copy_from_slice(block.as_slice());
            }
        }
        if !self.openings.is_empty() {
            let (g_at, h_at) = (3 * n * faces.len(), 9 * n * n * faces.len());
            volume += self.openings.evaluate(
                x,
                self.origin,
                3.0 * s,
                gradient.map(|g| &mut g[g_at..]),
                hessian.map(|h| &mut h[h_at..]),
            );
        }
        volume
    }

    /// `s V(x)`, adding `s dV/dx` into the full-space `gradient` (length `3 * x.len()`) and
    /// writing the Hessian blocks as [`EnclosedVolume::evaluate`] does, when asked.
    pub fn accumulate(
        &self,
        x: &[Vec3],
        s: f64,
        gradient: Option<&mut [f64]>,
        hessian: Option<&mut [f64]>,
    ) -> f64 {
        let Some(gradient) = gradient else {
            return self.evaluate(x, s, None, hessian);
        };
        let mut local = vec![0.0; self.gradient_len()];
        let v = self.evaluate(x, s, Some(&mut local), hessian);
        for (dof, g) in self.gradient_dofs().into_iter().zip(&local) {
            gradient[dof] += g;
        }
        v
    }
}
