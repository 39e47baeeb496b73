//! What is read off a state: pressures and stresses per element, the nodal pressure field,
//! the contact multipliers, the energies, and the frame an observer sees.

use super::state::{Energies, Frame, State};
use super::stepper::Progress;
use super::Simulation;
use crate::model::pressure_gauges::PressureReading;
use crate::model::Model;
use crate::nonlinear::report::StepReport;
use crate::problem::method::Method;
use crate::problem::schedule::LoadLevel;
use crate::terms::EnergyTerm;
use isochor_mesh::element::{deformation_gradient, TET_EDGES};
use isochor_mesh::Vec3;
use nalgebra::Matrix3;

impl Simulation {
    /// What the observer of a run sees after the accepted step of `report` (ending on
    /// `frame`, if it ends on one), at the current state and load `level` with `inverted`
    /// inverted tets.
    pub(super) fn frame<'a>(
        &'a self,
        frame: Option<usize>,
        progress: Progress,
        level: LoadLevel,
        inverted: usize,
        report: &'a StepReport,
        cuts: &'a [StepReport],
    ) -> Frame<'a> {
        let contact = self.model.contact.as_ref();
        let stress = self.cauchy_stress(&self.state);
        Frame {
            index: report.step,
            frame,
            progress,
            state: &self.state,
            tet_pressures: self.tet_pressures(&self.state),
            von_mises: stress.iter().map(von_mises).collect(),
            stress,
            nodal_pressures: self.nodal_pressures(&self.state),
            energies: self.energies(&self.state),
            inverted_tets: inverted,
            contact_forces: contact
                .map(|c| c.vertex_forces(&self.state.positions))
                .unwrap_or_default(),
            surface_contact: self
                .model
                .surface_contact
                .as_ref()
                .map(|c| c.summary(&self.state.positions, self.model.surface_friction.as_ref())),
            mesh_obstacles: self
                .model
                .surface_contact
                .as_ref()
                .map(|c| c.placed_obstacles())
                .unwrap_or_default(),
            report,
            cuts,
            contact_multipliers: contact.map(|c| c.multipliers()).unwrap_or_default(),
            pressure_loads: self.pressure_readings(&self.state, level),
        }
    }

    /// Every pressure load's pressure (given or solved) and enclosed volume ratio at `state`
    /// and load `level`, in the order of the problem's pressure loads.
    pub fn pressure_readings(&self, state: &State, level: LoadLevel) -> Vec<PressureReading> {
        self.model
            .pressure_readings(&state.positions, &level, &state.multipliers)
    }

    /// Pressure per tet at `state`: for `standard`, the mean Cauchy stress `tr(sigma)/3`;
    /// for the mixed and dual methods, the constraint pressures (P0 value, P1 average, `p/J`
    /// for the logarithmic measure); for `zonal`, the zone multipliers plus the mean stress
    /// of the energy (its penalty's `lambda U'(J)`, sec. 8.2 of Sheen et al. 2021).
    pub fn tet_pressures(&self, state: &State) -> Vec<f64> {
        let x = &state.positions;
        let constrained = match &self.model.constraints {
            Some(c) if state.multipliers.len() == c.num_constraints() => {
                Some(c.tet_pressures(x, &state.multipliers))
            }
            _ => None,
        };
        let material_pressure = |e: usize| mean_stress(&self.model, e, x);
        (0..self.model.mesh.num_elements())
            .map(|e| match (&constrained, self.model.method) {
                (None, _) => material_pressure(e),
                (Some(p), Method::Zonal | Method::Standard | Method::Condensed) => {
                    p[e] + material_pressure(e)
                }
                (Some(p), _) => p[e],
            })
            .collect()
    }

    /// Cauchy stress per element at its centroid: the material's `P F^T / J` plus, for the
    /// methods with constraints, their hydrostatic part (the multiplier pressure of the
    /// element, see [`Simulation::tet_pressures`]). NaN where the energy is undefined.
    pub fn cauchy_stress(&self, state: &State) -> Vec<Matrix3<f64>> {
        let x = &state.positions;
        let constrained = match &self.model.constraints {
            Some(c) if state.multipliers.len() == c.num_constraints() => {
                c.tet_pressures(x, &state.multipliers)
            }
            _ => Vec::new(),
        };
        (0..self.model.mesh.num_elements())
            .map(|e| {
                let material =
                    material_stress(&self.model, e, x).unwrap_or_else(|| Matrix3::repeat(f64::NAN));
                material + Matrix3::identity() * constrained.get(e).copied().unwrap_or(0.0)
            })
            .collect()
    }

    /// Von Mises stress `sqrt(3/2 s:s)` per element at its centroid, `s` the deviatoric
    /// Cauchy stress (NaN where the energy is undefined). The hydrostatic constraint
    /// pressures do not enter it, so it is the same for every method's stress.
    pub fn von_mises(&self, state: &State) -> Vec<f64> {
        self.cauchy_stress(state).iter().map(von_mises).collect()
    }

    /// The nodal (P1) pressure field of the methods with one multiplier per vertex
    /// (`mixed-p1`, `mixed-p1-log`, `dual`), tension positive like the multipliers, at every
    /// node: a vertex's multiplier, and on a 10-node mesh the mean of the two ends at a
    /// mid-edge node (the field is linear in each element). `None` for the other methods.
    pub fn nodal_pressures(&self, state: &State) -> Option<Vec<f64>> {
        let nodal = matches!(
            self.model.method,
            Method::MixedP1 | Method::MixedP1Log | Method::Dual
        );
        let mesh = &self.model.mesh;
        let vertices = mesh.corners().num_vertices();
        let cavities = self
            .model
            .cavities
            .as_ref()
            .map_or(0, |c| c.cavities().len());
        if !nodal || state.multipliers.len() != vertices + cavities {
            return None;
        }
        let mut p = state.multipliers[..vertices].to_vec();
        p.resize(mesh.num_nodes(), 0.0);
        for e in 0..mesh.num_elements() {
            let nodes = mesh.element(e);
            for (k, [a, b]) in TET_EDGES
                .iter()
                .enumerate()
                .take(nodes.len().saturating_sub(4))
            {
                p[nodes[4 + k]] =
                    0.5 * (state.multipliers[nodes[*a]] + state.multipliers[nodes[*b]]);
            }
        }
        Some(p)
    }

    /// The contact multipliers (normal force per vertex and obstacle, never negative),
    /// boundary-vertex-major over the obstacles; empty without obstacles.
    pub fn contact_multipliers(&self) -> Vec<f64> {
        self.model
            .contact
            .as_ref()
            .map(|c| c.multipliers())
            .unwrap_or_default()
    }

    /// Energies of `state`.
    pub fn energies(&self, state: &State) -> Energies {
        let mut energies = Energies {
            kinetic: 0.5
                * self
                    .model
                    .masses
                    .iter()
                    .zip(&state.velocities)
                    .map(|(m, v)| m * v.norm_squared())
                    .sum::<f64>(),
            ..Energies::default()
        };
        for term in &self.model.terms {
            let e = term
                .evaluate(&state.positions, &LoadLevel::FULL, None, None)
                .unwrap_or(f64::NAN);
            if term.is_external() {
                energies.external += e;
            } else {
                energies.elastic += e;
            }
        }
        // Relative to rest: minus the work of the loads on the displacements.
        energies.external -= self.rest_external;
        energies.constraint = self.constraint_energy(state);
        energies
    }

    /// [`Energies::constraint`] of `state`.
    fn constraint_energy(&self, state: &State) -> f64 {
        let p = &state.multipliers;
        match (&self.model.constraints, &self.model.augmented) {
            (Some(c), _)
                if p.len() == c.num_constraints() && self.model.method != Method::Condensed =>
            {
                0.5 * c
                    .compliance()
                    .nonzero_entries()
                    .into_iter()
                    .map(|(r, k, v)| p[r] * v * p[k])
                    .sum::<f64>()
            }
            (_, Some(augmented)) if self.model.method == Method::Condensed => augmented
                .evaluate(&state.positions, &LoadLevel::FULL, None, None)
                .unwrap_or(f64::NAN),
            _ => 0.0,
        }
    }
}

/// Cauchy stress `P F^T / J` of the model's material energy at the centroid of element `e`
/// (`None` where the energy is undefined). The constraint pressures of the mixed and zonal
/// methods add only a hydrostatic part.
fn material_stress(model: &Model, e: usize, x: &[Vec3]) -> Option<Matrix3<f64>> {
    let f = deformation_gradient(x, model.mesh.element(e), model.centroids.gradients(e, 0));
    let j = f.determinant();
    let p = model.regions.energy(e).pk1(&f).ok()?;
    Some(p * f.transpose() / j)
}

/// Von Mises stress `sqrt(3/2 s:s)` of a Cauchy stress, `s` its deviatoric part.
fn von_mises(sigma: &Matrix3<f64>) -> f64 {
    let dev = sigma - Matrix3::identity() * (sigma.trace() / 3.0);
    (1.5 * dev.norm_squared()).sqrt()
}

/// Mean Cauchy stress `tr(sigma) / 3` of the model's material at the centroid of element `e`
/// (NaN where the energy is undefined).
fn mean_stress(model: &Model, e: usize, x: &[Vec3]) -> f64 {
    material_stress(model, e, x).map_or(f64::NAN, |s| s.trace() / 3.0)
}
