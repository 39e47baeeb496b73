//! One finite-difference harness for the solver's energy terms: the gradient against central
//! differences of the energy and the Hessian (assembled from its pattern) against central
//! differences of the gradient, on randomly deformed boxes. Adding a term is one line. A
//! negative control shows the harness rejects derivatives wrong by 1e-5; gravity and the
//! zero-compliance folding of static condensation are also checked against their formulas.

use isochor_constraints::{
    exact_rule, Compliance, ConstraintSet, Measure, NodalCompliance, NodalConstraints, RowShape,
};
use isochor_energies::{standard_neo_hookean, Epidermis, Lame, MooneyRivlin};
use isochor_mesh::{ElementMesh, Vec3};
use isochor_solvers::terms::{
    AugmentedConstraints, DeadLoad, Elastic, EnergyTerm, EpidermisTerm, Faces, FollowerPressure,
    Inertia,
};
use isochor_solvers::{LoadLevel, SolverError};
use isochor_validation::strategies::{deformed_box, quadratic};
use isochor_validation::terms::evaluate_dense;
use nalgebra::DMatrix;
use proptest::prelude::*;
use std::sync::Arc;

/// Required agreement, relative to the derivative's max norm.
const TOLERANCE: f64 = 1e-6;
/// Central-difference step relative to the unit box. A central difference errs by about
/// `STEP^2 / l^2` (truncation; `l` the smallest deformed length scale) plus `eps / STEP`
/// times the ratio of the differenced quantity to its derivative (rounding), relative to
/// the derivative. These boxes have cells of 1 x 1 x 0.5 and every tet's volume ratio at least
/// 0.3, so `l` stays above about 0.1: both parts are near 1e-10, and the largest errors
/// measured over 64 cases are 1.0e-9 (the gradient of gravity, whose energy is ten times
/// its gradient) and 3.7e-10 (Hessians), three orders inside TOLERANCE. TOLERANCE would be
/// reached only at `l ~ 1e-3`, a tet squeezed a thousandfold; a larger step makes the
/// truncation grow as `STEP^2`, a smaller one the rounding as `1 / STEP`.
const STEP: f64 = 1e-6;

/// Size of the defects of the negative control: ten times TOLERANCE.
const DEFECT: f64 = 1e-5;

fn evaluate(term: &dyn EnergyTerm, x: &[Vec3]) -> (f64, Vec<f64>, DMatrix<f64>) {
    evaluate_dense(term, x, &LoadLevel::quasi_static(0.7))
}

fn energy(term: &dyn EnergyTerm, x: &[Vec3]) -> f64 {
    term.evaluate(x, &LoadLevel::quasi_static(0.7), None, None)
        .unwrap()
}

fn gradient(term: &dyn EnergyTerm, x: &[Vec3]) -> Vec<f64> {
    let mut g = vec![0.0; 3 * x.len()];
    term.evaluate(x, &LoadLevel::quasi_static(0.7), Some(&mut g), None)
        .unwrap();
    g
}

fn shifted(x: &[Vec3], dof: usize, by: f64) -> Vec<Vec3> {
    let mut y = x.to_vec();
    y[dof / 3][dof % 3] += by;
    y
}

/// Checks `term` at `x`, returning the relative errors (max norm, relative to the term's
/// own derivative) of its gradient against central differences of its energy and of its
/// Hessian against central differences of its gradient.
fn check(term: &dyn EnergyTerm, x: &[Vec3]) -> (f64, f64) {
    let (_, g, h) = evaluate(term, x);
    let n = g.len();
    let mut fd_g = vec![0.0; n];
    let mut fd_h = DMatrix::zeros(n, n);
    for dof in 0..n {
        let (plus, minus) = (shifted(x, dof, STEP), shifted(x, dof, -STEP));
        fd_g[dof] = (energy(term, &plus) - energy(term, &minus)) / (2.0 * STEP);
        let (gp, gm) = (gradient(term, &plus), gradient(term, &minus));
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

/// The lumped nodal constraints of the mixed and condensed methods, with `kappa = 1e3`.
fn nodal(mesh: &ElementMesh) -> Arc<dyn ConstraintSet> {
    Arc::new(
        NodalConstraints::on_elements(
            mesh,
            exact_rule(mesh.kind(), RowShape::Corners),
            Measure::Linear,
            1e3,
            NodalCompliance::Lumped,
        )
        .unwrap(),
    )
}

/// The folding of static condensation (eq. 36-37 of Francu et al. 2021) as the `condensed`
/// method builds it on `mesh`: zero compliance, zero multipliers, stiffness
/// `R = C_lumped^-1` (returned with the term).
fn condensed(mesh: &ElementMesh) -> (AugmentedConstraints, Vec<f64>) {
    let set = nodal(mesh);
    let Compliance::Diagonal(c) = set.compliance() else {
        panic!("lumped nodal compliance is diagonal");
    };
    let stiffness: Vec<f64> = c.iter().map(|ci| 1.0 / ci).collect();
    let term = AugmentedConstraints::new(set, vec![0.0; c.len()], stiffness.clone());
    (term, stiffness)
}

/// Lumped masses of the test terms (1 +- 0.1, varying per vertex).
fn masses(n: usize, seed: f64) -> Vec<f64> {
    (0..n)
        .map(|i| 1.0 + 0.1 * (i as f64 * seed).cos())
        .collect()
}

/// Every term on `mesh` (4- or 10-node tets), with data varying with `seed`.
fn terms(mesh: &ElementMesh, seed: f64) -> Vec<Box<dyn EnergyTerm>> {
    let triangles = mesh.corners().boundary().unwrap().triangles().to_vec();
    let faces = || Faces::new(mesh, &triangles).unwrap();
    let nodal = nodal(mesh);
    let m = nodal.num_constraints();
    let compliance = (0..m)
        .map(|i| 1e-3 * (1.0 + (i as f64 * seed).sin().abs()))
        .collect();
    let stiffness = (0..m)
        .map(|i| 10.0 * (1.0 + (i as f64 + seed).cos().abs()))
        .collect();
    let augmented = AugmentedConstraints::new(nodal, compliance, stiffness);
    augmented.set_multipliers(&(0..m).map(|i| (i as f64 * seed).sin()).collect::<Vec<_>>());
    let masses = masses(mesh.num_nodes(), seed);
    let gravity = DeadLoad::gravity(&masses, Vec3::new(0.3, -9.8, seed));
    let mut inertia = Inertia::new(mesh.lumped_volumes(), 0.01);
    let velocities: Vec<Vec3> = (0..mesh.num_nodes())
        .map(|i| Vec3::repeat((i as f64 * seed).sin()))
        .collect();
    inertia.begin_step(mesh.nodes(), &velocities, 0.01);
    let material = Arc::new(standard_neo_hookean(Lame::new(1.0, 10.0).unwrap()).unwrap());
    let traction = DeadLoad::traction(mesh.nodes(), &faces(), Vec3::new(seed, -1.0, 0.5));
    vec![
        Box::new(traction),
        Box::new(gravity),
        Box::new(FollowerPressure::new(faces(), 2.0 * seed)),
        Box::new(augmented),
        Box::new(condensed(mesh).0),
        Box::new(inertia),
        Box::new(Elastic::new(mesh, material.clone(), false).unwrap()),
        // Two materials (a region): every other element Mooney-Rivlin.
        Box::new(
            Elastic::with_materials(
                mesh,
                vec![material, Arc::new(MooneyRivlin::new(3.0, 1.0).unwrap())],
                (0..mesh.num_elements()).map(|e| e % 2).collect(),
                false,
            )
            .unwrap(),
        ),
        Box::new(EpidermisTerm::new(mesh, Epidermis::new(3.0, 1.0).unwrap()).unwrap()),
    ]
}

/// A wrong derivative for the negative control.
#[derive(Debug, Clone, Copy)]
enum Defect {
    /// The gradient times `1 + DEFECT`.
    ScaledGradient,
    /// One gradient entry off by `DEFECT` times the gradient's max norm.
    GradientEntry,
    /// The Hessian times `1 + DEFECT`.
    ScaledHessian,
    /// One Hessian entry off by `DEFECT` times the assembled Hessian's max norm.
    HessianEntry,
}

/// `inner` with one [`Defect`].
#[derive(Debug)]
struct Wrong<'a> {
    inner: &'a dyn EnergyTerm,
    defect: Defect,
}

impl EnergyTerm for Wrong<'_> {
    fn name(&self) -> &'static str {
        self.inner.name()
    }

    fn hessian_pattern(&self) -> Vec<(usize, usize)> {
        self.inner.hessian_pattern()
    }

    fn evaluate(
        &self,
        x: &[Vec3],
        level: &LoadLevel,
        mut gradient: Option<&mut [f64]>,
        mut hessian: Option<&mut [f64]>,
    ) -> Result<f64, SolverError> {
        let e = self
            .inner
            .evaluate(x, level, gradient.as_deref_mut(), hessian.as_deref_mut())?;
        match (self.defect, gradient, hessian) {
            (Defect::ScaledGradient, Some(g), _) => g.iter_mut().for_each(|v| *v *= 1.0 + DEFECT),
            (Defect::GradientEntry, Some(g), _) => {
                g[0] += DEFECT * g.iter().fold(0.0, |m: f64, v| m.max(v.abs()));
            }
            (Defect::ScaledHessian, _, Some(h)) => h.iter_mut().for_each(|v| *v *= 1.0 + DEFECT),
            (Defect::HessianEntry, _, Some(h)) => {
                // The pattern repeats entries: measure the assembled matrix.
                let n = 3 * x.len();
                let mut dense = DMatrix::<f64>::zeros(n, n);
                for (&(r, c), v) in self.inner.hessian_pattern().iter().zip(h.iter()) {
                    dense[(r, c)] += v;
                }
                h[0] += DEFECT * dense.amax();
            }
            _ => {}
        }
        Ok(e)
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    /// Every term's gradient and Hessian against central differences (see [`check`]).
    #[test]
    fn every_term_matches_finite_differences(deformed in deformed_box([1, 1, 2], 0.15, 0.3), seed in 0.1..1.0f64) {
        for term in terms(&deformed.mesh.clone().into(), seed) {
            let (g_error, h_error) = check(term.as_ref(), &deformed.x);
            prop_assert!(g_error < TOLERANCE, "{}: gradient error {g_error:e}", term.name());
            prop_assert!(h_error < TOLERANCE, "{}: Hessian error {h_error:e}", term.name());
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(12))]

    /// Every term on curved 10-node tets (6-node faces for traction, pressure and the
    /// epidermis; HRZ masses in the inertia; the degree-5 rules of curved elements), against
    /// central differences as above.
    #[test]
    fn every_term_on_quadratic_tets_matches_finite_differences(
        deformed in quadratic(deformed_box([1, 1, 1], 0.15, 0.3), 0.05, 0.05, 0.3),
        seed in 0.1..1.0f64,
    ) {
        for term in terms(&deformed.mesh, seed) {
            let (g_error, h_error) = check(term.as_ref(), &deformed.x);
            prop_assert!(g_error < TOLERANCE, "{}: gradient error {g_error:e}", term.name());
            prop_assert!(h_error < TOLERANCE, "{}: Hessian error {h_error:e}", term.name());
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(16))]

    /// Negative control: the same [`check`] and TOLERANCE report every term whose gradient or
    /// Hessian is wrong by DEFECT (scaled by `1 + DEFECT`, or one entry off by DEFECT times
    /// its max norm) as failing, so a term that passes is right to better than that. (16
    /// cases: the defect is ten times the tolerance and a thousand times the differences'
    /// own error, so the outcome does not depend on the case.)
    #[test]
    fn finite_differences_reject_a_wrong_derivative(deformed in deformed_box([1, 1, 2], 0.15, 0.3), seed in 0.1..1.0f64) {
        for term in terms(&deformed.mesh.clone().into(), seed) {
            let defects: &[Defect] = if term.hessian_pattern().is_empty() {
                &[Defect::ScaledGradient, Defect::GradientEntry]
            } else {
                &[Defect::ScaledGradient, Defect::GradientEntry, Defect::ScaledHessian, Defect::HessianEntry]
            };
            for &defect in defects {
                let (g_error, h_error) = check(&Wrong { inner: term.as_ref(), defect }, &deformed.x);
                let error = match defect {
                    Defect::ScaledGradient | Defect::GradientEntry => g_error,
                    Defect::ScaledHessian | Defect::HessianEntry => h_error,
                };
                prop_assert!(error >= TOLERANCE, "{} with {defect:?} passed: error {error:e}", term.name());
            }
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    /// `DeadLoad::gravity` is the potential of the weight: `-load sum_i m_i g . x_i`, with
    /// gradient `-load m_i g`, no Hessian, and total force `(sum_i m_i) g`, to rounding (sums
    /// of 12 products: `1e-13` of the sum of their sizes).
    #[test]
    fn gravity_is_the_potential_of_the_weight(
        deformed in deformed_box([1, 1, 2], 0.15, 0.3),
        seed in 0.1..1.0f64,
        g in proptest::array::uniform3(-10.0..10.0f64),
        load in 0.0..1.0f64,
    ) {
        let g = Vec3::from(g);
        let x = &deformed.x;
        let masses = masses(x.len(), seed);
        let term = DeadLoad::gravity(&masses, g);
        let mut gradient = vec![0.0; 3 * x.len()];
        let e = term.evaluate(x, &LoadLevel::quasi_static(load), Some(&mut gradient), None).unwrap();
        let expected = -load * masses.iter().zip(x).map(|(m, xi)| m * g.dot(xi)).sum::<f64>();
        let size: f64 = masses.iter().zip(x).map(|(m, xi)| m * g.norm() * xi.norm()).sum();
        prop_assert!((e - expected).abs() <= 1e-13 * size, "{e} against {expected}");
        for (i, m) in masses.iter().enumerate() {
            for k in 0..3 {
                prop_assert!((gradient[3 * i + k] + load * m * g[k]).abs() <= 1e-15 * m * g.norm());
            }
        }
        prop_assert!(term.hessian_pattern().is_empty() && term.is_external());
        let total: f64 = masses.iter().sum();
        prop_assert!((term.total_force() - total * g).norm() <= 1e-13 * total * g.norm());
    }

    /// The zero-compliance folding of `condensed` (`C = 0`, `p = 0`, `R = C_lumped^-1`) has
    /// the energy `sum_i R_i phi_i^2 / 2` of eq. 36 of Francu et al. 2021, to rounding (a sum
    /// of 12 positive terms: `1e-13` relative).
    #[test]
    fn condensed_folding_is_the_penalty_of_eq_36(deformed in deformed_box([1, 1, 2], 0.15, 0.3)) {
        let mesh = deformed.mesh.clone().into();
        let (term, stiffness) = condensed(&mesh);
        let mut phi = vec![0.0; stiffness.len()];
        nodal(&mesh).values(&deformed.x, &mut phi).unwrap();
        let e = term.evaluate(&deformed.x, &LoadLevel::FULL, None, None).unwrap();
        let expected: f64 = phi.iter().zip(&stiffness).map(|(p, r)| 0.5 * r * p * p).sum();
        prop_assert!((e - expected).abs() <= 1e-13 * expected, "{e} against {expected}");
    }
}

/// A dead traction is the consistent load `t integral N_a dA`: its total is `t` times the
/// loaded area on both elements, and on flat 6-node faces the corners carry nothing and
/// each mid-edge node a third of each face it borders (the exact `integral N_a dA` of the
/// quadratic triangle); the follower pressure on a closed 6-node surface at rest has the
/// energy `p V` of the volume it encloses.
#[test]
fn traction_and_pressure_on_quadratic_faces_are_the_consistent_loads() {
    let mesh = isochor_mesh::generate::box_grid(Vec3::zeros(), Vec3::new(0.3, 0.2, 0.1), [3, 2, 1])
        .unwrap();
    let boundary = mesh.boundary().unwrap();
    let triangles = boundary.triangles().to_vec();
    let area: f64 = boundary.rest_areas().iter().sum();
    let t = Vec3::new(0.5, -2.0, 1.5);
    for elements in [
        ElementMesh::linear(mesh.clone()),
        ElementMesh::quadratic(mesh.clone()),
    ] {
        let faces = Faces::new(&elements, &triangles).unwrap();
        let load = DeadLoad::traction(elements.nodes(), &faces, t);
        assert!((load.total_force() - area * t).norm() < 1e-14 * area * t.norm());
        let nv = elements.num_vertices();
        let mut per_node = vec![Vec3::zeros(); elements.num_nodes()];
        let mut gradient = vec![0.0; 3 * elements.num_nodes()];
        load.evaluate(
            elements.nodes(),
            &LoadLevel::FULL,
            Some(&mut gradient),
            None,
        )
        .unwrap();
        for (a, f) in per_node.iter_mut().enumerate() {
            *f = -Vec3::new(gradient[3 * a], gradient[3 * a + 1], gradient[3 * a + 2]);
        }
        if elements.num_nodes() > nv {
            let nodes = elements.face_elements(&triangles).unwrap();
            let mut expected = vec![Vec3::zeros(); elements.num_nodes()];
            for (face, a) in nodes.chunks_exact(6).zip(boundary.rest_areas()) {
                face[3..].iter().for_each(|&m| expected[m] += t * (a / 3.0));
            }
            for (f, e) in per_node.iter().zip(&expected) {
                assert!((f - e).norm() < 1e-15 * t.norm(), "{f} against {e}");
            }
        }
        let pressure = FollowerPressure::new(Faces::new(&elements, &triangles).unwrap(), 3.0);
        let energy = pressure
            .evaluate(elements.nodes(), &LoadLevel::FULL, None, None)
            .unwrap();
        assert!((energy - 3.0 * 0.3 * 0.2 * 0.1).abs() < 1e-15, "{energy}");
    }
}
