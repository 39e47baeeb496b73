//! One finite-difference harness for the solver's energy terms: the gradient against central
//! differences of the energy and the Hessian (assembled from its pattern) against central
//! differences of the gradient, on randomly deformed boxes. Adding a term is one line.

use isochor_constraints::{ConstraintSet, Measure, NodalCompliance, NodalConstraints};
use isochor_energies::{standard_neo_hookean, Epidermis, Lame};
use isochor_mesh::Vec3;
use isochor_solvers::terms::{
    AugmentedConstraints, DeadLoad, Elastic, EnergyTerm, EpidermisTerm, FollowerPressure, Inertia,
};
use isochor_validation::strategies::{deformed_box, Deformed};
use nalgebra::DMatrix;
use proptest::prelude::*;
use std::sync::Arc;

/// Required agreement, relative to the derivative's max norm.
const TOLERANCE: f64 = 1e-6;
/// Central-difference step relative to the unit box.
const STEP: f64 = 1e-6;

fn evaluate(term: &dyn EnergyTerm, x: &[Vec3]) -> (f64, Vec<f64>, DMatrix<f64>) {
    let n = 3 * x.len();
    let mut g = vec![0.0; n];
    let pattern = term.hessian_pattern();
    let mut values = vec![0.0; pattern.len()];
    let e = term
        .evaluate(x, 0.7, Some(&mut g), Some(&mut values))
        .unwrap();
    let mut h = DMatrix::zeros(n, n);
    for (&(r, c), v) in pattern.iter().zip(&values) {
        h[(r, c)] += v;
    }
    (e, g, h)
}

fn energy(term: &dyn EnergyTerm, x: &[Vec3]) -> f64 {
    term.evaluate(x, 0.7, None, None).unwrap()
}

fn shifted(x: &[Vec3], dof: usize, by: f64) -> Vec<Vec3> {
    let mut y = x.to_vec();
    y[dof / 3][dof % 3] += by;
    y
}

/// Checks `term` at `x`, returning the relative errors of gradient and Hessian.
fn check(term: &dyn EnergyTerm, x: &[Vec3]) -> (f64, f64) {
    let (_, g, h) = evaluate(term, x);
    let n = g.len();
    let mut fd_g = vec![0.0; n];
    let mut fd_h = DMatrix::zeros(n, n);
    for dof in 0..n {
        let (plus, minus) = (shifted(x, dof, STEP), shifted(x, dof, -STEP));
        fd_g[dof] = (energy(term, &plus) - energy(term, &minus)) / (2.0 * STEP);
        let (_, gp, _) = evaluate(term, &plus);
        let (_, gm, _) = evaluate(term, &minus);
        for r in 0..n {
            fd_h[(r, dof)] = (gp[r] - gm[r]) / (2.0 * STEP);
        }
    }
    let g_scale = g.iter().fold(1e-12_f64, |m, v| m.max(v.abs()));
    let g_error = g
        .iter()
        .zip(&fd_g)
        .fold(0.0, |m: f64, (a, b)| m.max((a - b).abs()))
        / g_scale;
    let h_error = (&h - &fd_h).amax() / h.amax().max(1e-12);
    (g_error, h_error)
}

fn terms(deformed: &Deformed, seed: f64) -> Vec<Box<dyn EnergyTerm>> {
    let mesh = &deformed.mesh;
    let faces = mesh.boundary().unwrap().triangles().to_vec();
    let nodal: Arc<dyn ConstraintSet> = Arc::new(
        NodalConstraints::new(mesh, Measure::Linear, 1e3, NodalCompliance::Lumped).unwrap(),
    );
    let m = nodal.num_constraints();
    let compliance = (0..m)
        .map(|i| 1e-3 * (1.0 + (i as f64 * seed).sin().abs()))
        .collect();
    let stiffness = (0..m)
        .map(|i| 10.0 * (1.0 + (i as f64 + seed).cos().abs()))
        .collect();
    let augmented = AugmentedConstraints::new(nodal, compliance, stiffness);
    augmented.set_multipliers(&(0..m).map(|i| (i as f64 * seed).sin()).collect::<Vec<_>>());
    let masses: Vec<f64> = (0..mesh.num_vertices())
        .map(|i| 1.0 + 0.1 * (i as f64 * seed).cos())
        .collect();
    let mut inertia = Inertia::new(masses, 0.01);
    let velocities: Vec<Vec3> = (0..mesh.num_vertices())
        .map(|i| Vec3::repeat((i as f64 * seed).sin()))
        .collect();
    inertia.begin_step(mesh.positions(), &velocities);
    let material = Arc::new(standard_neo_hookean(Lame::new(1.0, 10.0).unwrap()).unwrap());
    vec![
        Box::new(DeadLoad::traction(
            mesh.positions(),
            &faces,
            Vec3::new(seed, -1.0, 0.5),
        )),
        Box::new(FollowerPressure::new(faces, 2.0 * seed)),
        Box::new(augmented),
        Box::new(inertia),
        Box::new(Elastic::new(mesh, material, false)),
        Box::new(EpidermisTerm::new(mesh, Epidermis::new(3.0, 1.0).unwrap()).unwrap()),
    ]
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(8))]

    #[test]
    fn every_term_matches_finite_differences(deformed in deformed_box([1, 1, 2], 0.15, 0.3), seed in 0.1..1.0f64) {
        for term in terms(&deformed, seed) {
            let (g_error, h_error) = check(term.as_ref(), &deformed.x);
            prop_assert!(g_error < TOLERANCE, "{}: gradient error {g_error:e}", term.name());
            prop_assert!(h_error < TOLERANCE, "{}: Hessian error {h_error:e}", term.name());
        }
    }
}
