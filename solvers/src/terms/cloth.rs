//! A cloth sheet's stored energy: the membrane of every triangle and the discrete-shell
//! bending of every interior edge (`isochor_energies::cloth`), over the sheet's nodes among
//! the problem's. A sheet tighter than its placement (`rest_scale < 1`) is tightened as a load
//! is applied: its rest lengths shrink from the placed ones to `rest_scale` times them along
//! the load ramp (at once in dynamics, where loads are applied at once). The element
//! Hessians are exact or projected onto the PSD cone ([`EnergyTerm::project_hessian`]): a
//! sheet under compression buckles, and a hinge away from its rest angle is indefinite.

use super::{block_pattern, scatter, EnergyTerm};
use crate::error::SolverError;
use crate::problem::schedule::LoadLevel;
use isochor_energies::cloth::bending::{HingeTerms, RestHinge};
use isochor_energies::cloth::membrane::energy_gradient_hessian;
use isochor_energies::cloth::Fabric;
use isochor_energies::triangle::RestTriangle;
use isochor_energies::{project_to_psd, TriangleTerms, Vector12, Vector9};
use isochor_mesh::{hinges, Vec3};
use rayon::prelude::*;
use std::sync::atomic::{AtomicBool, Ordering};

/// One element's energy and gradient.
type Element<V> = (f64, V);

/// Membrane and bending energy of one cloth sheet.
#[derive(Debug)]
pub struct Cloth {
    fabric: Fabric,
    triangles: Vec<[usize; 3]>,
    /// The placed triangles (rest scale 1).
    placed_triangles: Vec<RestTriangle>,
    rest_scale: f64,
    hinges: Vec<[usize; 4]>,
    rest_hinges: Vec<RestHinge>,
    /// Whether the element Hessians are PSD-projected (the default) or exact.
    projected: AtomicBool,
}

impl Cloth {
    /// The sheet of consistently oriented `triangles` (indices into `rest`, the problem's rest
    /// positions) of `fabric`, whose rest lengths at full load are those of `rest` times
    /// `rest_scale` (a band with `rest_scale < 1` is tighter than its placement). The hinges'
    /// energy does not depend on the scale (`|e_0|^2 / (A_1 + A_2)` and `theta_0` are
    /// invariant). Errors name a degenerate triangle or hinge and a non-manifold or
    /// inconsistently oriented edge.
    pub fn new(
        rest: &[Vec3],
        triangles: Vec<[usize; 3]>,
        fabric: Fabric,
        rest_scale: f64,
    ) -> Result<Self, SolverError> {
        if !(rest_scale.is_finite() && rest_scale > 0.0) {
            return Err(SolverError::InvalidProblem(format!(
                "the cloth's rest_scale = {rest_scale} must be finite and positive"
            )));
        }
        let placed_triangles = triangles
            .iter()
            .enumerate()
            .map(|(t, nodes)| {
                RestTriangle::new(&nodes.map(|v| rest[v])).ok_or_else(|| {
                    SolverError::InvalidProblem(format!(
                        "cloth triangle {t} {nodes:?} is degenerate"
                    ))
                })
            })
            .collect::<Result<Vec<_>, _>>()?;
        let hinges = hinges(&triangles)?;
        let rest_hinges = hinges
            .iter()
            .map(|nodes| {
                RestHinge::new(&fabric, &nodes.map(|v| rest[v])).ok_or_else(|| {
                    SolverError::InvalidProblem(format!("cloth hinge {nodes:?} is degenerate"))
                })
            })
            .collect::<Result<Vec<_>, _>>()?;
        Ok(Cloth {
            fabric,
            triangles,
            placed_triangles,
            rest_scale,
            hinges,
            rest_hinges,
            projected: AtomicBool::new(true),
        })
    }

    /// Number of interior edges (hinges).
    pub fn num_hinges(&self) -> usize {
        self.hinges.len()
    }

    /// Adds the sheet's lumped masses to `masses` (one per node of the problem): each
    /// triangle's `density h A_0 / 3` to each of its corners, `A_0` its rest area (the
    /// placed one times `rest_scale^2`).
    pub fn add_lumped_masses(&self, density: f64, masses: &mut [f64]) {
        let areal = density * self.fabric.thickness();
        let rest_area = |t: &RestTriangle| t.area() * self.rest_scale * self.rest_scale;
        for (nodes, placed) in self.triangles.iter().zip(&self.placed_triangles) {
            nodes
                .iter()
                .for_each(|&v| masses[v] += areal * rest_area(placed) / 3.0);
        }
    }

    /// The fabric's membrane shear stiffness per node, `mu h` (N/m): the stiffness a node of
    /// the sheet opposes to a push, beside a solid's `mu h` of its cells.
    pub fn membrane_stiffness(&self) -> f64 {
        self.fabric.mu() * self.fabric.thickness()
    }

    /// The sheet's nodes, each once, in increasing order.
    pub fn nodes(&self) -> Vec<usize> {
        let mut nodes: Vec<usize> = self.triangles.iter().flatten().copied().collect();
        nodes.sort_unstable();
        nodes.dedup();
        nodes
    }
}

impl Cloth {
    /// The rest scale at `level`: from 1 (placed) to `rest_scale` along the load ramp.
    fn scale_at(&self, level: &LoadLevel) -> f64 {
        let ramp = level.load_scale(None);
        self.rest_scale + (1.0 - self.rest_scale) * (1.0 - ramp)
    }

    fn membrane(&self, x: &[Vec3], t: usize, scale: f64) -> TriangleTerms {
        let nodes = &self.triangles[t];
        let rest = self.placed_triangles[t].scaled(scale);
        energy_gradient_hessian(&self.fabric, &nodes.map(|v| x[v]), &rest)
    }

    fn bending(&self, x: &[Vec3], h: usize) -> Result<HingeTerms, SolverError> {
        let nodes = &self.hinges[h];
        self.rest_hinges[h]
            .energy_gradient_hessian(&nodes.map(|v| x[v]))
            .ok_or_else(|| {
                SolverError::InvalidProblem(format!(
                    "a triangle of cloth hinge {nodes:?} has collapsed"
                ))
            })
    }
}

impl EnergyTerm for Cloth {
    fn name(&self) -> &'static str {
        "cloth"
    }

    fn hessian_pattern(&self) -> Vec<(usize, usize)> {
        let triangles = self.triangles.iter().flat_map(|t| block_pattern(t));
        let hinges = self.hinges.iter().flat_map(|h| block_pattern(h));
        triangles.chain(hinges).collect()
    }

    fn project_hessian(&self, projected: bool) -> bool {
        self.projected.store(projected, Ordering::Relaxed);
        true
    }

    fn evaluate(
        &self,
        x: &[Vec3],
        level: &LoadLevel,
        gradient: Option<&mut [f64]>,
        hessian: Option<&mut [f64]>,
    ) -> Result<f64, SolverError> {
        // Elements evaluated in parallel, each Hessian written straight into its slot (the
        // rest kept per element only as energy and gradient), then summed in element order
        // (resumed runs must equal uninterrupted ones bit for bit).
        let scale = self.scale_at(level);
        let projected = self.projected.load(Ordering::Relaxed);
        let membrane = |t: usize, slot: Option<&mut [f64]>| {
            let m = self.membrane(x, t, scale);
            match (slot, projected) {
                (Some(o), true) => o.copy_from_slice(project_to_psd(&m.hessian).as_slice()),
                (Some(o), false) => o.copy_from_slice(m.hessian.as_slice()),
                (None, _) => {}
            }
            (m.energy, m.gradient)
        };
        let hinge = |h: usize, slot: Option<&mut [f64]>| {
            let b = self.bending(x, h)?;
            match (slot, projected) {
                (Some(o), true) => o.copy_from_slice(project_to_psd(&b.hessian).as_slice()),
                (Some(o), false) => o.copy_from_slice(b.hessian.as_slice()),
                (None, _) => {}
            }
            Ok((b.energy, b.gradient))
        };
        let (membranes, hinges): (Vec<Element<Vector9>>, Vec<Element<Vector12>>) = match hessian {
            Some(out) => {
                let (triangle_blocks, hinge_blocks) = out.split_at_mut(81 * self.triangles.len());
                let membranes = (triangle_blocks.par_chunks_mut(81).enumerate())
                    .map(|(t, o)| membrane(t, Some(o)))
                    .collect();
                let hinges = (hinge_blocks.par_chunks_mut(144).enumerate())
                    .map(|(h, o)| hinge(h, Some(o)))
                    .collect::<Result<_, SolverError>>()?;
                (membranes, hinges)
            }
            None => {
                let membranes = (0..self.triangles.len())
                    .into_par_iter()
                    .map(|t| membrane(t, None))
                    .collect();
                let hinges = (0..self.hinges.len())
                    .into_par_iter()
                    .map(|h| hinge(h, None))
                    .collect::<Result<_, SolverError>>()?;
                (membranes, hinges)
            }
        };
        if let Some(out) = gradient {
            for (nodes, (_, g)) in self.triangles.iter().zip(&membranes) {
                scatter(nodes, g.as_slice(), out);
            }
            for (nodes, (_, g)) in self.hinges.iter().zip(&hinges) {
                scatter(nodes, g.as_slice(), out);
            }
        }
        let energy =
            membranes.iter().map(|m| m.0).sum::<f64>() + hinges.iter().map(|h| h.0).sum::<f64>();
        Ok(energy)
    }
}
