//! The iterative linear path on the cantilever at nu = 0.4999: one load step solved by
//! `standard` (CG) and `mixed-p1` (MINRES with the block-diagonal preconditioner), both with
//! the incomplete-Cholesky preconditioner and inexact-Newton forcing terms, at the largest
//! resolution whose samples keep the bench under a minute on a 2-core machine (res 8: 7,776
//! and 10,449 unknowns). Printed once per case: Newton and Krylov iterations.

#[path = "../tests/common.rs"]
mod common;

use common::cantilever;
use criterion::{criterion_group, criterion_main, Criterion};
use isochor_solvers::{
    IterativeSettings, LinearSolver, Method, RunSummary, Settings, Simulation, Stepping,
};

const RES: usize = 8;

fn solve(method: Method) -> RunSummary {
    let settings = Settings {
        linear: LinearSolver::Iterative(IterativeSettings {
            max_iterations: 50_000,
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
    for method in [Method::Standard, Method::MixedP1] {
        let summary = solve(method);
        let krylov: usize = summary
            .reports
            .iter()
            .flat_map(|s| &s.iterations)
            .map(|i| i.linear_iterations)
            .sum();
        eprintln!(
            "res {RES} {method}: {} Newton iterations, {krylov} Krylov iterations",
            summary.newton_iterations()
        );
        group.bench_function(format!("{method}/res{RES}"), |b| b.iter(|| solve(method)));
    }
    group.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
