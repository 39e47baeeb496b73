//! The iterative linear path (preconditioned CG and MINRES with inexact-Newton forcing
//! terms) reaches the direct path's solutions, on linear and quadratic tets, and at
//! `nu = 0.5`.

use crate::common;

use common::{cantilever, cantilever_tet10, relative_difference, study_list};
use isochor_mesh::{generate::ball, Vec3};
use isochor_solvers::{
    Dirichlet, IterativeSettings, LinearSolver, Load, Material, Method, Motion, PreconditionerKind,
    Problem, RunSummary, Settings, Simulation, Stepping,
};

/// The direct or the iterative path.
fn settings(linear: LinearSolver) -> Settings {
    Settings {
        linear,
        ..Settings::default()
    }
}

/// The iterative path with `preconditioner` at the default tolerance floor (1e-8).
fn iterative(preconditioner: PreconditionerKind) -> LinearSolver {
    LinearSolver::Iterative(IterativeSettings {
        max_iterations: 5000,
        preconditioner,
        ..IterativeSettings::default()
    })
}

fn run(problem: Problem, linear: LinearSolver) -> Result<RunSummary, String> {
    Simulation::new(problem, settings(linear))
        .map_err(|e| e.to_string())?
        .run(Stepping::quasi_static(1), |_| {})
        .map_err(|e| e.to_string())
}

/// Both paths converge on `problem`: their positions' relative difference, and the Krylov
/// iterations of the iterative run.
fn compare(problem: Problem, preconditioner: PreconditionerKind) -> (f64, usize) {
    let rest = problem.mesh.nodes().to_vec();
    let method = problem.method;
    let direct = run(problem.clone(), LinearSolver::Direct)
        .unwrap_or_else(|e| panic!("{method} direct: {e}"));
    let iterative = run(problem, iterative(preconditioner))
        .unwrap_or_else(|e| panic!("{method} {preconditioner:?}: {e}"));
    let krylov = iterative
        .reports
        .iter()
        .flat_map(|s| &s.iterations)
        .map(|i| i.linear_iterations)
        .sum();
    let d = relative_difference(
        &rest,
        &direct.final_state.positions,
        &iterative.final_state.positions,
    );
    (d, krylov)
}

/// Both runs stop at a force residual below the Newton tolerance (1e-9 of the force scale)
/// and a constraint residual below 1e-10; on these well-conditioned coarse meshes (nu <=
/// 0.45) that pins the displacements to well within this bound, which a wrong step (a
/// missing block, a sign error in the preconditioner) misses by orders of magnitude.
const AGREEMENT: f64 = 1e-7;

/// CG and MINRES with either preconditioner reach the direct solution of the cantilever
/// (`standard`, `mixed-p1`, `zonal`) with inexact-Newton forcing terms.
#[test]
fn iterative_path_matches_direct_on_the_cantilever() {
    for preconditioner in [
        PreconditionerKind::Jacobi,
        PreconditionerKind::IncompleteCholesky,
    ] {
        for method in [Method::Standard, Method::MixedP1, Method::Zonal] {
            let (d, krylov) = compare(cantilever(2, method, 0.45), preconditioner);
            eprintln!("{method} {preconditioner:?}: difference {d:e}, {krylov} Krylov iterations");
            assert!(d < AGREEMENT, "{method} {preconditioner:?}: {d:e}");
        }
    }
}

/// Smoothed-aggregation multigrid as the preconditioner of CG and of MINRES's `K` block
/// reaches the direct solution of the cantilever at `res` 4 (1,200 free DOFs: a two-level
/// hierarchy; at `res` 2 the whole matrix would be the coarsest level).
#[test]
fn multigrid_path_matches_direct_on_the_cantilever() {
    for method in [Method::Standard, Method::MixedP1, Method::Zonal] {
        let (d, krylov) = compare(cantilever(4, method, 0.45), PreconditionerKind::Multigrid);
        eprintln!("{method} multigrid: difference {d:e}, {krylov} Krylov iterations");
        assert!(d < AGREEMENT, "{method} multigrid: {d:e}");
    }
}

/// A generated ball (radius 5 cm) resting on its clamped bottom cap under gravity, `zonal`
/// (one zone: the whole-body volume constraint, a dense row of `G`).
#[test]
fn iterative_path_matches_direct_on_a_zonal_ball() {
    let mesh = ball(0.05, 3).unwrap();
    let bottom: Vec<usize> = (0..mesh.num_vertices())
        .filter(|&v| mesh.positions()[v].y < -0.04)
        .collect();
    assert!(!bottom.is_empty());
    let problem = Problem {
        mesh: mesh.into(),
        method: Method::Zonal,
        material: Material::from_young_poisson(266e3, 0.45, 1070.0).unwrap(),
        regions: Vec::new(),
        zones: None,
        dirichlet: vec![Dirichlet {
            nodes: bottom,
            axes: [true; 3],
            motion: Motion::Fixed,
            curve: None,
        }],
        loads: vec![Load::Gravity(Vec3::new(0.0, -9.8, 0.0)).into()],
        obstacles: Vec::new(),
        cloths: Vec::new(),
    };
    let (d, krylov) = compare(problem, PreconditionerKind::IncompleteCholesky);
    eprintln!("zonal ball: difference {d:e}, {krylov} Krylov iterations");
    assert!(d < AGREEMENT, "{d:e}");
}

/// Quadratic tets: `standard` and `mixed-p1` (P2-P1, a stable pair) on the tet10 cantilever.
#[test]
fn iterative_path_matches_direct_on_tet10() {
    for method in [Method::Standard, Method::MixedP1] {
        let (d, krylov) = compare(
            cantilever_tet10(1, method, 0.45),
            PreconditionerKind::IncompleteCholesky,
        );
        eprintln!("tet10 {method}: difference {d:e}, {krylov} Krylov iterations");
        assert!(d < AGREEMENT, "tet10 {method}: {d:e}");
    }
}

/// At `nu = 0.5` (`C = 0`) the P2-P1 saddle point of `mixed-p1` on tet10 is nonsingular
/// (inf-sup stable), and MINRES with the block preconditioner converges to the direct
/// solution.
#[test]
fn iterative_path_converges_at_nu_one_half_on_tet10() {
    let (d, krylov) = compare(
        cantilever_tet10(1, Method::MixedP1, 0.5),
        PreconditionerKind::IncompleteCholesky,
    );
    eprintln!("tet10 mixed-p1 nu = 0.5: difference {d:e}, {krylov} Krylov iterations");
    assert!(d < AGREEMENT, "{d:e}");
}

/// At `nu = 0.5` the P1-P1 pair of `mixed-p1` on tet4 is not inf-sup stable: `G^T` has a
/// null space (spurious pressure modes) and the `C = 0` saddle point is singular. Its
/// right-hand side `-theta` is the volume change, `G u` to first order, so it is consistent
/// up to the nonlinear remainder; MINRES from zero iterates in the range of the operator and
/// converges there, and the displacements (unaffected by the null space) match the direct
/// path's, whose `LDL^T` regularizes the zero pivots.
#[test]
fn iterative_path_converges_on_the_singular_p1_p1_saddle_point() {
    let (d, krylov) = compare(
        cantilever(2, Method::MixedP1, 0.5),
        PreconditionerKind::IncompleteCholesky,
    );
    eprintln!("tet4 mixed-p1 nu = 0.5: difference {d:e}, {krylov} Krylov iterations");
    assert!(d < AGREEMENT, "{d:e}");
}

/// The measurements of the iterative-path table of docs/performance.md: the cantilever at nu =
/// 0.4999, one load step, each method, direct against CG / MINRES with each preconditioner. Per
/// run: Newton iterations, Krylov iterations per Newton iteration (the saddle path may solve twice:
/// its second-order correction), and the linear-solve time per Newton iteration (factorization and
/// solves). Resolutions from
/// `ISOCHOR_STUDY_RES` (comma-separated, default `4,8,12`), methods from
/// `ISOCHOR_STUDY_METHODS` (default `standard,mixed-p1,zonal`), linear solvers from
/// `ISOCHOR_STUDY_LINEAR` (names from the table, comma-separated, default all).
#[test]
#[ignore = "study of minutes: run with --release -- --ignored --nocapture"]
fn iterative_path_study() {
    let resolutions: Vec<usize> = study_list("ISOCHOR_STUDY_RES", "4,8,12");
    let chosen: Vec<String> = study_list("ISOCHOR_STUDY_LINEAR", "direct,Jacobi,IC(0),multigrid");
    let methods: Vec<Method> = study_list("ISOCHOR_STUDY_METHODS", "standard,mixed-p1,zonal");
    println!("| res | method | unknowns | linear | Newton its | Krylov its / Newton it | linear ms / Newton it | wall s |");
    println!("|---|---|---|---|---|---|---|---|");
    for &res in &resolutions {
        for &method in &methods {
            for (name, linear) in [
                ("direct", LinearSolver::Direct),
                (
                    "Jacobi",
                    LinearSolver::Iterative(IterativeSettings {
                        max_iterations: 50_000,
                        preconditioner: PreconditionerKind::Jacobi,
                        ..IterativeSettings::default()
                    }),
                ),
                (
                    "IC(0)",
                    LinearSolver::Iterative(IterativeSettings {
                        max_iterations: 50_000,
                        preconditioner: PreconditionerKind::IncompleteCholesky,
                        ..IterativeSettings::default()
                    }),
                ),
                (
                    "multigrid",
                    LinearSolver::Iterative(IterativeSettings {
                        max_iterations: 50_000,
                        preconditioner: PreconditionerKind::Multigrid,
                        ..IterativeSettings::default()
                    }),
                ),
            ] {
                if !chosen.iter().any(|c| c == name) {
                    continue;
                }
                let problem = cantilever(res, method, 0.4999);
                let mut sim = Simulation::new(problem, settings(linear)).unwrap();
                let unknowns = sim.num_dofs();
                let start = std::time::Instant::now();
                let result = sim.run(Stepping::quasi_static(1), |_| {});
                let wall = start.elapsed().as_secs_f64();
                match result {
                    Ok(summary) => {
                        let its: Vec<_> =
                            summary.reports.iter().flat_map(|s| &s.iterations).collect();
                        let newton = its.len().max(1);
                        let krylov: usize = its.iter().map(|i| i.linear_iterations).sum();
                        let linear: f64 = summary
                            .reports
                            .iter()
                            .map(|s| (s.timings.factorization + s.timings.solve).as_secs_f64())
                            .sum();
                        let per_solve = if name == "direct" {
                            "-".to_string()
                        } else {
                            format!("{:.0}", krylov as f64 / newton as f64)
                        };
                        println!(
                            "| {res} | {method} | {unknowns} | {name} | {} | {per_solve} | {:.1} | {wall:.2} |",
                            its.len(),
                            1e3 * linear / newton as f64
                        );
                    }
                    Err(e) => println!(
                        "| {res} | {method} | {unknowns} | {name} | failed: {e} | | | {wall:.2} |"
                    ),
                }
            }
        }
    }
}
