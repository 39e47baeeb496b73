//! Newton's quadratic convergence, iteration by iteration. The solvers' reports record the
//! residuals before every iteration (`StepReport::iterations`) and after the last; these are
//! compared with exact Newton's on the same problem, from the same starting point:
//!
//! - on the uniaxial patch test, exact Newton is computed independently of the solver's
//!   code: the iterates stay homogeneous, `F = diag(s, t, t)` with a uniform pressure `p`,
//!   so Newton on the mesh is Newton on the two or three unknowns `(s, t[, p])` of the
//!   stress balance, whose derivatives are written out below;
//! - on a cantilever step (not homogeneous), exact Newton is a dense solve with the matrix
//!   that `assembled.rs` checks against finite differences.
//!
//! Newton's residual obeys `r_{k+1} = |R''(dx_k, dx_k)| / 2 + O(|dx_k|^3)`, so matching
//! exact Newton to the accuracy of the linear solves means converging quadratically with
//! its constants `r_{k+1} / r_k^2` (printed, in units of the force scale, above the
//! tolerances: below them the residuals are rounding), and the iteration counts are exact
//! Newton's (asserted). The patch test's exact Newton does not use the solver's code, so a
//! Jacobian off by 0.1% shows there (linear convergence: a residual exact Newton does not
//! have); the cantilever's uses the solver's matrix, so it guards the iteration itself: a
//! damped or shifted step, a skipped multiplier update, a wrong Dirichlet right-hand side.

use isochor_mesh::{generate::box_grid, TetMesh, Vec3};
use isochor_solvers::{
    Dirichlet, Load, Material, Method, Motion, NewtonSystem, Problem, Settings, Simulation, State,
    StepReport, Stepping,
};
use nalgebra::{DVector, Matrix2, Matrix3, Vector2, Vector3};

/// Young's modulus and Poisson ratio of the patch; its traction stretches it by about 20%.
const YOUNG: f64 = 1e5;
const NU: f64 = 0.3;
const TRACTION: f64 = 2e4;
/// Load steps: each starts from the previous solution, a good initial guess.
const STEPS: usize = 4;

/// Residuals as the solvers report them: the force residual's 2-norm over the free DOFs,
/// the constraint residual's max-norm per unit rest volume, `max |phi_i - (C p)_i| / V_i`,
/// and the volume error `sum |phi_i - (C p)_i| / sum V_i` (Francu et al. 2021, Fig. 8).
type Residuals = (f64, f64, f64);

/// Every residual of a step: before each iteration, then at convergence.
fn reported(report: &StepReport) -> Vec<Residuals> {
    report
        .iterations
        .iter()
        .map(|i| (i.force_residual, i.constraint_residual, i.volume_error))
        .chain([(
            report.force_residual,
            report.constraint_residual,
            report.volume_error,
        )])
        .collect()
}

/// The residuals of a Newton system (`volumes`: rest volume of each constraint row).
fn residuals(system: &NewtonSystem, volumes: &[f64]) -> Residuals {
    let nf = system.free.len();
    let force = system.residual[..nf]
        .iter()
        .map(|r| r * r)
        .sum::<f64>()
        .sqrt();
    let theta = &system.residual[nf..];
    let constraint = theta
        .iter()
        .zip(volumes)
        .fold(0.0, |m: f64, (t, v)| m.max((t / v).abs()));
    let volume_error = theta.iter().map(|t| t.abs()).sum::<f64>() / volumes.iter().sum::<f64>();
    (force, constraint, volume_error)
}

/// Vertices of `mesh` with `coordinate[axis] == value`.
fn plane(mesh: &TetMesh, axis: usize, value: f64) -> Vec<usize> {
    (0..mesh.num_vertices())
        .filter(|&v| (mesh.positions()[v][axis] - value).abs() < 1e-12)
        .collect()
}

/// The unit box of 2 x 2 x 2 cells under a dead traction `TRACTION` on `x = 1`, on rollers
/// at `x = 0` and pinned so that it may contract freely: its exact solution is homogeneous.
fn patch(method: Method) -> Problem {
    let mesh = box_grid(Vec3::zeros(), Vec3::repeat(1.0), [2, 2, 2]).expect("box");
    let vertex = |p: Vec3| {
        (0..mesh.num_vertices())
            .find(|&v| (mesh.positions()[v] - p).norm() < 1e-12)
            .expect("corner")
    };
    let hold = |nodes: Vec<usize>, axes: [bool; 3]| Dirichlet {
        nodes,
        axes,
        motion: Motion::Fixed,
        curve: None,
    };
    let end_x = plane(&mesh, 0, 1.0);
    let end = mesh
        .boundary()
        .expect("boundary")
        .triangles()
        .iter()
        .filter(|f| f.iter().all(|v| end_x.contains(v)))
        .copied()
        .collect();
    Problem {
        dirichlet: vec![
            hold(plane(&mesh, 0, 0.0), [true, false, false]),
            hold(vec![vertex(Vec3::zeros())], [true; 3]),
            hold(vec![vertex(Vec3::y())], [true, false, true]),
        ],
        loads: vec![Load::Traction {
            faces: end,
            traction: Vec3::new(TRACTION, 0.0, 0.0),
        }
        .into()],
        method,
        material: Material::from_young_poisson(YOUNG, NU, 1000.0).expect("material"),
        regions: Vec::new(),
        zones: None,
        obstacles: Vec::new(),
        mesh: mesh.into(),
        cloths: Vec::new(),
    }
}

/// The cantilever of the locking study (0.2 x 0.05 x 0.05 m, 8 x 2 x 2 cells, 384 tets),
/// clamped at `x = 0`, bending under its own weight, at `nu = 0.45`.
fn cantilever(method: Method) -> Problem {
    crate::common::cantilever([8, 2, 2], false, method)
}

/// The stress balance of the homogeneous patch state `F = diag(s, t, t)` (with the pressure
/// `p` of the mixed method, `kappa` the bulk modulus) and its Jacobian: `P_xx - T`, `P_yy`
/// (and `J - 1 - p / kappa`). Newton on these is Newton on the mesh: at a homogeneous
/// state the tangent maps an affine increment to the nodal forces of a uniform stress
/// increment, and the traction's nodal forces are those of a uniform stress, so every
/// Newton increment is affine.
trait Homogeneous {
    fn unknowns(&self) -> usize;
    fn balance(&self, u: &[f64], traction: f64) -> (Vec<f64>, Vec<Vec<f64>>);
}

/// Standard neo-Hookean: `P = mu (F - F^-T) + lambda log(J) F^-T`.
struct StandardPatch {
    mu: f64,
    lambda: f64,
}

impl Homogeneous for StandardPatch {
    fn unknowns(&self) -> usize {
        2
    }
    fn balance(&self, u: &[f64], traction: f64) -> (Vec<f64>, Vec<Vec<f64>>) {
        let (s, t, mu, lambda) = (u[0], u[1], self.mu, self.lambda);
        let log_j = (s * t * t).ln();
        let g = vec![
            mu * (s - 1.0 / s) + lambda * log_j / s - traction,
            mu * (t - 1.0 / t) + lambda * log_j / t,
        ];
        let jac = vec![
            vec![
                mu * (1.0 + 1.0 / (s * s)) + lambda * (1.0 - log_j) / (s * s),
                2.0 * lambda / (s * t),
            ],
            vec![
                lambda / (s * t),
                mu * (1.0 + 1.0 / (t * t)) + lambda * (2.0 - log_j) / (t * t),
            ],
        ];
        (g, jac)
    }
}

/// Mixed P1 with the linear measure: `P = mu (F - F^-T) + p J F^-T` (eq. 6 and 24 of
/// Francu et al. 2021) and the constraint `J - 1 = p / kappa` (consistent compliance: a
/// uniform pressure's `C p` is `V_i p / kappa`).
struct MixedPatch {
    mu: f64,
    kappa: f64,
}

impl Homogeneous for MixedPatch {
    fn unknowns(&self) -> usize {
        3
    }
    fn balance(&self, u: &[f64], traction: f64) -> (Vec<f64>, Vec<Vec<f64>>) {
        let (s, t, p, mu) = (u[0], u[1], u[2], self.mu);
        let g = vec![
            mu * (s - 1.0 / s) + p * t * t - traction,
            mu * (t - 1.0 / t) + p * s * t,
            s * t * t - 1.0 - p / self.kappa,
        ];
        let jac = vec![
            vec![mu * (1.0 + 1.0 / (s * s)), 2.0 * p * t, t * t],
            vec![p * t, mu * (1.0 + 1.0 / (t * t)) + p * s, s * t],
            vec![t * t, 2.0 * s * t, -1.0 / self.kappa],
        ];
        (g, jac)
    }
}

/// Solves the 2 x 2 or 3 x 3 Newton system of a [`Homogeneous`] balance.
fn newton_step(g: &[f64], jac: &[Vec<f64>]) -> Vec<f64> {
    let step = match g.len() {
        2 => Matrix2::from_fn(|r, c| jac[r][c])
            .lu()
            .solve(&Vector2::new(-g[0], -g[1]))
            .map(|v| v.as_slice().to_vec()),
        _ => Matrix3::from_fn(|r, c| jac[r][c])
            .lu()
            .solve(&Vector3::new(-g[0], -g[1], -g[2]))
            .map(|v| v.as_slice().to_vec()),
    };
    step.expect("the homogeneous tangent is regular")
}

/// The homogeneous state `(s, t[, p])` of the patch.
fn homogeneous_state(rest: &[Vec3], start: &State, u: &[f64]) -> State {
    State {
        positions: rest
            .iter()
            .map(|x| Vec3::new(u[0] * x.x, u[1] * x.y, u[1] * x.z))
            .collect(),
        multipliers: start.multipliers.iter().map(|_| u[2]).collect(),
        ..start.clone()
    }
}

/// Whether residuals meet the solver's tolerances (absolute force tolerance `force_tol`).
fn converged((force, constraint, _): Residuals, force_tol: f64) -> bool {
    force <= force_tol && constraint <= Settings::default().constraint_tolerance
}

/// The accuracy to which the solver's residuals reproduce exact Newton's: a step solved to a
/// relative residual `delta` (the KKT solver accepts 1e-8, `KktOptions::residual_tolerance`;
/// Cholesky is exact to rounding) changes the next residual by at most `delta` times the
/// current one; rounding adds about `1e3 eps` of the force scale.
const LINEAR_SOLVE: f64 = 1e-8;

/// Numbers in scientific notation, for the logs.
fn sci(values: &[f64]) -> String {
    let items: Vec<String> = values.iter().map(|v| format!("{v:.3e}")).collect();
    format!("[{}]", items.join(", "))
}

/// Asserts that `measured` (the solver's residuals of one step) is `expected` (exact
/// Newton's), iteration by iteration, and returns the quadratic constants
/// `(r_{k+1} / F) / (r_k / F)^2` of the measured sequence above the tolerances.
fn assert_exact_newton(
    what: &str,
    measured: &[Residuals],
    expected: &[Residuals],
    force_scale: f64,
) -> Vec<f64> {
    let rho = |(f, c, _): Residuals| ((f / force_scale).powi(2) + c * c).sqrt();
    let show = |rs: &[Residuals]| sci(&rs.iter().map(|&r| rho(r)).collect::<Vec<_>>());
    eprintln!(
        "{what}: measured {}, exact {}",
        show(measured),
        show(expected)
    );
    assert_eq!(
        measured.len(),
        expected.len(),
        "{what}: {} residuals where exact Newton has {}",
        measured.len(),
        expected.len()
    );
    for k in 0..measured.len() {
        let previous = if k == 0 { 0.0 } else { rho(expected[k - 1]) };
        let allowed = LINEAR_SOLVE * previous + 1e3 * f64::EPSILON;
        let (m, e) = (measured[k], expected[k]);
        let error = ((m.0 - e.0) / force_scale)
            .abs()
            .max((m.1 - e.1).abs())
            .max((m.2 - e.2).abs());
        assert!(
            error <= allowed,
            "{what}: residual {k} is {m:?}, exact Newton's {e:?} (difference {error:.2e} of the force scale, allowed {allowed:.2e})"
        );
    }
    let force_tol = Settings::default().force_tolerance * force_scale;
    measured
        .windows(2)
        .filter(|w| !converged(w[1], force_tol))
        .map(|w| rho(w[1]) / (rho(w[0]) * rho(w[0])))
        .collect()
}

/// Runs the patch test with `method` and compares every step with Newton on `model`.
fn patch_matches_homogeneous_newton(method: Method, model: &dyn Homogeneous) -> (usize, f64) {
    let mut sim = Simulation::new(patch(method), Settings::default()).expect("patch");
    let stepping = Stepping::quasi_static(STEPS);
    let force_scale = sim.force_scale().expect("scale");
    let force_tol = Settings::default().force_tolerance * force_scale;
    let volumes = sim.constraint_volumes().to_vec();
    let rest = sim.mesh().nodes().to_vec();
    let start = sim.state().clone();
    let summary = sim.run(stepping, |_| {}).expect("the patch converges");
    let mut u = vec![1.0, 1.0, 0.0][..model.unknowns()].to_vec();
    let mut q_max: f64 = 0.0;
    for report in &summary.reports {
        let traction = TRACTION * report.step as f64 / STEPS as f64;
        let mut linearizer = sim.linearizer(stepping, report.step).expect("linearizer");
        let mut expected = Vec::new();
        loop {
            let state = homogeneous_state(&rest, &start, &u);
            let r = residuals(&linearizer.newton_system(&state).expect("system"), &volumes);
            expected.push(r);
            if converged(r, force_tol) || expected.len() > Settings::default().max_iterations {
                break;
            }
            let (g, jac) = model.balance(&u, traction);
            for (ui, di) in u.iter_mut().zip(newton_step(&g, &jac)) {
                *ui += di;
            }
        }
        let what = format!("{method} patch, step {}", report.step);
        let q = assert_exact_newton(&what, &reported(report), &expected, force_scale);
        eprintln!("{what}: quadratic constants {}", sci(&q));
        q_max = q.into_iter().fold(q_max, f64::max);
    }
    (summary.newton_iterations(), q_max)
}

/// Standard Newton on the uniaxial patch test is exact Newton on the homogeneous stretch:
/// same residual at every iteration (to the linear solve's accuracy), hence its quadratic
/// constants (0.18-0.45 in units of the force scale) and its 3 iterations per load step of
/// 5 kPa: from 7e-3 of the force scale after the first, 0.45 (7e-3)^2 = 2e-5, then 2e-10,
/// below the tolerance of 1e-9.
#[test]
fn standard_newton_is_exact_newton_on_the_patch_test() {
    let material = Material::from_young_poisson(YOUNG, NU, 1000.0).expect("material");
    let lame = material.lame().expect("lame");
    let (iterations, q) = patch_matches_homogeneous_newton(
        Method::Standard,
        &StandardPatch {
            mu: lame.mu,
            lambda: lame.lambda,
        },
    );
    eprintln!("standard patch: {iterations} iterations, largest quadratic constant {q:.3}");
    assert_eq!(iterations, 3 * STEPS, "iterations of the patch test");
}

/// Saddle-point Newton (mixed-p1) on the patch test is exact Newton on the homogeneous
/// stretch and pressure `(s, t, p)`, iteration by iteration: quadratic constants 0.21-0.24,
/// 3 iterations per load step (4e-3, 3e-6, then 2e-12).
#[test]
fn saddle_point_newton_is_exact_newton_on_the_patch_test() {
    let material = Material::from_young_poisson(YOUNG, NU, 1000.0).expect("material");
    let (iterations, q) = patch_matches_homogeneous_newton(
        Method::MixedP1,
        &MixedPatch {
            mu: material.mu,
            kappa: material.mixed_kappa().expect("kappa"),
        },
    );
    eprintln!("mixed-p1 patch: {iterations} iterations, largest quadratic constant {q:.3}");
    assert_eq!(iterations, 3 * STEPS, "iterations of the patch test");
}

/// Exact Newton from `start` through the linearization of `step`: dense solves of the
/// Newton systems whose matrices `assembled.rs` checks against finite differences.
fn exact_newton(
    sim: &mut Simulation,
    stepping: Stepping,
    step: usize,
    start: &State,
) -> Vec<Residuals> {
    let force_tol = Settings::default().force_tolerance * sim.force_scale().expect("scale");
    let volumes = sim.constraint_volumes().to_vec();
    let mut linearizer = sim.linearizer(stepping, step).expect("linearizer");
    let mut state = start.clone();
    let mut sequence = Vec::new();
    loop {
        let system = linearizer.newton_system(&state).expect("system");
        let r = residuals(&system, &volumes);
        sequence.push(r);
        let moving = system.gap.iter().any(|g| *g != 0.0);
        if (converged(r, force_tol) && !moving)
            || sequence.len() > Settings::default().max_iterations
        {
            return sequence;
        }
        let step = system
            .matrix
            .clone()
            .lu()
            .solve(&DVector::from_vec(system.rhs.clone()))
            .expect("regular Newton matrix");
        let nf = system.free.len();
        for (dof, g) in system.gap.iter().enumerate() {
            state.positions[dof / 3][dof % 3] += g;
        }
        for (k, &dof) in system.free.iter().enumerate() {
            state.positions[dof / 3][dof % 3] += step[k];
        }
        for (p, dp) in state.multipliers.iter_mut().zip(step.iter().skip(nf)) {
            *p += dp;
        }
    }
}

/// Runs `problem` in `STEPS` load steps and compares every step with exact Newton from the
/// previous step's solution; returns the Newton iterations of the run.
fn matches_exact_newton(what: &str, problem: Problem) -> usize {
    let mut sim = Simulation::new(problem, Settings::default()).expect("problem");
    let stepping = Stepping::quasi_static(STEPS);
    let force_scale = sim.force_scale().expect("scale");
    let mut starts = vec![sim.state().clone()];
    let summary = sim
        .run(stepping, |frame| starts.push(frame.state.clone()))
        .expect("the run converges");
    for report in &summary.reports {
        let expected = exact_newton(&mut sim, stepping, report.step, &starts[report.step - 1]);
        let step = format!("{what}, step {}", report.step);
        let q = assert_exact_newton(&step, &reported(report), &expected, force_scale);
        eprintln!("{step}: quadratic constants {}", sci(&q));
    }
    summary.newton_iterations()
}

/// Zonal saddle-point Newton (Schur complement on the zone row) on the patch test is exact
/// Newton, 4 iterations per step (its F-bar energy converges from 3e-2: constants 0.05-2).
#[test]
fn zonal_newton_is_exact_newton_on_the_patch_test() {
    let iterations = matches_exact_newton("zonal patch", patch(Method::Zonal));
    assert_eq!(iterations, 4 * STEPS, "iterations of the patch test");
}

/// Every load step of the cantilever under gravity matches exact Newton from the previous
/// step's solution. The slender beam's soft bending makes the residual's constants large
/// (up to 6e3 on the first iteration of a step, when the load increment's bending is
/// corrected), but Newton stays exact: 4 iterations per step for `standard` and `zonal`,
/// 3 for `mixed-p1`.
#[test]
fn newton_is_exact_newton_on_a_cantilever_step() {
    for (method, per_step) in [
        (Method::Standard, 4),
        (Method::MixedP1, 3),
        (Method::Zonal, 4),
    ] {
        let what = format!("{method} cantilever");
        let iterations = matches_exact_newton(&what, cantilever(method));
        assert_eq!(iterations, per_step * STEPS, "iterations of the {what}");
    }
}
