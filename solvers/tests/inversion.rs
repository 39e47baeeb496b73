//! A converged state with inverted elements is accepted only where the energy has a meaning
//! there: one 10-node tet, every node held, one mid-edge node moved so far towards a corner
//! that the element folds at that corner while its quadrature points stay unfolded.

use isochor_mesh::{ElementMesh, TetMesh, Vec3};
use isochor_solvers::{
    Dirichlet, Material, MaterialModel, Method, Motion, Problem, Settings, Simulation, SolverError,
    Stepping,
};

/// The unit 10-node tet with the mid-edge node of edge 0-1 moved from `e1 / 2` to `0.2 e1`:
/// the column `dx/dxi_1 = -3 x0 - x1 + 4 x01 = -0.2 e1` at corner 0 makes `J < 0` there.
fn folded_corner(method: Method, model: MaterialModel) -> Result<usize, SolverError> {
    let corners = vec![Vec3::zeros(), Vec3::x(), Vec3::y(), Vec3::z()];
    let mesh = ElementMesh::quadratic(TetMesh::new(corners, vec![[0, 1, 2, 3]]).unwrap());
    let nv = mesh.num_vertices();
    let moved = nv + mesh.mid_edges().iter().position(|&e| e == [0, 1]).unwrap();
    let held = (0..mesh.nodes().len()).filter(|&n| n != moved);
    let mut material = Material::from_young_poisson(1e5, 0.45, 1000.0).unwrap();
    material.model = model;
    let problem = Problem::builder(mesh)
        .method(method)
        .material(material)
        .clamp(held)
        .dirichlet(Dirichlet {
            nodes: vec![moved],
            axes: [true; 3],
            motion: Motion::Translate(Vec3::new(-0.3, 0.0, 0.0)),
            curve: None,
        })
        .build()
        .unwrap();
    let mut simulation = Simulation::new(problem, Settings::default()).unwrap();
    simulation
        .run(Stepping::quasi_static(1), |_| {})
        .map(|summary| summary.max_inverted_tets)
        .map_err(|failure| failure.error)
}

#[test]
fn a_folded_corner_fails_the_step_where_the_energy_is_undefined() {
    for method in [Method::Standard, Method::MixedP1, Method::MixedP0Log] {
        match folded_corner(method, MaterialModel::NeoHookean) {
            Err(SolverError::InvertedState { inverted }) => assert_eq!(inverted, 1),
            other => panic!("{method:?}: {other:?}"),
        }
    }
}

#[test]
fn an_invertible_energy_accepts_the_folded_corner_and_counts_it() {
    let inverted = folded_corner(Method::MixedP1, MaterialModel::StableNeoHookean).unwrap();
    assert_eq!(inverted, 1);
}
