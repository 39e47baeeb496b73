//! The cantilever of the locking study solved by `standard`, `mixed-p1` and `zonal` at
//! several resolutions: a full quasi-static solve per sample, and, printed once per case,
//! where one Newton iteration spends its time (assembly, factorization, solve).

#[path = "../tests/common.rs"]
mod common;

use common::{cantilever, per_iteration};
use criterion::{criterion_group, criterion_main, Criterion};
use isochor_solvers::{Method, RunSummary, Settings, Simulation, Stepping};

fn solve(res: usize, method: Method) -> (RunSummary, usize) {
    let mut sim = Simulation::new(cantilever(res, method, 0.4999), Settings::default())
        .expect("valid problem");
    let dofs = sim.num_dofs();
    let summary = sim
        .run(Stepping::quasi_static(1), |_| {})
        .expect("the cantilever converges");
    (summary, dofs)
}

fn bench(c: &mut Criterion) {
    let mut group = c.benchmark_group("cantilever");
    group.sample_size(10);
    for res in [2, 4, 8] {
        for method in [Method::Standard, Method::MixedP1, Method::Zonal] {
            let (summary, dofs) = solve(res, method);
            let [assembly, factorization, solve_time, total] = per_iteration(&summary);
            eprintln!(
                "res {res} {method}: {dofs} unknowns, {} Newton iterations; per iteration {:.1} ms \
                 (assembly {:.1}, factorization {:.1}, solve {:.1})",
                summary.newton_iterations(),
                total.as_secs_f64() * 1e3,
                assembly.as_secs_f64() * 1e3,
                factorization.as_secs_f64() * 1e3,
                solve_time.as_secs_f64() * 1e3,
            );
            group.bench_function(format!("{method}/res{res}"), |b| {
                b.iter(|| solve(res, method))
            });
        }
    }
    group.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
