//! As the mesh is refined, the methods' tip deflections on a mildly compressible
//! cantilever (nu = 0.3) approach each other.

use crate::common;

use common::{cantilever, end_deflection};
use isochor_energies::Lame;
use isochor_solvers::{Method, Settings, Simulation, Stepping};

#[test]
fn methods_agree_as_the_mesh_is_refined() {
    let nu = 0.3;
    let methods = [
        Method::Standard,
        Method::MixedP1,
        Method::MixedP0,
        Method::MixedP1Log,
        Method::Condensed,
        Method::Dual,
        Method::Zonal,
    ];
    let mut spreads = Vec::new();
    println!("res | {}", methods.map(|m| m.name()).join(" | "));
    for res in [1, 2, 4] {
        let deflections: Vec<f64> = methods
            .iter()
            .map(|&method| {
                let mut problem = cantilever(res, method, nu);
                problem.material.zonal_lambda = Lame::from_young_poisson(266e3, nu).unwrap().lambda;
                let mut sim = Simulation::new(problem, Settings::default()).unwrap();
                let summary = sim
                    .run(Stepping::quasi_static(2), |_| {})
                    .unwrap_or_else(|e| panic!("{method} at res {res}: {e}"));
                end_deflection(sim.mesh().corners(), &summary.final_state.positions)
            })
            .collect();
        let max = deflections.iter().copied().fold(f64::MIN, f64::max);
        let min = deflections.iter().copied().fold(f64::MAX, f64::min);
        let spread = (max - min) / max;
        println!(
            "{res} | {} | spread {spread:.3}",
            deflections
                .iter()
                .map(|d| format!("{:.2} mm", 1e3 * d))
                .collect::<Vec<_>>()
                .join(" | ")
        );
        spreads.push(spread);
    }
    assert!(
        spreads.windows(2).all(|w| w[1] < w[0]),
        "spreads {spreads:?} must shrink"
    );
}
