//! The surface-contact energy term against the barrier potential it wraps and against finite
//! differences: two cubes 1 mm apart within the barrier's reach, perturbed at random. Its
//! gradient is the central difference of its energy, the Hessian it writes into its own
//! pattern is the potential's PSD-projected Hessian at the term's stiffness, and its exact
//! Hessian (`EnergyTerm::project_hessian(false)`) the central difference of its gradient.

use isochor_mesh::contact::{contact_candidates, ContactSurface, PairFilter};
use isochor_mesh::element::ElementMesh;
use isochor_mesh::generate::box_grid;
use isochor_mesh::Vec3;
use isochor_solvers::contact::BarrierPotential;
use isochor_solvers::terms::{EnergyTerm, SurfaceContact, SurfaceContactSpec};
use isochor_solvers::LoadLevel;
use nalgebra::DMatrix;
use proptest::prelude::*;

const DHAT: f64 = 0.01;

/// Two unit cubes (one cell each), the upper 1 mm above the lower, as one mesh.
fn cubes() -> (ElementMesh, Vec<usize>) {
    let lower = box_grid(Vec3::zeros(), Vec3::new(1.0, 1.0, 1.0), [1, 1, 1]).unwrap();
    let upper = box_grid(
        Vec3::new(0.0, 0.0, 1.001),
        Vec3::new(1.0, 1.0, 2.001),
        [1, 1, 1],
    )
    .unwrap();
    let (mesh, parts) =
        ElementMesh::disjoint_union(vec![ElementMesh::linear(lower), ElementMesh::linear(upper)])
            .unwrap();
    let mut bodies = vec![0; mesh.num_nodes()];
    parts[1].nodes().for_each(|n| bodies[n] = 1);
    (mesh, bodies)
}

fn term(mesh: &ElementMesh, bodies: Vec<usize>) -> (SurfaceContact, ContactSurface) {
    let surface = ContactSurface::from_element_surface(&mesh.boundary().unwrap());
    let spec = SurfaceContactSpec {
        dhat: DHAT,
        self_contact: false,
        node_bodies: bodies,
    };
    let term = SurfaceContact::new(spec, surface.clone(), mesh.nodes().to_vec(), 1e5).unwrap();
    (term, surface)
}

fn energy(term: &SurfaceContact, x: &[Vec3]) -> f64 {
    term.evaluate(x, &LoadLevel::FULL, None, None).unwrap()
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(16))]

    #[test]
    fn the_term_is_the_potential_and_its_gradient_the_energys_slope(
        moves in proptest::collection::vec(-2e-4..2e-4f64, 48)
    ) {
        let (mesh, bodies) = cubes();
        let (term, surface) = term(&mesh, bodies.clone());
        let rest = mesh.nodes().to_vec();
        let x: Vec<Vec3> = rest
            .iter()
            .enumerate()
            .map(|(i, p)| p + Vec3::new(moves[3 * i % 48], moves[(3 * i + 1) % 48], moves[(3 * i + 2) % 48]))
            .collect();
        prop_assert!(term.update(&x), "the pairs appear");
        let n = 3 * x.len();
        let pattern = term.hessian_pattern();
        let mut values = vec![0.0; pattern.len()];
        let mut gradient = vec![0.0; n];
        let e = term
            .evaluate(&x, &LoadLevel::FULL, Some(&mut gradient), Some(&mut values))
            .unwrap();
        prop_assert!(e > 0.0 && e.is_finite());
        // The gradient against central differences of the energy.
        let h = 1e-8;
        for dof in 0..n {
            let (mut plus, mut minus) = (x.clone(), x.clone());
            plus[dof / 3][dof % 3] += h;
            minus[dof / 3][dof % 3] -= h;
            let fd = (energy(&term, &plus) - energy(&term, &minus)) / (2.0 * h);
            prop_assert!(
                (fd - gradient[dof]).abs() <= 1e-5 * gradient.iter().fold(0.0f64, |m, g| m.max(g.abs())),
                "dof {dof}: {fd} against {}", gradient[dof]
            );
        }
        // The Hessian in the term's pattern against the potential's at the same stiffness.
        let candidates = contact_candidates(&surface, &x, None, DHAT, PairFilter::BetweenBodies(&bodies));
        let unit = BarrierPotential { dhat: DHAT, kappa: 1.0 };
        let mut unit_gradient = vec![0.0; n];
        unit.add_gradient(&surface, &candidates, &rest, &x, &mut unit_gradient);
        let dot = |a: &[f64], b: &[f64]| a.iter().zip(b).map(|(p, q)| p * q).sum::<f64>();
        let kappa = dot(&gradient, &unit_gradient) / dot(&unit_gradient, &unit_gradient);
        let mut ours = DMatrix::<f64>::zeros(n, n);
        for (&(r, c), v) in pattern.iter().zip(&values) {
            ours[(r, c)] += v;
        }
        let mut theirs = DMatrix::<f64>::zeros(n, n);
        for (r, c, v) in unit.hessian_triplets(&surface, &candidates, &rest, &x) {
            theirs[(r, c)] += kappa * v;
        }
        prop_assert!((&ours - &theirs).norm() <= 1e-10 * theirs.norm(), "{} against {}", ours.norm(), theirs.norm());

        // The exact Hessian (what Newton factorizes first) against central differences of
        // the gradient, column by column.
        term.project_hessian(false);
        let mut exact_values = vec![0.0; pattern.len()];
        term.evaluate(&x, &LoadLevel::FULL, None, Some(&mut exact_values)).unwrap();
        term.project_hessian(true);
        let mut exact = DMatrix::<f64>::zeros(n, n);
        for (&(r, c), v) in pattern.iter().zip(&exact_values) {
            exact[(r, c)] += v;
        }
        if pattern.iter().all(|&(r, c)| r >= c) {
            // A lower-triangle pattern: mirror it.
            exact = &exact + exact.transpose() - DMatrix::from_diagonal(&exact.diagonal());
        }
        let gradient_at = |y: &[Vec3]| {
            let mut g = vec![0.0; n];
            term.evaluate(y, &LoadLevel::FULL, Some(&mut g), None).unwrap();
            g
        };
        let scale = exact.amax();
        prop_assert!(scale > 0.0);
        let h = 1e-8;
        for dof in 0..n {
            let (mut plus, mut minus) = (x.clone(), x.clone());
            plus[dof / 3][dof % 3] += h;
            minus[dof / 3][dof % 3] -= h;
            let (gp, gm) = (gradient_at(&plus), gradient_at(&minus));
            for row in 0..n {
                let fd = (gp[row] - gm[row]) / (2.0 * h);
                prop_assert!(
                    (fd - exact[(row, dof)]).abs() <= 1e-5 * scale,
                    "({row}, {dof}): {fd} against {}", exact[(row, dof)]
                );
            }
        }
    }
}
