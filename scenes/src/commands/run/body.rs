//! What a run keeps of its resolved scene once the solver owns the problem.

use crate::probes::ProbeInput;
use crate::record::StepRecord;
use crate::resolve::Selections;
use isochor_mesh::{ElementMesh, Vec3, Zones};
use isochor_solvers::{ClothSheet, Energies, Problem};

/// The rest mesh, the selections and zones the probes read, and the material's `kappa`.
pub(super) struct Body {
    pub mesh: ElementMesh,
    pub selections: Selections,
    pub zones: Option<Zones>,
    /// Volumetric stiffness of the mixed methods (`None` if it does not apply).
    pub kappa: Option<f64>,
    /// What the user should know about how the meshes were taken (the run's warnings).
    pub notices: Vec<String>,
    /// The cloth sheets.
    pub cloths: Vec<ClothSheet>,
}

/// One state as the probes read it.
pub(super) struct ProbedState<'a> {
    pub positions: &'a [Vec3],
    pub tet_pressures: &'a [f64],
    pub constraint_residual: f64,
    pub energies: Energies,
    pub history: &'a [StepRecord],
}

impl Body {
    /// The body of `problem`, with the resolved scene's selections and zones.
    pub fn new(problem: &Problem, selections: Selections, zones: Option<Zones>) -> Body {
        Body {
            mesh: problem.mesh.clone(),
            selections,
            zones,
            kappa: problem.material.mixed_kappa().ok(),
            notices: Vec::new(),
            cloths: problem.cloths.clone(),
        }
    }

    /// The probes' view of `state` on this body.
    pub fn probe_input<'a>(&'a self, state: &ProbedState<'a>) -> ProbeInput<'a> {
        ProbeInput {
            mesh: &self.mesh,
            selections: &self.selections,
            zones: self.zones.as_ref(),
            positions: state.positions,
            tet_pressures: state.tet_pressures,
            constraint_residual: state.constraint_residual,
            energies: state.energies,
            kappa: self.kappa,
            history: state.history,
            cloths: &self.cloths,
        }
    }

    /// The rest state, at which the probes are checked before the run.
    pub fn rest<'a>(&'a self, zeros: &'a [f64]) -> ProbedState<'a> {
        ProbedState {
            positions: self.mesh.nodes(),
            tet_pressures: zeros,
            constraint_residual: 0.0,
            energies: Energies::default(),
            history: &[],
        }
    }
}
