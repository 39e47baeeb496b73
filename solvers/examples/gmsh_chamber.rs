//! A Gmsh mesh with physical groups: a silicone tube of 10-node tets whose end faces
//! (surface groups `bottom` and `top`) are held while a follower pressure acts on its inner
//! wall (surface group `inner`), the chamber of a pneumatic actuator. Two materials: the
//! outer half of the wall (radius above 25 mm) is a sleeve ten times stiffer than the soft
//! inner half, a region given in code. Mixed FEM with nodal pressures. Prints the groups
//! read, the mean radial displacement of the inner wall and the volume change of the
//! (incompressible) wall.
//!
//! Run with `cargo run --example gmsh_chamber -p isochor-solvers`. The mesh is the
//! repository's `mesh/tests/data/tube-tet10-v41.msh`; any Gmsh file with these three surface
//! groups runs the same way.

use isochor_mesh::io::read_gmsh_with_groups;
use isochor_mesh::probes::volume_change;
use isochor_solvers::{Material, Problem, Settings, Simulation, Stepping};

pub fn main() -> Result<(), Box<dyn std::error::Error>> {
    let path = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../mesh/tests/data/tube-tet10-v41.msh"
    );
    let (mesh, groups) = read_gmsh_with_groups(path)?;
    println!("groups: {:?}", groups.keys().collect::<Vec<_>>());
    let faces = |key: &str| {
        groups
            .get(key)
            .map(|g| g.faces.clone())
            .ok_or(format!("{path} has no group '{key}'"))
    };
    // Every node of the end faces, mid-edge nodes included.
    let mut ends = mesh.face_elements(&faces("bottom")?)?;
    ends.extend(mesh.face_elements(&faces("top")?)?);
    let inner = faces("inner")?;
    let sleeve: Vec<usize> = (0..mesh.num_elements())
        .filter(|&e| mesh.corners().centroid(e).xy().norm() > 0.025)
        .collect();
    let problem = Problem::builder(mesh)
        .material(Material::from_young_poisson(1e5, 0.5, 1070.0)?)
        .region(
            "sleeve",
            sleeve,
            Material::from_young_poisson(1e6, 0.5, 1070.0)?,
        )
        .clamp(ends)
        .pressure(inner.iter().copied(), 5e3)
        .build()?;
    let mut simulation = Simulation::new(problem, Settings::default())?;
    let summary = simulation.run(Stepping::quasi_static(1), |_| {})?;
    let (mesh, x) = (simulation.mesh(), &summary.final_state.positions);
    let mut wall: Vec<usize> = inner.iter().flatten().copied().collect();
    wall.sort_unstable();
    wall.dedup();
    let radial = |v: usize, p: &[isochor_solvers::Vec3]| p[v].xy().norm();
    let growth = wall
        .iter()
        .map(|&v| radial(v, x) - radial(v, mesh.nodes()))
        .sum::<f64>()
        / wall.len() as f64;
    println!(
        "{} tets: inner radius grows by {:.3} mm on average, volume change {:.1e} ({:.2?})",
        mesh.num_elements(),
        1e3 * growth,
        volume_change(mesh, x)?,
        summary.wall_time
    );
    Ok(())
}
