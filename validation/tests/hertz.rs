//! Hertz contact: a nearly incompressible neo-Hookean sphere of radius `R` pressed onto a
//! rigid plate carries `F = 4/3 E* sqrt(R) delta^(3/2)`, `E* = E / (1 - nu^2)` (Johnson,
//! Contact Mechanics, 1985, eq. 4.22-4.23, a rigid flat), for indentations `delta` small
//! against `R`.
//!
//! The body is the lower hemisphere (`hemisphere`, graded towards the pole that touches) with
//! its equator plane moved down by `u` (`u_z` prescribed, `x` and `y` free but for one
//! centre node held in `x, y` and one node on the `x` axis held in `y`): the half of a sphere
//! squeezed between two plates, whose equator stays plane and slides freely by symmetry. The
//! plate is the analytic half-space (augmented Lagrangian contact, no gap) or a meshed
//! square (IPC barrier contact). The barrier holds the surface a distance below `dhat` off
//! the plate, so a plate `dhat` below the pole gives `delta = u - dhat + g` with a gap
//! `0 < g < dhat`; with `dhat = 1e-5 R` the indentation read as `u - dhat` is off by less
//! than `1e-3` of the smallest `delta` (0.01 R), the force by less than 0.15%. The force is
//! the plate's reaction (the contact forces' sum, or the meshed obstacle's force).
//!
//! The studies (`#[ignore]`, minutes:
//! `cargo test --release --workspace --locked --test validation -- --ignored hertz::`)
//! print the table of docs/validation.md (force against indentation, ours against Hertz,
//! `tet4`/`tet10`, `standard`/`mixed-p1`, over refinement). The few-percent agreement is not
//! reached on the meshes they run: `mixed-p1` comes down from 37% to 15% over Hertz on tet4
//! (res 4 to 8) and to 7-8% on tet10 at res 4.

use isochor_mesh::element::TetElement;
use isochor_mesh::generate::{ball_surface, hemisphere};
use isochor_solvers::{
    Dirichlet, ElementMesh, Material, MeshObstacle, Method, Motion, Obstacle, Problem, Settings,
    Shape, Simulation, Stepping, SurfaceContactSpec, Vec3,
};

/// The sphere's radius (m), Young's modulus (Pa) and Poisson's ratio.
const RADIUS: f64 = 0.01;
const YOUNG: f64 = 1e5;
const NU: f64 = 0.4999;
/// The grading exponent of the hemisphere towards its pole.
const GRADING: f64 = 2.0;
/// The barrier's reach, relative to the radius.
const DHAT: f64 = 1e-5;
/// The largest indentation, relative to the radius, reached in `steps` equal steps.
const DEPTH: f64 = 0.05;

/// Hertz's force at indentation `delta`.
fn hertz(delta: f64) -> f64 {
    4.0 / 3.0 * YOUNG / (1.0 - NU * NU) * RADIUS.sqrt() * delta.powf(1.5)
}

/// How the plate meets the sphere.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Plate {
    /// The analytic half-space `z >= -R` (augmented Lagrangian vertex contact).
    HalfSpace,
    /// A meshed square `dhat` below the pole (barrier contact).
    Barrier,
}

/// One run: element, method, `res`, plate and the number of frames.
#[derive(Debug, Clone, Copy)]
struct Case {
    element: TetElement,
    method: Method,
    res: usize,
    plate: Plate,
    steps: usize,
}

/// The hemisphere problem of `case`, its equator moved down by `u`.
fn problem(case: Case, u: f64) -> Problem {
    let corners = hemisphere(RADIUS, case.res, GRADING).unwrap();
    let mesh = match case.element {
        TetElement::Tet4 => ElementMesh::linear(corners),
        TetElement::Tet10 => {
            ElementMesh::quadratic_on_surface(corners, ball_surface(RADIUS)).unwrap()
        }
    };
    let x = mesh.nodes();
    let tiny = 1e-12 * RADIUS;
    let equator: Vec<usize> = (0..x.len()).filter(|&n| x[n].z.abs() < tiny).collect();
    let centre = *equator.iter().find(|&&n| x[n].norm() < tiny).unwrap();
    let on_x = *equator
        .iter()
        .find(|&&n| x[n].y.abs() < tiny && x[n].x > 0.5 * RADIUS)
        .unwrap();
    let down = Motion::Translate(Vec3::new(0.0, 0.0, -u));
    let held = |nodes: Vec<usize>, axes| Dirichlet {
        nodes,
        axes,
        motion: down,
        curve: None,
    };
    let rest = equator
        .iter()
        .copied()
        .filter(|&n| n != centre && n != on_x)
        .collect();
    let mut builder = Problem::builder(mesh)
        .method(case.method)
        .material(Material::from_young_poisson(YOUNG, NU, 1000.0).unwrap())
        .dirichlet(held(rest, [false, false, true]))
        .dirichlet(held(vec![centre], [true, true, true]))
        .dirichlet(held(vec![on_x], [false, true, true]));
    if case.plate == Plate::HalfSpace {
        builder = builder.obstacle(Obstacle::fixed(Shape::HalfSpace {
            point: Vec3::new(0.0, 0.0, -RADIUS),
            normal: Vec3::z(),
        }));
    }
    builder.build().unwrap()
}

/// The meshed plate: a square of two triangles, `2 R` wide each way, `dhat` below the pole.
fn meshed_plate() -> MeshObstacle {
    let (w, z) = (2.0 * RADIUS, -RADIUS * (1.0 + DHAT));
    MeshObstacle {
        name: "plate".into(),
        vertices: vec![
            Vec3::new(-w, -w, z),
            Vec3::new(w, -w, z),
            Vec3::new(w, w, z),
            Vec3::new(-w, w, z),
        ],
        triangles: vec![[0, 1, 2], [0, 2, 3]],
        translate: Vec3::zeros(),
        rotate: None,
        curve: None,
    }
}

/// `(delta, F)` at every step of `case`, and the Newton iterations of the run.
fn indent(case: Case) -> (Vec<(f64, f64)>, usize) {
    let gap = match case.plate {
        Plate::HalfSpace => 0.0,
        Plate::Barrier => DHAT * RADIUS,
    };
    let u = DEPTH * RADIUS + gap;
    let problem = problem(case, u);
    let nodes = problem.mesh.num_nodes();
    let mut sim = Simulation::new(problem, Settings::default()).unwrap();
    if case.plate == Plate::Barrier {
        sim.set_surface_contact(SurfaceContactSpec {
            dhat: DHAT * RADIUS,
            self_contact: false,
            node_bodies: vec![0; nodes],
        })
        .unwrap();
        sim.set_mesh_obstacles(vec![meshed_plate()]).unwrap();
    }
    let mut curve = Vec::new();
    let summary = sim
        .run(Stepping::adaptive(case.steps), |frame| {
            if frame.frame.is_none() {
                return;
            }
            let force = match case.plate {
                Plate::HalfSpace => frame.contact_forces.iter().map(|f| f.z).sum::<f64>(),
                Plate::Barrier => frame.surface_contact.as_ref().unwrap().obstacle_forces[0].z,
            };
            curve.push((frame.state.t * u - gap, force));
        })
        .unwrap_or_else(|e| panic!("{case:?}: {e}"));
    (curve, summary.newton_iterations())
}

/// The least-squares slope of `log F` against `log delta`.
fn exponent(curve: &[(f64, f64)]) -> f64 {
    let points: Vec<(f64, f64)> = curve.iter().map(|&(d, f)| (d.ln(), f.ln())).collect();
    let n = points.len() as f64;
    let (mx, my) = points
        .iter()
        .fold((0.0, 0.0), |(a, b), &(x, y)| (a + x / n, b + y / n));
    let (sxy, sxx) = points.iter().fold((0.0, 0.0), |(a, b), &(x, y)| {
        (a + (x - mx) * (y - my), b + (x - mx) * (x - mx))
    });
    sxy / sxx
}

/// The relative errors `F / F_Hertz - 1` of a curve.
fn errors(curve: &[(f64, f64)]) -> Vec<f64> {
    curve.iter().map(|&(d, f)| f / hertz(d) - 1.0).collect()
}

fn percent(errors: &[f64]) -> String {
    let shown: Vec<String> = errors
        .iter()
        .map(|e| format!("{:+.1}%", 100.0 * e))
        .collect();
    shown.join(" ")
}

#[test]
fn the_mixed_sphere_follows_hertz_and_the_standard_one_locks() {
    let case = |method| Case {
        element: TetElement::Tet4,
        method,
        res: 4,
        plate: Plate::Barrier,
        steps: 3,
    };
    let (mixed, _) = indent(case(Method::MixedP1));
    let (standard, _) = indent(case(Method::Standard));
    let (em, es) = (errors(&mixed), errors(&standard));
    let (pm, ps) = (exponent(&mixed), exponent(&standard));
    eprintln!(
        "hertz res 4 tet4: mixed-p1 {} (exponent {pm:.3}), standard {} (exponent {ps:.3})",
        percent(&em),
        percent(&es)
    );
    // Closer to Hertz's 3/2 than to a linear spring's 1 (the locked standard's is near 1).
    assert!((pm - 1.5).abs() < 0.25, "mixed-p1 exponent {pm}");
    for (m, s) in em.iter().zip(&es) {
        assert!(*m > 0.0 && *s > 3.0 * m, "mixed {m}, standard {s}");
    }
}

/// Runs each of `methods` on `element` at each of `levels` and prints the table of
/// docs/validation.md; returns the relative errors against Hertz per method and level.
fn study(element: TetElement, methods: &[Method], levels: &[usize]) -> Vec<Vec<Vec<f64>>> {
    let mut table = Vec::new();
    for &method in methods {
        let mut rows: Vec<Vec<f64>> = Vec::new();
        for &res in levels {
            let case = Case {
                element,
                method,
                res,
                plate: Plate::Barrier,
                steps: 5,
            };
            let start = std::time::Instant::now();
            let (curve, iterations) = indent(case);
            eprintln!(
                "hertz {element:?} {} res {res} ({} tets): {:.1} s, {iterations} Newton iterations, exponent {:.3}",
                method.name(),
                24 * res * res * res,
                start.elapsed().as_secs_f64(),
                exponent(&curve)
            );
            for &(d, f) in &curve {
                eprintln!(
                    "  delta/R {:.4}  F {:.6e} N  Hertz {:.6e} N  {:+.2}%",
                    d / RADIUS,
                    f,
                    hertz(d),
                    100.0 * (f / hertz(d) - 1.0)
                );
            }
            rows.push(errors(&curve));
        }
        // The observed order of the error against Hertz between successive levels, in the
        // cell size `1 / res`, at each indentation.
        for (k, w) in rows.windows(2).enumerate() {
            let ratio = levels[k + 1] as f64 / levels[k] as f64;
            let orders: Vec<String> = w[0]
                .iter()
                .zip(&w[1])
                .map(|(a, b)| format!("{:.2}", (a.abs() / b.abs()).ln() / ratio.ln()))
                .collect();
            eprintln!(
                "hertz {element:?} {}: order from res {} to {}: {}",
                method.name(),
                levels[k],
                levels[k + 1],
                orders.join(" ")
            );
        }
        table.push(rows);
    }
    table
}

#[test]
#[ignore = "minutes: cargo test --release --workspace --locked --test validation -- --ignored hertz::"]
fn hertz_study_tet10() {
    let table = study(TetElement::Tet10, &[Method::MixedP1], &[3, 4]);
    // At res 4 (1,536 tets) within 10% from delta / R = 0.02 on: closer than mixed-p1 on
    // 4-node tets at res 8 (12,288 tets, 11-15%). At 0.01 the contact radius spans about one
    // ring of nodes, and the error swings with which ring is inside.
    let finest = table[0].last().unwrap();
    assert!(finest[1..].iter().all(|e| e.abs() < 0.1), "{finest:?}");
}

#[test]
#[ignore = "minutes: cargo test --release --workspace --locked --test validation -- --ignored hertz::"]
fn hertz_study_tet4() {
    let table = study(
        TetElement::Tet4,
        &[Method::MixedP1, Method::Standard],
        &[4, 6, 8],
    );
    let (mixed, standard) = (&table[0], &table[1]);
    // Refinement brings mixed-p1 towards Hertz at the deepest indentation; standard locks.
    for w in mixed.windows(2) {
        assert!(w[1][4] < w[0][4], "{mixed:?}");
    }
    for (m, s) in mixed.iter().flatten().zip(standard.iter().flatten()) {
        assert!(*s > 3.0 * m.abs(), "mixed {m}, standard {s}");
    }
}
