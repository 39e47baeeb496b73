//! Hertz contact: a nearly incompressible neo-Hookean sphere of radius `R` pressed onto a
//! rigid plate carries `F = 4/3 E* sqrt(R*) delta^(3/2)` with `E* = E / (1 - nu^2)`,
//! `R* = R`; two identical spheres pressed together carry the same law in their approach
//! with `E* = E / (2 (1 - nu^2))`, `R* = R / 2` (Johnson, Contact Mechanics, 1985, eq.
//! 4.22-4.23), for indentations `delta` small against `R`.
//!
//! The body is the lower hemisphere (`hemisphere`, graded towards the pole that touches) with
//! its equator plane moved down by `u` (`u_z` prescribed, `x` and `y` free but for one
//! centre node held in `x, y` and one node on the `x` axis held in `y`): the half of a sphere
//! squeezed between two plates, whose equator stays plane and slides freely by symmetry. It
//! meets a meshed square plate `dhat` below its pole, or its twin (the same hemisphere turned
//! upside down, pole to pole `dhat` below, its equator held the same way), in IPC barrier
//! contact. The barrier keeps the surfaces a gap `0 < g < dhat` apart, so the approach is read
//! where it is physical: the equators' displacement less the starting distance `dhat` plus
//! the gap `g` left at the end (the smallest distance between the surfaces); each body's
//! indentation is read at its pole. The force is the plate's reaction (the meshed obstacle's
//! force) or the force between the two bodies.
//!
//! The studies (`#[ignore]`, minutes:
//! `cargo test --release --workspace --locked --test validation -- --ignored hertz::`)
//! print the tables of docs/validation.md (force against indentation, ours against Hertz,
//! `tet4`/`tet10`, `standard`/`mixed-p1`, over refinement; the two spheres), with per frame
//! the rings of surface nodes in contact and the finite-sphere compliance `C` of
//! [`Sample::compliance`], which separates the sphere's finite size from the mesh's error.

use isochor_mesh::element::TetElement;
use isochor_mesh::generate::{ball_surface, hemisphere};
use isochor_solvers::{
    Dirichlet, ElementMesh, Material, MeshObstacle, Method, Motion, Problem, Settings, Simulation,
    Stepping, SurfaceContactSpec, Vec3,
};

/// The sphere's radius (m), Young's modulus (Pa) and Poisson's ratio.
const RADIUS: f64 = 0.01;
const YOUNG: f64 = 1e5;
const NU: f64 = 0.4999;
/// The largest indentation of each body, relative to the radius, reached in `steps` frames.
const DEPTH: f64 = 0.05;

/// What the sphere is pressed against.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Counterpart {
    /// A meshed rigid square of two triangles, `2 R` wide each way, `dhat` below the pole.
    Plate,
    /// The same hemisphere upside down, its pole `dhat` below, its equator held.
    Twin,
}

impl Counterpart {
    /// The bodies in contact.
    fn bodies(self) -> usize {
        match self {
            Counterpart::Plate => 1,
            Counterpart::Twin => 2,
        }
    }

    /// `E*` and `R*` of Hertz's law (Johnson eq. 4.22-4.23 with the plate rigid, or both
    /// bodies alike).
    fn moduli(self) -> (f64, f64) {
        let e = YOUNG / (1.0 - NU * NU);
        match self {
            Counterpart::Plate => (e, RADIUS),
            Counterpart::Twin => (0.5 * e, 0.5 * RADIUS),
        }
    }

    /// Hertz's force at approach `delta`.
    fn hertz(self, delta: f64) -> f64 {
        let (e, r) = self.moduli();
        4.0 / 3.0 * e * r.sqrt() * delta.powf(1.5)
    }

    /// Hertz's approach at force `force`.
    fn hertz_approach(self, force: f64) -> f64 {
        let (e, r) = self.moduli();
        (0.75 * force / (e * r.sqrt())).powf(2.0 / 3.0)
    }
}

/// One run: element, method, mesh (`res`, grading exponent towards the pole), barrier reach
/// relative to `R`, counterpart and number of frames.
#[derive(Debug, Clone, Copy)]
struct Case {
    element: TetElement,
    method: Method,
    res: usize,
    grading: f64,
    dhat: f64,
    against: Counterpart,
    steps: usize,
}

impl Case {
    /// The default study case of `element`, `method` and `res` against the plate.
    fn plate(element: TetElement, method: Method, res: usize) -> Case {
        Case {
            element,
            method,
            res,
            grading: 2.0,
            dhat: 1e-5,
            against: Counterpart::Plate,
            steps: 5,
        }
    }
}

/// What one frame measured.
#[derive(Debug, Clone, Copy)]
struct Sample {
    /// The approach: how far the equators came closer, less how far the surfaces did not
    /// (their starting distance `dhat` minus `gap`).
    approach: f64,
    /// Each body's indentation read at its pole (its equator's displacement towards the
    /// contact minus its pole's; zero for the rigid plate): their sum is the approach where
    /// the poles touch.
    indentations: [f64; 2],
    /// The contact force.
    force: f64,
    /// The gap the barrier leaves: the smallest distance between the surfaces.
    gap: f64,
    /// How many surface nodes on the ray from the pole along `x` are within the barrier's
    /// reach of the contact plane (the pole included).
    rings: usize,
}

impl Sample {
    /// `F / F_Hertz - 1`.
    fn error(&self, against: Counterpart) -> f64 {
        self.force / against.hertz(self.approach) - 1.0
    }

    /// The finite-sphere compliance `C = (delta_Hertz(F) - delta) E R / F` per body: a
    /// sphere's centre is at a finite distance from its contact, so its approach falls short
    /// of the half-space's by a term linear in `F` (the far field of the contact pressure,
    /// `O(a / R)` relative to `delta`). A constant `C` over indentations and meshes is that
    /// effect; a `C` that moves with refinement is the mesh's error.
    fn compliance(&self, against: Counterpart) -> f64 {
        let shortfall = against.hertz_approach(self.force) - self.approach;
        shortfall / against.bodies() as f64 * YOUNG * RADIUS / self.force
    }
}

/// The hemisphere of `case`.
fn hemisphere_mesh(case: Case) -> ElementMesh {
    let corners = hemisphere(RADIUS, case.res, case.grading).unwrap();
    match case.element {
        TetElement::Tet4 => ElementMesh::linear(corners),
        TetElement::Tet10 => {
            ElementMesh::quadratic_on_surface(corners, ball_surface(RADIUS)).unwrap()
        }
    }
}

/// The node of `nodes` at `p`.
fn node_at(x: &[Vec3], mut nodes: impl Iterator<Item = usize>, p: Vec3) -> usize {
    nodes.find(|&n| (x[n] - p).norm() < 1e-9 * RADIUS).unwrap()
}

/// The conditions that move the equator plane `z = height` of the body of `nodes` by
/// `motion` in `z` and leave it free to slide but for its rigid motions in `x, y`.
fn equator_held(x: &[Vec3], nodes: &[usize], height: f64, motion: Motion) -> [Dirichlet; 3] {
    let tiny = 1e-9 * RADIUS;
    let equator: Vec<usize> = nodes
        .iter()
        .copied()
        .filter(|&n| (x[n].z - height).abs() < tiny)
        .collect();
    let centre = node_at(x, equator.iter().copied(), Vec3::new(0.0, 0.0, height));
    let on_x = node_at(x, equator.iter().copied(), Vec3::new(RADIUS, 0.0, height));
    let held = |nodes: Vec<usize>, axes| Dirichlet {
        nodes,
        axes,
        motion,
        curve: None,
    };
    let rest = equator
        .iter()
        .copied()
        .filter(|&n| n != centre && n != on_x)
        .collect();
    [
        held(rest, [false, false, true]),
        held(vec![centre], [true, true, true]),
        held(vec![on_x], [false, true, true]),
    ]
}

/// The meshed plate: a square of two triangles, `2 R` wide each way, `dhat` below the pole.
fn meshed_plate(dhat: f64) -> MeshObstacle {
    let (w, z) = (2.0 * RADIUS, -RADIUS - dhat);
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

/// The samples at every frame of `case`, and the Newton iterations of the run.
fn indent(case: Case) -> (Vec<Sample>, usize) {
    let dhat = case.dhat * RADIUS;
    let u = case.against.bodies() as f64 * DEPTH * RADIUS + dhat;
    let upper = hemisphere_mesh(case);
    let mut parts = vec![upper.clone()];
    if case.against == Counterpart::Twin {
        // Turned about the `x` axis (the hemisphere is symmetric in `y`, so this is its
        // mirror image in the contact plane) and moved down.
        let twin = upper.mapped(|p| Vec3::new(p.x, -p.y, -p.z - 2.0 * RADIUS - dhat));
        parts.push(twin.unwrap());
    }
    let (mesh, layout) = ElementMesh::disjoint_union(parts).unwrap();
    let x = mesh.nodes().to_vec();
    let nodes: Vec<Vec<usize>> = layout.iter().map(|part| part.nodes().collect()).collect();
    let mut node_bodies = vec![0; x.len()];
    for &n in nodes.get(1).into_iter().flatten() {
        node_bodies[n] = 1;
    }
    let down = Motion::Translate(Vec3::new(0.0, 0.0, -u));
    let mut held = equator_held(&x, &nodes[0], 0.0, down).to_vec();
    let pole = node_at(&x, nodes[0].iter().copied(), Vec3::new(0.0, 0.0, -RADIUS));
    let lower_pole = nodes.get(1).map(|lower| {
        held.extend(equator_held(&x, lower, -2.0 * RADIUS - dhat, Motion::Fixed));
        node_at(
            &x,
            lower.iter().copied(),
            Vec3::new(0.0, 0.0, -RADIUS - dhat),
        )
    });
    let mut builder = Problem::builder(mesh)
        .method(case.method)
        .material(Material::from_young_poisson(YOUNG, NU, 1000.0).unwrap());
    for condition in held {
        builder = builder.dirichlet(condition);
    }
    let tiny = 1e-9 * RADIUS;
    let ray: Vec<usize> = nodes[0]
        .iter()
        .copied()
        .filter(|&n| x[n].y.abs() < tiny && x[n].x > -tiny && (x[n].norm() - RADIUS).abs() < tiny)
        .collect();
    let mut sim = Simulation::new(builder.build().unwrap(), Settings::default()).unwrap();
    sim.set_surface_contact(SurfaceContactSpec {
        dhat,
        self_contact: false,
        node_bodies,
    })
    .unwrap();
    if case.against == Counterpart::Plate {
        sim.set_mesh_obstacles(vec![meshed_plate(dhat)]).unwrap();
    }
    let mut samples = Vec::new();
    let summary = sim
        .run(Stepping::adaptive(case.steps), |frame| {
            if frame.frame.is_none() {
                return;
            }
            let p = &frame.state.positions;
            let contact = frame.surface_contact.as_ref().unwrap();
            // The surfaces started `dhat` apart and end `gap` apart.
            let gap = contact.min_distance;
            let upper = frame.state.t * u - (x[pole].z - p[pole].z);
            // The lower body's indentation, the contact plane, the barrier's reach from it
            // and the force on the upper body.
            let (lower, plane, reach, force) = match lower_pole {
                None => {
                    let force = contact.obstacle_forces[0].z;
                    (0.0, -RADIUS - dhat, dhat, force)
                }
                Some(q) => {
                    let mid = 0.5 * (p[pole].z + p[q].z);
                    let force = contact.body_pair_forces[0].z;
                    (x[q].z - p[q].z, mid, 0.5 * dhat, force)
                }
            };
            samples.push(Sample {
                approach: frame.state.t * u - dhat + gap,
                indentations: [upper, lower],
                force,
                gap,
                rings: ray.iter().filter(|&&n| p[n].z - plane < reach).count(),
            });
        })
        .unwrap_or_else(|e| panic!("{case:?}: {e}"));
    (samples, summary.newton_iterations())
}

/// The least-squares slope of `log F` against `log delta`.
fn exponent(samples: &[Sample]) -> f64 {
    let points: Vec<(f64, f64)> = samples
        .iter()
        .map(|s| (s.approach.ln(), s.force.ln()))
        .collect();
    let n = points.len() as f64;
    let (mx, my) = points
        .iter()
        .fold((0.0, 0.0), |(a, b), &(x, y)| (a + x / n, b + y / n));
    let (sxy, sxx) = points.iter().fold((0.0, 0.0), |(a, b), &(x, y)| {
        (a + (x - mx) * (y - my), b + (x - mx) * (x - mx))
    });
    sxy / sxx
}

/// The relative errors `F / F_Hertz - 1` of a run.
fn errors(samples: &[Sample], against: Counterpart) -> Vec<f64> {
    samples.iter().map(|s| s.error(against)).collect()
}

fn percent(errors: &[f64]) -> String {
    let shown: Vec<String> = errors
        .iter()
        .map(|e| format!("{:+.1}%", 100.0 * e))
        .collect();
    shown.join(" ")
}

/// Runs `case`, prints its samples (one table row per frame), returns them.
fn report(case: Case) -> Vec<Sample> {
    let start = std::time::Instant::now();
    let (samples, iterations) = indent(case);
    eprintln!(
        "hertz {:?} {:?} {} res {} grading {} dhat {:.0e} R ({} tets per body): {:.1} s, {iterations} Newton iterations, exponent {:.3}",
        case.against,
        case.element,
        case.method.name(),
        case.res,
        case.grading,
        case.dhat,
        24 * case.res.pow(3),
        start.elapsed().as_secs_f64(),
        exponent(&samples)
    );
    for s in &samples {
        eprintln!(
            "  approach/R {:.4} (bodies {:.4} {:.4})  F {:.5e} N  Hertz {:.5e} N  {:+.2}%  gap/dhat {:.2}  rings {}  C {:+.3}",
            s.approach / RADIUS,
            s.indentations[0] / RADIUS,
            s.indentations[1] / RADIUS,
            s.force,
            case.against.hertz(s.approach),
            100.0 * s.error(case.against),
            s.gap / (case.dhat * RADIUS),
            s.rings,
            s.compliance(case.against),
        );
    }
    samples
}

/// Prints the observed order of the error against Hertz between successive levels, in the
/// cell size `1 / res`, at each frame.
fn orders(name: &str, levels: &[usize], rows: &[Vec<f64>]) {
    for (k, w) in rows.windows(2).enumerate() {
        let ratio = levels[k + 1] as f64 / levels[k] as f64;
        let orders: Vec<String> = w[0]
            .iter()
            .zip(&w[1])
            .map(|(a, b)| format!("{:.2}", (a.abs() / b.abs()).ln() / ratio.ln()))
            .collect();
        eprintln!(
            "hertz {name}: order from res {} to {}: {}",
            levels[k],
            levels[k + 1],
            orders.join(" ")
        );
    }
}

/// Runs `base` at each of `levels`; the errors per level.
fn study(base: Case, levels: &[usize]) -> Vec<Vec<f64>> {
    let rows: Vec<Vec<f64>> = levels
        .iter()
        .map(|&res| errors(&report(Case { res, ..base }), base.against))
        .collect();
    let name = format!(
        "{:?} {} grading {}",
        base.element,
        base.method.name(),
        base.grading
    );
    orders(&name, levels, &rows);
    rows
}

#[test]
fn the_mixed_sphere_follows_hertz_and_the_standard_one_locks() {
    let case = |method| Case {
        steps: 3,
        dhat: 1e-3,
        ..Case::plate(TetElement::Tet4, method, 4)
    };
    let (mixed, _) = indent(case(Method::MixedP1));
    let (standard, _) = indent(case(Method::Standard));
    let (em, es) = (
        errors(&mixed, Counterpart::Plate),
        errors(&standard, Counterpart::Plate),
    );
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

#[test]
fn two_spheres_share_the_approach_and_carry_the_sphere_on_the_plate() {
    let twin = Case {
        against: Counterpart::Twin,
        steps: 2,
        dhat: 1e-3,
        ..Case::plate(TetElement::Tet4, Method::MixedP1, 3)
    };
    let (pair, _) = indent(twin);
    let (plate, _) = indent(Case {
        against: Counterpart::Plate,
        ..twin
    });
    for (p, s) in pair.iter().zip(&plate) {
        let [a, b] = p.indentations;
        let (ep, es) = (p.error(Counterpart::Twin), s.error(Counterpart::Plate));
        eprintln!(
            "hertz two spheres tet4 res 3: approach/R {:.4}, indentations/R {:.5} {:.5}, error {:+.1}% (one on the plate {:+.1}%)",
            p.approach / RADIUS,
            a / RADIUS,
            b / RADIUS,
            100.0 * ep,
            100.0 * es
        );
        // The two bodies are mirror images in the contact plane, and so is the solution.
        assert!((a - b).abs() < 1e-3 * p.approach, "indentations {a}, {b}");
        // By that symmetry the contact plane stays flat and frictionless: each sphere of the
        // pair is the sphere on the plate, and Hertz's combined law holds as the single one
        // does (a wrong combined modulus or radius would be off by a factor of 2 or more).
        // What differs is the barrier between two surfaces instead of one, within the
        // effect of `dhat` itself (under 2 points at 1e-3 R, `hertz_study_effects`).
        assert!((ep - es).abs() < 0.02, "pair {ep}, plate {es}");
    }
}

#[test]
#[ignore = "minutes: cargo test --release --workspace --locked --test validation -- --ignored hertz::"]
fn hertz_study_tet10() {
    let table = study(Case::plate(TetElement::Tet10, Method::MixedP1, 0), &[3, 4]);
    // At res 4 (1,536 tets) within 10% from delta / R = 0.02 on.
    let finest = table.last().unwrap();
    assert!(finest[1..].iter().all(|e| e.abs() < 0.1), "{finest:?}");
}

#[test]
#[ignore = "minutes: cargo test --release --workspace --locked --test validation -- --ignored hertz::"]
fn hertz_study_tet4() {
    let levels = [4, 6, 8];
    let mixed = study(Case::plate(TetElement::Tet4, Method::MixedP1, 0), &levels);
    let standard = study(Case::plate(TetElement::Tet4, Method::Standard, 0), &levels);
    // Refinement brings mixed-p1 towards Hertz at the deepest indentation; standard locks.
    for w in mixed.windows(2) {
        assert!(w[1][4] < w[0][4], "{mixed:?}");
    }
    for (m, s) in mixed.iter().flatten().zip(standard.iter().flatten()) {
        assert!(*s > 3.0 * m.abs(), "mixed {m}, standard {s}");
    }
}

#[test]
#[ignore = "minutes: cargo test --release --workspace --locked --test validation -- --ignored hertz::"]
fn hertz_study_effects() {
    // (d) The barrier's reach against the indentation: the approach is read with the gap
    // it leaves, so a reach ten times smaller than 1e-4 R must not move the force.
    let reaches = [1e-5, 1e-4, 1e-3];
    let runs: Vec<Vec<Sample>> = reaches
        .iter()
        .map(|&dhat| {
            report(Case {
                dhat,
                ..Case::plate(TetElement::Tet4, Method::MixedP1, 4)
            })
        })
        .collect();
    for (a, b) in runs[0].iter().zip(&runs[1]) {
        let (ea, eb) = (a.error(Counterpart::Plate), b.error(Counterpart::Plate));
        assert!((ea - eb).abs() < 5e-3, "dhat 1e-5 R: {ea}, 1e-4 R: {eb}");
    }
    // (b) The grading towards the pole: how many rings of nodes the contact spans.
    for grading in [1.5, 2.0, 3.0] {
        report(Case {
            grading,
            ..Case::plate(TetElement::Tet10, Method::MixedP1, 3)
        });
    }
}

#[test]
#[ignore = "minutes: cargo test --release --workspace --locked --test validation -- --ignored hertz::"]
fn hertz_study_two_spheres() {
    // Slow: the barrier between two bodies at `dhat = 1e-5 R` took 512 Newton iterations
    // against 93 on the plate (19 min on the project's machine under load).
    let twin = Case {
        against: Counterpart::Twin,
        ..Case::plate(TetElement::Tet10, Method::MixedP1, 3)
    };
    let pair = report(twin);
    let plate = report(Case {
        against: Counterpart::Plate,
        ..twin
    });
    for (p, s) in pair.iter().zip(&plate) {
        let [a, b] = p.indentations;
        assert!((a - b).abs() < 1e-3 * p.approach, "indentations {a}, {b}");
        // Each sphere of the pair is the sphere on the plate (see the fast test).
        let (ep, es) = (p.error(Counterpart::Twin), s.error(Counterpart::Plate));
        assert!((ep - es).abs() < 0.02, "pair {ep}, plate {es}");
    }
}

#[test]
#[ignore = "minutes to an hour, one level of a study: scripts/hertz-levels.sh"]
fn hertz_study_level() {
    // The level from the environment, so that each runs in a process of its own (its time
    // and peak memory measured alone): HERTZ_RES (4, seconds), HERTZ_ELEMENT (tet4),
    // HERTZ_METHOD (mixed-p1).
    let var = |key: &str, default: &str| std::env::var(key).unwrap_or_else(|_| default.into());
    let res: usize = var("HERTZ_RES", "4")
        .parse()
        .expect("HERTZ_RES, a mesh level");
    let element = TetElement::from_name(&var("HERTZ_ELEMENT", "tet4")).expect("HERTZ_ELEMENT");
    let method: Method = var("HERTZ_METHOD", "mixed-p1").parse().unwrap();
    let samples = report(Case::plate(element, method, res));
    // A mixed method follows the 3/2 power (fitted 1.41-1.52 at res 4-12 on tet4).
    let p = exponent(&samples);
    assert!(
        method == Method::Standard || (p - 1.5).abs() < 0.1,
        "exponent {p}"
    );
}
