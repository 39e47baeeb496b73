//! The inflation of an incompressible neo-Hookean spherical shell (inner radius `A`, outer
//! `B = 1.2 A`), on an octant with symmetry conditions on the three coordinate planes and
//! its cavity's volume measured about the centre: `P / mu = 2 integral_{lambda_b}^{lambda_a}
//! (l - l^-5) / (l^3 - 1) dl = 2 [1/l + 1/(4 l^4)]_{lambda_a}^{lambda_b}` (the integrand is
//! `l^-2 + l^-5`), `lambda_a = a / A`, `b^3 = B^3 + a^3 - A^3`, `lambda_b = b / B`, whose
//! maximum `P / mu = 0.22514` lies at `lambda_a = 1.4699` (docs/validation.md#inflated-shell).
//! Volume control traces the curve through and past the maximum; pressure control stops at
//! the limit point with the message that says so; both agree below it.

use isochor_mesh::generate::{shell_octant, shell_octant_quadratic};
use isochor_mesh::{ElementMesh, Vec3};
use isochor_solvers::{
    Dirichlet, Load, Material, Method, Motion, Problem, Settings, Simulation, SolverError, Stepping,
};

const INNER: f64 = 1.0;
const OUTER: f64 = 1.2;

/// `P / mu` of the exact solution at `lambda_a`.
fn exact(lambda_a: f64) -> f64 {
    let (a, b) = (INNER, OUTER);
    let lambda_b = ((b.powi(3) + (lambda_a * a).powi(3) - a.powi(3)).cbrt()) / b;
    let f = |l: f64| 1.0 / l + 0.25 / l.powi(4);
    2.0 * (f(lambda_b) - f(lambda_a))
}

/// The octant at `res` triangles per edge and `layers` through the wall, 4- or 10-node.
fn mesh(res: usize, layers: usize, quadratic: bool) -> ElementMesh {
    if quadratic {
        shell_octant_quadratic(INNER, OUTER, res, layers).expect("tet10")
    } else {
        ElementMesh::linear(shell_octant(INNER, OUTER, res, layers).expect("shell"))
    }
}

/// The boundary faces of `mesh` (corner triangles) on the sphere of `radius`.
fn faces_at(mesh: &ElementMesh, radius: f64) -> Vec<[usize; 3]> {
    let x = mesh.nodes();
    mesh.boundary()
        .expect("boundary")
        .corners()
        .triangles()
        .iter()
        .filter(|f| f.iter().all(|&v| (x[v].norm() - radius).abs() < 1e-9))
        .copied()
        .collect()
}

/// The octant(s) with symmetry conditions, `mu = 1`, and `loads`.
fn problem(mesh: &ElementMesh, loads: Vec<Load>) -> Problem {
    let x = mesh.nodes();
    let mut builder = Problem::builder(mesh.clone())
        .method(Method::MixedP1)
        .material(Material::from_young_poisson(3.0, 0.5, 1.0).expect("material"));
    for k in 0..3 {
        builder = builder.dirichlet(Dirichlet {
            nodes: (0..x.len()).filter(|&v| x[v][k] == 0.0).collect(),
            axes: [k == 0, k == 1, k == 2],
            motion: Motion::Fixed,
            curve: None,
        });
    }
    for load in loads {
        builder = builder.load(load);
    }
    builder.build().expect("problem")
}

/// The cavity of the octant whose inner radius is `radius`, held at `ratio` at full load.
fn cavity(mesh: &ElementMesh, radius: f64, ratio: f64) -> Load {
    Load::Cavity {
        faces: faces_at(mesh, radius),
        volume_ratio: ratio,
        origin: Vec3::zeros(),
        cap_openings: false,
    }
}

/// A given pressure `p` (in units of `mu`) in the cavity of inner radius `radius`.
fn pressure(mesh: &ElementMesh, radius: f64, p: f64) -> Load {
    Load::Pressure {
        faces: faces_at(mesh, radius),
        pressure: p,
        origin: Vec3::zeros(),
        cap_openings: false,
    }
}

/// Every pressure load's `(cavity volume ratio, P / mu)` at every accepted step of
/// `stepping`, and the run's error.
fn run(problem: Problem, stepping: Stepping) -> (Vec<Vec<(f64, f64)>>, Option<SolverError>) {
    let mut simulation = Simulation::new(problem, Settings::default()).expect("simulation");
    let mut curve = Vec::new();
    let result = simulation.run(stepping, |frame| {
        curve.push(
            frame
                .pressure_loads
                .iter()
                .map(|r| (r.volume_ratio, r.pressure))
                .collect(),
        );
    });
    (curve, result.err().map(|f| f.error))
}

/// The curve of volume control from 1 to `ratio` in `steps` frames.
fn volume_control(mesh: &ElementMesh, ratio: f64, steps: usize) -> Vec<(f64, f64)> {
    let loads = vec![cavity(mesh, INNER, ratio)];
    let (curve, error) = run(problem(mesh, loads), Stepping::quasi_static(steps));
    assert!(error.is_none(), "{error:?}");
    curve.into_iter().map(|c| c[0]).collect()
}

/// The largest relative error of `P(lambda_a)` over the frames.
fn largest_error(curve: &[(f64, f64)]) -> f64 {
    curve
        .iter()
        .map(|&(v, p)| {
            let e = exact(v.cbrt());
            (p - e).abs() / e
        })
        .fold(0.0, f64::max)
}

/// The exact maximum `P / mu` (golden-section search on `lambda_a` in `[1.2, 1.8]`).
fn exact_maximum() -> f64 {
    let (mut a, mut b) = (1.2f64, 1.8f64);
    let g = (5f64.sqrt() - 1.0) / 2.0;
    for _ in 0..100 {
        let (c, d) = (b - g * (b - a), a + g * (b - a));
        if exact(c) > exact(d) {
            b = d;
        } else {
            a = c;
        }
    }
    exact(0.5 * (a + b))
}

#[test]
fn the_formula_has_its_maximum_where_stated() {
    let (l, p) = (1.4699, 0.22514);
    assert!((exact(l) - p).abs() < 5e-5, "{}", exact(l));
    assert!(exact(l - 0.01) < exact(l) && exact(l + 0.01) < exact(l));
    assert!((l.powi(3) - 3.176).abs() < 1e-3);
}

/// Volume control from 1 to 8 (`lambda_a` to 2) in 14 frames on 27 curved 10-node tets
/// (`mixed-p1`): within 1% of the formula at every frame, before, at and past the maximum
/// (measured 0.02%; the convergence table below).
#[test]
fn volume_control_traces_the_shell_through_its_limit_point_on_tet10() {
    let curve = volume_control(&mesh(3, 1, true), 8.0, 14);
    assert_eq!(curve.len(), 14);
    let error = largest_error(&curve);
    assert!(error < 0.01, "largest error {error}");
    // The frames climb to the maximum and come down past it.
    let top = (0..curve.len())
        .max_by(|&a, &b| curve[a].1.total_cmp(&curve[b].1))
        .unwrap();
    assert!(top > 1 && top < curve.len() - 4, "maximum at frame {top}");
    assert!(curve.last().unwrap().1 < 0.9 * curve[top].1);
}

/// The same on 216 4-node tets: linear tets converge slowly (largest error 15%, 11.6%, 6.5%,
/// 3.3% and 2.2% at res 3, 4 (one layer), 4, 6 and 8 (two layers); measured), so the bound
/// is the one of this mesh, 3.3%, with room for rounding.
#[test]
fn volume_control_on_tet4_converges_to_the_shell_curve() {
    let error = largest_error(&volume_control(&mesh(6, 2, false), 8.0, 14));
    assert!(error < 0.035, "largest error {error}");
}

/// Pressure control aimed past the maximum (at 0.24 mu) climbs to within 1% of it with
/// adaptive increments, then ends with the limit-point error naming the load and the
/// pressure reached and suggesting `volume_ratio`, instead of halving its increments down
/// to the smallest.
#[test]
fn pressure_control_stops_at_the_limit_point_and_says_so() {
    let m = mesh(3, 1, true);
    let (curve, error) = run(
        problem(&m, vec![pressure(&m, INNER, 0.24)]),
        Stepping::adaptive(1),
    );
    let reached = curve.last().expect("accepted steps")[0].1;
    let top = exact_maximum();
    eprintln!(
        "reached {reached} of {top} in {} steps: {error:?}",
        curve.len()
    );
    assert!(
        reached > 0.99 * top && reached < 1.001 * top,
        "{reached} of {top}"
    );
    match error {
        Some(SolverError::PressureLimitPoint {
            load: 0, pressure, ..
        }) => {
            assert_eq!(pressure, reached);
            let message = error.unwrap().to_string();
            assert!(message.contains("volume_ratio"), "{message}");
            assert!(message.contains("loads.pressure.0"), "{message}");
        }
        other => panic!("expected the limit point, got {other:?}"),
    }
}

/// Below the limit point, the pressure volume control finds for a volume is the pressure
/// that produces it, to the solver's tolerance.
#[test]
fn volume_control_equals_pressure_control_below_the_limit_point() {
    let m = mesh(3, 1, true);
    let p = 0.2;
    let (curve, error) = run(
        problem(&m, vec![pressure(&m, INNER, p)]),
        Stepping::quasi_static(4),
    );
    assert!(error.is_none(), "{error:?}");
    let ratio = curve.last().unwrap()[0].0;
    let found = volume_control(&m, ratio, 4).last().unwrap().1;
    assert!((found - p).abs() < 1e-6 * p, "{found} for {p}");
}

/// Two cavities in one body (two nested octants, radii 1-1.2 and 2-2.4, about the same
/// centre), each held at its own volume: each keeps it, and their pressures differ as the
/// formula says (it does not depend on the size).
#[test]
fn several_cavities_keep_their_own_volumes() {
    let parts = vec![
        shell_octant_quadratic(INNER, OUTER, 3, 1).unwrap(),
        shell_octant_quadratic(2.0 * INNER, 2.0 * OUTER, 3, 1).unwrap(),
    ];
    let (m, _) = ElementMesh::disjoint_union(parts).unwrap();
    let loads = vec![cavity(&m, INNER, 2.0), cavity(&m, 2.0 * INNER, 3.0)];
    let (curve, error) = run(problem(&m, loads), Stepping::quasi_static(4));
    assert!(error.is_none(), "{error:?}");
    let last = curve.last().unwrap();
    for (&(v, p), target) in last.iter().zip([2.0, 3.0]) {
        assert!((v - target).abs() < 1e-8, "{v} for {target}");
        let e = exact(target.cbrt());
        assert!((p - e).abs() < 0.01 * e, "{p} for {e}");
    }
    assert!(last[1].1 - last[0].1 > 0.01, "{last:?}");
}

#[test]
#[ignore = "a convergence table, not a check: run with --ignored --nocapture"]
fn shell_convergence_table() {
    let cases = [(3, 1), (4, 1), (4, 2), (6, 2), (8, 2), (8, 3)];
    for (quadratic, (res, layers)) in [false, true]
        .into_iter()
        .flat_map(|q| cases.map(|c| (q, c)))
    {
        let m = mesh(res, layers, quadratic);
        let start = std::time::Instant::now();
        let curve = volume_control(&m, 8.0, 14);
        eprintln!(
            "| tet{} | {res} | {layers} | {} | {:.3}% | {:.1} s |",
            if quadratic { 10 } else { 4 },
            m.num_elements(),
            100.0 * largest_error(&curve),
            start.elapsed().as_secs_f64(),
        );
        if (quadratic, res, layers) == (true, 3, 1) || (quadratic, res, layers) == (false, 8, 3) {
            for (v, p) in &curve {
                eprintln!("|| {:.4} | {:.5} | {:.5} |", v.cbrt(), p, exact(v.cbrt()));
            }
        }
    }
}
