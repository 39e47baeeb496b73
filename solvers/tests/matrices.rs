//! The sparse matrices a user asks for (`Simulation::matrices`) are the ones Newton builds:
//! equal to the dense system of `Linearizer::newton_system` (itself checked against finite
//! differences of the residual in the validation crate), symmetric, of the stated shapes.

use crate::common;

use isochor_solvers::sprs::CsMat;
use isochor_solvers::{Matrices, Method, Settings, Simulation, Stepping};
use nalgebra::DMatrix;

fn dense(a: &CsMat<f64>) -> DMatrix<f64> {
    let mut d = DMatrix::zeros(a.rows(), a.cols());
    for (v, (r, c)) in a {
        d[(r, c)] += v;
    }
    d
}

/// Runs one load step of the small cantilever and returns the matrices at the final state
/// with the dense Newton matrix there.
fn at_final_state(method: Method, nu: f64) -> (Matrices, DMatrix<f64>, usize) {
    let problem = common::beam(
        [2, 1, 1],
        method,
        nu,
        isochor_solvers::Vec3::new(0.2, 0.05, 0.05),
    );
    let mut sim = Simulation::new(problem, Settings::default()).unwrap();
    let stepping = Stepping::quasi_static(1);
    let state = sim.run(stepping, |_| {}).unwrap().final_state;
    let matrices = sim.matrices(&state).unwrap();
    let newton = sim
        .linearizer(stepping, 1)
        .unwrap()
        .newton_system(&state)
        .unwrap();
    (matrices, newton.matrix, state.multipliers.len())
}

#[test]
fn kkt_matrix_is_the_newton_matrix() {
    let (m, newton, rows) = at_final_state(Method::MixedP1, 0.45);
    let n = m.free.len();
    assert!(rows > 0);
    assert_eq!(m.kkt.shape(), (n + rows, n + rows));
    assert_eq!(m.stiffness.shape(), (n, n));
    let kkt = dense(&m.kkt);
    let scale = newton.amax();
    assert!(
        (&kkt - &newton).amax() <= 1e-14 * scale,
        "KKT differs from Newton's"
    );
    assert!(
        (&kkt - kkt.transpose()).amax() <= 1e-14 * scale,
        "KKT is not symmetric"
    );
    let stiffness = dense(&m.stiffness);
    assert_eq!(stiffness, kkt.view((0, 0), (n, n)));
    let g = dense(m.jacobian.as_ref().expect("mixed-p1 has G"));
    assert_eq!(g.shape(), (rows, n));
    assert_eq!(g, kkt.view((n, 0), (rows, n)));
    let c = dense(m.compliance.as_ref().expect("mixed-p1 has C"));
    assert_eq!(-c, kkt.view((n, n), (rows, rows)));
    assert!(
        m.compliance.as_ref().unwrap().nnz() > 0,
        "C != 0 at nu = 0.45"
    );
}

#[test]
fn minimization_methods_give_the_stiffness_alone() {
    let (m, newton, rows) = at_final_state(Method::Standard, 0.45);
    assert_eq!(rows, 0);
    assert!(m.jacobian.is_none() && m.compliance.is_none());
    assert_eq!(m.kkt, m.stiffness);
    let k = dense(&m.stiffness);
    assert!((&k - &newton).amax() <= 1e-14 * newton.amax());
}

#[test]
fn matrices_are_written_as_matrix_market() {
    let (m, _, _) = at_final_state(Method::MixedP1, 0.5);
    let folder = std::env::temp_dir().join(format!("isochor-mtx-{}", std::process::id()));
    std::fs::create_dir_all(&folder).unwrap();
    m.write_matrix_market(&folder).unwrap();
    for name in ["stiffness", "kkt", "jacobian", "compliance"] {
        let path = folder.join(format!("{name}.mtx"));
        let read: CsMat<f64> = isochor_solvers::sprs::io::read_matrix_market(&path)
            .unwrap()
            .to_csr();
        let expected = match name {
            "stiffness" => &m.stiffness,
            "kkt" => &m.kkt,
            "jacobian" => m.jacobian.as_ref().unwrap(),
            _ => m.compliance.as_ref().unwrap(),
        };
        assert_eq!(read.shape(), expected.shape(), "{name}");
        assert!(
            (dense(&read) - dense(expected)).amax() <= 1e-12 * dense(expected).amax().max(1.0),
            "{name}"
        );
    }
    std::fs::remove_dir_all(&folder).unwrap();
}
