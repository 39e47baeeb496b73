//! Speed of the linear-algebra layer on the cantilever-sized box (res = 8: 32 x 8 x 8
//! cells, 2,673 nodes): refilling the fixed pattern, `LL^T` of `K`, and the nodal P1
//! saddle point `LDL^T` at `C = 0` and `C > 0` (symbolic once, numeric per iteration).

use criterion::{criterion_group, criterion_main, Criterion};
use faer::sparse::SparseColMat;
use isochor_mesh::generate::box_grid;
use isochor_mesh::Vec3;
use isochor_solvers::linear::{CholeskySolver, KktOptions, KktSolver, SparsityPattern, Triangle};
use nalgebra::Matrix3;
use std::hint::black_box;

/// Element-stiffness triplets of a linear-elasticity-like operator
/// (`grad_a . grad_b I + grad_a grad_b^T`, full 3x3 blocks as for real materials) and the
/// nodal volume Jacobian (eq. 26-27), with the face `x = 0` clamped.
struct Problem {
    n: usize,
    m: usize,
    k_pairs: Vec<(usize, usize)>,
    k_values: Vec<f64>,
    g: SparseColMat<usize, f64>,
    anchors: Vec<Option<usize>>,
}

fn problem(cells: [usize; 3]) -> Problem {
    let mesh = box_grid(Vec3::zeros(), Vec3::new(4.0, 1.0, 1.0), cells).expect("box");
    let x = mesh.positions();
    let nv = x.len();
    let mut dof = vec![None; 3 * nv];
    let mut n = 0;
    for (v, p) in x.iter().enumerate() {
        if p.x > 1e-12 {
            for a in 0..3 {
                dof[3 * v + a] = Some(n);
                n += 1;
            }
        }
    }
    let (mut k_pairs, mut k_values, mut gp, mut gv) =
        (Vec::new(), Vec::new(), Vec::new(), Vec::new());
    for tet in mesh.tets() {
        let xs = tet.map(|v| x[v]);
        let e = [xs[1] - xs[0], xs[2] - xs[0], xs[3] - xs[0]];
        let d = Matrix3::from_columns(&e);
        let inv = d.try_inverse().expect("non-degenerate tet");
        let vol = d.determinant().abs() / 6.0;
        let (g1, g2, g3) = (
            inv.row(0).transpose(),
            inv.row(1).transpose(),
            inv.row(2).transpose(),
        );
        let grads = [-(g1 + g2 + g3), g1, g2, g3];
        let v1 = e[1].cross(&e[2]) / 6.0;
        let v2 = e[2].cross(&e[0]) / 6.0;
        let v3 = e[0].cross(&e[1]) / 6.0;
        let vgrad = [-(v1 + v2 + v3), v1, v2, v3];
        for a in 0..4 {
            for b in 0..4 {
                for j in 0..3 {
                    let Some(col) = dof[3 * tet[b] + j] else {
                        continue;
                    };
                    gp.push((tet[a], col));
                    gv.push(0.25 * vgrad[b][j]);
                    for i in 0..3 {
                        if let Some(row) = dof[3 * tet[a] + i] {
                            let lap = if i == j { grads[a].dot(&grads[b]) } else { 0.0 };
                            k_pairs.push((row, col));
                            k_values.push(vol * (lap + grads[a][i] * grads[b][j]));
                        }
                    }
                }
            }
        }
    }
    let g = SparsityPattern::new(nv, n, &gp, Triangle::Full)
        .and_then(|p| p.assemble(&gv))
        .expect("G");
    let anchors = (0..nv).map(|v| dof[3 * v + 2]).collect();
    Problem {
        n,
        m: nv,
        k_pairs,
        k_values,
        g,
        anchors,
    }
}

fn bench(c: &mut Criterion) {
    let p = problem([32, 8, 8]);
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

    let mut chol = CholeskySolver::new(k.symbolic()).expect("symbolic LL^T");
    chol.factorize(k.as_ref(), 0.0).expect("LL^T");
    eprintln!("LL^T(K): {:?}", chol.report());
    group.bench_function("cholesky_K_numeric", |b| {
        b.iter(|| chol.factorize(black_box(k.as_ref()), 0.0).expect("LL^T"))
    });
    let rhs_u = vec![1.0; p.n];
    group.bench_function("cholesky_K_solve", |b| {
        b.iter(|| chol.solve(black_box(&rhs_u)).expect("solve"))
    });

    for (name, c_opt) in [("C0", None), ("C1e-6", Some(c_mat.as_ref()))] {
        let mut kkt = KktSolver::new(
            k.symbolic(),
            p.g.symbolic(),
            c_opt.map(|c| c.symbolic()),
            &p.anchors,
            KktOptions::default(),
        )
        .expect("symbolic KKT");
        kkt.factorize(k.as_ref(), p.g.as_ref(), c_opt, 0.0)
            .expect("KKT");
        // A consistent right-hand side: the C = 0 system is singular (spurious pressure modes).
        let mut b_kkt = vec![0.0; p.n + p.m];
        b_kkt[..p.n].fill(1.0);
        let x = kkt.solve(&b_kkt).expect("solve");
        eprintln!("KKT {name}: {:?}", kkt.report());
        black_box(x);
        group.bench_function(format!("kkt_{name}_numeric"), |b| {
            b.iter(|| {
                kkt.factorize(black_box(k.as_ref()), p.g.as_ref(), c_opt, 0.0)
                    .expect("KKT")
            })
        });
        group.bench_function(format!("kkt_{name}_solve"), |b| {
            b.iter(|| kkt.solve(black_box(&b_kkt)).expect("solve"))
        });
        group.bench_function(format!("kkt_{name}_symbolic"), |b| {
            b.iter(|| {
                KktSolver::new(
                    k.symbolic(),
                    p.g.symbolic(),
                    c_opt.map(|c| c.symbolic()),
                    &p.anchors,
                    KktOptions::default(),
                )
                .expect("symbolic")
            })
        });
    }
    group.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
