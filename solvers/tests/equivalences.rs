//! Exact equivalences between methods, to solver tolerance on the same mesh: they catch
//! sign and scaling errors that plausible-looking results hide.

use crate::common;

use common::{cantilever, relative_difference};
use isochor_constraints::NodalCompliance;
use isochor_mesh::Vec3;
use isochor_solvers::{
    Kappa, MaterialModel, Method, Problem, Region, Settings, Simulation, Stepping,
};

fn solve(problem: Problem) -> Vec<Vec3> {
    let method = problem.method;
    let mut sim = Simulation::new(problem, Settings::default()).unwrap();
    let summary = sim
        .run(Stepping::quasi_static(2), |_| {})
        .unwrap_or_else(|e| panic!("{method}: {e}"));
    summary.final_state.positions
}

fn pair(mut a: Problem, mut b: Problem, configure: impl Fn(&mut Problem)) -> f64 {
    configure(&mut a);
    configure(&mut b);
    let rest = a.mesh.nodes().to_vec();
    relative_difference(&rest, &solve(a), &solve(b))
}

/// Element (P0) constraints with the logarithmic measure and compliance `V_e / lambda`,
/// condensed, are `lambda/2 (log J)^2`: with the distortional energy of eq. 32 that is the
/// standard neo-Hookean energy of eq. 6.
#[test]
fn mixed_p0_log_with_kappa_lambda_is_standard_neo_hookean() {
    let d = pair(
        cantilever(2, Method::MixedP0Log, 0.45),
        cantilever(2, Method::Standard, 0.45),
        |p| p.material.kappa = Kappa::Lambda,
    );
    assert!(d < 1e-8, "relative difference {d:e}");
}

/// The same for the isochoric models: element log constraints with compliance `V_e / kappa`
/// (the bulk modulus) condense to `kappa/2 (log J)^2`, the volumetric term `standard` adds to
/// an uncoupled Mooney-Rivlin, Yeoh or Ogden energy.
#[test]
fn mixed_p0_log_is_standard_for_the_isochoric_models() {
    let models = [
        MaterialModel::MooneyRivlin {
            c10: 30e3,
            c01: 10e3,
        },
        MaterialModel::Yeoh {
            c10: 40e3,
            c20: -2e3,
            c30: 500.0,
        },
        MaterialModel::Ogden {
            terms: vec![(50e3, 1.5), (-5e3, -2.0)],
        },
    ];
    for model in models {
        let name = model.name();
        let d = pair(
            cantilever(2, Method::MixedP0Log, 0.45),
            cantilever(2, Method::Standard, 0.45),
            |p| {
                p.material = p.material.clone().with_model(model.clone()).unwrap();
                p.material.kappa = Kappa::Bulk;
            },
        );
        assert!(d < 1e-8, "{name}: relative difference {d:e}");
    }
}

/// Static condensation, dual ascent and the nodal mixed system agree on a body of two
/// materials too (per-element compliances, lumped alike).
#[test]
fn condensed_and_dual_equal_mixed_p1_with_two_materials() {
    let two = |p: &mut Problem| {
        p.material.nodal_compliance = NodalCompliance::Lumped;
        let stiff = p.material.clone().with_model(MaterialModel::MooneyRivlin {
            c10: 400e3,
            c01: 100e3,
        });
        let half = p.mesh.num_elements() / 2;
        p.regions = vec![Region {
            name: "stiff half".into(),
            elements: (0..half).collect(),
            material: stiff.unwrap(),
        }];
    };
    for method in [Method::Condensed, Method::Dual] {
        let d = pair(
            cantilever(2, method, 0.45),
            cantilever(2, Method::MixedP1, 0.45),
            two,
        );
        assert!(d < 1e-7, "{method}: relative difference {d:e}");
    }
}

/// Static condensation (eq. 37) solves the same equations as the nodal mixed system with
/// the same lumped compliance.
#[test]
fn condensed_equals_mixed_p1_with_lumped_compliance() {
    let d = pair(
        cantilever(2, Method::Condensed, 0.45),
        cantilever(2, Method::MixedP1, 0.45),
        |p| p.material.nodal_compliance = NodalCompliance::Lumped,
    );
    assert!(d < 1e-8, "relative difference {d:e}");
}

/// Dual ascent, converged, reaches the saddle point of the nodal mixed system.
#[test]
fn dual_equals_mixed_p1() {
    let d = pair(
        cantilever(2, Method::Dual, 0.45),
        cantilever(2, Method::MixedP1, 0.45),
        |p| p.material.nodal_compliance = NodalCompliance::Lumped,
    );
    assert!(d < 1e-7, "relative difference {d:e}");
}
