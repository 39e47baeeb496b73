//! Speed of the linear-algebra layer on the cantilever-sized box (res = 8: 32 x 8 x 8
//! cells, 2,673 nodes): refilling the fixed pattern, `LL^T` of `K`, and the nodal P1
//! saddle point `LDL^T` at `C = 0` and `C > 0` (symbolic once, numeric per iteration),
//! each under both fill-reducing orderings (`amd`, `nd`: METIS nested dissection).

#[path = "../tests/common.rs"]
mod common;

use common::p1_box;
use criterion::{criterion_group, criterion_main, Criterion};
use faer::sparse::SparseColMat;
use isochor_solvers::linear::{
    CholeskySolver, KktOptions, KktSolver, Ordering, SparsityPattern, Triangle,
};
use std::hint::black_box;

fn bench(c: &mut Criterion) {
    let p = p1_box([32, 8, 8]);
    let pattern = SparsityPattern::new(p.n, p.n, &p.k_pairs, Triangle::Full).expect("pattern");
    let mut k = pattern.assemble(&p.k_values).expect("K");
    let compliance: Vec<(usize, usize)> = (0..p.m).map(|i| (i, i)).collect();
    let c_mat = SparsityPattern::new(p.m, p.m, &compliance, Triangle::Full)
        .and_then(|s| s.assemble(&vec![1e-6; p.m]))
        .expect("C");
    eprintln!(
        "box 32x8x8: n = {} displacement DOFs, m = {} pressures, {} K triplets, nnz(K) = {}",
        p.n,
        p.m,
        p.k_pairs.len(),
        pattern.nnz()
    );

    let mut group = c.benchmark_group("linear");
    group.sample_size(10);
    group.bench_function("assemble_K_fixed_pattern", |b| {
        b.iter(|| {
            pattern
                .assemble_into(black_box(&p.k_values), &mut k)
                .expect("assemble")
        })
    });
    group.bench_function("assemble_K_faer_try_new_from_triplets", |b| {
        let triplets: Vec<_> = p
            .k_pairs
            .iter()
            .zip(&p.k_values)
            .map(|(&(i, j), &v)| faer::sparse::Triplet::new(i, j, v))
            .collect();
        b.iter(|| {
            SparseColMat::<usize, f64>::try_new_from_triplets(p.n, p.n, black_box(&triplets))
                .expect("triplets")
        })
    });

    let orderings = [("amd", Ordering::Amd), ("nd", Ordering::NestedDissection)];
    for (tag, ordering) in orderings {
        let mut chol =
            CholeskySolver::with_ordering(k.symbolic(), ordering).expect("symbolic LL^T");
        chol.factorize(k.as_ref(), 0.0).expect("LL^T");
        eprintln!("LL^T(K) {tag}: {:?}", chol.report());
        group.bench_function(format!("cholesky_K_numeric_{tag}"), |b| {
            b.iter(|| chol.factorize(black_box(k.as_ref()), 0.0).expect("LL^T"))
        });
        let rhs_u = vec![1.0; p.n];
        group.bench_function(format!("cholesky_K_solve_{tag}"), |b| {
            b.iter(|| chol.solve(black_box(&rhs_u)).expect("solve"))
        });
    }

    for (name, c_opt) in [("C0", None), ("C1e-6", Some(c_mat.as_ref()))] {
        for (tag, ordering) in orderings {
            let options = KktOptions {
                ordering,
                ..KktOptions::default()
            };
            let symbolic = || {
                KktSolver::new(
                    k.symbolic(),
                    p.g.symbolic(),
                    c_opt.map(|c| c.symbolic()),
                    &p.anchors,
                    options,
                )
                .expect("symbolic KKT")
            };
            let mut kkt = symbolic();
            kkt.factorize(k.as_ref(), p.g.as_ref(), c_opt, 0.0)
                .expect("KKT");
            // A consistent right-hand side: the C = 0 system is singular (spurious pressure
            // modes).
            let mut b_kkt = vec![0.0; p.n + p.m];
            b_kkt[..p.n].fill(1.0);
            let x = kkt.solve(&b_kkt).expect("solve");
            eprintln!("KKT {name} {tag}: {:?}", kkt.report());
            black_box(x);
            group.bench_function(format!("kkt_{name}_numeric_{tag}"), |b| {
                b.iter(|| {
                    kkt.factorize(black_box(k.as_ref()), p.g.as_ref(), c_opt, 0.0)
                        .expect("KKT")
                })
            });
            group.bench_function(format!("kkt_{name}_solve_{tag}"), |b| {
                b.iter(|| kkt.solve(black_box(&b_kkt)).expect("solve"))
            });
            group.bench_function(format!("kkt_{name}_symbolic_{tag}"), |b| b.iter(symbolic));
        }
    }
    group.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
