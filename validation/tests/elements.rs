//! Validation of the physics on 10-node tets and 6-node faces: the quadrature element kernel of
//! every material, the P0, P1, logarithmic and zonal constraints and the epidermis against
//! central differences and a direct quadrature; the patch test; the quadrature degree of each
//! term; and the 4-node path pinned to its values from before the element layer.
//!
//! The quadrature degree of each term, and why (each claim is a test below):
//!
//! - **Elastic energy, 10-node tets: the 4-point degree-2 rule.** `F` is linear on a straight
//!   element and `Psi(F)` is not a polynomial, so no rule is exact. The degree-2 rule integrates
//!   the small-strain stiffness (`dN_a/dX . C dN_b/dX`, degree 2) exactly, so its rest Hessian
//!   equals the degree-5 rule's; the one-point rule leaves spurious zero-energy modes.
//! - **Constraints: the degree-3 rule for element and zonal rows, the degree-5 rule for nodal
//!   rows** ([`isochor_constraints::exact_rule`]). With the linear measure,
//!   `W_q (J_q - 1) c(xi_q) = w_q (det(dx/dxi) - det(dX/dxi)) c(xi_q)` is a polynomial of
//!   degree 3 (`c = 1`) or 4 (`c = L_j`) in `xi` on straight and curved elements, so the
//!   8-point degree-3 rule integrates the P0 rows and the 15-point degree-5 rule the P1 rows
//!   exactly (checked against a composite rule on 8 sub-tets), and the rules one degree lower
//!   do not; zone volumes and the total volume change are then exact. The logarithmic measure
//!   is not a polynomial and uses the same points.
//! - **Epidermis, 6-node faces: the 3-point degree-2 rule.** At rest `U'(1) = 0`, so the
//!   Hessian is `lambda_e U''(1) ds/dx ds/dx^T / S`, with `ds/dx` linear on a flat face: degree
//!   2, integrated exactly (equal to the degree-4 rule's).
//! - **Patch test.** Under `x = A X`, `F = A` at every point and the internal force of node `a`
//!   is `P(A) integral dN_a/dX dV`, zero at interior nodes if the rule integrates
//!   `dN_a/dX det(dX/dxi) = adj(dX/dxi)^T dN_a/dxi` exactly: degree 1 on straight elements
//!   (any rule), degree 3 on curved ones (the degree-5 rule).

use isochor_constraints::{
    exact_rule, Compliance, ConstraintSet, Measure, NodalCompliance, NodalConstraints,
    PerElementConstraints, RowShape, ZonalConstraints,
};
use isochor_energies::kernel::{self, RestPoints};
use isochor_energies::triangle::{self, area_element, RestFacePoints};
use isochor_energies::{
    constrained_neo_hookean, quadratic_neo_hookean, stable_neo_hookean, standard_neo_hookean, tet,
    BonetWood, DistortionalNeoHookean, DistortionalStableNeoHookean, Epidermis, FbarNeoHookean,
    Hyperelastic, Lame, Mooney, MooneyRivlin, Ogden, StableNeoHookean, Yeoh,
};
use isochor_mesh::element::{
    deformation_gradient, RestGeometry, TetElement, TetQuadrature, TriElement, TriQuadrature,
};
use isochor_mesh::{generate::box_grid, ElementMesh, TetMesh, Vec3, Zones};
use isochor_validation::constraint_checks::{self, flatten, jacobian, unflatten, values};
use isochor_validation::fd::{self, relative_error, relative_error_vec};
use isochor_validation::pinned::{assert_pinned, Run, Tolerance};
use isochor_validation::strategies::{
    deform_nodes, deformed_box, material_params as params, max_edge, near_identity, quadratic,
    rest_tet10, rest_triangle, two_tets, with_determinant, DeformedElements,
    MaterialParams as Params,
};
use nalgebra::{DMatrix, DVector, Matrix3, SymmetricEigen, Vector2, Vector3};
use proptest::prelude::*;
use proptest::test_runner::TestCaseError;
use std::collections::BTreeMap;
use std::sync::Mutex;

/// Finite-difference agreement required of every derivative (relative, max norm).
const TOLERANCE: f64 = 1e-6;

/// The largest error seen per check, printed when it grows (`--nocapture` shows the table).
static WORST: Mutex<BTreeMap<String, f64>> = Mutex::new(BTreeMap::new());

fn record(name: &str, error: f64) {
    let mut worst = WORST.lock().unwrap_or_else(|p| p.into_inner());
    let entry = worst.entry(name.to_string()).or_insert(0.0);
    if error > *entry {
        *entry = error;
        eprintln!("largest error so far: {name}: {error:.2e}");
    }
}

// ---------------------------------------------------------------------------------------------
// The quadrature element kernel on 10-node tets, every material

/// Every material of the energy layer, the F-bar energy with its C2 extension and the
/// constrained neo-Hookean included.
fn materials(p: &Params) -> Vec<Box<dyn Hyperelastic>> {
    let lame = Lame::new(p.mu, p.lambda).expect("Lame parameters");
    let (mr, yeoh) = (p.mooney_rivlin(), p.yeoh());
    vec![
        Box::new(Mooney::new(p.mu).expect("Mooney")),
        Box::new(DistortionalNeoHookean::new(p.mu).expect("distortional")),
        Box::new(BonetWood::new(p.mu).expect("Bonet-Wood")),
        Box::new(stable_neo_hookean(lame).expect("stable")),
        Box::new(FbarNeoHookean::new(p.mu, p.epsilon).expect("F-bar")),
        Box::new(DistortionalStableNeoHookean::new(p.mu).expect("distortional stable")),
        Box::new(MooneyRivlin::new(mr.0, mr.1).expect("Mooney-Rivlin")),
        Box::new(Yeoh::new(yeoh.0, yeoh.1, yeoh.2).expect("Yeoh")),
        Box::new(Ogden::new(&p.ogden()).expect("Ogden")),
        Box::new(standard_neo_hookean(lame).expect("standard")),
        Box::new(quadratic_neo_hookean(lame).expect("quadratic")),
        Box::new(constrained_neo_hookean(p.mu, p.lambda, p.beta, p.epsilon).expect("constrained")),
    ]
}

/// Any tabulated rule.
fn rule() -> impl Strategy<Value = TetQuadrature> {
    prop_oneof![
        Just(TetQuadrature::Degree1),
        Just(TetQuadrature::Degree2),
        Just(TetQuadrature::Degree5)
    ]
}

/// A straight or curved 10-node tet deformed by `F_0` of [`with_determinant`] and up to
/// `noise` times its deformed size per node, with every volume ratio passing `accept`.
fn tet10(
    (j_min, j_max, inverted): (f64, f64, bool),
    noise: f64,
    accept: fn(f64) -> bool,
) -> impl Strategy<Value = DeformedElements> {
    prop_oneof![rest_tet10(0.0), rest_tet10(0.1)].prop_flat_map(move |mesh| {
        deform_nodes(
            mesh,
            with_determinant(j_min, j_max, inverted),
            noise,
            accept,
        )
    })
}

/// The rest data of element `e` for the kernel.
fn rest_points(geometry: &RestGeometry, e: usize) -> RestPoints<'_> {
    RestPoints {
        weights: geometry.element_weights(e),
        gradients: geometry.element_gradients(e),
    }
}

/// The kernel of `m` on the one element of `d` with `rule`: the energy against a direct sum
/// `sum_q W_q Psi(F_q)`, the gradient against central differences of the energy and the Hessian
/// against central differences of the gradient (floors `mu V / l` and `mu V / l^2`), exact
/// symmetry, translations in the Hessian's kernel, and the energy-only and gradient-only
/// paths against the full one. Where `Psi` is undefined at a point, an error.
fn check_kernel(
    m: &dyn Hyperelastic,
    d: &DeformedElements,
    rule: TetQuadrature,
    mu: f64,
    label: &str,
) -> Result<(), TestCaseError> {
    let geometry = d.mesh.rest_geometry(rule).expect("rest geometry");
    let rest = rest_points(&geometry, 0);
    // The element's own positions, in its local node order.
    let x: Vec<Vec3> = d.mesh.element(0).iter().map(|&i| d.x[i]).collect();
    let nodes: Vec<usize> = (0..x.len()).collect();
    let nodes = nodes.as_slice();
    let n = 3 * nodes.len();
    let (mut g, mut h) = (vec![0.0; n], vec![0.0; n * n]);
    let f_at = |x: &[Vec3], q: usize| deformation_gradient(x, nodes, geometry.gradients(0, q));
    let defined = (0..rule.num_points()).all(|q| m.is_defined_at(f_at(&x, q).determinant()));
    let result = kernel::evaluate(m, &x, nodes, rest, Some(&mut g), Some(&mut h));
    if !defined {
        prop_assert!(result.is_err(), "{}: no error outside the domain", m.name());
        return Ok(());
    }
    let energy = result.map_err(|e| TestCaseError::fail(e.to_string()))?;
    let direct: f64 = (0..rule.num_points())
        .map(|q| geometry.weight(0, q) * m.energy_density(&f_at(&x, q)).expect("defined"))
        .sum();
    let volume = geometry.volume();
    let l = max_edge(&std::array::from_fn::<_, 4, _>(|a| {
        d.mesh.nodes()[d.mesh.element(0)[a]]
    }));
    let scale = mu * volume;
    prop_assert!(
        (energy - direct).abs() <= 1e-13 * energy.abs().max(scale),
        "{}: energy {energy} vs direct quadrature {direct}",
        m.name()
    );
    let energy_of = |v: &DVector<f64>| {
        kernel::evaluate(m, &unflatten(v), nodes, rest, None, None).expect("defined")
    };
    let gradient_of = |v: &DVector<f64>| {
        let mut g = vec![0.0; n];
        kernel::evaluate(m, &unflatten(v), nodes, rest, Some(&mut g), None).expect("defined");
        DVector::from_vec(g)
    };
    let xv = flatten(&x);
    prop_assert_eq!(energy_of(&xv), energy);
    let gv = DVector::from_vec(g);
    prop_assert_eq!(&gradient_of(&xv), &gv);

    // The step follows the smallest deformed length, l times the smallest singular value of F:
    // near-singular and strongly stretched elements are thin somewhere.
    let thinnest = (0..rule.num_points())
        .map(|q| f_at(&x, q).svd(false, false).singular_values.min())
        .fold(f64::INFINITY, f64::min);
    let step = fd::STEP * l * thinnest;
    let err = relative_error_vec(&gv, &fd::gradient(energy_of, &xv, step), scale / l);
    record(&format!("tet10 gradient, {label}, {}", m.name()), err);
    prop_assert!(
        err < TOLERANCE,
        "{}: gradient, relative error {err:e}",
        m.name()
    );
    let hm = DMatrix::from_vec(n, n, h);
    let err = relative_error(&hm, &fd::jacobian(gradient_of, &xv, step), scale / (l * l));
    record(&format!("tet10 Hessian, {label}, {}", m.name()), err);
    prop_assert!(
        err < TOLERANCE,
        "{}: Hessian, relative error {err:e}",
        m.name()
    );
    prop_assert_eq!(&hm, &hm.transpose());
    let shift = DVector::from_fn(n, |i, _| if i % 3 == 1 { 1.0 } else { 0.0 });
    prop_assert!((&hm * shift).amax() <= 1e-12 * hm.amax().max(scale / (l * l)));
    Ok(())
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    /// `det F_0` in `[0.05, 20]`: every material, straight and curved elements, every rule.
    #[test]
    fn tet10_kernel_matches_differences(
        p in params(),
        d in tet10((0.05, 20.0, false), 0.05, |j| j >= 0.02),
        rule in rule(),
    ) {
        for m in materials(&p) {
            check_kernel(m.as_ref(), &d, rule, p.mu, "regular")?;
        }
    }

    /// `det F_0` in `[0.003, 0.1]` with 1% noise (so that `J` is nearly uniform and the
    /// differences resolve it): the F-bar energy's C2 extension below `epsilon`, and the
    /// log-based energies near their singularity.
    #[test]
    fn tet10_kernel_near_singular(
        p in params(),
        d in tet10((0.003, 0.1, false), 0.01, |j| j >= 1e-3),
        rule in rule(),
    ) {
        for m in materials(&p) {
            check_kernel(m.as_ref(), &d, rule, p.mu, "near-singular")?;
        }
    }

    /// Inverted elements: the F-bar energy and the constrained neo-Hookean (defined for every
    /// `J`) match differences; the others refuse with an error.
    #[test]
    fn tet10_kernel_inverted(
        p in params(),
        d in tet10((0.05, 2.0, true), 0.05, |j| j <= -0.02),
        rule in rule(),
    ) {
        for m in materials(&p) {
            check_kernel(m.as_ref(), &d, rule, p.mu, "inverted")?;
        }
    }
}

/// The eigenvalues of the rest Hessian of one 10-node tet with `rule`.
fn rest_stiffness(mesh: &ElementMesh, rule: TetQuadrature, m: &dyn Hyperelastic) -> DMatrix<f64> {
    let geometry = mesh.rest_geometry(rule).expect("rest geometry");
    let mut h = vec![0.0; 900];
    kernel::evaluate(
        m,
        mesh.nodes(),
        mesh.element(0),
        rest_points(&geometry, 0),
        None,
        Some(&mut h),
    )
    .expect("defined at rest");
    DMatrix::from_vec(30, 30, h)
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(16))]

    /// The elastic rule: on a straight 10-node tet the degree-2 rule's rest stiffness equals the
    /// degree-5 rule's (the small-strain integrand has degree 2); it has exactly the 6 rigid
    /// zero modes, the one-point rule more.
    #[test]
    fn degree_two_integrates_the_small_strain_stiffness(mesh in rest_tet10(0.0), p in params()) {
        let m = standard_neo_hookean(Lame::new(p.mu, p.lambda).expect("Lame")).expect("material");
        let k2 = rest_stiffness(&mesh, TetQuadrature::Degree2, &m);
        let k5 = rest_stiffness(&mesh, TetQuadrature::Degree5, &m);
        let err = relative_error(&k2, &k5, 0.0);
        record("rest stiffness, degree 2 vs degree 5 (straight)", err);
        prop_assert!(err < 1e-12, "degree 2 vs 5: {err:e}");
        let zero_modes = |k: DMatrix<f64>| {
            let e = SymmetricEigen::new(k).eigenvalues;
            let top = e.amax();
            e.iter().filter(|v| v.abs() < 1e-10 * top).count()
        };
        prop_assert_eq!(zero_modes(k2), 6);
        prop_assert!(zero_modes(rest_stiffness(&mesh, TetQuadrature::Degree1, &m)) > 6);
    }
}

// ---------------------------------------------------------------------------------------------
// Constraints on 10-node tets

/// The corner shape functions `L_j(xi) = (1 - xi - eta - zeta, xi, eta, zeta)`, written out.
fn barycentric(xi: &Vec3) -> [f64; 4] {
    [1.0 - xi.x - xi.y - xi.z, xi.x, xi.y, xi.z]
}

/// `Phi(J)` of a measure, written out.
fn phi(measure: Measure, j: f64) -> f64 {
    match measure {
        Measure::Linear => j - 1.0,
        Measure::Logarithmic => j.ln(),
    }
}

/// `integral_e c Phi(J) dV` of every element by a direct sum over the points of `rule`, with
/// `c = L_j` (four values per element) or `c = 1` (one).
fn direct_integrals(
    d: &DeformedElements,
    rule: TetQuadrature,
    measure: Measure,
    corners: bool,
) -> Vec<Vec<f64>> {
    let geometry = d.mesh.rest_geometry(rule).expect("rest geometry");
    (0..d.mesh.num_elements())
        .map(|e| {
            let mut rows = vec![0.0; if corners { 4 } else { 1 }];
            for (q, xi) in rule.points().iter().enumerate() {
                let f = deformation_gradient(&d.x, d.mesh.element(e), geometry.gradients(e, q));
                let m = geometry.weight(e, q) * phi(measure, f.determinant());
                if corners {
                    for (row, l) in rows.iter_mut().zip(barycentric(xi)) {
                        *row += l * m;
                    }
                } else {
                    rows[0] += m;
                }
            }
            rows
        })
        .collect()
}

/// The P1 rows `phi_j` from per-element corner integrals.
fn nodal_rows(mesh: &ElementMesh, integrals: &[Vec<f64>]) -> DVector<f64> {
    let mut phi = DVector::zeros(mesh.num_vertices());
    for (e, rows) in integrals.iter().enumerate() {
        for (&v, m) in mesh.element(e)[..4].iter().zip(rows) {
            phi[v] += m;
        }
    }
    phi
}

/// Overlapping zones: all elements, the first half, every other one.
fn test_zones(n: usize) -> Zones {
    let all: Vec<usize> = (0..n).collect();
    let half = all[..n.div_ceil(2)].to_vec();
    let even = all.iter().copied().filter(|e| e % 2 == 0).collect();
    Zones::from_sets(vec![all, half, even])
}

/// A constraint set and its values by a direct quadrature.
struct Case {
    set: Box<dyn ConstraintSet>,
    reference: DVector<f64>,
}

/// Every constraint type on `d.mesh` with its [`exact_rule`]: P0 and P1 with both measures,
/// and zonal with overlapping zones.
fn all_cases(d: &DeformedElements) -> Vec<Case> {
    let rule = |shape| exact_rule(d.mesh.kind(), shape);
    let mut cases = Vec::new();
    for measure in [Measure::Linear, Measure::Logarithmic] {
        let element_rows = direct_integrals(d, rule(RowShape::One), measure, false);
        cases.push(Case {
            set: Box::new(
                PerElementConstraints::on_elements(&d.mesh, rule(RowShape::One), measure, 10.0)
                    .expect("P0"),
            ),
            reference: DVector::from_iterator(
                element_rows.len(),
                element_rows.iter().map(|r| r[0]),
            ),
        });
        cases.push(Case {
            set: Box::new(
                NodalConstraints::on_elements(
                    &d.mesh,
                    rule(RowShape::Corners),
                    measure,
                    10.0,
                    NodalCompliance::Consistent,
                )
                .expect("P1"),
            ),
            reference: nodal_rows(
                &d.mesh,
                &direct_integrals(d, rule(RowShape::Corners), measure, true),
            ),
        });
    }
    let zones = test_zones(d.mesh.num_elements());
    let element_rows = direct_integrals(d, rule(RowShape::One), Measure::Linear, false);
    cases.push(Case {
        set: Box::new(
            ZonalConstraints::on_elements(&d.mesh, rule(RowShape::One), &zones).expect("zonal"),
        ),
        reference: DVector::from_iterator(
            zones.len(),
            zones
                .iter()
                .map(|z| z.iter().map(|&e| element_rows[e][0]).sum()),
        ),
    });
    cases
}

/// Values against the direct quadrature, `G` and `K_g` against central differences.
fn check_constraints(d: &DeformedElements, p: &[f64], label: &str) -> Result<(), TestCaseError> {
    for case in all_cases(d) {
        let set = case.set.as_ref();
        let name = set.name();
        let phi = values(set, &d.x);
        let err = relative_error_vec(&phi, &case.reference, 1e-12);
        record(&format!("{name} values vs direct quadrature, {label}"), err);
        prop_assert!(err < 1e-12, "{name}: phi vs direct quadrature {err:e}");
        let errors = constraint_checks::derivative_errors(set, &d.x, p, 1.0);
        record(&format!("{name} G, {label}"), errors.jacobian);
        record(&format!("{name} K_g, {label}"), errors.geometric_stiffness);
        prop_assert!(
            errors.jacobian < TOLERANCE,
            "{name}: G {:e}",
            errors.jacobian
        );
        prop_assert!(
            errors.geometric_stiffness < TOLERANCE,
            "{name}: K_g {:e}",
            errors.geometric_stiffness
        );
        prop_assert!(
            errors.asymmetry <= 1e-14,
            "{name}: K_g asymmetry {:e}",
            errors.asymmetry
        );
    }
    Ok(())
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(32))]

    #[test]
    fn constraints_on_two_tet10s(
        d in prop_oneof![
            quadratic(two_tets(0.1, 0.15, 0.3), 0.0, 0.05, 0.2),
            quadratic(two_tets(0.1, 0.15, 0.3), 0.08, 0.05, 0.2),
        ],
        p in proptest::collection::vec(-1.0..1.0f64, 8),
    ) {
        check_constraints(&d, &p, "two tets")?;
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(4))]

    #[test]
    fn constraints_on_a_tet10_box(
        d in quadratic(deformed_box([1, 1, 2], 0.05, 0.3), 0.05, 0.03, 0.2),
        p in proptest::collection::vec(-1.0..1.0f64, 20),
    ) {
        check_constraints(&d, &p, "box")?;
    }
}

/// The sub-tetrahedra of the reference tet split at its edge midpoints (4 corner tets and the
/// central octahedron cut along one diagonal), as corner lists.
fn sub_tets() -> [[Vec3; 4]; 8] {
    let v = [Vec3::zeros(), Vec3::x(), Vec3::y(), Vec3::z()];
    let m = |a: usize, b: usize| 0.5 * (v[a] + v[b]);
    let (m01, m02, m03, m12, m13, m23) = (m(0, 1), m(0, 2), m(0, 3), m(1, 2), m(1, 3), m(2, 3));
    [
        [v[0], m01, m02, m03],
        [m01, v[1], m12, m13],
        [m02, m12, v[2], m23],
        [m03, m13, m23, v[3]],
        [m02, m13, m01, m03],
        [m02, m13, m03, m23],
        [m02, m13, m23, m12],
        [m02, m13, m12, m01],
    ]
}

/// The degree-5 rule on each of the [`sub_tets`]: 120 points, still exact to degree 5, but a
/// different rule (it integrates non-polynomials differently).
fn composite_rule() -> Vec<(Vec3, f64)> {
    let rule = TetQuadrature::Degree5;
    sub_tets()
        .iter()
        .flat_map(|t| {
            let map = Matrix3::from_columns(&[t[1] - t[0], t[2] - t[0], t[3] - t[0]]);
            let det = map.determinant().abs();
            rule.points()
                .iter()
                .zip(rule.weights())
                .map(move |(xi, w)| (t[0] + map * xi, w * det))
        })
        .collect()
}

/// `integral_e (J - 1) L_j dV = integral (det(dx/dxi) - det(dX/dxi)) L_j dxi` of every corner
/// of every element, by the composite rule, from the isoparametric maps alone.
fn composite_corner_integrals(d: &DeformedElements) -> Vec<Vec<f64>> {
    let kind = d.mesh.kind();
    let mut dn = vec![Vec3::zeros(); kind.num_nodes()];
    let mut integrals = vec![vec![0.0; 4]; d.mesh.num_elements()];
    for (xi, w) in composite_rule() {
        kind.shape_gradients(&xi, &mut dn);
        for (e, rows) in integrals.iter_mut().enumerate() {
            let nodes = d.mesh.element(e);
            let change = deformation_gradient(&d.x, nodes, &dn).determinant()
                - deformation_gradient(d.mesh.nodes(), nodes, &dn).determinant();
            for (row, l) in rows.iter_mut().zip(barycentric(&xi)) {
                *row += w * change * l;
            }
        }
    }
    integrals
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(24))]

    /// The constraint rules: [`exact_rule`] integrates the linear P0 rows (degree 3) and P1
    /// rows (degree 5) exactly on straight and curved 10-node tets (equal to the composite
    /// rule), the rules one degree lower do not; zone volumes by quadrature equal the
    /// divergence-theorem volume of the zone's 6-node faces.
    #[test]
    fn exact_rules_integrate_the_linear_measure_exactly(
        d in prop_oneof![
            quadratic(two_tets(0.1, 0.2, 0.3), 0.0, 0.08, 0.2),
            quadratic(two_tets(0.1, 0.2, 0.3), 0.08, 0.08, 0.2),
        ],
    ) {
        let corners = composite_corner_integrals(&d);
        let volume = d.mesh.rest_volume();
        let nodal = |rule| {
            let set = NodalConstraints::on_elements(
                &d.mesh, rule, Measure::Linear, 1.0, NodalCompliance::Lumped,
            )
            .expect("P1");
            values(&set, &d.x)
        };
        let exact = nodal_rows(&d.mesh, &corners);
        let err5 = (nodal(exact_rule(TetElement::Tet10, RowShape::Corners)) - &exact).amax() / volume;
        let err3 = (nodal(TetQuadrature::Degree3) - &exact).amax() / volume;
        record("P1 rows, degree 5 vs composite (relative to V)", err5);
        prop_assert!(err5 < 1e-13, "degree 5: {err5:e}");
        prop_assert!(err3 > 1e-9, "P1 rows: degree 3 is exact here? {err3:e}");

        let element = |rule| {
            let set = PerElementConstraints::on_elements(&d.mesh, rule, Measure::Linear, 1.0)
                .expect("P0");
            values(&set, &d.x)
        };
        let exact = DVector::from_iterator(corners.len(), corners.iter().map(|r| r.iter().sum()));
        let err3 = (element(exact_rule(TetElement::Tet10, RowShape::One)) - &exact).amax() / volume;
        let err2 = (element(TetQuadrature::Degree2) - &exact).amax() / volume;
        record("P0 rows, degree 3 vs composite (relative to V)", err3);
        prop_assert!(err3 < 1e-13, "degree 3: {err3:e}");
        prop_assert!(err2 > 1e-9, "P0 rows: degree 2 is exact here? {err2:e}");

        let zones = test_zones(d.mesh.num_elements());
        let zonal =
            ZonalConstraints::on_elements(&d.mesh, exact_rule(TetElement::Tet10, RowShape::One), &zones)
                .expect("zonal");
        for z in 0..zones.len() {
            let by_points = zonal.zone_volume(z, &d.x).expect("zone volume");
            let by_faces = zonal.zone_boundary_volume(z, &d.x).expect("boundary volume");
            let err = (by_points - by_faces).abs() / by_faces;
            record("zone volume, degree 3 vs 6-node faces", err);
            prop_assert!(err < 1e-13, "zone {z}: {by_points} vs {by_faces}");
        }
    }
}

/// Taylor-Hood P2-P1 on a free box: the nodal Jacobian has full rank (no spurious pressure
/// modes), where P1-P1 on the same corners has 3.
#[test]
fn taylor_hood_jacobian_has_no_spurious_pressure_modes() {
    let corners = box_grid(Vec3::zeros(), Vec3::new(3.0, 2.0, 2.0), [3, 2, 2]).expect("box");
    let rank = |set: &dyn ConstraintSet, x: &[Vec3]| {
        let s = jacobian(set, x).svd(false, false).singular_values;
        let top = s.amax();
        (s.iter().filter(|&&v| v > 1e-10 * top).count(), s.len())
    };
    let quadratic = ElementMesh::quadratic(corners.clone());
    let p2 = NodalConstraints::on_elements(
        &quadratic,
        exact_rule(TetElement::Tet10, RowShape::Corners),
        Measure::Linear,
        f64::INFINITY,
        NodalCompliance::Lumped,
    )
    .expect("P2-P1");
    let p1 = NodalConstraints::new(
        &corners,
        Measure::Linear,
        f64::INFINITY,
        NodalCompliance::Lumped,
    )
    .expect("P1-P1");
    let (r2, n2) = rank(&p2, quadratic.nodes());
    let (r1, n1) = rank(&p1, corners.positions());
    println!("free 3x2x2 box: P2-P1 G rank {r2} of {n2}, P1-P1 G rank {r1} of {n1}");
    assert_eq!(r2, n2);
    assert_eq!(r1, n1 - 3);
}

// ---------------------------------------------------------------------------------------------
// The patch test

/// A 2x2x2-cell box of 10-node tets: straight, or with every mid-edge node (interior ones
/// included) moved by a deterministic offset of up to 6% of a cell.
fn patch_mesh(curved: bool) -> ElementMesh {
    let corners = box_grid(Vec3::zeros(), Vec3::repeat(2.0), [2, 2, 2]).expect("box");
    let straight = ElementMesh::quadratic(corners);
    if !curved {
        return straight;
    }
    let nv = straight.num_vertices();
    let wobble =
        |i: usize, k: usize| (((i * 7919 + k * 104_729) % 1009) as f64 / 1009.0 - 0.5) * 0.12;
    let nodes = straight
        .nodes()
        .iter()
        .enumerate()
        .map(|(i, p)| {
            if i < nv {
                *p
            } else {
                p + Vec3::new(wobble(i, 0), wobble(i, 1), wobble(i, 2))
            }
        })
        .collect();
    ElementMesh::from_nodes(TetElement::Tet10, nodes, straight.connectivity().to_vec())
        .expect("curved box")
}

/// The assembled internal forces `sum_e dE_e/dx` of `mesh` at `x` with `rule`.
fn internal_forces(
    mesh: &ElementMesh,
    x: &[Vec3],
    rule: TetQuadrature,
    m: &dyn Hyperelastic,
) -> Vec<Vec3> {
    let geometry = mesh.rest_geometry(rule).expect("rest geometry");
    let mut forces = vec![Vec3::zeros(); mesh.num_nodes()];
    let mut g = vec![0.0; 30];
    for e in 0..mesh.num_elements() {
        let nodes = mesh.element(e);
        kernel::evaluate(m, x, nodes, rest_points(&geometry, e), Some(&mut g), None)
            .expect("defined");
        for (&i, ge) in nodes.iter().zip(g.chunks_exact(3)) {
            forces[i] += Vec3::from_column_slice(ge);
        }
    }
    forces
}

/// The largest interior and boundary force under `x = A X`.
fn patch_residual(
    mesh: &ElementMesh,
    a: &Matrix3<f64>,
    rule: TetQuadrature,
    m: &dyn Hyperelastic,
) -> (f64, f64) {
    let x: Vec<Vec3> = mesh
        .nodes()
        .iter()
        .map(|p| a * p + Vec3::new(0.3, -0.1, 0.2))
        .collect();
    let forces = internal_forces(mesh, &x, rule, m);
    let boundary = mesh.boundary().expect("boundary").nodes();
    let (mut interior, mut outer) = (0.0f64, 0.0f64);
    for (i, f) in forces.iter().enumerate() {
        if boundary.binary_search(&i).is_ok() {
            outer = outer.max(f.amax());
        } else {
            interior = interior.max(f.amax());
        }
    }
    (interior, outer)
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(8))]

    /// Under `x = A X` the interior nodal forces vanish: on straight elements with the
    /// elastic rule (degree 2), on curved ones with the degree-5 rule; the constraint values
    /// of an isochoric `A` vanish for every set.
    #[test]
    fn patch_test(a in near_identity(0.3), p in params()) {
        let lame = Lame::new(p.mu, p.lambda).expect("Lame");
        let standard = standard_neo_hookean(lame).expect("material");
        let constrained = constrained_neo_hookean(p.mu, p.lambda, p.beta, p.epsilon).expect("material");
        let materials: [&dyn Hyperelastic; 2] = [&standard, &constrained];
        for (curved, rule) in [(false, TetQuadrature::Degree2), (true, TetQuadrature::Degree5)] {
            let mesh = patch_mesh(curved);
            for m in materials {
                let (interior, boundary) = patch_residual(&mesh, &a, rule, m);
                let label = if curved { "curved, degree 5" } else { "straight, degree 2" };
                record(&format!("patch test interior force / boundary force, {label}"), interior / boundary);
                prop_assert!(interior <= 1e-12 * boundary, "{label}: {interior:e} vs {boundary:e}");
            }
            // Isochoric: A / det(A)^(1/3).
            let iso = a / a.determinant().cbrt();
            let x: Vec<Vec3> = mesh.nodes().iter().map(|q| iso * q).collect();
            let d = DeformedElements { mesh: mesh.clone(), x };
            for case in all_cases(&d) {
                let phi = values(case.set.as_ref(), &d.x);
                let err = phi.amax() / mesh.rest_volume();
                record("isochoric patch, constraint values / V", err);
                prop_assert!(err < 1e-12, "{}: {err:e}", case.set.name());
            }
        }
    }
}

/// On curved elements the elastic rule (degree 2) does not integrate `adj(dX/dxi)^T dN_a/dxi`
/// (degree 3) exactly: the patch test leaves a residual, which the degree-5 rule removes.
#[test]
fn degree_two_patch_residual_on_curved_elements() {
    let mesh = patch_mesh(true);
    let m = standard_neo_hookean(Lame::new(1.0, 10.0).expect("Lame")).expect("material");
    let a = Matrix3::new(1.1, 0.1, 0.0, -0.05, 0.95, 0.1, 0.0, 0.02, 1.05);
    let (r2, b2) = patch_residual(&mesh, &a, TetQuadrature::Degree2, &m);
    let (r5, b5) = patch_residual(&mesh, &a, TetQuadrature::Degree5, &m);
    println!(
        "curved patch: interior force / boundary force {:.2e} with degree 2, {:.2e} with degree 5",
        r2 / b2,
        r5 / b5
    );
    assert!(r2 > 1e-6 * b2 && r5 < 1e-12 * b5);
}

// ---------------------------------------------------------------------------------------------
// The epidermis on 6-node faces

/// A rest 6-node face: a [`rest_triangle`] with its mid-edge nodes moved by up to 10% of its
/// size (out of plane too), kept while its area element stays within a factor 3.
fn rest_tri6(curvature: f64) -> impl Strategy<Value = Vec<Vec3>> {
    (rest_triangle(), proptest::array::uniform9(-1.0..1.0f64)).prop_filter_map(
        "curved face must stay well shaped",
        move |(corners, d)| {
            let l = max_edge(&corners);
            let mut nodes = corners.to_vec();
            for (k, [a, b]) in [[0, 1], [1, 2], [2, 0]].iter().enumerate() {
                let offset = Vec3::new(d[3 * k], d[3 * k + 1], d[3 * k + 2]) * (curvature * l);
                nodes.push(0.5 * (corners[*a] + corners[*b]) + offset);
            }
            let (_, areas, _) = face_points(&nodes, TriQuadrature::Degree4);
            let (lo, hi) = areas.iter().fold((f64::INFINITY, 0.0f64), |(lo, hi), &s| {
                (lo.min(s), hi.max(s))
            });
            (lo >= hi / 3.0).then_some(nodes)
        },
    )
}

/// The rest data of a 6-node face with `rule`: weights, rest area elements, reference
/// gradients.
fn face_points(rest: &[Vec3], rule: TriQuadrature) -> (Vec<f64>, Vec<f64>, Vec<Vector2<f64>>) {
    let kind = TriElement::Tri6;
    let mut gradients = vec![Vector2::zeros(); 6 * rule.num_points()];
    for (xi, g) in rule.points().iter().zip(gradients.chunks_exact_mut(6)) {
        kind.shape_gradients(xi, g);
    }
    let areas = gradients
        .chunks_exact(6)
        .map(|g| area_element(rest, &[0, 1, 2, 3, 4, 5], g))
        .collect();
    (rule.weights().to_vec(), areas, gradients)
}

fn deformed_tri6() -> impl Strategy<Value = (Vec<Vec3>, Vec<Vec3>)> {
    (
        prop_oneof![rest_tri6(0.0), rest_tri6(0.1)],
        near_identity(0.5),
        proptest::array::uniform18(-0.1..0.1f64),
    )
        .prop_map(|(rest, f0, noise)| {
            let l = max_edge(&[rest[0], rest[1], rest[2]]);
            let x = rest
                .iter()
                .zip(noise.chunks_exact(3))
                .map(|(p, d)| f0 * p + Vec3::from_column_slice(d) * l)
                .collect();
            (rest, x)
        })
}

/// The epidermis on a 6-node face against central differences, and its energy against a
/// direct sum `sum_q w_q S_q Psi_e(s_q / S_q)`.
fn check_epidermis(
    skin: &Epidermis,
    rest: &[Vec3],
    x: &[Vec3],
    rule: TriQuadrature,
) -> Result<(), TestCaseError> {
    let (weights, areas, gradients) = face_points(rest, rule);
    let points = RestFacePoints {
        weights: &weights,
        areas: &areas,
        gradients: &gradients,
    };
    let nodes = [0, 1, 2, 3, 4, 5];
    let (mut g, mut h) = (vec![0.0; 18], vec![0.0; 324]);
    let energy = skin.evaluate(x, &nodes, points, Some(&mut g), Some(&mut h));
    let direct: f64 = gradients
        .chunks_exact(6)
        .zip(weights.iter().zip(&areas))
        .map(|(gq, (w, s))| w * s * skin.energy_density(area_element(x, &nodes, gq) / s))
        .sum();
    let area: f64 = weights.iter().zip(&areas).map(|(w, s)| w * s).sum();
    let l = max_edge(&[rest[0], rest[1], rest[2]]);
    let scale = skin.lambda() * area;
    prop_assert!((energy - direct).abs() <= 1e-13 * energy.abs().max(scale));
    let energy_of = |v: &DVector<f64>| skin.evaluate(&unflatten(v), &nodes, points, None, None);
    let gradient_of = |v: &DVector<f64>| {
        let mut g = vec![0.0; 18];
        skin.evaluate(&unflatten(v), &nodes, points, Some(&mut g), None);
        DVector::from_vec(g)
    };
    let xv = flatten(x);
    let step = fd::STEP * l;
    let gv = DVector::from_vec(g);
    let err = relative_error_vec(&gv, &fd::gradient(energy_of, &xv, step), scale / l);
    record(&format!("tri6 epidermis gradient, {rule:?}"), err);
    prop_assert!(err < TOLERANCE, "gradient {err:e}");
    let hm = DMatrix::from_vec(18, 18, h);
    let err = relative_error(&hm, &fd::jacobian(gradient_of, &xv, step), scale / (l * l));
    record(&format!("tri6 epidermis Hessian, {rule:?}"), err);
    prop_assert!(err < TOLERANCE, "Hessian {err:e}");
    prop_assert_eq!(&hm, &hm.transpose());
    Ok(())
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(48))]

    #[test]
    fn tri6_epidermis_matches_differences(
        (rest, x) in deformed_tri6(),
        lambda_e in 0.1..100.0f64,
        gamma in 0.0..10.0f64,
        rule in prop_oneof![Just(TriQuadrature::Degree2), Just(TriQuadrature::Degree4)],
    ) {
        let skin = Epidermis::new(lambda_e, gamma).expect("skin");
        check_epidermis(&skin, &rest, &x, rule)?;
    }

    /// The epidermis rule: on a flat 6-node face the degree-2 rule's rest Hessian equals the
    /// degree-4 rule's.
    #[test]
    fn degree_two_integrates_the_rest_epidermis(rest in rest_tri6(0.0), gamma in 0.0..10.0f64) {
        let skin = Epidermis::new(3.0, gamma).expect("skin");
        let hessian = |rule| {
            let (weights, areas, gradients) = face_points(&rest, rule);
            let points = RestFacePoints { weights: &weights, areas: &areas, gradients: &gradients };
            let mut h = vec![0.0; 324];
            skin.evaluate(&rest, &[0, 1, 2, 3, 4, 5], points, None, Some(&mut h));
            DMatrix::from_vec(18, 18, h)
        };
        let err = relative_error(&hessian(TriQuadrature::Degree2), &hessian(TriQuadrature::Degree4), 0.0);
        record("rest epidermis Hessian, degree 2 vs degree 4 (flat)", err);
        prop_assert!(err < 1e-12, "{err:e}");
    }
}

// ---------------------------------------------------------------------------------------------
// The 4-node path keeps its values

/// Pins of the 4-node path; the values come from the kernels and constraint sets as they were
/// before the element layer (commit 99416f574b1f).
const PINS: &str = "elements-tet4";

/// Pins every entry of `values` as probe `i` of the record `key`, relative to the largest
/// entry (a reordered sum rounds by a few ulps of its largest term, not of each entry).
fn pin_all(key: &str, values: &[f64]) {
    let floor = values.iter().fold(0.0f64, |s, v| s.max(v.abs()));
    for (i, v) in values.iter().enumerate() {
        assert_pinned(
            PINS,
            &Run::named(key),
            &i.to_string(),
            *v,
            Tolerance::relative(1e-12, floor),
        );
    }
}

/// A fixed probe direction of `n` entries.
fn probe(n: usize) -> DVector<f64> {
    DVector::from_iterator(n, (0..n).map(|i| ((i * 7 + 3) % 11) as f64 / 11.0 - 0.4))
}

/// `matrix * probe` for a column-major `n x n` matrix.
fn probed(matrix: &[f64], n: usize) -> Vec<f64> {
    (DMatrix::from_column_slice(n, n, matrix) * probe(n))
        .as_slice()
        .to_vec()
}

/// The 4-node kernels (energy, gradient, Hessian times a probe, for three materials), the
/// 3-node epidermis, and every constraint set on two tets (values, `G` and `K_g` times a probe,
/// compliance, pressures), all at their values from before the element layer to 1e-12.
#[test]
fn tet4_results_keep_their_pinned_values() {
    let rest = [
        Vector3::new(0.1, 0.0, -0.2),
        Vector3::new(1.0, 0.2, 0.0),
        Vector3::new(0.3, 0.9, 0.1),
        Vector3::new(0.2, 0.1, 1.1),
    ];
    let a = Matrix3::new(1.1, 0.2, -0.1, 0.05, 0.85, 0.15, -0.2, 0.1, 1.2);
    let x: [Vector3<f64>; 4] =
        std::array::from_fn(|i| a * rest[i] + Vector3::new(0.01 * i as f64, -0.02, 0.03));
    let dm = Matrix3::from_columns(&[rest[1] - rest[0], rest[2] - rest[0], rest[3] - rest[0]]);
    let (dm_inv, volume) = (
        dm.try_inverse().expect("invertible"),
        dm.determinant() / 6.0,
    );
    let lame = Lame::new(1.3, 7.0).expect("Lame");
    let materials: [(&str, Box<dyn Hyperelastic>); 3] = [
        (
            "standard",
            Box::new(standard_neo_hookean(lame).expect("material")),
        ),
        (
            "stable",
            Box::new(StableNeoHookean::from_linear_lame(lame).expect("material")),
        ),
        (
            "constrained",
            Box::new(constrained_neo_hookean(1.3, 7.0, 2.0, 0.2).expect("material")),
        ),
    ];
    for (name, m) in &materials {
        let t = tet::energy_gradient_hessian(m.as_ref(), &x, &dm_inv, volume).expect("inside");
        pin_all(&format!("tet4/{name}/energy"), &[t.energy]);
        pin_all(&format!("tet4/{name}/gradient"), t.gradient.as_slice());
        pin_all(
            &format!("tet4/{name}/hessian_probe"),
            &probed(t.hessian.as_slice(), 12),
        );
    }

    let face = triangle::RestTriangle::new(&[rest[0], rest[1], rest[2]]).expect("triangle");
    let t = Epidermis::new(3.0, 1.5)
        .expect("skin")
        .energy_gradient_hessian(&[x[0], x[1], x[2]], &face);
    pin_all("tri3/epidermis/energy", &[t.energy]);
    pin_all("tri3/epidermis/gradient", t.gradient.as_slice());
    pin_all(
        "tri3/epidermis/hessian_probe",
        &probed(t.hessian.as_slice(), 9),
    );

    let mesh = TetMesh::new(
        vec![
            Vec3::new(0.0, 0.0, 0.0),
            Vec3::new(1.0, 0.0, 0.0),
            Vec3::new(0.0, 1.0, 0.0),
            Vec3::new(0.3, 0.3, 1.0),
            Vec3::new(0.2, 0.3, -0.8),
        ],
        vec![[0, 1, 2, 3], [0, 2, 1, 4]],
    )
    .expect("two tets");
    let y: Vec<Vec3> = mesh
        .positions()
        .iter()
        .enumerate()
        .map(|(i, p)| p + Vec3::new(0.03 * i as f64, -0.05, 0.02 * (i % 3) as f64))
        .collect();
    let zones = Zones::from_sets(vec![vec![0, 1], vec![1]]);
    let consistent = NodalCompliance::Consistent;
    let sets: [(&str, Box<dyn ConstraintSet>); 5] = [
        (
            "P0",
            Box::new(PerElementConstraints::new(&mesh, Measure::Linear, 3.0).expect("P0")),
        ),
        (
            "P0-log",
            Box::new(PerElementConstraints::new(&mesh, Measure::Logarithmic, 3.0).expect("P0")),
        ),
        (
            "P1",
            Box::new(NodalConstraints::new(&mesh, Measure::Linear, 3.0, consistent).expect("P1")),
        ),
        (
            "P1-log",
            Box::new(
                NodalConstraints::new(&mesh, Measure::Logarithmic, 3.0, NodalCompliance::Lumped)
                    .expect("P1"),
            ),
        ),
        (
            "zonal",
            Box::new(
                ZonalConstraints::new(&mesh, &zones)
                    .and_then(|z| z.with_bulk_modulus(2.0))
                    .expect("zonal"),
            ),
        ),
    ];
    for (name, set) in &sets {
        let m = set.num_constraints();
        pin_all(
            &format!("constraints/{name}/values"),
            values(set.as_ref(), &y).as_slice(),
        );
        let gv = jacobian(set.as_ref(), &y) * probe(15);
        pin_all(&format!("constraints/{name}/jacobian_probe"), gv.as_slice());
        let p: Vec<f64> = (0..m).map(|i| 0.7 - 0.3 * i as f64).collect();
        let kv = constraint_checks::geometric_stiffness(set.as_ref(), &y, &p) * probe(15);
        pin_all(
            &format!("constraints/{name}/geometric_stiffness_probe"),
            kv.as_slice(),
        );
        let mut c = vec![0.0; m];
        match set.compliance() {
            Compliance::Diagonal(d) => c.copy_from_slice(&d),
            Compliance::Sparse(t) => t.iter().for_each(|&(i, j, v)| c[i] += v * probe(m)[j]),
        }
        pin_all(&format!("constraints/{name}/compliance_probe"), &c);
        pin_all(
            &format!("constraints/{name}/pressures"),
            &set.tet_pressures(&y, &p),
        );
    }
}
