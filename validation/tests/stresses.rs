//! The stress outputs against a closed form: a bar of incompressible neo-Hookean material in
//! homogeneous uniaxial stretch `F = diag(l, l^-1/2, l^-1/2)` (symmetry planes at x, y, z = 0,
//! the end x = L pulled). With the distortional energy of the mixed methods (eq. 32 of Francu
//! et al. 2021) under the constraint `J = 1`, `sigma = mu (b - I) + p I`; free lateral faces
//! give `p = mu (1 - 1/l)` and `sigma_xx = mu (l^2 - 1/l)`, the other components zero, von
//! Mises `|sigma_xx|`.
//!
//! The nodal pressure is the constant `p` on 10-node tets (Taylor-Hood P2-P1, stable). On
//! this structured 4-node mesh the P1-P1 pair with zero compliance has spurious pressure
//! modes (`G^T q = 0`, checkerboards with zero element means): the nodal values are not
//! unique there, only their element means are, and those are checked.

use isochor_mesh::generate::box_grid;
use isochor_mesh::{ElementMesh, Vec3};
use isochor_solvers::{
    Dirichlet, Material, Method, Motion, Problem, Settings, Simulation, Stepping,
};

const MU: f64 = 1e4;

/// The bar `[0, 2] x [0, 1] x [0, 1]` pulled to `stretch` on `element` nodes.
fn stretched_bar(stretch: f64, quadratic: bool) -> Problem {
    let corners = box_grid(Vec3::zeros(), Vec3::new(2.0, 1.0, 1.0), [4, 2, 2]).unwrap();
    let mesh = if quadratic {
        ElementMesh::quadratic(corners)
    } else {
        ElementMesh::linear(corners)
    };
    let on = |axis: usize, value: f64| -> Vec<usize> {
        (0..mesh.num_nodes())
            .filter(|&v| (mesh.nodes()[v][axis] - value).abs() < 1e-9)
            .collect()
    };
    let hold = |axis: usize, value: f64, motion: Motion| {
        let mut axes = [false; 3];
        axes[axis] = true;
        Dirichlet {
            nodes: on(axis, value),
            axes,
            motion,
            curve: None,
        }
    };
    let pull = Motion::Translate(Vec3::new(2.0 * (stretch - 1.0), 0.0, 0.0));
    let dirichlet = vec![
        hold(0, 0.0, Motion::Fixed),
        hold(1, 0.0, Motion::Fixed),
        hold(2, 0.0, Motion::Fixed),
        hold(0, 2.0, pull),
    ];
    let mut material = Material::from_young_poisson(3.0 * MU, 0.5, 1000.0).unwrap();
    material.mu = MU;
    Problem {
        mesh,
        method: Method::MixedP1,
        material,
        regions: Vec::new(),
        zones: None,
        dirichlet,
        loads: Vec::new(),
        obstacles: Vec::new(),
        cloths: Vec::new(),
    }
}

#[test]
fn cauchy_stress_von_mises_and_nodal_pressure_match_uniaxial_stretch() {
    for quadratic in [false, true] {
        for stretch in [0.8, 1.3] {
            let mut sim =
                Simulation::new(stretched_bar(stretch, quadratic), Settings::default()).unwrap();
            sim.run(Stepping::adaptive(1), |_| {}).unwrap();
            let state = sim.state().clone();
            let sigma_xx = MU * (stretch * stretch - 1.0 / stretch);
            let p = MU * (1.0 - 1.0 / stretch);
            let scale = sigma_xx.abs();
            for (e, s) in sim.cauchy_stress(&state).iter().enumerate() {
                let mut expected = nalgebra::Matrix3::zeros();
                expected[(0, 0)] = sigma_xx;
                let err = (s - expected).amax() / scale;
                assert!(
                    err < 1e-6,
                    "tet10 {quadratic}, l {stretch}, element {e}: {s} ({err:e})"
                );
            }
            for v in sim.von_mises(&state) {
                assert!((v - scale).abs() < 1e-6 * scale, "von Mises {v} vs {scale}");
            }
            let nodal = sim
                .nodal_pressures(&state)
                .expect("mixed-p1 has nodal pressures");
            let mesh = sim.mesh();
            assert_eq!(nodal.len(), mesh.num_nodes());
            if quadratic {
                for q in &nodal {
                    assert!((q - p).abs() < 1e-6 * scale, "nodal pressure {q} vs {p}");
                }
            }
            for e in 0..mesh.num_elements() {
                let mean = mesh.element(e)[..4].iter().map(|&v| nodal[v]).sum::<f64>() / 4.0;
                assert!(
                    (mean - p).abs() < 1e-6 * scale,
                    "element {e} mean {mean} vs {p}"
                );
            }
        }
    }
}

/// A method with element pressures has no nodal pressure field.
#[test]
fn nodal_pressures_exist_only_for_the_p1_methods() {
    let mut problem = stretched_bar(1.1, false);
    problem.method = Method::MixedP0;
    problem.material.nu = 0.49;
    let mut sim = Simulation::new(problem, Settings::default()).unwrap();
    sim.run(Stepping::adaptive(1), |_| {}).unwrap();
    assert!(sim.nodal_pressures(sim.state()).is_none());
}
