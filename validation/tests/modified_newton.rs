//! Modified Newton (`Jacobian::Modified`): on every method and both elements, the run that
//! reuses factorizations ends on the state full Newton ends on, to the solver's tolerances,
//! with fewer factorizations than iterations; full Newton factorizes at every iteration.

use isochor_mesh::element::ElementMesh;
use isochor_mesh::{generate::box_grid, Vec3};
use isochor_solvers::{
    Dirichlet, Jacobian, Load, Material, Method, Motion, Problem, RunSummary, Settings, Simulation,
    Stepping,
};

/// The cantilever of `newton.rs` on 4 x 1 x 1 cells, nu = 0.45, of 4- or 10-node tets.
fn cantilever(method: Method, quadratic: bool) -> Problem {
    let tets = box_grid(Vec3::zeros(), Vec3::new(0.2, 0.05, 0.05), [4, 1, 1]).expect("beam");
    let mesh = if quadratic {
        ElementMesh::quadratic(tets)
    } else {
        ElementMesh::linear(tets)
    };
    let clamped = (0..mesh.num_nodes())
        .filter(|&n| mesh.nodes()[n].x.abs() < 1e-12)
        .collect();
    Problem {
        dirichlet: vec![Dirichlet {
            nodes: clamped,
            axes: [true; 3],
            motion: Motion::Fixed,
            curve: None,
        }],
        loads: vec![Load::Gravity(Vec3::new(0.0, -9.8, 0.0)).into()],
        method,
        material: Material::from_young_poisson(266e3, 0.45, 1070.0).expect("material"),
        regions: Vec::new(),
        zones: None,
        obstacles: Vec::new(),
        mesh,
        cloths: Vec::new(),
    }
}

fn run(method: Method, quadratic: bool, jacobian: Jacobian) -> RunSummary {
    let settings = Settings {
        jacobian,
        ..Settings::default()
    };
    let mut sim = Simulation::new(cantilever(method, quadratic), settings).expect("simulation");
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
            let rest = cantilever(method, quadratic).mesh.nodes().to_vec();
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
