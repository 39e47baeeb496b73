//! Modified Newton (`Jacobian::Modified`): on every method and both elements, the run that
//! reuses factorizations ends on the state full Newton ends on, to the solver's tolerances,
//! with fewer factorizations than iterations; full Newton factorizes at every iteration.

use crate::common::cantilever;
use isochor_mesh::Vec3;
use isochor_solvers::{Jacobian, Method, RunSummary, Settings, Simulation, Stepping};

/// The beam of 4 x 1 x 1 cells.
const CELLS: [usize; 3] = [4, 1, 1];

fn run(method: Method, quadratic: bool, jacobian: Jacobian) -> RunSummary {
    let settings = Settings {
        jacobian,
        ..Settings::default()
    };
    let mut sim =
        Simulation::new(cantilever(CELLS, quadratic, method), settings).expect("simulation");
    sim.run(Stepping::quasi_static(2), |_| {})
        .unwrap_or_else(|e| panic!("{} ({jacobian:?}): {}", method.name(), e.error))
}

/// The largest difference of two lists over the largest magnitude of the first.
fn relative_difference<T: Copy>(
    a: &[T],
    b: &[T],
    norm: impl Fn(T) -> f64,
    sub: impl Fn(T, T) -> T,
) -> f64 {
    let scale = a.iter().map(|&v| norm(v)).fold(0.0, f64::max);
    let diff = a
        .iter()
        .zip(b)
        .map(|(&u, &v)| norm(sub(u, v)))
        .fold(0.0, f64::max);
    diff / scale.max(f64::MIN_POSITIVE)
}

#[test]
fn modified_newton_reaches_full_newtons_state_on_every_method() {
    for quadratic in [false, true] {
        for method in Method::ALL {
            // Dual ascent on 10-node tets stalls at this Poisson ratio (docs/elements.md).
            if quadratic && method == Method::Dual {
                continue;
            }
            let what = format!(
                "{} on {}",
                method.name(),
                if quadratic { "tet10" } else { "tet4" }
            );
            let full = run(method, quadratic, Jacobian::Full);
            let modified = run(method, quadratic, Jacobian::Modified);
            let rest = cantilever(CELLS, quadratic, method).mesh.nodes().to_vec();
            let displacement = |s: &RunSummary| -> Vec<Vec3> {
                s.final_state
                    .positions
                    .iter()
                    .zip(&rest)
                    .map(|(x, r)| x - r)
                    .collect()
            };
            let dx = relative_difference(
                &displacement(&full),
                &displacement(&modified),
                |v: Vec3| v.norm(),
                |a, b| a - b,
            );
            let dp = relative_difference(
                &full.final_state.multipliers,
                &modified.final_state.multipliers,
                f64::abs,
                |a, b| a - b,
            );
            let count = |s: &RunSummary| {
                let iterations: usize = s.reports.iter().map(|r| r.newton_iterations()).sum();
                let reused: usize = s
                    .reports
                    .iter()
                    .flat_map(|r| &r.iterations)
                    .filter(|i| i.reused)
                    .count();
                let factorizations: usize = s.reports.iter().map(|r| r.factorizations).sum();
                (iterations, reused, factorizations)
            };
            let (full_its, full_reused, full_factors) = count(&full);
            let (its, reused, factors) = count(&modified);
            println!(
                "{what}: full {full_its} iterations, {full_factors} factorizations; modified {its} iterations ({reused} reused), {factors} factorizations; state difference {dx:.1e}, pressures {dp:.1e}"
            );
            assert!(
                dx < 1e-6 && dp < 1e-6,
                "{what}: states differ by {dx:.1e} / {dp:.1e}"
            );
            assert_eq!(full_reused, 0, "{what}");
            if method == Method::Dual {
                // Dual ascent reads the factorization at the iterate (eq. 41): never reused.
                assert_eq!(reused, 0, "{what}");
                assert_eq!(factors, full_factors, "{what}");
            } else {
                assert!(reused > 0, "{what}: no iteration reused a factorization");
                assert!(factors < full_factors, "{what}: {factors} factorizations");
                assert_eq!(full_factors, full_its, "{what}");
            }
        }
    }
}
