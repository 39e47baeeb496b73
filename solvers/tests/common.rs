//! Problems shared by the solver tests.

#![allow(dead_code)]

use isochor_mesh::{generate::box_grid, TetMesh, Vec3};
use isochor_solvers::{Dirichlet, Load, Material, Method, Motion, Problem};

/// Vertices of `mesh` with `coordinate[axis] == value` (to rounding).
pub fn plane(mesh: &TetMesh, axis: usize, value: f64) -> Vec<usize> {
    (0..mesh.num_vertices())
        .filter(|&v| (mesh.positions()[v][axis] - value).abs() < 1e-9)
        .collect()
}

/// The cantilever of the locking study: 0.2 x 0.05 x 0.05 m, `4 res x res x res` cells,
/// clamped at x = 0, under gravity.
pub fn cantilever(res: usize, method: Method, nu: f64) -> Problem {
    beam([4 * res, res, res], method, nu, Vec3::new(0.2, 0.05, 0.05))
}

/// A beam `[0, size]` with `cells`, clamped at x = 0, under gravity.
pub fn beam(cells: [usize; 3], method: Method, nu: f64, size: Vec3) -> Problem {
    let mesh = box_grid(Vec3::zeros(), size, cells).unwrap();
    let clamped = plane(&mesh, 0, 0.0);
    Problem {
        mesh,
        method,
        material: Material::from_young_poisson(266e3, nu, 1070.0).unwrap(),
        zones: None,
        dirichlet: vec![Dirichlet {
            vertices: clamped,
            axes: [true; 3],
            motion: Motion::Fixed,
        }],
        loads: vec![Load::Gravity(Vec3::new(0.0, -9.8, 0.0))],
        obstacles: Vec::new(),
    }
}

/// Mean `-u_y` over the free end face `x = length`.
pub fn end_deflection(mesh: &TetMesh, x: &[Vec3]) -> f64 {
    let length = mesh.bounding_box().1.x;
    let end = plane(mesh, 0, length);
    end.iter()
        .map(|&v| mesh.positions()[v].y - x[v].y)
        .sum::<f64>()
        / end.len() as f64
}
