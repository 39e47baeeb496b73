//! The iterative linear path on the cantilever at nu = 0.4999: one load step solved by
//! `standard` (CG), `mixed-p1` and `zonal` (MINRES with the block-diagonal preconditioner)
//! with the incomplete-Cholesky or the multigrid preconditioner and inexact-Newton forcing
//! terms, at the largest resolution whose samples keep each case near a minute on a 2-core
//! machine (res 8: 7,776 to 10,449 unknowns). Printed once per case: Newton and Krylov
//! iterations.

#[path = "../tests/common.rs"]
mod common;

use common::cantilever;
use criterion::{criterion_group, criterion_main, Criterion};
use isochor_solvers::{
    IterativeSettings, LinearSolver, Method, PreconditionerKind, RunSummary, Settings, Simulation,
    Stepping,
};

const RES: usize = 8;

fn solve(method: Method, preconditioner: PreconditionerKind) -> RunSummary {
    let settings = Settings {
        linear: LinearSolver::Iterative(IterativeSettings {
            max_iterations: 50_000,
            preconditioner,
            ..IterativeSettings::default()
        }),
        ..Settings::default()
    };
    Simulation::new(cantilever(RES, method, 0.4999), settings)
        .expect("valid problem")
        .run(Stepping::quasi_static(1), |_| {})
        .expect("the cantilever converges")
}

fn bench(c: &mut Criterion) {
    let mut group = c.benchmark_group("iterative");
    group.sample_size(10);
    let cases = [
        (Method::Standard, PreconditionerKind::IncompleteCholesky),
        (Method::Standard, PreconditionerKind::Multigrid),
        (Method::MixedP1, PreconditionerKind::IncompleteCholesky),
        (Method::Zonal, PreconditionerKind::IncompleteCholesky),
        (Method::Zonal, PreconditionerKind::Multigrid),
    ];
    for (method, preconditioner) in cases {
        let summary = solve(method, preconditioner);
        let krylov: usize = summary
            .reports
            .iter()
            .flat_map(|s| &s.iterations)
            .map(|i| i.linear_iterations)
            .sum();
        eprintln!(
            "res {RES} {method} {preconditioner:?}: {} Newton iterations, {krylov} Krylov iterations",
            summary.newton_iterations()
        );
        group.bench_function(format!("{method}/{preconditioner:?}/res{RES}"), |b| {
            b.iter(|| solve(method, preconditioner))
        });
    }
    group.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
