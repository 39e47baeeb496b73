mod common;

use common::{cantilever, end_deflection};
use isochor_solvers::{Method, Settings, Simulation, Stepping};

#[test]
fn cantilever_runs_for_every_method() {
    for method in [
        Method::Standard,
        Method::MixedP1,
        Method::MixedP0,
        Method::MixedP1Log,
        Method::MixedP0Log,
        Method::Condensed,
        Method::Dual,
        Method::Zonal,
    ] {
        let mut sim = Simulation::new(cantilever(2, method, 0.4999), Settings::default()).unwrap();
        let summary = sim.run(Stepping::QuasiStatic { steps: 2 }, |_| {});
        match summary {
            Ok(s) => {
                let d = end_deflection(sim.mesh(), &s.final_state.positions);
                println!(
                    "{method}: deflection {d:.5} m, {} iterations, {:?}",
                    s.newton_iterations(),
                    s.wall_time
                );
            }
            Err(e) => println!("{method}: FAILED {e}"),
        }
    }
}
