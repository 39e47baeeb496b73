//! Physical checks of the solvers: a nonlinear patch test, the linear (Euler-Bernoulli)
//! limit, incompressibility at nu = 0.5, and the discrete free fall of implicit Euler.

use crate::common;

use common::{beam, cantilever, end_deflection, plane};
use isochor_energies::Lame;
use isochor_mesh::{generate::box_grid, Vec3};
use isochor_solvers::{
    Dirichlet, Load, Material, Method, Motion, Problem, Settings, Simulation, Stepping,
};

/// Uniaxial dead traction on a box: linear tets reproduce the homogeneous state
/// `F = diag(s, t, t)` whose neo-Hookean stress satisfies `P_xx = T`, `P_yy = P_zz = 0`.
#[test]
fn patch_test_reproduces_the_analytic_uniaxial_neo_hookean_state() {
    let (length, traction) = (1.0, 2.0e4);
    let mesh = box_grid(Vec3::zeros(), Vec3::repeat(length), [3, 3, 3]).unwrap();
    let x0 = plane(&mesh, 0, 0.0);
    let corner = |y: f64, z: f64| {
        (0..mesh.num_vertices())
            .find(|&v| (mesh.positions()[v] - Vec3::new(0.0, y, z)).norm() < 1e-12)
            .unwrap()
    };
    let hold = |nodes: Vec<usize>, axes: [bool; 3]| Dirichlet {
        nodes,
        axes,
        motion: Motion::Fixed,
        curve: None,
    };
    let boundary = mesh.boundary().unwrap();
    let end_faces: Vec<[usize; 3]> = boundary
        .triangles()
        .iter()
        .filter(|f| {
            f.iter()
                .all(|&v| (mesh.positions()[v].x - length).abs() < 1e-12)
        })
        .copied()
        .collect();
    let material = Material::from_young_poisson(1e5, 0.3, 1000.0).unwrap();
    let problem = Problem {
        dirichlet: vec![
            hold(x0, [true, false, false]),
            hold(vec![corner(0.0, 0.0)], [true; 3]),
            hold(vec![corner(length, 0.0)], [true, false, true]),
        ],
        loads: vec![Load::Traction {
            faces: end_faces,
            traction: Vec3::new(traction, 0.0, 0.0),
        }
        .into()],
        mesh: mesh.into(),
        method: Method::Standard,
        material: material.clone(),
        regions: Vec::new(),
        zones: None,
        obstacles: Vec::new(),
        cloths: Vec::new(),
    };
    let mut sim = Simulation::new(problem, Settings::default()).unwrap();
    let summary = sim.run(Stepping::quasi_static(3), |_| {}).unwrap();
    let x = &summary.final_state.positions;
    let rest = sim.mesh().nodes();
    // Analytic: P = mu (F - F^-T) + lambda log(J) F^-T with F = diag(s, t, t).
    let Lame { mu, lambda } = material.lame().unwrap();
    let p = |s: f64, t: f64| {
        let j = s * t * t;
        (
            mu * (s - 1.0 / s) + lambda * j.ln() / s,
            mu * (t - 1.0 / t) + lambda * j.ln() / t,
        )
    };
    let (mut s, mut t) = (1.0, 1.0);
    for _ in 0..100 {
        // Newton on (P_xx - T, P_yy) with a finite-difference Jacobian.
        let h = 1e-7;
        let (a, b) = p(s, t);
        let (a_s, b_s) = p(s + h, t);
        let (a_t, b_t) = p(s, t + h);
        let jac =
            nalgebra::Matrix2::new((a_s - a) / h, (a_t - a) / h, (b_s - b) / h, (b_t - b) / h);
        let step = jac
            .lu()
            .solve(&nalgebra::Vector2::new(traction - a, -b))
            .unwrap();
        s += step[0];
        t += step[1];
    }
    for (r, xi) in rest.iter().zip(x) {
        let expected = Vec3::new(s * r.x, t * r.y, t * r.z);
        assert!(
            (xi - expected).norm() < 1e-8 * length,
            "vertex at {r:?}: {xi:?} instead of {expected:?} (s = {s}, t = {t})"
        );
    }
}

/// A slender cantilever (length 20 x height) under a small self-weight, refined, bends as
/// Euler-Bernoulli predicts: `delta = q L^4 / (8 E I)`. Linear tets are stiff in bending, so
/// "refined" means the Richardson extrapolation (second order) of the two finest meshes;
/// the finest mesh itself must already be within 10% and the sequence must increase.
#[test]
fn slender_cantilever_matches_euler_bernoulli() {
    let (length, height, young, rho): (f64, f64, f64, f64) = (1.0, 0.05, 266e3, 1070.0);
    let g = 1e-4;
    let q = rho * g * height * height;
    let expected = q * length.powi(4) / (8.0 * young * height.powi(4) / 12.0);
    let ratios: Vec<f64> = [4, 6, 8]
        .iter()
        .map(|&res| {
            let size = Vec3::new(length, height, height);
            let mut problem = beam([20 * res, res, res], Method::Standard, 0.3, size);
            problem.loads = vec![Load::Gravity(Vec3::new(0.0, -g, 0.0)).into()];
            let mut sim = Simulation::new(problem, Settings::default()).unwrap();
            let summary = sim.run(Stepping::quasi_static(1), |_| {}).unwrap();
            end_deflection(sim.mesh().corners(), &summary.final_state.positions) / expected
        })
        .collect();
    let extrapolated = (64.0 * ratios[2] - 36.0 * ratios[1]) / 28.0;
    println!(
        "deflection / Euler-Bernoulli at res 4, 6, 8: {ratios:?}, extrapolated {extrapolated:.4}"
    );
    assert!(
        ratios.windows(2).all(|w| w[0] < w[1] && w[1] < 1.0),
        "{ratios:?}"
    );
    assert!(ratios[2] > 0.9, "{ratios:?}");
    assert!(
        (extrapolated - 1.0).abs() < 0.05,
        "extrapolated ratio {extrapolated}"
    );
}

/// At nu = 0.5 the nodal constraints have zero compliance; their sum is the total volume
/// change, which therefore vanishes to solver tolerance.
#[test]
fn mixed_p1_keeps_the_volume_at_nu_one_half() {
    let mut sim =
        Simulation::new(cantilever(2, Method::MixedP1, 0.5), Settings::default()).unwrap();
    let summary = sim.run(Stepping::quasi_static(2), |_| {}).unwrap();
    let mesh = sim.mesh();
    let change = mesh.total_volume_at(&summary.final_state.positions) / mesh.rest_volume() - 1.0;
    let deflection = end_deflection(mesh.corners(), &summary.final_state.positions);
    println!("volume change {change:e}, deflection {deflection}");
    assert!(change.abs() < 1e-8, "volume change {change:e}");
    assert!(
        deflection > 0.01,
        "the beam must bend without locking: {deflection}"
    );
}

#[test]
fn condensed_refuses_nu_one_half() {
    let err =
        Simulation::new(cantilever(2, Method::Condensed, 0.5), Settings::default()).unwrap_err();
    assert!(err.to_string().contains("condensed"), "{err}");
}

/// A solve that cannot converge returns an error with the last accepted state and the log.
#[test]
fn non_convergence_is_an_error_that_keeps_the_last_state() {
    let settings = Settings {
        max_iterations: 2,
        ..Settings::default()
    };
    let problem = cantilever(2, Method::Standard, 0.4999);
    let rest = problem.mesh.nodes().to_vec();
    let mut sim = Simulation::new(problem, settings).unwrap();
    let failure = sim.run(Stepping::quasi_static(1), |_| {}).unwrap_err();
    assert_eq!(failure.failed_step, 1);
    assert_eq!(failure.last_state.positions, rest);
    assert_eq!(failure.reports.len(), 1);
    assert_eq!(failure.reports[0].iterations.len(), 2);
    assert!(
        failure.to_string().contains("did not converge"),
        "{failure}"
    );
    assert_eq!(sim.state().positions, rest);
}

/// `accept_unconverged` takes every dynamic step after exactly `max_iterations` Newton
/// iterations (2 here, short of the tolerances for the cantilever swinging under its weight)
/// and reports it as not converged; without it the same steps fail and are cut. It is refused
/// in quasi-static stepping and for `dual`.
#[test]
fn accept_unconverged_takes_a_fixed_iteration_count_in_dynamics_only() {
    let stepping = Stepping::ImplicitEuler {
        dt: 0.016,
        frames: 3,
    };
    for method in [Method::Standard, Method::MixedP1] {
        let fixed = Settings {
            max_iterations: 2,
            accept_unconverged: true,
            ..Settings::default()
        };
        let mut sim = Simulation::new(cantilever(1, method, 0.49), fixed).unwrap();
        let summary = sim.run(stepping, |_| {}).unwrap();
        assert_eq!(summary.reports.len(), 3, "{method}: no step was cut");
        for r in &summary.reports {
            assert_eq!(r.newton_iterations(), 2, "{method}");
            assert!(!r.converged && r.failure.is_none(), "{method}: {r:?}");
        }
        let strict = Settings {
            max_iterations: 2,
            ..Settings::default()
        };
        let mut sim = Simulation::new(cantilever(1, method, 0.49), strict).unwrap();
        let short = match sim.run(stepping, |_| {}) {
            Ok(summary) => summary.cuts() > 0,
            Err(_) => true,
        };
        assert!(short, "{method}: 2 iterations converged without the option");
    }
    let fixed = Settings {
        max_iterations: 3,
        accept_unconverged: true,
        ..Settings::default()
    };
    let mut sim = Simulation::new(cantilever(1, Method::Standard, 0.49), fixed).unwrap();
    let failure = sim.run(Stepping::quasi_static(1), |_| {}).unwrap_err();
    assert!(
        failure.to_string().contains("implicit Euler only"),
        "{failure}"
    );
    let err = Simulation::new(cantilever(1, Method::Dual, 0.49), fixed).unwrap_err();
    assert!(err.to_string().contains("dual"), "{err}");
}

/// Without supports, implicit Euler under gravity gives `x_N = x_0 + h^2 g N (N + 1) / 2`
/// exactly (no deformation, constant acceleration), for every method.
#[test]
fn free_fall_follows_the_discrete_implicit_euler_trajectory() {
    let (dt, frames) = (0.01, 10);
    let g = Vec3::new(0.0, 0.0, -9.81);
    for method in [Method::Standard, Method::MixedP1, Method::Zonal] {
        let mut problem = cantilever(1, method, 0.45);
        problem.dirichlet.clear();
        problem.loads = vec![Load::Gravity(g).into()];
        let rest = problem.mesh.nodes().to_vec();
        let mut sim = Simulation::new(problem, Settings::default()).unwrap();
        let summary = sim
            .run(Stepping::ImplicitEuler { dt, frames }, |_| {})
            .unwrap();
        let n = frames as f64;
        let drop = g * dt * dt * n * (n + 1.0) / 2.0;
        for (r, x) in rest.iter().zip(&summary.final_state.positions) {
            assert!(
                (x - (r + drop)).norm() < 1e-9,
                "{method}: {x:?} vs {:?}",
                r + drop
            );
        }
    }
}

/// The von Mises stress of an isochoric uniaxial stretch `F = diag(s, 1/sqrt(s), 1/sqrt(s))`
/// is `mu (s^2 - 1/s)` for every method (the deviatoric Cauchy stress of the neo-Hookean
/// energies, `mu dev(F F^T)` at `J = 1`; constraint pressures are hydrostatic), on every tet.
#[test]
fn von_mises_stress_of_an_isochoric_stretch() {
    let mesh = box_grid(Vec3::zeros(), Vec3::repeat(1.0), [2, 2, 2]).unwrap();
    let s: f64 = 1.3;
    let f = nalgebra::Matrix3::from_diagonal(&Vec3::new(s, 1.0 / s.sqrt(), 1.0 / s.sqrt()));
    for method in [Method::Standard, Method::MixedP1, Method::Zonal] {
        let material = Material::from_young_poisson(1e5, 0.45, 1000.0).unwrap();
        let problem = Problem {
            mesh: mesh.clone().into(),
            method,
            material: material.clone(),
            regions: Vec::new(),
            zones: None,
            dirichlet: vec![],
            loads: vec![],
            obstacles: vec![],
            cloths: Vec::new(),
        };
        let sim = Simulation::new(problem, Settings::default()).unwrap();
        let mut state = sim.state().clone();
        state.positions = mesh.positions().iter().map(|x| f * x).collect();
        let expected = material.mu * (s * s - 1.0 / s);
        for vm in sim.von_mises(&state) {
            assert!(
                (vm - expected).abs() <= 1e-12 * expected,
                "{method}: {vm} vs {expected}"
            );
        }
    }
}
