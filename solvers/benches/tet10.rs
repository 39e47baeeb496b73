//! The cantilever of the locking study on 10-node tets (`mixed-p1`, nu = 0.4999) at res 1, 2
//! and 4 (236, 1,281 and 8,201 unknowns):
//!
//! - `solve/resR`: one load step from rest, the model built outside the measurement (as the
//!   `isochor` program's `wall_time_s`), and `setup_and_solve/resR` with `Simulation::new`.
//! - One Newton iteration at the converged state, split into `assembly/resR` (the elastic and
//!   gravity terms' values, gradients and Hessians, the constraints' values, Jacobian and
//!   geometric stiffness, the residuals and the scatter of `K` and `G` into their fixed
//!   patterns), `factorization/resR` (the numeric `LDL^T` of the KKT matrix with its inertia
//!   check) and `kkt_solve/resR` (triangular solves and refinement). The solver's own
//!   iteration is not reachable from outside the crate (its `System` and `SaddleNewton` are
//!   private; `Linearizer::newton_system` is public but returns the system dense, 0.5 GB at
//!   res 4, and densifying would dominate), so these three are rebuilt from the public pieces
//!   (`terms`, `isochor_constraints`, `linear`) the same way `SaddleNewton::linearize`,
//!   `factorize` and `solve_factorized` use them.
//!
//! Printed once per resolution: the solver's own per-iteration timings of a full solve (its
//! `Timings`: `assembly` there counts only the terms' and constraints' evaluations, also those
//! of the line search; the scatter into `K` and `G`, the residual vectors and the constraint
//! values of the line search are in none of the three columns), and the sizes of `K` and `G`.

#[path = "../tests/common.rs"]
mod common;

use common::{cantilever_tet10, per_iteration};
use criterion::{criterion_group, criterion_main, BatchSize, Criterion};
use faer::sparse::SparseColMat;
use isochor_constraints::{exact_rule, ConstraintSet, Measure, NodalConstraints, RowShape};
use isochor_energies::DistortionalNeoHookean;
use isochor_mesh::Vec3;
use isochor_solvers::linear::{KktOptions, KktSolver, ShiftSchedule, SparsityPattern, Triangle};
use isochor_solvers::terms::{DeadLoad, Elastic, EnergyTerm};
use isochor_solvers::{
    Dofs, Load, LoadLevel, Method, Problem, RunSummary, Settings, Simulation, State, Stepping,
};
use std::hint::black_box;
use std::sync::Arc;
use std::time::Duration;

const NU: f64 = 0.4999;
const RESOLUTIONS: [usize; 3] = [1, 2, 4];

fn problem(res: usize) -> Problem {
    cantilever_tet10(res, Method::MixedP1, NU)
}

fn simulation(res: usize) -> Simulation {
    Simulation::new(problem(res), Settings::default()).expect("valid problem")
}

fn solve(mut sim: Simulation) -> RunSummary {
    sim.run(Stepping::quasi_static(1), |_| {})
        .expect("the cantilever converges")
}

/// Kept entries and fixed pattern of a matrix over the free DOFs (see the solver's `Layout`).
struct Layout {
    kept: Vec<usize>,
    pattern: SparsityPattern,
}

impl Layout {
    fn new(
        pairs: &[(usize, usize)],
        row: impl Fn(usize) -> Option<usize>,
        dofs: &Dofs,
        triangle: Triangle,
        rows: usize,
    ) -> Self {
        let mut kept = Vec::new();
        let mut reduced = Vec::new();
        for (k, &(r, c)) in pairs.iter().enumerate() {
            if let (Some(i), Some(j)) = (row(r), dofs.free_index(c)) {
                if triangle == Triangle::Full || i >= j {
                    kept.push(k);
                    reduced.push((i, j));
                }
            }
        }
        let pattern =
            SparsityPattern::new(rows, dofs.num_free(), &reduced, triangle).expect("pattern");
        Layout { kept, pattern }
    }

    fn matrix(&self, values: &[f64]) -> SparseColMat<usize, f64> {
        let reduced: Vec<f64> = self.kept.iter().map(|&k| values[k]).collect();
        self.pattern.assemble(&reduced).expect("assemble")
    }
}

/// The terms and constraints of the `mixed-p1` model, built from the public pieces as the
/// solver's `Model::new` builds them.
struct Iteration {
    elastic: Elastic,
    gravity: DeadLoad,
    constraints: NodalConstraints,
    dofs: Dofs,
    /// Entries of the elastic Hessian, then of the geometric stiffness: `hessian_len` in all.
    elastic_len: usize,
    hessian_len: usize,
    hessian: Layout,
    jacobian_pairs: Vec<(usize, usize)>,
    jacobian: Layout,
    compliance: Option<SparseColMat<usize, f64>>,
    compliance_entries: Vec<(usize, usize, f64)>,
    anchors: Vec<Option<usize>>,
}

/// What [`Iteration::assemble`] hands to the factorization and solve.
struct Assembled {
    k: SparseColMat<usize, f64>,
    g: SparseColMat<usize, f64>,
    rhs: Vec<f64>,
}

impl Iteration {
    fn new(problem: Problem) -> Self {
        let Problem {
            mesh,
            material,
            dirichlet,
            loads,
            ..
        } = problem;
        let dofs = Dofs::new(mesh.num_nodes(), &dirichlet).expect("dofs");
        let elastic = Elastic::new(
            &mesh,
            Arc::new(DistortionalNeoHookean::new(material.mu).expect("mu")),
            Settings::default().project_hessians,
        )
        .expect("elastic term");
        let Load::Gravity(g) = loads[0].load else {
            panic!("the cantilever is loaded by gravity")
        };
        let weights: Vec<f64> = mesh
            .node_volumes()
            .iter()
            .map(|v| material.density * v)
            .collect();
        let gravity = DeadLoad::gravity(&weights, g);
        let constraints = NodalConstraints::on_elements(
            &mesh,
            exact_rule(mesh.kind(), RowShape::Corners),
            Measure::Linear,
            material.mixed_kappa().expect("kappa"),
            material.nodal_compliance,
        )
        .expect("nodal constraints");
        let mut pairs = elastic.hessian_pattern();
        let elastic_len = pairs.len();
        pairs.extend(constraints.geometric_stiffness_pattern());
        let hessian_len = pairs.len();
        let hessian = Layout::new(
            &pairs,
            |r| dofs.free_index(r),
            &dofs,
            Triangle::Lower,
            dofs.num_free(),
        );
        let m = constraints.num_constraints();
        let jacobian_pairs = constraints.jacobian_pattern();
        let jacobian = Layout::new(&jacobian_pairs, Some, &dofs, Triangle::Full, m);
        let compliance_entries: Vec<(usize, usize, f64)> =
            constraints.compliance().nonzero_entries();
        let compliance = (!compliance_entries.is_empty()).then(|| {
            let triplets: Vec<_> = compliance_entries
                .iter()
                .map(|&(r, c, v)| faer::sparse::Triplet::new(r, c, v))
                .collect();
            SparseColMat::try_new_from_triplets(m, m, &triplets).expect("C")
        });
        let anchors = (0..m)
            .map(|row| {
                constraints
                    .anchor_vertex(row)
                    .and_then(|v| (0..3).rev().find_map(|k| dofs.free_index(3 * v + k)))
            })
            .collect();
        Iteration {
            elastic,
            gravity,
            constraints,
            dofs,
            elastic_len,
            hessian_len,
            hessian,
            jacobian_pairs,
            jacobian,
            compliance,
            compliance_entries,
            anchors,
        }
    }

    /// The linearization at `(x, p)`: `K` (lower, with the geometric stiffness), `G` and the
    /// right-hand side `-(sigma_f, theta)` (no prescribed motion in the cantilever).
    fn assemble(&self, x: &[Vec3], p: &[f64]) -> Assembled {
        let mut gradient = vec![0.0; 3 * x.len()];
        let mut values = vec![0.0; self.hessian_len];
        let (elastic, geometric) = values.split_at_mut(self.elastic_len);
        self.elastic
            .evaluate(x, &LoadLevel::FULL, Some(&mut gradient), Some(elastic))
            .expect("elastic");
        self.gravity
            .evaluate(x, &LoadLevel::FULL, Some(&mut gradient), None)
            .expect("gravity");
        self.constraints
            .geometric_stiffness_values(x, p, geometric)
            .expect("geometric stiffness");
        let mut g_values = vec![0.0; self.jacobian_pairs.len()];
        self.constraints
            .jacobian_values(x, &mut g_values)
            .expect("jacobian");
        for (&(row, dof), v) in self.jacobian_pairs.iter().zip(&g_values) {
            gradient[dof] += v * p[row];
        }
        let mut theta = vec![0.0; p.len()];
        self.constraints.values(x, &mut theta).expect("values");
        for &(r, c, v) in &self.compliance_entries {
            theta[r] -= v * p[c];
        }
        let mut rhs: Vec<f64> = self.dofs.gather(&gradient).iter().map(|s| -s).collect();
        rhs.extend(theta.iter().map(|t| -t));
        Assembled {
            k: self.hessian.matrix(&values),
            g: self.jacobian.matrix(&g_values),
            rhs,
        }
    }

    fn kkt(&self) -> KktSolver {
        KktSolver::new(
            self.hessian.pattern.symbolic(),
            self.jacobian.pattern.symbolic(),
            self.compliance.as_ref().map(|c| c.symbolic()),
            &self.anchors,
            KktOptions::default(),
        )
        .expect("symbolic KKT")
    }

    fn factorize(&self, kkt: &mut KktSolver, a: &Assembled) -> f64 {
        kkt.factorize_with_shifts(
            a.k.as_ref(),
            a.g.as_ref(),
            self.compliance.as_ref().map(|c| c.as_ref()),
            &ShiftSchedule::default(),
        )
        .expect("KKT factorization")
    }
}

fn ms(d: Duration) -> f64 {
    d.as_secs_f64() * 1e3
}

fn bench(c: &mut Criterion) {
    let mut group = c.benchmark_group("tet10_cantilever_mixed_p1");
    group.sample_size(10);
    for res in RESOLUTIONS {
        // The solver's own split, from one full solve.
        let sim = simulation(res);
        let dofs = sim.num_dofs();
        let summary = solve(sim);
        let [assembly, factorization, solve_time, step] = per_iteration(&summary);
        let state: State = summary.final_state.clone();
        eprintln!(
            "tet10 res {res}: {dofs} unknowns, {} Newton iterations, step {:.1} ms; solver timings per \
             iteration {:.2} ms: assembly {:.2}, factorization {:.2}, solve {:.2}, elsewhere {:.2}",
            summary.newton_iterations(),
            ms(summary.wall_time),
            ms(step),
            ms(assembly),
            ms(factorization),
            ms(solve_time),
            ms(step.saturating_sub(assembly + factorization + solve_time)),
        );

        let it = Iteration::new(problem(res));
        let x = &state.positions;
        let p = &state.multipliers;
        let assembled = it.assemble(x, p);
        let mut kkt = it.kkt();
        let shift = it.factorize(&mut kkt, &assembled);
        eprintln!(
            "tet10 res {res}: rebuilt iteration n = {}, m = {}, nnz(K lower) = {}, nnz(G) = {}, shift {shift:e}; {:?}",
            assembled.k.ncols(),
            assembled.g.nrows(),
            assembled.k.compute_nnz(),
            assembled.g.compute_nnz(),
            kkt.report()
        );
        assert_eq!(assembled.k.ncols() + assembled.g.nrows(), dofs);

        group.bench_function(format!("assembly/res{res}"), |b| {
            b.iter(|| it.assemble(black_box(x), black_box(p)))
        });
        group.bench_function(format!("factorization/res{res}"), |b| {
            b.iter(|| it.factorize(&mut kkt, black_box(&assembled)))
        });
        group.bench_function(format!("kkt_solve/res{res}"), |b| {
            b.iter(|| {
                let mut rhs = assembled.rhs.clone();
                kkt.solve_in_place(&mut rhs).expect("KKT solve");
                rhs
            })
        });
        group.bench_function(format!("solve/res{res}"), |b| {
            b.iter_batched(|| simulation(res), solve, BatchSize::PerIteration)
        });
        group.bench_function(format!("setup_and_solve/res{res}"), |b| {
            b.iter(|| solve(simulation(res)))
        });
    }
    group.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
