//! A soft silicone cube (2 cm, the builder's default material) dropped from 5 mm onto a
//! rigid ground: implicit Euler (eq. 20-21 of Francu et al. 2021) with frictionless contact
//! against a half-space, mixed FEM with nodal pressures. Prints the lowest point of the body
//! over time: it falls, touches the ground at `z = 0` and stays above it.
//!
//! Run with `cargo run --example drop -p isochor-solvers`.

use isochor_mesh::generate::box_grid;
use isochor_solvers::{Obstacle, Problem, Settings, Shape, Simulation, Stepping, Vec3};

pub fn main() -> Result<(), Box<dyn std::error::Error>> {
    let (side, height) = (0.02, 0.005);
    let mesh = box_grid(
        Vec3::new(0.0, 0.0, height),
        Vec3::new(side, side, height + side),
        [2, 2, 2],
    )?;
    let ground = Obstacle::fixed(Shape::HalfSpace {
        point: Vec3::zeros(),
        normal: Vec3::z(),
    });
    let problem = Problem::builder(mesh)
        .gravity(Vec3::new(0.0, 0.0, -9.81))
        .obstacle(ground)
        .build()?;
    let mut simulation = Simulation::new(problem, Settings::default())?;
    let stepping = Stepping::ImplicitEuler {
        dt: 2e-3,
        frames: 30,
    };
    let summary = simulation.run(stepping, |frame| {
        if frame.index % 3 == 0 {
            let lowest = frame
                .state
                .positions
                .iter()
                .map(|p| p.z)
                .fold(f64::INFINITY, f64::min);
            let contacts = frame.report.contact.active_vertices;
            let t = 1e3 * frame.state.t;
            println!(
                "t = {t:5.1} ms  lowest z = {:7.3} mm  {contacts} vertices in contact",
                1e3 * lowest
            );
        }
    })?;
    println!(
        "{} steps in {:.2?}",
        summary.reports.len(),
        summary.wall_time
    );
    Ok(())
}
