//! A soft silicone beam (10 x 2 x 2 cm, the builder's default material) clamped at `x = 0`
//! sags under its own weight. Mixed FEM with nodal pressures (`mixed-p1`, the default) on a
//! coarse box mesh; prints the deflection at the centre of the free end.
//!
//! Run with `cargo run --example cantilever -p isochor-solvers`.

use isochor_mesh::generate::box_grid;
use isochor_mesh::probes::displacement_at;
use isochor_solvers::{Problem, Settings, Simulation, Stepping, Vec3};

pub fn main() -> Result<(), Box<dyn std::error::Error>> {
    let (length, side) = (0.1, 0.02);
    let mesh = box_grid(Vec3::zeros(), Vec3::new(length, side, side), [10, 2, 2])?;
    let clamped: Vec<usize> = (0..mesh.num_vertices())
        .filter(|&v| mesh.positions()[v].x == 0.0)
        .collect();
    let problem = Problem::builder(mesh)
        .clamp(clamped)
        .gravity(Vec3::new(0.0, 0.0, -9.81))
        .build()?;
    let mut simulation = Simulation::new(problem, Settings::default())?;
    let summary = simulation.run(Stepping::quasi_static(4), |_| {})?;
    let tip = Vec3::new(length, side / 2.0, side / 2.0);
    let u = displacement_at(simulation.mesh(), &summary.final_state.positions, &tip)?;
    println!(
        "tip deflection {:.2} mm ({} Newton iterations, {:.2?})",
        -1e3 * u.z,
        summary.newton_iterations(),
        summary.wall_time
    );
    Ok(())
}
