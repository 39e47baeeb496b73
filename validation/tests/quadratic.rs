//! The 10-node quadratic tetrahedron end to end, through the solvers (the element kernels
//! are checked against finite differences in `elements.rs` and `terms.rs`):
//!
//! 1. patch tests: prescribed affine motion of every boundary node (mid-edge nodes included)
//!    puts every interior node on the affine map and makes the pressure uniform, on a
//!    straight box and on a curved cylinder;
//! 2. a quadratic field of linear elasticity (pure bending) is reproduced exactly by the
//!    linearized tet10 problem, and not by tet4;
//! 3. the cantilever of the locking study converges to the Taylor-Hood reference at second
//!    order in h (mixed-p1, nu = 0.4999 and 0.5);
//! 4. at nu = 0.5: the volume is kept, the constraint Jacobian has no spurious pressure modes
//!    (tet4's has three), and the pressure does not checkerboard.
//!
//! Run with `-- --nocapture` to see the measured numbers.

use crate::common;

use isochor_constraints::{exact_rule, Measure, NodalCompliance, NodalConstraints, RowShape};
use isochor_mesh::generate::{ball, ball_surface, box_grid, cylinder, cylinder_surface};
use isochor_mesh::probes::displacement_at;
use isochor_mesh::{ElementMesh, TetMesh, Vec3};
use isochor_scenes::probes::checkerboard;
use isochor_scenes::{load_scene, resolve::build, Override};
use isochor_solvers::{
    Dirichlet, Material, Method, Motion, Problem, Settings, Simulation, Stepping,
};
use isochor_validation::constraint_checks::jacobian;
use nalgebra::{DVector, Matrix3};
use std::collections::HashMap;
use std::sync::{Arc, Mutex, OnceLock};
use std::time::Instant;

/// Young's modulus of the patch and bending problems (the cantilever's).
const YOUNG: f64 = 266e3;

/// The bulk modulus `kappa = E / (3 (1 - 2 nu))` of the mixed methods.
fn bulk(nu: f64) -> f64 {
    YOUNG / (3.0 * (1.0 - 2.0 * nu))
}

/// The shear modulus `mu = E / (2 (1 + nu))`.
fn shear(nu: f64) -> f64 {
    YOUNG / (2.0 * (1.0 + nu))
}

/// A problem on `mesh` without loads (and without mass) under `dirichlet`.
fn problem(mesh: ElementMesh, method: Method, nu: f64, dirichlet: Vec<Dirichlet>) -> Problem {
    Problem {
        mesh,
        method,
        material: Material::from_young_poisson(YOUNG, nu, 0.0).expect("material"),
        regions: Vec::new(),
        zones: None,
        dirichlet,
        loads: Vec::new(),
        obstacles: Vec::new(),
        cloths: Vec::new(),
    }
}

/// One condition per node of `nodes`: it moves by `u(X)` at full load.
fn prescribe(mesh: &ElementMesh, nodes: &[usize], u: impl Fn(&Vec3) -> Vec3) -> Vec<Dirichlet> {
    nodes
        .iter()
        .map(|&i| Dirichlet {
            nodes: vec![i],
            axes: [true; 3],
            motion: Motion::Translate(u(&mesh.nodes()[i])),
            curve: None,
        })
        .collect()
}

/// Nodes of the boundary faces: corners and, on a 10-node mesh, mid-edge nodes.
fn boundary_nodes(mesh: &ElementMesh) -> Vec<usize> {
    mesh.boundary().expect("boundary").nodes()
}

/// `max - min` of `values` over their largest magnitude.
fn spread(values: &[f64]) -> f64 {
    let max = values.iter().copied().fold(f64::NEG_INFINITY, f64::max);
    let min = values.iter().copied().fold(f64::INFINITY, f64::min);
    let scale = values.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    (max - min) / scale
}

// ---------------------------------------------------------------------------------------------
// 1. Patch tests

/// What a patch test measured.
struct Patch {
    /// Interior nodes.
    interior: usize,
    /// Largest distance of an interior node from the affine map, over the largest
    /// displacement.
    error: f64,
    /// Spread of the tet pressures (`Simulation::tet_pressures`), relative.
    tet_spread: f64,
    /// Mean tet pressure.
    tet_pressure: f64,
    /// Spread of the nodal pressures (mixed-p1), relative; 0 for standard.
    nodal_spread: f64,
}

/// Solves `method` at `nu` on `mesh` with every boundary node moved by the affine map
/// `x = A X + b` (in one load step), and measures how far the interior nodes land from
/// it and how uniform the pressure is.
fn affine_patch(mesh: &ElementMesh, method: Method, nu: f64, a: &Matrix3<f64>, b: &Vec3) -> Patch {
    let map = |p: &Vec3| a * p + b;
    let boundary = boundary_nodes(mesh);
    let dirichlet = prescribe(mesh, &boundary, |p| map(p) - p);
    let mut sim = Simulation::new(
        problem(mesh.clone(), method, nu, dirichlet),
        Settings::default(),
    )
    .expect("simulation");
    sim.run(Stepping::quasi_static(1), |_| {})
        .unwrap_or_else(|e| panic!("{method} nu {nu}: {e}"));
    let state = sim.state();
    let x = &state.positions;
    let rest = mesh.nodes();
    let largest = rest.iter().map(|p| (map(p) - p).norm()).fold(0.0, f64::max);
    let error = worst_unprescribed(mesh.num_nodes(), &boundary, |i| x[i] - map(&rest[i])) / largest;
    let tet = sim.tet_pressures(state);
    Patch {
        interior: mesh.num_nodes() - boundary.len(),
        error,
        tet_spread: spread(&tet),
        tet_pressure: tet.iter().sum::<f64>() / tet.len() as f64,
        nodal_spread: if state.multipliers.is_empty() {
            0.0
        } else {
            spread(&state.multipliers)
        },
    }
}

/// The mean Cauchy stress `tr(sigma) / 3` of the standard neo-Hookean energy
/// `mu/2 (I_C - 3) - mu log J + lambda/2 log^2 J` at a homogeneous `F`.
fn standard_mean_stress(f: &Matrix3<f64>, nu: f64) -> f64 {
    let mu = shear(nu);
    let lambda = 2.0 * mu * nu / (1.0 - 2.0 * nu);
    let j = f.determinant();
    (mu * (f.norm_squared() / 3.0 - 1.0) + lambda * j.ln()) / j
}

/// [`affine_patch`] with `standard` and `mixed-p1` at nu = 0.45: the interior nodes on the
/// map and a uniform pressure equal to the analytic one, to 1e-10 relative.
fn check_patch(label: &str, mesh: &ElementMesh, a: &Matrix3<f64>, b: &Vec3) {
    let nu = 0.45;
    for method in [Method::Standard, Method::MixedP1] {
        let start = Instant::now();
        let p = affine_patch(mesh, method, nu, a, b);
        // The pressure the affine state must have: kappa (J - 1) for mixed-p1's linear
        // measure (phi = C p with a consistent C), the neo-Hookean mean stress for standard.
        let expected = match method {
            Method::MixedP1 => bulk(nu) * (a.determinant() - 1.0),
            _ => standard_mean_stress(a, nu),
        };
        let pressure_error = (p.tet_pressure - expected).abs() / expected.abs();
        println!(
            "{label}, {method}: {} interior nodes of {}, interior error {:.2e} (of the largest displacement), \
             tet pressure {:.6e} Pa (expected {expected:.6e}, error {pressure_error:.1e}), spread {:.1e} over tets, \
             {:.1e} over nodes [{:.2} s]",
            p.interior,
            mesh.num_nodes(),
            p.error,
            p.tet_pressure,
            p.tet_spread,
            p.nodal_spread,
            start.elapsed().as_secs_f64()
        );
        assert!(p.interior > 0);
        assert!(
            p.error < 1e-10,
            "{label}, {method}: interior error {:e}",
            p.error
        );
        assert!(
            p.tet_spread < 1e-10 && p.nodal_spread < 1e-10 && pressure_error < 1e-10,
            "{label}, {method}: pressure {} vs {expected}, spread {:e} / {:e}",
            p.tet_pressure,
            p.tet_spread,
            p.nodal_spread
        );
    }
}

/// Homogeneous stretch `diag(1.1, 0.95, 0.97)` (volume +1.4%) of a straight 3x2x2-cell box of
/// 10-node tets, prescribed on all 130 boundary nodes (corners and mid-edge nodes); nu =
/// 0.45, one load step. For `standard` and `mixed-p1` the 45 interior nodes land on the
/// affine map and the pressure is uniform (over tets, and over mixed-p1's nodes) and equals
/// the analytic one, all to 1e-10 relative.
///
/// Measured: interior error 2.0e-15 (standard) and 4.8e-16 (mixed-p1) of the largest
/// displacement; pressure 12.652 kPa (standard) and 12.103 kPa (mixed-p1), off the analytic
/// values by 4e-15 and 1e-14, spread 9e-14 and 2e-14.
#[test]
fn patch_test_straight_tet10_box() {
    let corners = box_grid(Vec3::zeros(), Vec3::new(0.3, 0.2, 0.2), [3, 2, 2]).expect("box");
    let mesh = ElementMesh::quadratic(corners);
    let a = Matrix3::from_diagonal(&Vec3::new(1.1, 0.95, 0.97));
    check_patch("straight box", &mesh, &a, &Vec3::zeros());
}

/// A general affine map (stretch, shear and translation; volume +6.5%) of a curved 10-node
/// cylinder (radius 0.05, height 0.1, res 2: mid-edge nodes of the side wall on the circle),
/// prescribed on all 386 boundary nodes; nu = 0.45, one load step. The 343 interior nodes
/// follow the map and the pressure is uniform and analytic, to 1e-10 relative: the elastic
/// term integrates curved elements with the degree-5 rule, exact for `adj(dX/dxi)^T dN/dxi`
/// (degree 3), so the interior forces of an affine state cancel; the constraints use the
/// degree-5 rule too. This mesh does not tell the degree-5 rule from degree 2, though (see
/// [`patch_test_curved_tet10_ball`]); `elements.rs` shows the degree-2 residual on a box with
/// randomly moved mid-edge nodes.
///
/// Measured: interior error 2.9e-15 (standard) and 1.6e-15 (mixed-p1) of the largest
/// displacement; pressure 53.442 kPa and 57.874 kPa, off the analytic values by 5e-15 and
/// 2e-15, spread 3e-14 and 3e-14.
#[test]
fn patch_test_curved_tet10_cylinder() {
    let radius = 0.05;
    let corners: TetMesh = cylinder(radius, 0.1, 2).expect("cylinder");
    let mesh =
        ElementMesh::quadratic_on_surface(corners, cylinder_surface(radius)).expect("curved mesh");
    assert!(!mesh.is_affine());
    let a = Matrix3::new(1.08, 0.05, -0.02, 0.03, 0.96, 0.04, -0.01, 0.02, 1.03);
    let b = Vec3::new(0.004, -0.002, 0.003);
    check_patch("curved cylinder", &mesh, &a, &b);
}

/// The affine patch test on a curved 10-node ball (radius 0.05, res 2: mid-edge nodes of the
/// boundary on the sphere), as [`patch_test_curved_tet10_cylinder`].
///
/// The ball is the case that needs the degree-5 rule: on the extruded cylinder every curved
/// element has the offsets of its moved mid-edge nodes parallel (the two non-vertical edges of
/// a wall face share their mid-angle, the vertical one is not moved), so the correction
/// `sum_k delta_k dN_k/dxi^T` to `dX/dxi` has rank one, its cofactor vanishes, and
/// `adj(dX/dxi)^T dN/dxi` is only quadratic: with the elastic rule forced to degree 2 on
/// curved meshes the cylinder still passes (interior error 3e-15) while the ball fails
/// (interior error 1.2e-5, tet pressures spread by 9e-5).
///
/// Measured: interior error 2.1e-15 (standard) and 1.5e-15 (mixed-p1) of the largest
/// displacement at the 343 interior nodes (of 729); pressure off the analytic values by 5e-15
/// and 1e-15, spread 3e-14 and 1e-14.
#[test]
fn patch_test_curved_tet10_ball() {
    let radius = 0.05;
    let corners: TetMesh = ball(radius, 2).expect("ball");
    let mesh =
        ElementMesh::quadratic_on_surface(corners, ball_surface(radius)).expect("curved mesh");
    assert!(!mesh.is_affine());
    let a = Matrix3::new(1.08, 0.05, -0.02, 0.03, 0.96, 0.04, -0.01, 0.02, 1.03);
    let b = Vec3::new(0.004, -0.002, 0.003);
    check_patch("curved ball", &mesh, &a, &b);
}

// ---------------------------------------------------------------------------------------------
// 2. A quadratic field in the linear limit

/// Pure bending of linear elasticity with Poisson ratio `nu` and curvature `k` about the
/// line through `center` along z: `u = k (-x y, (x^2 + nu (y^2 - z^2)) / 2, nu y z)` in
/// coordinates relative to `center`. Its strain is `eps = k y diag(-1, nu, nu)`, so the
/// stress is uniaxial, `sigma_xx = -E k y`: an equilibrium without body force, traction-free
/// on the planes y = const and z = const, with a linear pressure.
fn bending(center: Vec3, k: f64, nu: f64) -> impl Fn(&Vec3) -> Vec3 + Copy {
    move |p| {
        let d = p - center;
        let (x, y, z) = (d.x, d.y, d.z);
        k * Vec3::new(-x * y, 0.5 * (x * x + nu * (y * y - z * z)), nu * y * z)
    }
}

/// The Poisson ratio of the linear elasticity that `method` reduces to at rest: the standard
/// neo-Hookean energy linearizes to Lame parameters `(lambda, mu)` of `nu`; mixed-p1's
/// distortional energy `mu/2 (I_C - 3) - mu log J` to `(0, mu)`, its volume constraint with
/// compliance `1 / kappa` adding `kappa (tr eps)^2 / 2`: Lame parameters `(kappa, mu)`.
fn linearized_poisson(method: Method, nu: f64) -> f64 {
    match method {
        Method::MixedP1 if nu == 0.5 => 0.5,
        Method::MixedP1 => {
            let (lambda, mu) = (bulk(nu), shear(nu));
            lambda / (2.0 * (lambda + mu))
        }
        _ => nu,
    }
}

/// The response of the problem linearized at rest to its prescribed motion: one Newton
/// system of the single load step at the rest state, solved densely. Returns the
/// displacement of every node and the multipliers (pressures; empty for standard).
fn linear_response(problem: Problem) -> (Vec<Vec3>, Vec<f64>) {
    let n = problem.mesh.num_nodes();
    let mut sim = Simulation::new(problem, Settings::default()).expect("simulation");
    let rest = sim.state().clone();
    let mut linearizer = sim
        .linearizer(Stepping::quasi_static(1), 1)
        .expect("linearizer");
    let system = linearizer.newton_system(&rest).expect("Newton system");
    let step = system
        .matrix
        .clone()
        .lu()
        .solve(&DVector::from_vec(system.rhs.clone()))
        .expect("regular system");
    let mut u = vec![Vec3::zeros(); n];
    for (dof, g) in system.gap.iter().enumerate() {
        u[dof / 3][dof % 3] += g;
    }
    for (k, &dof) in system.free.iter().enumerate() {
        u[dof / 3][dof % 3] += step[k];
    }
    let pressures = step.iter().skip(system.free.len()).copied().collect();
    (u, pressures)
}

/// The box of the bending tests, `[0, 0.2] x [0, 0.1]^2` in 6 x 3 x 3 cells with its interior
/// vertices moved by a deterministic offset of up to 15% of a cell per axis, and the
/// curvature that makes the largest displacement of the bending field 1e-7 of the length.
///
/// The offsets matter for the tet4 control: on the uniform Kuhn grid, P1 elements are
/// nodally exact for this field (their stencil is a consistent difference scheme, exact on
/// quadratics: measured interior error 2.4e-10 with standard at nu = 0.3), like linear elements in 1D.
fn bending_box() -> (TetMesh, Vec3, f64) {
    let size = Vec3::new(0.2, 0.1, 0.1);
    let cells = [6, 3, 3];
    let grid = box_grid(Vec3::zeros(), size, cells).expect("box");
    let h = size.x / cells[0] as f64;
    let wobble =
        |i: usize, k: usize| (((i * 7919 + k * 104_729) % 1009) as f64 / 1009.0 - 0.5) * 0.3 * h;
    let on_boundary =
        |p: &Vec3| (0..3).any(|k| p[k].abs() < 1e-12 || (p[k] - size[k]).abs() < 1e-12);
    let positions = grid
        .positions()
        .iter()
        .enumerate()
        .map(|(i, p)| {
            if on_boundary(p) {
                *p
            } else {
                p + Vec3::new(wobble(i, 0), wobble(i, 1), wobble(i, 2))
            }
        })
        .collect();
    let corners = TetMesh::new(positions, grid.tets().to_vec()).expect("jittered box");
    let center = 0.5 * size;
    let unit = bending(center, 1.0, 0.5);
    let largest = corners
        .positions()
        .iter()
        .map(|p| unit(p).norm())
        .fold(0.0, f64::max);
    (corners, center, 1e-7 * size.x / largest)
}

/// What a bending test measured: displacement error at the free nodes over the largest
/// displacement, and nodal pressure error over the largest pressure (mixed-p1).
fn bending_errors(
    mesh: &ElementMesh,
    method: Method,
    nu: f64,
    prescribed: &[usize],
    center: Vec3,
    k: f64,
) -> (usize, f64, Option<f64>) {
    let nu_lin = linearized_poisson(method, nu);
    let u_exact = bending(center, k, nu_lin);
    let dirichlet = prescribe(mesh, prescribed, u_exact);
    let (u, p) = linear_response(problem(mesh.clone(), method, nu, dirichlet));
    let rest = mesh.nodes();
    let largest = rest.iter().map(|x| u_exact(x).norm()).fold(0.0, f64::max);
    let error =
        worst_unprescribed(mesh.num_nodes(), prescribed, |i| u[i] - u_exact(&rest[i])) / largest;
    let pressure = (!p.is_empty()).then(|| {
        // sigma = 2 mu eps + p I with eps = k y diag(-1, nu, nu): p = kappa tr(eps) for
        // nu < 1/2 (tension positive); at nu = 1/2, sigma_yy = 0 gives p = -2 mu nu k y.
        let exact = |x: &Vec3| {
            let y = x.y - center.y;
            if nu == 0.5 {
                -2.0 * shear(nu) * 0.5 * k * y
            } else {
                bulk(nu) * k * y * (2.0 * nu_lin - 1.0)
            }
        };
        let top = (0..p.len())
            .map(|i| exact(&rest[i]).abs())
            .fold(0.0, f64::max);
        (0..p.len())
            .map(|i| (p[i] - exact(&rest[i])).abs())
            .fold(0.0, f64::max)
            / top
    });
    (mesh.num_nodes() - prescribed.len(), error, pressure)
}

/// Pure bending (a quadratic displacement, linear pressure) of amplitude 1e-7 of the length
/// prescribed on the whole boundary of a 6x3x3-cell box, solved by one Newton system at rest
/// (the linear limit): on 10-node tets `standard` and `mixed-p1` reproduce it at every interior
/// node (and mixed-p1's nodal pressures are `kappa div u`) to rounding, at nu = 0.3 and 0.4999;
/// on the 4-node tets of the same corners the interior error is orders larger (P1 cannot
/// represent it). The corners are jittered ([`bending_box`]): on the uniform grid P1 is
/// nodally exact for this field.
///
/// The prescribed positions `X + u` are rounded to about 1e-9 of `u` (|X| / |u| = 1e7), the
/// floor of every error here; the Newton system is linear in the data, so a larger amplitude
/// would only lower that floor. Displacements are checked at 1e-6. A rounding error of the
/// data that changes the volume moves the pressure `kappa div u` by `kappa / mu` times as much
/// (2.2 at nu = 0.3, 5000 at 0.4999), so pressures are checked at 1e-6 times that ratio.
///
/// Measured (interior displacement error over the largest displacement; pressure error over
/// the largest pressure):
///
/// | nu | method | tet10 | tet10 pressure | tet4 |
/// |---|---|---|---|---|
/// | 0.3 | standard | 4.3e-10 | - | 1.5e-2 |
/// | 0.3 | mixed-p1 | 3.9e-10 | 3.4e-8 | 8.8e-3 |
/// | 0.4999 | standard | 5.9e-9 | - | 5.4e-2 |
/// | 0.4999 | mixed-p1 | 9.9e-10 | 2.2e-6 | 6.1e-2 |
///
/// (tet4's nodal pressures are off by 1.6 and 3.1e3 times the largest pressure.)
#[test]
fn quadratic_bending_is_exact_on_tet10_in_the_linear_limit() {
    let (corners, center, k) = bending_box();
    let quadratic = ElementMesh::quadratic(corners.clone());
    let linear = ElementMesh::linear(corners);
    for nu in [0.3, 0.4999] {
        for method in [Method::Standard, Method::MixedP1] {
            let mut errors = Vec::new();
            for mesh in [&quadratic, &linear] {
                let start = Instant::now();
                let boundary = boundary_nodes(mesh);
                let (free, error, pressure) =
                    bending_errors(mesh, method, nu, &boundary, center, k);
                println!(
                    "bending, nu {nu}, {method}, {:?}: {free} interior nodes, displacement error {error:.2e}, \
                     pressure error {} [{:.2} s]",
                    mesh.kind(),
                    pressure.map_or("-".to_string(), |e| format!("{e:.2e}")),
                    start.elapsed().as_secs_f64()
                );
                errors.push((error, pressure));
            }
            let ((quadratic_error, pressure), (linear_error, _)) = (errors[0], errors[1]);
            assert!(
                quadratic_error < 1e-6,
                "nu {nu}, {method}: tet10 interior error {quadratic_error:e}"
            );
            // The prescribed positions `X + u` carry the rounding of `X`, about 1e-9 of
            // `u`; a perturbation of the boundary data that changes the volume moves the
            // pressure `kappa div u` by up to `kappa / mu` times as much, relative.
            let amplification = (bulk(nu) / shear(nu)).max(1.0);
            assert!(
                pressure.is_none_or(|e| e < 1e-6 * amplification),
                "nu {nu}, {method}: tet10 pressure error {pressure:?}"
            );
            assert!(
                linear_error > 1e4 * quadratic_error,
                "nu {nu}, {method}: tet4 error {linear_error:e} vs tet10 {quadratic_error:e}"
            );
        }
    }
}

/// Pure bending at nu = 0.5 exactly with mixed-p1 (no compliance): prescribed only on the end
/// faces x = 0 and x = 0.2, the sides traction-free (as the exact stress is) so that the
/// pressure is unique. The linearized 10-node Taylor-Hood problem reproduces the displacement
/// and the pressure `-mu k y` exactly (no spurious pressure mode, see
/// [`cantilever_tet10_jacobian_has_full_row_rank`], so the KKT matrix is regular).
///
/// Measured: displacement error 6.0e-10 of the largest displacement at the 539 free nodes,
/// pressure error 1.5e-8 of the largest pressure.
#[test]
fn quadratic_bending_is_exact_on_tet10_at_nu_one_half() {
    let (corners, center, k) = bending_box();
    let mesh = ElementMesh::quadratic(corners);
    let ends: Vec<usize> = (0..mesh.num_nodes())
        .filter(|&i| {
            let x = mesh.nodes()[i].x;
            x.abs() < 1e-12 || (x - 0.2).abs() < 1e-12
        })
        .collect();
    let (free, error, pressure) = bending_errors(&mesh, Method::MixedP1, 0.5, &ends, center, k);
    let pressure = pressure.expect("mixed-p1 has pressures");
    println!(
        "bending, nu 0.5, mixed-p1, ends prescribed: {free} free nodes, displacement error {error:.2e}, \
         pressure error {pressure:.2e}"
    );
    assert!(error < 1e-6 && pressure < 1e-6, "{error:e}, {pressure:e}");
}

// ---------------------------------------------------------------------------------------------
// 3. and 4. The cantilever

/// The converged tip deflection (m) of the cantilever at nu -> 1/2, from independent
/// Taylor-Hood computations extrapolated in h (+-0.3%).
const REFERENCE_TIP: f64 = 37.38e-3;

/// What a cantilever run measured.
#[derive(Debug, Clone)]
struct Cantilever {
    /// Free displacement DOFs plus pressures.
    unknowns: usize,
    /// Elements.
    tets: usize,
    /// `-u_y` at the tip point (0.2, 0.025, 0.025), the scene's `tip_deflection` probe.
    tip: f64,
    /// Deformed over rest volume, minus one.
    volume_change: f64,
    /// [`checkerboard`] of the tet pressures.
    checkerboard: f64,
    /// Wall time of the run.
    seconds: f64,
}

/// The `cantilever` scene (mixed-p1) with `element`, `res` and `nu`, in one load step (its
/// equilibrium does not depend on the ramp, see `locking.rs`), computed once per process.
fn cantilever(element: &str, res: u32, nu: &str) -> Cantilever {
    type Cell = Arc<OnceLock<Cantilever>>;
    static CACHE: OnceLock<Mutex<HashMap<String, Cell>>> = OnceLock::new();
    let sets = [
        "method=mixed-p1".to_string(),
        format!("element={element}"),
        format!("res={res}"),
        format!("nu={nu}"),
        "steps=1".to_string(),
    ];
    let cell: Cell = CACHE
        .get_or_init(Default::default)
        .lock()
        .unwrap()
        .entry(sets.join(" "))
        .or_default()
        .clone();
    cell.get_or_init(|| {
        let overrides: Vec<Override> = sets
            .iter()
            .map(|s| Override::parse(s).expect("override"))
            .collect();
        let scene = load_scene("cantilever", None, &overrides).expect("scene");
        let built = build(&scene).expect("problem");
        let start = Instant::now();
        let mut sim = Simulation::new(built.problem, built.settings).expect("simulation");
        sim.run(built.stepping, |_| {})
            .unwrap_or_else(|e| panic!("cantilever {sets:?}: {e}"));
        let seconds = start.elapsed().as_secs_f64();
        let (mesh, state) = (sim.mesh(), sim.state());
        let x = &state.positions;
        let tip = -displacement_at(mesh, x, &Vec3::new(0.2, 0.025, 0.025))
            .expect("tip")
            .y;
        let run = Cantilever {
            unknowns: sim.num_dofs(),
            tets: mesh.num_elements(),
            tip,
            volume_change: mesh.total_volume_at(x) / mesh.rest_volume() - 1.0,
            checkerboard: checkerboard(mesh.corners(), &sim.tet_pressures(state)),
            seconds,
        };
        println!("cantilever {}: {run:?}", sets.join(" "));
        run
    })
    .clone()
}

/// Prints the refinement table of tet10 mixed-p1 at `nu` over the resolutions 1, 2, 4 and
/// checks it: the observed orders `log2(e_h / e_h/2)` against [`REFERENCE_TIP`] are at least
/// 1.5 on both halvings and the error at res 4 is under 2%. The reference-free order
/// `log2((d_2 - d_1) / (d_4 - d_2))` is at least 1.5 too, and the Richardson extrapolate of the
/// three deflections with it lands within 0.5% of the reference (its own +-0.3% plus the
/// extrapolation's error).
fn check_refinement(nu: &str) {
    let resolutions = [1u32, 2, 4];
    let runs: Vec<Cantilever> = resolutions
        .iter()
        .map(|&res| cantilever("tet10", res, nu))
        .collect();
    let tips: Vec<f64> = runs.iter().map(|r| r.tip).collect();
    let errors: Vec<f64> = tips
        .iter()
        .map(|t| (t - REFERENCE_TIP).abs() / REFERENCE_TIP)
        .collect();
    let orders: Vec<f64> = errors.windows(2).map(|e| (e[0] / e[1]).log2()).collect();
    println!(
        "cantilever, mixed-p1 on tet10, nu = {nu}, one load step; reference {:.2} mm",
        1e3 * REFERENCE_TIP
    );
    println!("res  unknowns  tip (mm)   error  order  time (s)");
    for (i, (res, r)) in resolutions.iter().zip(&runs).enumerate() {
        let order = if i == 0 {
            "    -".to_string()
        } else {
            format!("{:5.2}", orders[i - 1])
        };
        println!(
            "{res:<4} {:>8}  {:>8.3}  {:>6.2}%  {order}  {:>8.2}",
            r.unknowns,
            1e3 * r.tip,
            100.0 * errors[i],
            r.seconds
        );
    }
    let order = ((tips[1] - tips[0]) / (tips[2] - tips[1])).log2();
    let extrapolated = tips[2] + (tips[2] - tips[1]) / (2f64.powf(order) - 1.0);
    let off = (extrapolated - REFERENCE_TIP) / REFERENCE_TIP;
    println!(
        "reference-free order {order:.2}, Richardson extrapolate {:.3} mm ({:+.2}% from the reference)",
        1e3 * extrapolated,
        100.0 * off
    );
    assert!(
        orders.iter().all(|&o| o >= 1.5),
        "nu {nu}: observed orders {orders:?} (errors {errors:?})"
    );
    assert!(
        errors[2] < 0.02,
        "nu {nu}: res 4 error {:.2}%",
        100.0 * errors[2]
    );
    assert!(order >= 1.5, "nu {nu}: reference-free order {order}");
    assert!(off.abs() < 0.005, "nu {nu}: extrapolate {extrapolated}");
}

/// Cantilever, mixed-p1 on 10-node tets, nu = 0.4999, res 1, 2, 4 (one load step): the tip
/// deflection approaches the Taylor-Hood reference 37.38 mm at second order.
///
/// Measured (also the release CLI's numbers):
///
/// | res | unknowns | tip (mm) | error | order |
/// |---|---|---|---|---|
/// | 1 | 236 | 32.652 | 12.65% | - |
/// | 2 | 1281 | 35.961 | 3.80% | 1.74 |
/// | 4 | 8201 | 36.917 | 1.24% | 1.61 |
///
/// Reference-free order 1.79, Richardson extrapolate 37.305 mm (-0.20%). The orders against
/// the reference depend on it: at the ends of its +-0.3% band (37.27 and 37.49 mm) the second
/// halving reads 1.89 and 1.42, which is why the reference-free order is checked too.
#[test]
fn cantilever_tet10_converges_at_nu_0_4999() {
    check_refinement("0.4999");
}

/// As [`cantilever_tet10_converges_at_nu_0_4999`] at nu = 0.5 exactly (zero compliance).
///
/// Measured: tip 32.649, 35.959, 36.915 mm (errors 12.66%, 3.80%, 1.24%; orders 1.74,
/// 1.61), reference-free order 1.79, extrapolate 37.304 mm (-0.20%).
#[test]
fn cantilever_tet10_converges_at_nu_one_half() {
    check_refinement("0.5");
}

/// At nu = 0.5 mixed-p1 on 10-node tets keeps the whole-body volume (exactly integrated,
/// `ElementMesh::total_volume_at`) of the cantilever at res 1, 2, 4 to the bound the solver's
/// constraint tolerance guarantees (`incompressible_volume_bound` of `tests/common`: 1e-10
/// plus rounding; the P1 rows on the corners partition the body, their shape functions
/// summing to one), well inside 1e-8.
///
/// Measured: -4.4e-16, -6.7e-16, +2.0e-14.
#[test]
fn cantilever_tet10_keeps_the_volume_at_nu_one_half() {
    for res in [1, 2, 4] {
        let run = cantilever("tet10", res, "0.5");
        println!("res {res}: volume change {:+.2e}", run.volume_change);
        let bound = common::incompressible_volume_bound(run.tets);
        assert!(
            run.volume_change.abs() < bound.min(1e-8),
            "res {res}: {:e} (bound {bound:e})",
            run.volume_change
        );
    }
}

/// Singular values of the nodal constraint Jacobian `G` (P1 rows on the corners, columns of
/// the free DOFs, clamped face x = 0 removed) of the cantilever at rest, ascending, over the
/// largest.
fn jacobian_singular_values(mesh: &ElementMesh) -> Vec<f64> {
    let set = NodalConstraints::on_elements(
        mesh,
        exact_rule(mesh.kind(), RowShape::Corners),
        Measure::Linear,
        f64::INFINITY,
        NodalCompliance::Consistent,
    )
    .expect("nodal constraints");
    let g = jacobian(&set, mesh.nodes());
    let free: Vec<usize> = (0..3 * mesh.num_nodes())
        .filter(|dof| mesh.nodes()[dof / 3].x > 1e-12)
        .collect();
    let g = g.select_columns(&free);
    let mut s: Vec<f64> = g
        .svd(false, false)
        .singular_values
        .iter()
        .copied()
        .collect();
    s.sort_by(f64::total_cmp);
    let top = s[s.len() - 1];
    s.iter().map(|v| v / top).collect()
}

/// The constraint Jacobian of the cantilever restricted to the free DOFs: on 10-node tets
/// (Taylor-Hood P2-P1) it has full row rank, on the 4-node tets of the same corners (P1-P1)
/// exactly three zero singular values (the spurious pressure modes of Kuhn box meshes, see
/// docs/toolchain.md), at res 1 and 2.
///
/// Measured (smallest singular values over the largest):
///
/// | res | rows | tet10 | tet4 |
/// |---|---|---|---|
/// | 1 | 20 | 0.173, 0.258, 0.273 | 0, 0, 9e-17, then 0.027 |
/// | 2 | 81 | 0.150, 0.170, 0.173 | 0, 0, 2e-16, then 0.018 |
#[test]
fn cantilever_tet10_jacobian_has_full_row_rank() {
    for res in [1, 2] {
        let corners = box_grid(
            Vec3::zeros(),
            Vec3::new(0.2, 0.05, 0.05),
            [4 * res, res, res],
        )
        .expect("beam");
        let quadratic = jacobian_singular_values(&ElementMesh::quadratic(corners.clone()));
        let linear = jacobian_singular_values(&ElementMesh::linear(corners));
        let show = |s: &[f64]| {
            s.iter()
                .take(5)
                .map(|v| format!("{v:.2e}"))
                .collect::<Vec<_>>()
                .join(", ")
        };
        println!(
            "res {res}: {} pressure rows; smallest singular values / largest: tet10 [{}], tet4 [{}]",
            quadratic.len(),
            show(&quadratic),
            show(&linear)
        );
        let zero = 1e-12;
        assert!(
            quadratic[0] > 1e-3,
            "res {res}: tet10 {:?}",
            &quadratic[..5]
        );
        assert!(
            linear[..3].iter().all(|&v| v < zero) && linear[3] > 1e-3,
            "res {res}: tet4 {:?}",
            &linear[..5]
        );
    }
}

/// At nu = 0.5 the tet pressures of mixed-p1 on the cantilever are smooth on 10-node tets and
/// checkerboard on 4-node tets (`isochor_scenes::probes::checkerboard`: mean jump across
/// interior faces over the standard deviation). A smooth field's jumps shrink with h, so
/// tet10's measure halves with each refinement; tet4's stays near 0.8 (the jumps of the
/// spurious modes do not shrink). At res 2 and 4, tet10's is under half of tet4's.
///
/// Measured (res 1, 2, 4): tet10 0.691, 0.303, 0.155; tet4 0.774, 0.811, 0.789.
#[test]
fn cantilever_tet10_pressure_does_not_checkerboard() {
    let measure = |element: &str| -> Vec<f64> {
        [2, 4]
            .iter()
            .map(|&res| cantilever(element, res, "0.5").checkerboard)
            .collect()
    };
    let (quadratic, linear) = (measure("tet10"), measure("tet4"));
    println!(
        "pressure checkerboard at nu = 0.5, res 2 and 4: tet10 {quadratic:.3?}, tet4 {linear:.3?}"
    );
    for i in 0..2 {
        assert!(
            quadratic[i] < 0.5 * linear[i],
            "tet10 {quadratic:?} vs tet4 {linear:?}"
        );
    }
    assert!(
        quadratic[1] < 0.6 * quadratic[0] && linear[1] > 0.8 * linear[0],
        "tet10 {quadratic:?}, tet4 {linear:?}"
    );
}

/// The largest `|error(i)|` over the nodes `0..n` not in the sorted list `prescribed`.
fn worst_unprescribed(n: usize, prescribed: &[usize], error: impl Fn(usize) -> Vec3) -> f64 {
    (0..n)
        .filter(|i| prescribed.binary_search(i).is_err())
        .map(|i| error(i).norm())
        .fold(0.0, f64::max)
}
