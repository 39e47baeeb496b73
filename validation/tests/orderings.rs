//! The fill-reducing orderings (AMD, METIS nested dissection) of the direct solvers give the
//! same solutions: the ordering changes only the rounding of the factorization, and every run
//! is stopped by the same Newton tolerances. Behind `#[ignore]`: the fill and factorization
//! time of both orderings on the systems of docs/performance.md's table (run in release).

use isochor_scenes::resolve::build;
use isochor_scenes::{load_scene, Override};
use isochor_solvers::linear::Ordering;
use isochor_solvers::{RunSummary, Simulation, Vec3};
use std::time::Duration;

/// Runs a built-in scene with overrides under `ordering`; returns the rest positions, the
/// run and the unknowns (free DOFs and multipliers).
fn run(scene: &str, sets: &[&str], ordering: Ordering) -> (Vec<Vec3>, RunSummary, usize) {
    let overrides: Vec<Override> = sets.iter().map(|s| Override::parse(s).unwrap()).collect();
    let scene = load_scene(scene, None, &overrides).unwrap_or_else(|e| panic!("{sets:?}: {e}"));
    let mut built = build(&scene).unwrap_or_else(|e| panic!("{sets:?}: {e}"));
    built.settings.ordering = ordering;
    let rest = built.problem.mesh.nodes().to_vec();
    let mut sim = Simulation::new(built.problem, built.settings).expect("valid problem");
    let unknowns = sim.num_dofs();
    let summary = sim
        .run(built.stepping, |_| {})
        .unwrap_or_else(|e| panic!("{} {sets:?} {ordering:?}: {e}", scene.name));
    (rest, summary, unknowns)
}

/// `max |a - b| / max |a - rest|` over the nodes: the difference of two final states relative
/// to the displacement.
fn relative_difference(rest: &[Vec3], a: &[Vec3], b: &[Vec3]) -> f64 {
    let max = |it: &mut dyn Iterator<Item = f64>| it.fold(0.0, f64::max);
    let diff = max(&mut a.iter().zip(b).map(|(p, q)| (p - q).norm()));
    let displacement = max(&mut a.iter().zip(rest).map(|(p, r)| (p - r).norm()));
    diff / displacement
}

/// Solves `scene` under AMD and nested dissection and asserts equal final states.
///
/// Both runs stop at the same Newton tolerances (force residual 1e-9 relative, constraint
/// residual 1e-10 relative to the rest volumes) from the same iterates, which the orderings
/// change only by rounding; the existing equivalence tests of the solvers crate compare
/// converged states of different solvers at 1e-7 relative, and so does this one.
fn assert_orderings_agree(scene: &str, sets: &[&str]) {
    let (rest, amd, _) = run(scene, sets, Ordering::Amd);
    let (_, nd, _) = run(scene, sets, Ordering::NestedDissection);
    let d = relative_difference(&rest, &amd.final_state.positions, &nd.final_state.positions);
    let fill = |s: &RunSummary| s.reports.last().map_or(0, |r| r.factor_nnz);
    eprintln!(
        "{scene} {sets:?}: relative difference {d:.1e}, Newton iterations {} (AMD) / {} (ND), nnz(L) {} / {}",
        amd.newton_iterations(),
        nd.newton_iterations(),
        fill(&amd),
        fill(&nd)
    );
    assert!(d < 1e-7, "{scene} {sets:?}: relative difference {d:e}");
    assert!(fill(&amd) > 0 && fill(&nd) > 0, "both runs factorize");
}

/// The cantilever of the locking study, `standard` (`LL^T` of `K`) and `mixed-p1` (the
/// anchored KKT `LDL^T`) at nu = 0.4999.
#[test]
fn cantilever_solutions_do_not_depend_on_the_ordering() {
    for method in ["standard", "mixed-p1"] {
        let m = format!("method={method}");
        assert_orderings_agree("cantilever", &["res=2", "steps=1", "nu=0.4999", &m]);
    }
}

/// The coarse ball dropped on the ground (its reduced run: 12 frames of implicit Euler and
/// contact), with its `zonal` method (`LL^T` of `K` and the Schur complement of the global
/// zone) and with `mixed-p1`.
#[test]
fn ball_drop_solutions_do_not_depend_on_the_ordering() {
    let reduced = isochor_scenes::builtin::reduced("ball-drop-coarse").unwrap();
    for method in ["zonal", "mixed-p1"] {
        let m = format!("method={method}");
        let sets: Vec<&str> = reduced.iter().copied().chain([m.as_str()]).collect();
        assert_orderings_agree("ball-drop-coarse", &sets);
    }
}

/// The cantilever on 10-node tets, `mixed-p1` at nu = 0.4999.
#[test]
fn tet10_solutions_do_not_depend_on_the_ordering() {
    assert_orderings_agree(
        "cantilever",
        &[
            "res=1",
            "steps=1",
            "nu=0.4999",
            "method=mixed-p1",
            "element=tet10",
        ],
    );
}

/// Per Newton iteration of the last step (the symbolic analysis, with the ordering, is paid
/// in the first step only): numeric factorization, assembly, solve and wall time (ms), the
/// iterations, and the factor's stored entries.
fn per_iteration(summary: &RunSummary) -> ([f64; 4], usize, usize) {
    let last = summary.reports.last().expect("a step");
    let iterations = last.newton_iterations().max(1);
    let ms = |d: Duration| d.as_secs_f64() * 1e3 / iterations as f64;
    let t = &last.timings;
    (
        [
            ms(t.factorization),
            ms(t.assembly),
            ms(t.solve),
            ms(last.wall_time),
        ],
        iterations,
        last.factor_nnz,
    )
}

/// Fill and numeric factorization time of AMD against nested dissection on the systems of
/// docs/performance.md (two load steps or frames; the second is measured), and where an
/// iteration's time goes. Run in release:
/// `cargo test --release -p isochor-validation --test validation -- --ignored --nocapture orderings::`.
#[test]
#[ignore = "a measurement (minutes in release), printed for docs/performance.md"]
fn fill_and_factorization_time_of_amd_and_nested_dissection() {
    let cases: &[(&str, &[&str])] = &[
        ("cantilever", &["res=4", "method=standard"]),
        ("cantilever", &["res=4", "method=mixed-p1"]),
        ("cantilever", &["res=8", "method=standard"]),
        ("cantilever", &["res=8", "method=mixed-p1"]),
        ("cantilever", &["res=2", "method=mixed-p1", "element=tet10"]),
        ("cantilever", &["res=3", "method=mixed-p1", "element=tet10"]),
        ("ball-drop-coarse", &["frames=2", "method=zonal"]),
        ("ball-drop-coarse", &["frames=2", "method=mixed-p1"]),
        ("cantilever", &["res=12", "method=standard"]),
        ("cantilever", &["res=12", "method=mixed-p1"]),
        ("ball-drop", &["frames=2", "method=zonal"]),
        ("ball-drop", &["frames=2", "method=mixed-p1"]),
    ];
    println!("| system | unknowns | nnz(L) AMD | nnz(L) ND | ND/AMD | factorization ms AMD | ND | ND/AMD | iteration ms AMD (assembly, solve) | ND (assembly, solve) |");
    println!("|---|---|---|---|---|---|---|---|---|---|");
    for (scene, sets) in cases {
        let mut sets = sets.to_vec();
        if *scene == "cantilever" {
            sets.extend(["steps=2", "nu=0.4999"]);
        }
        let (_, amd, unknowns) = run(scene, &sets, Ordering::Amd);
        let (_, nd, _) = run(scene, &sets, Ordering::NestedDissection);
        let (a, ia, la) = per_iteration(&amd);
        let (b, ib, lb) = per_iteration(&nd);
        println!(
            "| {scene} {} | {unknowns} | {la} | {lb} | {:.2} | {:.1} | {:.1} | {:.2} | {:.1} ({:.1}, {:.1}; {ia} it.) | {:.1} ({:.1}, {:.1}; {ib} it.) |",
            sets.join(" "),
            lb as f64 / la as f64,
            a[0],
            b[0],
            b[0] / a[0],
            a[3],
            a[1],
            a[2],
            b[3],
            b[1],
            b[2],
        );
    }
}
