//! The silicone cantilever of the locking study as a library problem: 0.2 x 0.05 x 0.05 m,
//! clamped at `x = 0`, under gravity, `E` = 266 kPa, `nu` = 0.45, `rho` = 1070 kg/m^3.

use isochor_mesh::element::ElementMesh;
use isochor_mesh::{generate::box_grid, Vec3};
use isochor_solvers::{Dirichlet, Load, Material, Method, Motion, Problem};

/// The cantilever on `cells` box cells of 4-node tets, or of 10-node tets if `quadratic`.
pub fn cantilever(cells: [usize; 3], quadratic: bool, method: Method) -> Problem {
    let tets = box_grid(Vec3::zeros(), Vec3::new(0.2, 0.05, 0.05), cells).expect("beam");
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
