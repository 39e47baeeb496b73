//! Finite-difference validation of the energy layer: every density's `P` against differences
//! of `Psi` and `dP/dF` against differences of `P`, the penalties, the tet and triangle
//! kernels, rest stability, frame indifference, the penalty conditions of Sheen et al. 2021
//! (sec. 5), PSD projection and parameter validation, and a negative control showing that the
//! finite-difference check rejects a stress or tangent wrong by 1e-5.
//!
//! One harness, every term: [`density_suite!`] turns one line per density into its full set of
//! property tests; [`penalty_suite!`] does the same for penalties.

use isochor_energies::{
    constrained_neo_hookean, kinematics, project_to_psd, quadratic_neo_hookean, stable_neo_hookean,
    standard_neo_hookean, tet, triangle, BonetWood, DistortionalNeoHookean,
    DistortionalStableNeoHookean, Epidermis, FbarNeoHookean, Hyperelastic, Lame, LogPenalty,
    Matrix12, Matrix9, Mooney, MooneyRivlin, Ogden, OutOfDomain, QuadraticPenalty, SheenPenalty,
    Snh2Penalty, StableNeoHookean, StvkPenalty, VolumetricPenalty, Yeoh,
};
use isochor_validation::fd::{self, relative_error, relative_error_vec};
use isochor_validation::strategies::{
    material_params as params, max_edge, near_identity, rest_tet, rest_triangle, with_determinant,
    MaterialParams as Params,
};
use nalgebra::{DMatrix, DVector, Matrix3, Rotation3, SymmetricEigen, Unit, Vector3};
use proptest::prelude::*;
use proptest::test_runner::TestCaseError;

/// Finite-difference agreement required everywhere (relative, max norm).
const TOLERANCE: f64 = 1e-6;

fn to_dvec(f: &Matrix3<f64>) -> DVector<f64> {
    DVector::from_column_slice(f.as_slice())
}

fn to_mat(v: &DVector<f64>) -> Matrix3<f64> {
    Matrix3::from_column_slice(v.as_slice())
}

/// `P` against central differences of `Psi`, `dP/dF` against central differences of `P`, and
/// symmetry of `dP/dF`. The floor of the relative error is the material's modulus `mu` (the
/// natural scale of `P` and `dP/dF` near rest).
///
/// The step is `STEP` times the size of `F`, but never below `STEP`. A central difference errs
/// by the truncation `h^2 |Psi'''| / 6` plus the rounding `eps |Psi| / h`. Near-singular `F`
/// (`det F ~ 1e-3`, entries ~0.1) keeps `Psi` large (Stable neo-Hookean's
/// `lambda/2 (J - 1)^2 ~ lambda/2` reaches 1e3 `mu`) while `P` is small, so a step of `1e-7` made the
/// rounding 2e-7 of the floor, a fifth of TOLERANCE (measured); the floor `h >= 1e-6` brings
/// it to 2e-8, and the truncation stays near `(h / sigma_min)^2 ~ 1e-9` for the smallest
/// singular value `sigma_min ~ 0.03` of those `F` (the largest tangent error measured over
/// 256 cases per density: 8e-10).
fn check_derivatives<M: Hyperelastic + ?Sized>(
    m: &M,
    f: &Matrix3<f64>,
    mu: f64,
) -> Result<(), TestCaseError> {
    let x = to_dvec(f);
    let h = fd::STEP * f.amax().max(1.0);
    let psi = |v: &DVector<f64>| m.energy_density(&to_mat(v)).expect("inside the domain");
    let pk1 = |v: &DVector<f64>| to_dvec(&m.pk1(&to_mat(v)).expect("inside the domain"));

    let p = to_dvec(&m.pk1(f).map_err(|e| TestCaseError::fail(e.to_string()))?);
    let p_fd = fd::gradient(psi, &x, h);
    let err = relative_error_vec(&p, &p_fd, mu);
    prop_assert!(
        err < TOLERANCE,
        "{}: P vs FD of Psi, relative error {err:e}",
        m.name()
    );

    let a = m
        .pk1_derivative(f)
        .map_err(|e| TestCaseError::fail(e.to_string()))?;
    let a = DMatrix::from_column_slice(9, 9, a.as_slice());
    let a_fd = fd::jacobian(pk1, &x, h);
    let err = relative_error(&a, &a_fd, mu);
    prop_assert!(
        err < TOLERANCE,
        "{}: dP/dF vs FD of P, relative error {err:e}",
        m.name()
    );
    let asym = relative_error(&a, &a.transpose(), mu);
    prop_assert!(asym < 1e-12, "{}: dP/dF not symmetric ({asym:e})", m.name());
    Ok(())
}

/// Agreement of `Psi(QF)` with `Psi(F)` and of `P(QF)` with `Q P(F)`, relative to the
/// first-order effect of rounding: `QF` is `F` rotated with an error of a few `eps` per entry,
/// which moves `Psi` by about `eps |P| |F|` and `P` by about `eps |dP/dF| |F|`, and the
/// densities sum terms of size up to `|Psi|` or `|P|` (and `mu`) with rounding. 1e-13 is
/// about 450 `eps`, for the sums over 9 entries and the logarithms and powers of `J`;
/// an energy that is not objective errs by order 1 (measured: at most 9e-16 over 9 densities x 64 cases).
const FRAME_TOLERANCE: f64 = 1e-13;

/// A random rotation: a random axis and an angle in `(-pi, pi)`.
fn rotation() -> impl Strategy<Value = Matrix3<f64>> {
    (
        proptest::array::uniform3(-1.0..1.0f64),
        -std::f64::consts::PI..std::f64::consts::PI,
    )
        .prop_filter_map("the axis must not vanish", |(axis, angle)| {
            let axis = Vector3::from(axis);
            (axis.norm() > 0.1)
                .then(|| Rotation3::from_axis_angle(&Unit::new_normalize(axis), angle).into_inner())
        })
}

/// Frame indifference: `Psi(QF) = Psi(F)` and `P(QF) = Q P(F)` for a rotation `Q`.
fn check_frame_indifference<M: Hyperelastic + ?Sized>(
    m: &M,
    f: &Matrix3<f64>,
    q: &Matrix3<f64>,
    mu: f64,
) -> Result<(), TestCaseError> {
    let fail = |e: OutOfDomain| TestCaseError::fail(e.to_string());
    let qf = q * f;
    let (psi, psi_q) = (
        m.energy_density(f).map_err(fail)?,
        m.energy_density(&qf).map_err(fail)?,
    );
    let (p, p_q) = (m.pk1(f).map_err(fail)?, m.pk1(&qf).map_err(fail)?);
    let a = m.pk1_derivative(f).map_err(fail)?;
    let scale_psi = psi.abs().max(p.amax() * f.amax()).max(mu);
    let scale_p = p.amax().max(a.amax() * f.amax()).max(mu);
    let psi_error = (psi_q - psi).abs() / scale_psi;
    let p_error = (p_q - q * p).amax() / scale_p;
    prop_assert!(
        psi_error <= FRAME_TOLERANCE,
        "{}: Psi(QF) - Psi(F) = {psi_error:e} relative",
        m.name()
    );
    prop_assert!(
        p_error <= FRAME_TOLERANCE,
        "{}: P(QF) - Q P(F) = {p_error:e} relative",
        m.name()
    );
    Ok(())
}

/// Size of the defects of the negative control: ten times TOLERANCE.
const DEFECT: f64 = 1e-5;

/// `inner` with its stress (`tangent == false`) or its tangent wrong in the first diagonal
/// entry by DEFECT times the scale [`check_derivatives`] measures errors against
/// (`max(|P|, mu)` or `max(|dP/dF|, mu)`): a diagonal entry, so the symmetry check cannot be
/// what catches it.
#[derive(Debug)]
struct Wrong<M> {
    inner: M,
    tangent: bool,
    mu: f64,
}

impl<M: Hyperelastic> Hyperelastic for Wrong<M> {
    fn name(&self) -> &'static str {
        self.inner.name()
    }

    fn energy_density(&self, f: &Matrix3<f64>) -> Result<f64, OutOfDomain> {
        self.inner.energy_density(f)
    }

    fn pk1(&self, f: &Matrix3<f64>) -> Result<Matrix3<f64>, OutOfDomain> {
        let mut p = self.inner.pk1(f)?;
        if !self.tangent {
            p[(0, 0)] += DEFECT * p.amax().max(self.mu);
        }
        Ok(p)
    }

    fn pk1_derivative(&self, f: &Matrix3<f64>) -> Result<Matrix9, OutOfDomain> {
        let mut a = self.inner.pk1_derivative(f)?;
        if self.tangent {
            a[(0, 0)] += DEFECT * a.amax().max(self.mu);
        }
        Ok(a)
    }

    fn is_defined_at(&self, j: f64) -> bool {
        self.inner.is_defined_at(j)
    }
}

/// Outside the domain every evaluation is an [`isochor_energies::OutOfDomain`] error, never NaN.
fn check_refuses<M: Hyperelastic + ?Sized>(m: &M, f: &Matrix3<f64>) -> Result<(), TestCaseError> {
    let j = f.determinant();
    prop_assert!(!m.is_defined_at(j));
    prop_assert!(
        m.energy_density(f).is_err(),
        "{} gave an energy at J = {j}",
        m.name()
    );
    prop_assert!(m.pk1(f).is_err(), "{} gave a stress at J = {j}", m.name());
    prop_assert!(
        m.pk1_derivative(f).is_err(),
        "{} gave a tangent at J = {j}",
        m.name()
    );
    Ok(())
}

/// Checks derivatives where the density is defined at `det F`, else that it refuses.
fn check_or_refuse<M: Hyperelastic + ?Sized>(
    m: &M,
    f: &Matrix3<f64>,
    mu: f64,
) -> Result<(), TestCaseError> {
    if m.is_defined_at(f.determinant()) {
        check_derivatives(m, f, mu)
    } else {
        check_refuses(m, f)
    }
}

/// One module of property tests per density: regular (`det F` in `[0.05, 20]`), near-singular
/// (`det F ~ 1e-3`), inverted (`det F < 0`, checked where the density is defined and refused
/// elsewhere), plus rest stability: `P(I) = 0` when `rest_stable`, `P(I) != 0` otherwise.
macro_rules! density_suite {
    ($($name:ident => |$p:ident| $build:expr, rest_stable = $rest:expr;)*) => {$(
        mod $name {
            use super::*;

            fn build($p: &Params) -> impl Hyperelastic {
                $build
            }

            proptest! {
                #![proptest_config(ProptestConfig::with_cases(256))]

                #[test]
                fn derivatives_regular(p in params(), f in with_determinant(0.05, 20.0, false)) {
                    check_derivatives(&build(&p), &f, p.mu)?;
                }

                #[test]
                fn derivatives_near_identity(p in params(), f in near_identity(0.3)) {
                    check_or_refuse(&build(&p), &f, p.mu)?;
                }

                #[test]
                fn derivatives_near_singular(p in params(), f in with_determinant(5e-4, 2e-3, false)) {
                    check_derivatives(&build(&p), &f, p.mu)?;
                }

                #[test]
                fn frame_indifference(
                    p in params(),
                    f in with_determinant(0.05, 20.0, false),
                    q in rotation(),
                ) {
                    check_frame_indifference(&build(&p), &f, &q, p.mu)?;
                }

                #[test]
                fn derivatives_inverted(
                    p in params(),
                    f in prop_oneof![
                        with_determinant(0.05, 20.0, true),
                        with_determinant(5e-4, 2e-3, true),
                    ],
                ) {
                    check_or_refuse(&build(&p), &f, p.mu)?;
                }
            }

            proptest! {
                #![proptest_config(ProptestConfig::with_cases(16))]

                /// Negative control: [`check_derivatives`] reports a stress or a tangent wrong
                /// by DEFECT (ten times its tolerance) as failing.
                #[test]
                fn finite_differences_reject_a_wrong_derivative(
                    p in params(),
                    f in with_determinant(0.05, 20.0, false),
                ) {
                    for tangent in [false, true] {
                        let wrong = Wrong { inner: build(&p), tangent, mu: p.mu };
                        prop_assert!(
                            check_derivatives(&wrong, &f, p.mu).is_err(),
                            "{} with a wrong {} passed",
                            wrong.name(),
                            if tangent { "tangent" } else { "stress" }
                        );
                    }
                }
            }

            #[test]
            fn rest_stability() {
                let p = Params {
                    mu: 1.7,
                    lambda: 23.0,
                    beta: 3.0,
                    epsilon: 0.1,
                    c01_ratio: 0.4,
                    c20_ratio: -0.1,
                    c30_ratio: 0.02,
                };
                let m = build(&p);
                let stress = m.pk1(&Matrix3::identity()).unwrap().amax();
                if $rest {
                    assert!(stress < 1e-13 * (p.mu + p.lambda), "{}: P(I) = {stress:e}", m.name());
                } else {
                    assert!(stress > 0.1 * p.mu, "{} should not be rest stable", m.name());
                }
            }
        }
    )*};
}

// Rest stability as claimed by the papers: standard neo-Hookean (eq. 6 / eq. 4), distortional
// neo-Hookean (eq. 32), Bonet-Wood (eq. 30), Stable neo-Hookean and its distortional part,
// F-bar deviatoric (eq. 12), the composed constrained neo-Hookean, and the uncoupled
// Mooney-Rivlin and Yeoh models are rest stable. Mooney (eq. 29) is not: P(I) = mu I.
density_suite! {
    mooney => |p| Mooney::new(p.mu).unwrap(), rest_stable = false;
    distortional_neo_hookean => |p| DistortionalNeoHookean::new(p.mu).unwrap(), rest_stable = true;
    bonet_wood => |p| BonetWood::new(p.mu).unwrap(), rest_stable = true;
    mooney_rivlin => |p| {
        let (c10, c01) = p.mooney_rivlin();
        MooneyRivlin::new(c10, c01).unwrap()
    }, rest_stable = true;
    yeoh => |p| {
        let (c10, c20, c30) = p.yeoh();
        Yeoh::new(c10, c20, c30).unwrap()
    }, rest_stable = true;
    ogden => |p| Ogden::new(&p.ogden()).unwrap(), rest_stable = true;
    distortional_stable_neo_hookean => |p| DistortionalStableNeoHookean::new(p.mu).unwrap(),
        rest_stable = true;
    stable_neo_hookean => |p| stable_neo_hookean(Lame::new(p.mu, p.lambda).unwrap()).unwrap(),
        rest_stable = true;
    stable_neo_hookean_linear_lame =>
        |p| StableNeoHookean::from_linear_lame(Lame::new(p.mu, p.lambda).unwrap()).unwrap(),
        rest_stable = true;
    fbar_neo_hookean => |p| FbarNeoHookean::new(p.mu, p.epsilon).unwrap(), rest_stable = true;
    standard_neo_hookean_ => |p| standard_neo_hookean(Lame::new(p.mu, p.lambda).unwrap()).unwrap(),
        rest_stable = true;
    quadratic_neo_hookean_ => |p| quadratic_neo_hookean(Lame::new(p.mu, p.lambda).unwrap()).unwrap(),
        rest_stable = true;
    constrained_neo_hookean_ =>
        |p| constrained_neo_hookean(p.mu, p.lambda, p.beta, p.epsilon).unwrap(),
        rest_stable = true;
}

/// The densities that must accept inverted and singular `F`.
#[test]
fn invertible_densities_are_defined_everywhere() {
    let lame = Lame::new(1.0, 10.0).unwrap();
    let invertible: Vec<Box<dyn Hyperelastic>> = vec![
        Box::new(Mooney::new(1.0).unwrap()),
        Box::new(stable_neo_hookean(lame).unwrap()),
        Box::new(DistortionalStableNeoHookean::new(1.0).unwrap()),
        Box::new(FbarNeoHookean::new(1.0, 0.1).unwrap()),
        Box::new(constrained_neo_hookean(1.0, 10.0, 2.0, 0.1).unwrap()),
    ];
    let flat = Matrix3::from_diagonal(&Vector3::new(1.0, 1.0, 0.0));
    for m in &invertible {
        for j in [-5.0, -1e-3, 0.0, 1e-3] {
            assert!(m.is_defined_at(j), "{}", m.name());
        }
        let p = m.pk1(&flat).unwrap();
        let a = m.pk1_derivative(&flat).unwrap();
        assert!(
            p.iter().chain(a.iter()).all(|v| v.is_finite()),
            "{}",
            m.name()
        );
    }
    let singular: Vec<Box<dyn Hyperelastic>> = vec![
        Box::new(DistortionalNeoHookean::new(1.0).unwrap()),
        Box::new(BonetWood::new(1.0).unwrap()),
        Box::new(MooneyRivlin::new(0.3, 0.2).unwrap()),
        Box::new(Yeoh::new(0.5, -0.05, 0.01).unwrap()),
        Box::new(standard_neo_hookean(lame).unwrap()),
        Box::new(quadratic_neo_hookean(lame).unwrap()),
    ];
    for m in &singular {
        assert!(m.energy_density(&flat).is_err() && m.pk1_derivative(&flat).is_err());
    }
}

/// The F-bar deviatoric energy equals Bonet-Wood above `epsilon` (eq. 11 with `alpha = J^-1/3`).
#[test]
fn fbar_equals_bonet_wood_above_epsilon() {
    let (fbar, bw) = (
        FbarNeoHookean::new(2.0, 0.1).unwrap(),
        BonetWood::new(2.0).unwrap(),
    );
    let f = Matrix3::new(1.1, 0.3, 0.0, -0.2, 0.7, 0.1, 0.0, 0.2, 0.9);
    let rel = |a: f64, b: f64| (a - b).abs() / b.abs().max(1.0);
    assert!(
        rel(
            fbar.energy_density(&f).unwrap(),
            bw.energy_density(&f).unwrap()
        ) < 1e-14
    );
    assert!((fbar.pk1(&f).unwrap() - bw.pk1(&f).unwrap()).amax() < 1e-13);
    assert!((fbar.pk1_derivative(&f).unwrap() - bw.pk1_derivative(&f).unwrap()).amax() < 1e-12);
}

// ---------------------------------------------------------------------------------------------
// Invariant models and Stable neo-Hookean: closed forms

/// Cauchy stress `sigma = P F^T / J`.
fn cauchy<M: Hyperelastic + ?Sized>(m: &M, f: &Matrix3<f64>) -> Matrix3<f64> {
    m.pk1(f).unwrap() * f.transpose() / f.determinant()
}

/// Stretches `l` in `[0.5, 3]` (26 points, `l = 1` included).
fn uniaxial_stretches() -> impl Iterator<Item = f64> {
    (0..=25).map(|k| 0.5 + 0.1 * k as f64)
}

/// Homogeneous incompressible uniaxial stretch `F = diag(l, l^-1/2, l^-1/2)`: the Cauchy
/// stress difference `sigma11 - sigma22` (free of the pressure, which a purely distortional
/// density leaves undetermined) equals `l Pnom(l)`, with the closed-form nominal stress
/// `Pnom` of each model, to 1e-12 of `max(|l Pnom|, mu)`.
#[test]
fn uniaxial_stress_matches_closed_forms() {
    type Nominal = Box<dyn Fn(f64) -> f64>;
    let mut cases: Vec<(Box<dyn Hyperelastic>, f64, Nominal)> = Vec::new();
    for mu in [0.3, 2.0] {
        cases.push((
            Box::new(BonetWood::new(mu).unwrap()),
            mu,
            Box::new(move |l: f64| mu * (l - l.powi(-2))),
        ));
        // Smith et al. 2018: at J = 1 the distortional part adds the hydrostatic -3 mu/4 I.
        cases.push((
            Box::new(DistortionalStableNeoHookean::new(mu).unwrap()),
            0.75 * mu,
            Box::new(move |l: f64| {
                let i1 = l * l + 2.0 / l;
                mu * (1.0 - 1.0 / (i1 + 1.0)) * (l - l.powi(-2))
            }),
        ));
    }
    for (c10, c01) in [(0.5, 0.0), (0.3, 0.2), (0.2, 0.2), (1.0, -0.3)] {
        cases.push((
            Box::new(MooneyRivlin::new(c10, c01).unwrap()),
            2.0 * (c10 + c01),
            Box::new(move |l: f64| 2.0 * (l - l.powi(-2)) * (c10 + c01 / l)),
        ));
    }
    for (c10, c20, c30) in [(0.5, 0.0, 0.0), (0.298, -0.014, 8.6e-4), (0.5, 0.1, 0.0)] {
        cases.push((
            Box::new(Yeoh::new(c10, c20, c30).unwrap()),
            2.0 * c10,
            Box::new(move |l: f64| {
                let x = l * l + 2.0 / l - 3.0;
                2.0 * (l - l.powi(-2)) * (c10 + 2.0 * c20 * x + 3.0 * c30 * x * x)
            }),
        ));
    }
    for terms in [
        vec![(0.63, 1.3), (0.0012, 5.0), (-0.01, -2.0)],
        vec![(1.0, 2.0)],
        vec![(0.4, 2.0), (-0.2, -2.0)],
        vec![(0.2, 0.5), (0.05, 8.0)],
    ] {
        let ogden = Ogden::new(&terms).unwrap();
        let mu0 = ogden.mu();
        cases.push((
            Box::new(ogden),
            mu0,
            Box::new(move |l: f64| {
                terms
                    .iter()
                    .map(|&(m, a)| m * (l.powf(a - 1.0) - l.powf(-0.5 * a - 1.0)))
                    .sum()
            }),
        ));
    }
    let mut worst: f64 = 0.0;
    for (m, mu, nominal) in &cases {
        for l in uniaxial_stretches() {
            let t = 1.0 / l.sqrt();
            let f = Matrix3::from_diagonal(&Vector3::new(l, t, t));
            let sigma = cauchy(m.as_ref(), &f);
            let expected = l * nominal(l);
            let error = (sigma[(0, 0)] - sigma[(1, 1)] - expected).abs() / expected.abs().max(*mu);
            worst = worst.max(error);
            assert!(
                error <= 1e-12,
                "{} at l = {l}: sigma11 - sigma22 = {:e}, expected {expected:e}",
                m.name(),
                sigma[(0, 0)] - sigma[(1, 1)]
            );
            // The transverse directions are free of shear and equal.
            assert!((sigma[(1, 1)] - sigma[(2, 2)]).abs() <= 1e-12 * expected.abs().max(*mu));
        }
    }
    eprintln!(
        "uniaxial: largest relative error {worst:.1e} over {} models",
        cases.len()
    );
}

/// Small simple shear `F = I + gamma e1 e2^T`, `gamma = 1e-6`: `sigma12 / gamma` is the
/// initial shear modulus of each density, to 1e-6 relative (the `O(gamma^2)` terms are 1e-12;
/// the rounding of `P` is about `eps mu / gamma ~ 1e-10`).
#[test]
fn small_shear_gives_the_initial_shear_modulus() {
    let gamma = 1e-6;
    let mut f = Matrix3::identity();
    f[(0, 1)] = gamma;
    let lame = Lame::new(1.3, 40.0).unwrap();
    let cases: Vec<(Box<dyn Hyperelastic>, f64)> = vec![
        (Box::new(Mooney::new(1.3).unwrap()), 1.3),
        (Box::new(DistortionalNeoHookean::new(1.3).unwrap()), 1.3),
        (Box::new(BonetWood::new(1.3).unwrap()), 1.3),
        (Box::new(FbarNeoHookean::new(1.3, 0.1).unwrap()), 1.3),
        (Box::new(MooneyRivlin::new(0.45, 0.2).unwrap()), 1.3),
        (Box::new(MooneyRivlin::new(0.8, -0.15).unwrap()), 1.3),
        (Box::new(Yeoh::new(0.65, -0.06, 0.004).unwrap()), 1.3),
        (
            Box::new(Ogden::new(&[(1.0, 2.0), (-0.3, -1.0)]).unwrap()),
            1.15,
        ),
        (
            Box::new(Ogden::new(&[(0.63, 1.3), (0.0012, 5.0), (-0.01, -2.0)]).unwrap()),
            0.4225,
        ),
        // The energy's mu times 3/4 (Smith et al. 2018, sec. 3.4).
        (
            Box::new(DistortionalStableNeoHookean::new(1.3).unwrap()),
            0.975,
        ),
        (Box::new(stable_neo_hookean(lame).unwrap()), 0.975),
        (
            Box::new(StableNeoHookean::from_linear_lame(lame).unwrap()),
            1.3,
        ),
        (Box::new(standard_neo_hookean(lame).unwrap()), 1.3),
    ];
    for (m, mu0) in &cases {
        let measured = cauchy(m.as_ref(), &f)[(0, 1)] / gamma;
        let error = (measured - mu0).abs() / mu0;
        assert!(
            error <= 1e-6,
            "{}: sigma12 / gamma = {measured}, expected {mu0}",
            m.name()
        );
    }
}

/// `F = Q diag(l, l (1 + d1), l (1 + d2)) R` for rotations `Q`, `R`, `l` in `[0.3, 3]` and
/// relative gaps `d1`, `d2` each 0 or `+-1e-12 .. +-1e-3` (log-uniform): equal and nearly equal
/// principal stretches.
fn nearly_equal_stretches() -> impl Strategy<Value = Matrix3<f64>> {
    let gap = || {
        prop_oneof![
            Just(0.0),
            (-12.0..-3.0f64, proptest::bool::ANY).prop_map(|(e, negative)| if negative {
                -(10f64.powf(e))
            } else {
                10f64.powf(e)
            }),
        ]
    };
    (rotation(), rotation(), 0.3..3.0f64, gap(), gap()).prop_map(|(q, r, l, d1, d2)| {
        q * Matrix3::from_diagonal(&Vector3::new(l, l * (1.0 + d1), l * (1.0 + d2))) * r
    })
}

/// `|a - b|` in the max norm over `max(|a|, |b|, floor)`.
fn matrix_error<const R: usize, const C: usize>(
    a: &nalgebra::SMatrix<f64, R, C>,
    b: &nalgebra::SMatrix<f64, R, C>,
    floor: f64,
) -> f64 {
    (a - b).amax() / a.amax().max(b.amax()).max(floor)
}

/// `|a - b| / max(|a|, |b|, floor)` for `a`, `b` `Psi`, `P`, `dP/dF` of two densities at `f`.
fn density_difference<A: Hyperelastic, B: Hyperelastic>(
    a: &A,
    b: &B,
    f: &Matrix3<f64>,
    floor: f64,
) -> [f64; 3] {
    let (ea, eb) = (a.energy_density(f).unwrap(), b.energy_density(f).unwrap());
    [
        (ea - eb).abs() / ea.abs().max(eb.abs()).max(floor),
        matrix_error(&a.pk1(f).unwrap(), &b.pk1(f).unwrap(), floor),
        matrix_error(
            &a.pk1_derivative(f).unwrap(),
            &b.pk1_derivative(f).unwrap(),
            floor,
        ),
    ]
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(256))]

    /// Mooney-Rivlin with `c01 = 0` and Yeoh with `c20 = c30 = 0` are Bonet-Wood with
    /// `mu = 2 c10`: energy, stress and tangent agree to 1e-12 of their size (floor `mu`).
    #[test]
    fn invariant_models_reduce_to_bonet_wood(
        p in params(),
        f in prop_oneof![with_determinant(0.05, 20.0, false), with_determinant(5e-4, 2e-3, false)],
    ) {
        let bw = BonetWood::new(p.mu).unwrap();
        let mr = MooneyRivlin::new(0.5 * p.mu, 0.0).unwrap();
        let yeoh = Yeoh::new(0.5 * p.mu, 0.0, 0.0).unwrap();
        for error in density_difference(&mr, &bw, &f, p.mu)
            .into_iter()
            .chain(density_difference(&yeoh, &bw, &f, p.mu))
        {
            prop_assert!(error <= 1e-12, "relative difference {error:e}");
        }
    }

    /// Ogden with one term `(mu, 2)` is Bonet-Wood, and with `(2 c10, 2), (-2 c01, -2)`
    /// Mooney-Rivlin (`sum lb_i^-2 = Ib2`): energy, stress and tangent agree to 1e-12 of their
    /// size (floor `mu`), at general and at equal or nearly equal stretches.
    #[test]
    fn ogden_reduces_to_invariant_models(
        p in params(),
        f in prop_oneof![
            with_determinant(0.05, 20.0, false),
            with_determinant(5e-4, 2e-3, false),
            nearly_equal_stretches(),
        ],
    ) {
        let (c10, c01) = p.mooney_rivlin();
        let one_term = Ogden::new(&[(p.mu, 2.0)]).unwrap();
        let two_terms = Ogden::new(&[(2.0 * c10, 2.0), (-2.0 * c01, -2.0)]).unwrap();
        let bw = BonetWood::new(p.mu).unwrap();
        let mr = MooneyRivlin::new(c10, c01).unwrap();
        for error in density_difference(&one_term, &bw, &f, p.mu)
            .into_iter()
            .chain(density_difference(&two_terms, &mr, &f, p.mu))
        {
            prop_assert!(error <= 1e-12, "relative difference {error:e}");
        }
    }

    /// The Ogden tangent at equal and nearly equal principal stretches (relative gaps from 0 to
    /// 1e-3, where `1 / (l_i^2 - l_j^2)` formulas lose every digit) against differences.
    #[test]
    fn ogden_derivatives_at_nearly_equal_stretches(p in params(), f in nearly_equal_stretches()) {
        check_derivatives(&Ogden::new(&p.ogden()).unwrap(), &f, p.mu)?;
    }

    /// Stable neo-Hookean as `Composed<DistortionalStableNeoHookean, QuadraticPenalty>` against
    /// eq. 14 of Smith et al. 2018 written out: `Psi = mu/2 (I_C - 3) + lambda/2 (J - alpha)^2
    /// - mu/2 log(I_C + 1)` minus its rest value, `P = mu (1 - 1/(I_C + 1)) F
    /// + lambda (J - alpha) cof F` and its tangent, to 1e-12 of their size (floor `mu`),
    /// inverted `F` included.
    #[test]
    fn stable_neo_hookean_is_eq_14(
        p in params(),
        f in prop_oneof![
            with_determinant(0.05, 20.0, false),
            with_determinant(5e-4, 2e-3, false),
            with_determinant(0.05, 20.0, true),
        ],
    ) {
        let (mu, lambda) = (p.mu, p.lambda);
        let m = stable_neo_hookean(Lame::new(mu, lambda).unwrap()).unwrap();
        let alpha = 1.0 + 0.75 * mu / lambda;
        let (ic, j) = (f.norm_squared(), f.determinant());
        let eq14 = |ic: f64, j: f64| {
            0.5 * mu * (ic - 3.0) + 0.5 * lambda * (j - alpha).powi(2) - 0.5 * mu * (ic + 1.0).ln()
        };
        let psi = eq14(ic, j) - eq14(3.0, 1.0);
        let scale = psi.abs().max(eq14(ic, j).abs()).max(mu);
        prop_assert!((m.energy_density(&f).unwrap() - psi).abs() <= 1e-12 * scale);
        let cof = kinematics::cofactor(&f);
        let stress = f * (mu * (1.0 - 1.0 / (ic + 1.0))) + cof * (lambda * (j - alpha));
        prop_assert!(matrix_error(&m.pk1(&f).unwrap(), &stress, mu) <= 1e-12);
        let (fv, g) = (kinematics::flatten(&f), kinematics::flatten(&cof));
        let tangent = Matrix9::identity() * (mu * (1.0 - 1.0 / (ic + 1.0)))
            + fv * fv.transpose() * (2.0 * mu / (ic + 1.0).powi(2))
            + g * g.transpose() * lambda
            + kinematics::det_hessian(&f) * (lambda * (j - alpha));
        prop_assert!(matrix_error(&m.pk1_derivative(&f).unwrap(), &tangent, mu) <= 1e-12);
    }
}

// ---------------------------------------------------------------------------------------------
// Penalties

/// `U'` against differences of `U` and `U''` against differences of `U'` at `J` (floor 1: the
/// scale of `U''(1) = 1`). The step is relative to `max(|J|, 1)`, or to `J` for a barrier
/// penalty (undefined at `J <= 0`), so that `J - h` stays in its domain as `J -> 0+`: there the
/// truncation is `(h / J)^2 = 1e-12` and the rounding `eps U / (h U') ~ 2e-9` at `J = 1e-6`.
fn check_penalty<U: VolumetricPenalty>(u: &U, j: f64) -> Result<(), TestCaseError> {
    let h = fd::STEP
        * if u.is_defined_at(-1.0) {
            j.abs().max(1.0)
        } else {
            j
        };
    let rel = |a: f64, b: f64| (a - b).abs() / a.abs().max(b.abs()).max(1.0);
    let d1 = u.first_derivative(j).unwrap();
    let d1_fd = (u.value(j + h).unwrap() - u.value(j - h).unwrap()) / (2.0 * h);
    prop_assert!(rel(d1, d1_fd) < TOLERANCE, "{}: U' at J = {j}", u.name());
    let d2 = u.second_derivative(j).unwrap();
    let d2_fd =
        (u.first_derivative(j + h).unwrap() - u.first_derivative(j - h).unwrap()) / (2.0 * h);
    prop_assert!(rel(d2, d2_fd) < TOLERANCE, "{}: U'' at J = {j}", u.name());
    Ok(())
}

/// One property test per penalty over `J` in `[j_min, j_max]`.
macro_rules! penalty_suite {
    ($($name:ident => |$beta:ident| $build:expr, j in $range:expr;)*) => {$(
        proptest! {
            #![proptest_config(ProptestConfig::with_cases(256))]
            #[test]
            fn $name($beta in 0.0..20.0f64, j in $range) {
                check_penalty(&$build, j)?;
            }
        }
    )*};
}

penalty_suite! {
    log_penalty_derivatives => |_beta| LogPenalty, j in 1e-3..20.0f64;
    quadratic_penalty_derivatives => |_beta| QuadraticPenalty, j in -20.0..20.0f64;
    sheen_penalty_derivatives => |beta| SheenPenalty::new(beta).unwrap(), j in -20.0..20.0f64;
    snh2_penalty_derivatives => |_beta| Snh2Penalty, j in -20.0..20.0f64;
    stvk_penalty_derivatives => |_beta| StvkPenalty, j in 1e-3..20.0f64;
    // The extremes of Fig. 3 of Sheen et al. 2021 and beyond: J -> 0+ and large J.
    log_penalty_derivatives_near_zero => |_beta| LogPenalty, j in 1e-6..1e-2f64;
    log_penalty_derivatives_large => |_beta| LogPenalty, j in 20.0..1e3f64;
    sheen_penalty_derivatives_large => |beta| SheenPenalty::new(beta).unwrap(), j in 20.0..1e3f64;
    snh2_penalty_derivatives_near_zero => |_beta| Snh2Penalty, j in 1e-6..1e-2f64;
    snh2_penalty_derivatives_large => |_beta| Snh2Penalty, j in 20.0..1e3f64;
    stvk_penalty_derivatives_near_zero => |_beta| StvkPenalty, j in 1e-6..1e-2f64;
    stvk_penalty_derivatives_large => |_beta| StvkPenalty, j in 20.0..1e3f64;
}

/// Which of the conditions a-e of sec. 5 of Sheen et al. 2021 a penalty meets: a) `U(1) = 0`,
/// b) `U'(1) = 0`, c) `U''(1) = 1`, d) defined (and finite) for every real `J`, e) `U''(J) >= 0`
/// wherever defined. d and e are sampled on `J` in `[-10, 10]` every 1e-3 (with 0) and at
/// `+-1e3`; a to c are exact (the penalties are polynomials or logarithms exact at `J = 1`).
fn conditions(u: &dyn VolumetricPenalty) -> [bool; 5] {
    let grid = (-10_000..=10_000)
        .map(|i| f64::from(i) * 1e-3)
        .chain([-1e3, 1e3]);
    let (mut defined, mut convex) = (true, true);
    for j in grid {
        match (u.value(j), u.first_derivative(j), u.second_derivative(j)) {
            (Ok(v), Ok(d1), Ok(d2)) if u.is_defined_at(j) => {
                defined &= v.is_finite() && d1.is_finite() && d2.is_finite();
                convex &= d2 >= 0.0;
            }
            _ => defined = false,
        }
    }
    [
        u.value(1.0) == Ok(0.0),
        u.first_derivative(1.0) == Ok(0.0),
        u.second_derivative(1.0) == Ok(1.0),
        defined,
        convex,
    ]
}

/// The conditions a-e (sec. 5 of Sheen et al. 2021) for the penalties of their Fig. 3.
/// The paper's own claims: `U(J; beta)` meets all five for every `beta >= 0` (after eq. 15),
/// so does Stable neo-Hookean `(J - 1)^2 / 2 = U(J; 0)`, and the neo-Hookean `(log J)^2 / 2` is
/// undefined for `J <= 0` (Fig. 3: fails d). What the paper does not state, by analysis: the
/// neo-Hookean `U'' = (1 - log J) / J^2 < 0` for `J > e` (fails e); SNH2 meets a-d but
/// `U'' = 1 - 3d + 3d^2 / 2 < 0` for `d = J - 1` in `(1 - 1/sqrt 3, 1 + 1/sqrt 3)` (fails e);
/// our reading of the Kikuuwe et al. 2009 curve (Saint Venant-Kirchhoff under pure dilation)
/// is convex but its stress `-3 (J^(-1/3) - J^(1/3)) / 2` diverges as `J -> 0+` (fails d).
#[test]
fn penalty_conditions_of_sheen_et_al() {
    let sheen = |beta| SheenPenalty::new(beta).unwrap();
    let cases: [(&str, &dyn VolumetricPenalty, [bool; 5]); 7] = [
        ("neo-Hookean", &LogPenalty, [true, true, true, false, false]),
        ("Stable neo-Hookean", &QuadraticPenalty, [true; 5]),
        ("SNH2", &Snh2Penalty, [true, true, true, true, false]),
        (
            "StVK dilation",
            &StvkPenalty,
            [true, true, true, false, true],
        ),
        ("U(J; 0)", &sheen(0.0), [true; 5]),
        ("U(J; 1)", &sheen(1.0), [true; 5]),
        ("U(J; 6)", &sheen(6.0), [true; 5]),
    ];
    for (name, u, expected) in cases {
        assert_eq!(conditions(u), expected, "{name}: conditions a-e");
    }
}

/// SNH2 is non-convex exactly on `J` in `(2 - 1/sqrt 3, 2 + 1/sqrt 3)` (the roots of its `U''`),
/// and its `U` returns to 0 at `J = 3` where the truncated logarithm vanishes: it stops
/// penalizing stretch, unlike `U(J; beta)`.
#[test]
fn snh2_is_non_convex_between_the_roots_of_its_second_derivative() {
    let r = 1.0 / 3f64.sqrt();
    for (j, negative) in [(2.0 - r - 1e-6, false), (2.0 - r + 1e-6, true), (2.0, true)]
        .into_iter()
        .chain([(2.0 + r - 1e-6, true), (2.0 + r + 1e-6, false)])
    {
        let d2 = Snh2Penalty.second_derivative(j).unwrap();
        assert_eq!(d2 < 0.0, negative, "U''({j}) = {d2}");
    }
    assert_eq!(Snh2Penalty.value(3.0).unwrap(), 0.0);
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(256))]

    /// Conditions a-e of sec. 5 of Sheen et al. 2021 for `U(J; beta)`, `beta` in `[0, 20]`:
    /// a) `U(1) = 0`, b) `U'(1) = 0`, c) `U''(1) = 1`, d) defined (finite) for every real `J`,
    /// e) `U''(J) >= 0`; and `U(J; 0) = (J - 1)^2 / 2` (Stable neo-Hookean).
    #[test]
    fn sheen_penalty_conditions(beta in 0.0..20.0f64, j in -1e3..1e3f64) {
        let u = SheenPenalty::new(beta).unwrap();
        prop_assert_eq!(u.value(1.0).unwrap(), 0.0);
        prop_assert_eq!(u.first_derivative(1.0).unwrap(), 0.0);
        prop_assert_eq!(u.second_derivative(1.0).unwrap(), 1.0);
        prop_assert!(u.is_defined_at(j));
        let (v, d1, d2) = (u.value(j).unwrap(), u.first_derivative(j).unwrap(), u.second_derivative(j).unwrap());
        prop_assert!(v.is_finite() && d1.is_finite() && d2.is_finite());
        prop_assert!(d2 >= 0.0 && v >= 0.0);
        // Convex with minimum at 1: U' has the sign of J - 1.
        prop_assert!(d1 * (j - 1.0) >= 0.0);
        let snh = SheenPenalty::new(0.0).unwrap().value(j).unwrap();
        prop_assert!((snh - QuadraticPenalty.value(j).unwrap()).abs() <= 1e-15 * snh.max(1.0));
    }
}

#[test]
fn log_penalty_refuses_non_positive_j() {
    for j in [0.0, -1e-9, -3.0] {
        assert!(LogPenalty.value(j).is_err() && LogPenalty.second_derivative(j).is_err());
    }
}

// ---------------------------------------------------------------------------------------------
// Tet element kernel

fn flatten_positions<const N: usize>(x: &[Vector3<f64>; N]) -> DVector<f64> {
    DVector::from_iterator(3 * N, x.iter().flat_map(|v| v.iter().copied()))
}

fn unflatten_positions<const N: usize>(v: &DVector<f64>) -> [Vector3<f64>; N] {
    std::array::from_fn(|a| Vector3::new(v[3 * a], v[3 * a + 1], v[3 * a + 2]))
}

fn rest_data(rest: &[Vector3<f64>; 4]) -> (Matrix3<f64>, f64) {
    let dm = Matrix3::from_columns(&[rest[1] - rest[0], rest[2] - rest[0], rest[3] - rest[0]]);
    (dm.try_inverse().unwrap(), dm.determinant() / 6.0)
}

/// Deformed positions `F0 x_rest + noise` (noise up to 10% of the longest edge), kept to
/// `det F >= 0.05` like the regular density cases: the fixed relative step of the element
/// differences would resolve flatter tets poorly (near-singular `F` is tested per density,
/// with its own step).
fn deformed_tet() -> impl Strategy<Value = ([Vector3<f64>; 4], [Vector3<f64>; 4])> {
    (
        rest_tet(),
        with_determinant(0.3, 3.0, false),
        proptest::array::uniform12(-0.1..0.1f64),
    )
        .prop_filter_map("deformed tet must not be flat", |(rest, f0, noise)| {
            let l = max_edge(&rest);
            let x = std::array::from_fn(|a| {
                f0 * rest[a] + Vector3::new(noise[3 * a], noise[3 * a + 1], noise[3 * a + 2]) * l
            });
            let (dm_inv, _) = rest_data(&rest);
            (tet::deformation_gradient(&x, &dm_inv).determinant() >= 0.05).then_some((rest, x))
        })
}

/// Element gradient and Hessian of `m` against differences of the element energy and gradient.
/// The floors are the natural scales `mu V / l` and `mu V / l^2` (l the longest rest edge).
fn check_tet<M: Hyperelastic + ?Sized>(
    m: &M,
    rest: &[Vector3<f64>; 4],
    x: &[Vector3<f64>; 4],
    mu: f64,
) -> Result<(), TestCaseError> {
    let (dm_inv, volume) = rest_data(rest);
    let f = tet::deformation_gradient(x, &dm_inv);
    if !m.is_defined_at(f.determinant()) {
        prop_assert!(tet::energy_gradient_hessian(m, x, &dm_inv, volume).is_err());
        return Ok(());
    }
    let l = max_edge(rest);
    let h = fd::STEP * max_edge(x);
    let terms = tet::energy_gradient_hessian(m, x, &dm_inv, volume).unwrap();
    let xv = flatten_positions(x);
    let energy =
        |v: &DVector<f64>| tet::energy(m, &unflatten_positions(v), &dm_inv, volume).unwrap();
    let grad = |v: &DVector<f64>| {
        let g = tet::gradient(m, &unflatten_positions(v), &dm_inv, volume).unwrap();
        DVector::from_column_slice(g.as_slice())
    };

    prop_assert!((terms.energy - energy(&xv)).abs() <= 1e-15 * terms.energy.abs());
    let g = DVector::from_column_slice(terms.gradient.as_slice());
    let err = relative_error_vec(&g, &fd::gradient(energy, &xv, h), mu * volume / l);
    prop_assert!(
        err < TOLERANCE,
        "{}: element gradient, relative error {err:e}",
        m.name()
    );
    let hm = DMatrix::from_column_slice(12, 12, terms.hessian.as_slice());
    let err = relative_error(&hm, &fd::jacobian(grad, &xv, h), mu * volume / (l * l));
    prop_assert!(
        err < TOLERANCE,
        "{}: element Hessian, relative error {err:e}",
        m.name()
    );
    prop_assert_eq!(terms.hessian, terms.hessian.transpose());
    // Rigid translations are in the kernel of the Hessian and do not change the gradient sum.
    let ones = nalgebra::SVector::<f64, 12>::from_fn(|i, _| if i % 3 == 0 { 1.0 } else { 0.0 });
    let scale = terms.hessian.amax().max(mu * volume / (l * l));
    prop_assert!((terms.hessian * ones).amax() < 1e-12 * scale);
    Ok(())
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(256))]

    #[test]
    fn tet_kernel_matches_differences(p in params(), (rest, x) in deformed_tet()) {
        let lame = Lame::new(p.mu, p.lambda).unwrap();
        let materials: [&dyn Hyperelastic; 3] = [
            &standard_neo_hookean(lame).unwrap(),
            &stable_neo_hookean(lame).unwrap(),
            &constrained_neo_hookean(p.mu, p.lambda, p.beta, p.epsilon).unwrap(),
        ];
        for m in materials {
            check_tet(m, &rest, &x, p.mu)?;
        }
    }

    /// Inverted deformed tets: the invertible energies still match differences.
    #[test]
    fn tet_kernel_inverted(p in params(), (rest, x) in deformed_tet()) {
        let mut x = x;
        x.swap(1, 2);
        let m = constrained_neo_hookean(p.mu, p.lambda, p.beta, p.epsilon).unwrap();
        check_tet(&m, &rest, &x, p.mu)?;
        check_tet(&standard_neo_hookean(Lame::new(p.mu, p.lambda).unwrap()).unwrap(), &rest, &x, p.mu)?;
    }

    #[test]
    fn tet_deformation_gradient_and_jacobian(rest in rest_tet(), f0 in near_identity(0.5)) {
        let (dm_inv, _) = rest_data(&rest);
        let x: [Vector3<f64>; 4] = std::array::from_fn(|a| f0 * rest[a] + Vector3::new(0.3, -1.0, 2.0));
        let f = tet::deformation_gradient(&x, &dm_inv);
        prop_assert!((f - f0).amax() < 1e-12 * f0.amax());
        let d = tet::deformation_jacobian(&dm_inv);
        let fv = kinematics::flatten(&f);
        let xv = nalgebra::SVector::<f64, 12>::from_column_slice(flatten_positions(&x).as_slice());
        prop_assert!((d * xv - fv).amax() < 1e-11 * f0.amax() * (1.0 + xv.amax()));
    }
}

// ---------------------------------------------------------------------------------------------
// Triangle kernel and epidermis (eq. 16 of Sheen et al. 2021)

fn deformed_triangle() -> impl Strategy<Value = ([Vector3<f64>; 3], [Vector3<f64>; 3])> {
    (
        rest_triangle(),
        near_identity(0.6),
        proptest::array::uniform9(-0.2..0.2f64),
    )
        .prop_map(|(rest, f0, noise)| {
            let l = max_edge(&rest);
            let x = std::array::from_fn(|a| {
                f0 * rest[a] + Vector3::new(noise[3 * a], noise[3 * a + 1], noise[3 * a + 2]) * l
            });
            (rest, x)
        })
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(256))]

    #[test]
    fn area_ratio_matches_differences((rest, x) in deformed_triangle()) {
        let t = triangle::RestTriangle::new(&rest).unwrap();
        let d = triangle::area_ratio_derivatives(&x, &t);
        // J~ = sqrt(det(F~^T F~)).
        let ft = triangle::reduced_deformation_gradient(&x, &t);
        let j = (ft.transpose() * ft).determinant().sqrt();
        prop_assert!((d.value - j).abs() <= 1e-12 * j.max(1.0));
        let h = fd::STEP * max_edge(&x);
        let l = max_edge(&rest);
        let xv = flatten_positions(&x);
        let value = |v: &DVector<f64>| triangle::area_ratio(&unflatten_positions(v), &t);
        let grad = |v: &DVector<f64>| {
            let g = triangle::area_ratio_derivatives(&unflatten_positions(v), &t).gradient;
            DVector::from_column_slice(g.as_slice())
        };
        let g = DVector::from_column_slice(d.gradient.as_slice());
        let err = relative_error_vec(&g, &fd::gradient(value, &xv, h), 1.0 / l);
        prop_assert!(err < TOLERANCE, "dJ~/dx relative error {err:e}");
        let hm = DMatrix::from_column_slice(9, 9, d.hessian.as_slice());
        let err = relative_error(&hm, &fd::jacobian(grad, &xv, h), 1.0 / (l * l));
        prop_assert!(err < TOLERANCE, "d2J~/dx2 relative error {err:e}");
        prop_assert!(relative_error(&hm, &hm.transpose(), 1.0 / (l * l)) < 1e-12);
    }

    #[test]
    fn epidermis_matches_differences(
        (rest, x) in deformed_triangle(),
        lambda_e in 0.1..100.0f64,
        gamma in 0.0..5.0f64,
    ) {
        let t = triangle::RestTriangle::new(&rest).unwrap();
        let skin = Epidermis::new(lambda_e, gamma).unwrap();
        let terms = skin.energy_gradient_hessian(&x, &t);
        // eq. 16 written out.
        let jt = triangle::area_ratio(&x, &t);
        let eq16 = t.area() * lambda_e / 12.0 * (jt - 1.0).powi(2) * (gamma * (jt - 1.0).powi(2) + 6.0);
        prop_assert!((terms.energy - eq16).abs() <= 1e-12 * eq16.max(lambda_e * t.area()));
        let h = fd::STEP * max_edge(&x);
        let l = max_edge(&rest);
        let xv = flatten_positions(&x);
        let energy = |v: &DVector<f64>| skin.energy(&unflatten_positions(v), &t);
        let grad = |v: &DVector<f64>| {
            DVector::from_column_slice(skin.gradient(&unflatten_positions(v), &t).as_slice())
        };
        let scale = lambda_e * t.area();
        let g = DVector::from_column_slice(terms.gradient.as_slice());
        let err = relative_error_vec(&g, &fd::gradient(energy, &xv, h), scale / l);
        prop_assert!(err < TOLERANCE, "epidermis gradient relative error {err:e}");
        let hm = DMatrix::from_column_slice(9, 9, terms.hessian.as_slice());
        let err = relative_error(&hm, &fd::jacobian(grad, &xv, h), scale / (l * l));
        prop_assert!(err < TOLERANCE, "epidermis Hessian relative error {err:e}");
        prop_assert!(relative_error(&hm, &hm.transpose(), scale / (l * l)) < 1e-12);
    }

    /// Frame indifference of the epidermis energy (eq. 16 of Sheen et al. 2021): a rigid
    /// motion `x -> Q x + b` of the deformed triangle keeps the energy and rotates each
    /// vertex's gradient, to FRAME_TOLERANCE of their sizes (at least `lambda_e A`, per `l`).
    #[test]
    fn epidermis_frame_indifference(
        (rest, x) in deformed_triangle(),
        q in rotation(),
        b in proptest::array::uniform3(-1.0..1.0f64),
        lambda_e in 0.1..100.0f64,
        gamma in 0.0..5.0f64,
    ) {
        let t = triangle::RestTriangle::new(&rest).unwrap();
        let skin = Epidermis::new(lambda_e, gamma).unwrap();
        let moved = x.map(|v| q * v + Vector3::from(b));
        let scale = lambda_e * t.area();
        let (e, e_moved) = (skin.energy(&x, &t), skin.energy(&moved, &t));
        prop_assert!((e_moved - e).abs() <= FRAME_TOLERANCE * e.max(scale), "{e} against {e_moved}");
        let (g, g_moved) = (skin.gradient(&x, &t), skin.gradient(&moved, &t));
        let g_scale = g.amax().max(scale / max_edge(&rest));
        for a in 0..3 {
            let rotated = q * g.fixed_rows::<3>(3 * a);
            let error = (g_moved.fixed_rows::<3>(3 * a) - rotated).amax() / g_scale;
            prop_assert!(error <= FRAME_TOLERANCE, "vertex {a}: {error:e}");
        }
    }
}

#[test]
fn epidermis_is_at_rest_when_area_is_kept() {
    let rest = [
        Vector3::new(0.0, 0.0, 0.0),
        Vector3::new(2.0, 0.0, 0.0),
        Vector3::new(0.0, 1.0, 0.0),
    ];
    let t = triangle::RestTriangle::new(&rest).unwrap();
    let skin = Epidermis::from_young_poisson(10.0, 0.45, 1.0).unwrap();
    // A rotated and sheared (area-preserving) copy: zero energy and zero force.
    let shear = Matrix3::new(0.0, 0.0, 1.0, 1.0, 0.7, 0.0, 0.0, 1.0, 0.0);
    let x = rest.map(|v| shear * v);
    let terms = skin.energy_gradient_hessian(&x, &t);
    assert!(terms.energy.abs() < 1e-14 && terms.gradient.amax() < 1e-13);
}

// ---------------------------------------------------------------------------------------------
// PSD projection

fn min_eigenvalue(m: &Matrix12) -> f64 {
    SymmetricEigen::new(*m).eigenvalues.min()
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    #[test]
    fn projection_gives_psd(entries in proptest::collection::vec(-10.0..10.0f64, 144)) {
        let a = Matrix12::from_column_slice(&entries);
        let m = (a + a.transpose()) * 0.5;
        let p = project_to_psd(&m);
        prop_assert!(min_eigenvalue(&p) >= -1e-12 * m.amax());
        prop_assert_eq!(p, p.transpose());
        // Idempotent up to rounding, and unchanged where m already was PSD.
        prop_assert!((project_to_psd(&p) - p).amax() <= 1e-12 * m.amax());
    }

    #[test]
    fn projection_keeps_psd_input(entries in proptest::collection::vec(-10.0..10.0f64, 144)) {
        let a = Matrix12::from_column_slice(&entries);
        let m = a * a.transpose();
        prop_assert_eq!(project_to_psd(&m), m);
    }

    /// An element Hessian at a compressed, inverted configuration becomes PSD; a rest-state
    /// Hessian (PSD, singular: rigid modes) is left as is.
    #[test]
    fn projection_of_element_hessians(p in params(), (rest, x) in deformed_tet()) {
        let (dm_inv, volume) = rest_data(&rest);
        let m = constrained_neo_hookean(p.mu, p.lambda, p.beta, p.epsilon).unwrap();
        let mut inverted = x;
        inverted.swap(1, 2);
        let h = tet::hessian(&m, &inverted, &dm_inv, volume).unwrap();
        prop_assert!(min_eigenvalue(&project_to_psd(&h)) >= -1e-12 * h.amax());
        let at_rest = tet::hessian(&m, &rest, &dm_inv, volume).unwrap();
        prop_assert_eq!(project_to_psd(&at_rest), at_rest);
    }
}

// ---------------------------------------------------------------------------------------------
// Parameters

#[test]
fn bad_parameters_are_named_errors() {
    let cases: [(Result<Lame, isochor_energies::ParameterError>, &str); 9] = [
        (Lame::from_young_poisson(f64::NAN, 0.3), "E"),
        (Lame::from_young_poisson(0.0, 0.3), "E"),
        (Lame::from_young_poisson(-2.0, 0.3), "E"),
        (Lame::from_young_poisson(1.0, f64::NAN), "nu"),
        (Lame::from_young_poisson(1.0, -1.0), "nu"),
        (Lame::from_young_poisson(1.0, 0.6), "nu"),
        (Lame::from_young_poisson(1.0, 0.5), "nu"),
        (Lame::new(f64::NAN, 1.0), "mu"),
        (Lame::new(1.0, f64::INFINITY), "lambda"),
    ];
    for (result, name) in cases {
        assert_eq!(result.unwrap_err().name, name);
    }
    let lame = Lame::from_young_poisson(1e5, 0.45).unwrap();
    assert!((lame.mu - 1e5 / 2.9).abs() < 1e-9 * lame.mu);
    assert!((lame.lambda - 1e5 * 0.45 / (1.45 * 0.1)).abs() < 1e-9 * lame.lambda);
    assert_eq!(Mooney::new(0.0).unwrap_err().name, "mu");
    assert_eq!(BonetWood::new(-1.0).unwrap_err().name, "mu");
    assert_eq!(MooneyRivlin::new(0.1, -0.2).unwrap_err().name, "c01");
    assert_eq!(MooneyRivlin::new(f64::NAN, 0.2).unwrap_err().name, "c10");
    assert_eq!(Yeoh::new(-0.1, 0.0, 0.0).unwrap_err().name, "c10");
    assert_eq!(Yeoh::new(0.1, f64::INFINITY, 0.0).unwrap_err().name, "c20");
    assert_eq!(
        DistortionalStableNeoHookean::new(0.0).unwrap_err().name,
        "mu"
    );
    assert_eq!(
        stable_neo_hookean(Lame {
            mu: 1.0,
            lambda: -1.0
        })
        .unwrap_err()
        .name,
        "lambda"
    );
    assert_eq!(FbarNeoHookean::new(1.0, 0.0).unwrap_err().name, "epsilon");
    assert_eq!(SheenPenalty::new(f64::NAN).unwrap_err().name, "beta");
    assert_eq!(
        constrained_neo_hookean(1.0, f64::NAN, 1.0, 0.1)
            .unwrap_err()
            .name,
        "lambda"
    );
    assert_eq!(
        Epidermis::from_young_poisson(1.0, 0.5, 1.0)
            .unwrap_err()
            .name,
        "nu"
    );
}
