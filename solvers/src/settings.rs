//! Solver settings: Newton limits, tolerances, the linear solver choice and the volume
//! projection of implicit Euler steps.

use crate::error::SolverError;
use crate::linear::Ordering;

/// How linear systems are solved.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub enum LinearSolver {
    /// Sparse direct factorization (Cholesky for SPD systems, LDL^T for saddle points),
    /// symbolic factorization reused.
    #[default]
    Direct,
    /// Preconditioned iterative solve (CG for SPD, MINRES for saddle points), for meshes too
    /// large to factor (sec. 8 of Francu et al.).
    Iterative(IterativeSettings),
    /// [`LinearSolver::Direct`] for systems of at most [`AUTO_DIRECT_UNKNOWNS`] unknowns,
    /// [`LinearSolver::Iterative`] with these settings above.
    Auto(IterativeSettings),
}

/// Systems of at most this many unknowns (free DOFs plus constraint rows) are solved directly by
/// [`LinearSolver::Auto`]. On the cantilever at nu = 0.4999 the direct solver was faster than the
/// iterative one at every size measured (docs/performance.md, "The iterative linear path"), so the
/// switch sits where the direct factor's memory becomes the limit: the scenes' memory model
/// (`410 B * n^(4/3)` of fill) reaches 4 GiB, a sixth of a 24 GiB machine, at about 180k
/// unknowns.
pub const AUTO_DIRECT_UNKNOWNS: usize = 180_000;

impl LinearSolver {
    /// The iterative settings to use for a system of `unknowns` unknowns, or `None` for
    /// the direct solver.
    pub fn iterative_for(self, unknowns: usize) -> Option<IterativeSettings> {
        match self {
            LinearSolver::Direct => None,
            LinearSolver::Iterative(s) => Some(s),
            LinearSolver::Auto(s) => (unknowns > AUTO_DIRECT_UNKNOWNS).then_some(s),
        }
    }
}

/// Settings of the iterative linear solver.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct IterativeSettings {
    /// The tightest relative residual a solve is asked for: the floor of the inexact-Newton
    /// forcing terms, which loosen the solves far from convergence (Eisenstat and Walker
    /// 1996, choice 2).
    pub tolerance: f64,
    /// Iterations allowed per linear solve.
    pub max_iterations: usize,
    /// Preconditioner of the stiffness block.
    pub preconditioner: PreconditionerKind,
}

impl Default for IterativeSettings {
    fn default() -> Self {
        IterativeSettings {
            tolerance: 1e-8,
            max_iterations: 1000,
            preconditioner: PreconditionerKind::default(),
        }
    }
}

/// Preconditioner of the stiffness block `K` in CG, and of the `K` block of the
/// block-diagonal saddle-point preconditioner in MINRES.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum PreconditionerKind {
    /// `diag(K)` (sec. 8 of Francu et al. 2021).
    Jacobi,
    /// Zero-fill incomplete Cholesky of `K`, shifted if a pivot breaks down.
    #[default]
    IncompleteCholesky,
    /// One V-cycle of smoothed-aggregation algebraic multigrid on `K` with the rigid-body
    /// modes as near null space.
    Multigrid,
}

/// Which matrix a Newton iteration solves with (the direct linear solver; the iterative one
/// always builds its preconditioner afresh).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Jacobian {
    /// The Newton matrix at the iterate, assembled and factorized every iteration:
    /// quadratic convergence.
    #[default]
    Full,
    /// Modified Newton: within a step (after its first iteration, with no prescribed motion
    /// left), the last factorization is reused with the residual at the iterate alone, as
    /// long as a full step along that direction halves the residual norm (the saddle-point
    /// merit, or the force residual with sufficient energy decrease); otherwise the
    /// iteration is redone with a fresh matrix (a reformation). Linear convergence with
    /// fewer assemblies and factorizations; the same solution to the tolerances.
    Modified,
}

/// Limits and tolerances of the nonlinear solvers.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Settings {
    /// Newton iterations per step (or primal iterations per dual iteration).
    pub max_iterations: usize,
    /// Force residual tolerance, relative to the problem's force scale (see
    /// [`crate::Simulation::force_scale`]).
    pub force_tolerance: f64,
    /// Constraint residual tolerance: `max_i |phi_i - (C p)_i| / V_i` with `V_i` the rest
    /// volume measured by constraint `i`.
    pub constraint_tolerance: f64,
    /// Line-search halvings before a step is declared failed.
    pub max_backtracks: usize,
    /// Outer iterations of the dual solver per step.
    pub max_dual_iterations: usize,
    /// Conjugate the dual ascent directions (otherwise plain steepest ascent, eq. 41).
    pub dual_conjugate: bool,
    /// Project element Hessians to PSD (displacement-only Newton).
    pub project_hessians: bool,
    /// Linear solver.
    pub linear: LinearSolver,
    /// Fill-reducing ordering of the direct factorizations (`K` and the KKT matrix).
    pub ordering: Ordering,
    /// Whether each Newton iteration factorizes a fresh matrix (the default) or reuses the
    /// last factorization while it converges fast enough.
    pub jacobian: Jacobian,
    /// Largest penetration of a vertex into an obstacle accepted at convergence, relative to
    /// the diagonal of the mesh's rest bounding box.
    pub contact_tolerance: f64,
    /// Multiplier updates (outer augmented-Lagrangian iterations) of the contact per step.
    pub max_contact_iterations: usize,
    /// Accept a step of implicit Euler after `max_iterations` Newton iterations even if the
    /// tolerances are not met, as interactive simulators do (Francu et al. 2021, Fig. 9: 3
    /// Newton iterations per 16 ms step); the step's report says it did not converge.
    /// Refused in quasi-static stepping (whose steps must be equilibria) and for `dual`
    /// (whose `max_iterations` counts primal iterations per dual iteration).
    pub accept_unconverged: bool,
    /// The volume correction after each implicit Euler step (none by default): the
    /// baselines of Fig. 8 of Sheen et al. 2021. Refused in quasi-static stepping.
    pub volume_projection: VolumeProjection,
}

impl Default for Settings {
    fn default() -> Self {
        Settings {
            max_iterations: 50,
            force_tolerance: 1e-9,
            constraint_tolerance: 1e-10,
            max_backtracks: 30,
            max_dual_iterations: 500,
            dual_conjugate: true,
            project_hessians: false,
            linear: LinearSolver::Direct,
            ordering: Ordering::Auto,
            jacobian: Jacobian::Full,
            contact_tolerance: 1e-6,
            max_contact_iterations: 30,
            accept_unconverged: false,
            volume_projection: VolumeProjection::None,
        }
    }
}

/// What corrects the volume after each implicit Euler step.
///
/// **One-ring pressure projection** (Irving, Schroeder and Fedkiw 2007, "Volume Conserving
/// Finite Element Simulations of Deformable Models"). Each vertex `i` of a 4-node tet mesh
/// owns the volume of its one ring, `V_i(x) = sum_{e incident to i} V_e(x)`, rest value
/// `V0_i`. `G = dV/dx` (one row per vertex) is four times the Jacobian of the nodal (P1)
/// volume constraints, whose row `i` is `sum_e V_e (J_e - 1) / 4` ([`NodalConstraints`](isochor_constraints::NodalConstraints));
/// on 10-node tets the same rows define `V_i = 4 integral L_i J dV` (`L_i` the corner's
/// linear shape function), the one-ring volume on 4-node tets.
/// `W` is the inverse lumped mass per DOF, zero on prescribed DOFs (they do not move). After
/// the elastic update (here a full implicit Euler step of the base material) two pressure
/// solves with the SPD matrix `A = dt^2 G W G^T` follow, one pressure per vertex:
///
/// 1. positions, with the clamped volume recovery: the linearized one-ring constraint
///    `V_i(x + dx) ~ V_i(x) + (G dx)_i = V_i(x) + d_i` with the target change
///    `d_i = clamp(V0_i - V_i(x), -r V0_i, r V0_i)` (`r` the recovery per step), solved by
///    `A p = d`, `dx = dt^2 W G^T p`;
/// 2. velocities, at the corrected positions: the incompressible motion `G v' = 0`,
///    `v' = v + dt W G^T p'` with `A p' = -dt G v`.
///
/// `p` and `p'` are pressures (Pa): `G^T p` is the force of a pressure on the one rings.
/// Positions and velocities are corrected by separate solves, so that the volume recovery
/// does not enter the velocities (the reason Irving et al. give for splitting them), and
/// the recovery is clamped as Sheen et al. did to keep this scene stable ("an aggressive
/// clamping of the volume recovery"). What is ours, not taken from the paper (which we could
/// not consult): the elastic update is our fully implicit Euler step rather than their
/// semi-implicit one, the clamp is relative to each one ring's rest volume, both solves use
/// one linearization each (no iteration to the exact volume), and contact is not part of the
/// pressure solve. A one ring whose vertices are all prescribed is left as it is. On
/// structured boxes `G` has spurious pressure modes (`G^T q = 0`, see [`NodalConstraints`](isochor_constraints::NodalConstraints)),
/// so `A` is factored with the diagonal shift `1e-8 max A_ii`: a shifted mode moves no
/// vertex, and the other pressures change by at most that shift over `A`'s smallest nonzero
/// eigenvalue, relatively.
///
/// **Global rescaling** (the "naive global volume rescaling" of Sheen et al. 2021, sec.
/// 8.3): the free DOFs are scaled about their centre of mass, `x' = c + s (x - c)` per axis
/// (`c` mass-weighted over the free DOFs of that axis, so it does not move), with `s` such
/// that the body's total volume equals its rest volume (`s = (V0 / V)^(1/3)` without
/// prescribed DOFs; with them, `V(s)` is a cubic solved by secant iterations). Velocities
/// are left as the step computed them: the rescaling is a correction of positions alone,
/// like Irving et al.'s position solve, so its displacement is not turned into motion (which
/// would add the correction's energy as kinetic energy every frame), and momentum is kept.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub enum VolumeProjection {
    /// Nothing: the state is the step's.
    #[default]
    None,
    /// Irving et al. 2007's one-ring pressure projection (above), recovering at most
    /// `recovery` of each one ring's rest volume per step.
    OneRing {
        /// The largest volume change of a one ring per step, relative to its rest volume.
        recovery: f64,
    },
    /// Rescale the body about its centre of mass to its rest volume (above).
    GlobalRescale,
}

impl VolumeProjection {
    /// Checks the recovery of [`VolumeProjection::OneRing`]: `0 < recovery <= 1`.
    pub fn validate(&self) -> Result<(), SolverError> {
        match *self {
            VolumeProjection::OneRing { recovery } if !(recovery > 0.0 && recovery <= 1.0) => {
                Err(SolverError::InvalidProblem(format!(
                    "the one-ring volume recovery {recovery} must lie in (0, 1]"
                )))
            }
            _ => Ok(()),
        }
    }
}
