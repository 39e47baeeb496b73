//! Setup of the tet10 cantilever (`mixed-p1`, nu = 0.4999) at res 2, 3 and 4 (1,281, 3,843
//! and 8,201 unknowns): the Hessian layout of the elastic term and the constraints'
//! geometric stiffness (the two blocks of the saddle-point Hessian),
//!
//! - `pairs/resR`: from `(dof, dof)` pairs, as before node patterns: the terms' pairs, the
//!   free-free lower ones, and [`SparsityPattern::new`] on them;
//! - `node_pattern/resR`: from the element node lists, [`NodePattern::new`] (the solver's
//!   layout);
//!
//! and `kkt_symbolic/resR`, the rest of the setup: the anchored ordering, the KKT pattern and
//! the symbolic factorization ([`KktSolver::new`]).

#[path = "../tests/common.rs"]
mod common;

use common::cantilever_tet10;
use criterion::{criterion_group, criterion_main, Criterion};
use isochor_constraints::{exact_rule, ConstraintSet, Measure, NodalConstraints, RowShape};
use isochor_energies::DistortionalNeoHookean;
use isochor_solvers::linear::{KktOptions, KktSolver, SparsityPattern, Triangle};
use isochor_solvers::terms::{BlockOrder, Elastic, ElementBlocks, EnergyTerm};
use isochor_solvers::{Dofs, HessianBlock, Method, NodePattern, Problem, Settings};
use std::hint::black_box;
use std::sync::Arc;

const NU: f64 = 0.4999;
const RESOLUTIONS: [usize; 3] = [2, 3, 4];

/// The terms whose patterns the setup lays out, built as the solver's `Model::new` does.
struct Setup {
    elastic: Elastic,
    constraints: NodalConstraints,
    dofs: Dofs,
}

impl Setup {
    fn new(problem: Problem) -> Self {
        let Problem {
            mesh,
            material,
            dirichlet,
            ..
        } = problem;
        let dofs = Dofs::new(mesh.num_nodes(), &dirichlet).expect("dofs");
        let elastic = Elastic::new(
            &mesh,
            Arc::new(DistortionalNeoHookean::new(material.mu).expect("mu")),
            Settings::default().project_hessians,
        )
        .expect("elastic term");
        let constraints = NodalConstraints::on_elements(
            &mesh,
            exact_rule(mesh.kind(), RowShape::Corners),
            Measure::Linear,
            material.mixed_kappa().expect("kappa"),
            material.nodal_compliance,
        )
        .expect("nodal constraints");
        Setup {
            elastic,
            constraints,
            dofs,
        }
    }

    /// The layout from `(dof, dof)` pairs.
    fn pairs(&self) -> SparsityPattern {
        let mut pairs = self.elastic.hessian_pattern();
        pairs.extend(self.constraints.geometric_stiffness_pattern());
        let free = |d| self.dofs.free_index(d);
        let reduced: Vec<(usize, usize)> = pairs
            .iter()
            .filter_map(|&(r, c)| Some((free(r)?, free(c)?)))
            .filter(|(i, j)| i >= j)
            .collect();
        let n = self.dofs.num_free();
        SparsityPattern::new(n, n, &reduced, Triangle::Lower).expect("pattern")
    }

    /// The layout from the element node lists.
    fn node_pattern(&self) -> NodePattern {
        let (nodes, per_element) = self
            .constraints
            .geometric_stiffness_blocks()
            .expect("blocks");
        let blocks = [
            HessianBlock::Elements(self.elastic.hessian_blocks().expect("blocks")),
            HessianBlock::Elements(ElementBlocks {
                nodes: nodes.to_vec(),
                per_element,
                order: BlockOrder::RowMajor,
            }),
        ];
        NodePattern::new(&blocks, &self.dofs).expect("node pattern")
    }

    fn kkt(&self, k: &SparsityPattern) -> KktSolver {
        let m = self.constraints.num_constraints();
        let pairs: Vec<(usize, usize)> = self
            .constraints
            .jacobian_pattern()
            .into_iter()
            .filter_map(|(r, c)| Some((r, self.dofs.free_index(c)?)))
            .collect();
        let g = SparsityPattern::new(m, self.dofs.num_free(), &pairs, Triangle::Full).expect("G");
        let anchors: Vec<Option<usize>> = (0..m)
            .map(|row| {
                self.constraints
                    .anchor_vertex(row)
                    .and_then(|v| (0..3).rev().find_map(|k| self.dofs.free_index(3 * v + k)))
            })
            .collect();
        KktSolver::new(
            k.symbolic(),
            g.symbolic(),
            None,
            &anchors,
            KktOptions::default(),
        )
        .expect("symbolic KKT")
    }
}

fn bench(c: &mut Criterion) {
    let mut group = c.benchmark_group("tet10_cantilever_setup");
    group.sample_size(10);
    for res in RESOLUTIONS {
        let setup = Setup::new(cantilever_tet10(res, Method::MixedP1, NU));
        let node = setup.node_pattern();
        assert_eq!(
            node.pattern.symbolic().row_idx(),
            setup.pairs().symbolic().row_idx()
        );
        println!(
            "res {res}: {} free DOFs, {} stored entries of K",
            setup.dofs.num_free(),
            node.pattern.nnz()
        );
        group.bench_function(format!("pairs/res{res}"), |b| b.iter(|| setup.pairs()));
        group.bench_function(format!("node_pattern/res{res}"), |b| {
            b.iter(|| setup.node_pattern())
        });
        group.bench_function(format!("kkt_symbolic/res{res}"), |b| {
            b.iter(|| setup.kkt(black_box(&node.pattern)))
        });
    }
    group.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
