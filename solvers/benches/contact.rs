//! Surface contact at about 50k tets (issue 30's speed split): two stacked slabs, each
//! `48 x 48 x 2` cells (27,648 tets), the upper one's top pushed down and sideways so that
//! every triangle of the two facing surfaces (9,216 of them) is within `dhat` of the other
//! slab, with friction between them (`mixed-p1`, `nu = 0.49`, one quasi-static step).
//!
//! Printed once: the solve's split per Newton iteration from the solver's own timers
//! ([`isochor_solvers::Timings`]: assembly with its contact share, factorization, solve,
//! line search with its CCD share) and the pattern rebuilds. Timed by criterion at the
//! solved state: the broad phase, the barrier's and the friction's gradient and Hessian,
//! the CCD of a line-search step (the step's whole displacement), and the two terms'
//! energies (what a line-search trial adds for contact). `ISOCHOR_BENCH_CELLS` sets the slabs' cells per
//! side (48 by default; 12 for a quick check); `ISOCHOR_BENCH_CONTACT=off` solves the same
//! slabs without contact (each on its own supports) and times nothing, for the peak memory
//! against the run with contact (`/usr/bin/time -v`).

use criterion::{criterion_group, criterion_main, Criterion};
use isochor_mesh::contact::{contact_candidates, ContactSurface, PairFilter};
use isochor_mesh::generate::box_grid;
use isochor_mesh::{ElementMesh, Vec3};
use isochor_solvers::terms::{EnergyTerm, SurfaceContact, SurfaceContactSpec, SurfaceFriction};
use isochor_solvers::{
    Dirichlet, FrictionSpec, LoadLevel, Material, Method, Motion, Problem, RunSummary, Settings,
    Simulation, Stepping, SurfaceFrictionSpec,
};
use std::time::Duration;

/// Side of the slabs (m).
const SIDE: f64 = 0.1;
/// The barrier's reach (m).
const DHAT: f64 = 1e-4;
/// The slabs' gap at rest (m).
const GAP: f64 = 0.5 * DHAT;
/// Friction between the slabs and its slip length (m).
const MU: f64 = 0.5;
const EPSV: f64 = 1e-6;
const YOUNG: f64 = 1e5;
const NU: f64 = 0.49;

/// The two slabs as one mesh, the body of every node, and the problem: the lower slab's
/// bottom clamped, the upper slab's top moved down by 40% of the gap and sideways by 10%.
fn slabs(cells: usize) -> (Problem, Vec<usize>) {
    let thickness = 2.0 * SIDE / cells as f64;
    let slab = |z0: f64| {
        box_grid(
            Vec3::new(0.0, 0.0, z0),
            Vec3::new(SIDE, SIDE, z0 + thickness),
            [cells, cells, 2],
        )
        .expect("a valid box")
    };
    let (mesh, parts) =
        ElementMesh::disjoint_union(vec![slab(-thickness).into(), slab(GAP).into()])
            .expect("disjoint slabs");
    let bodies = (0..mesh.num_nodes())
        .map(|n| usize::from(!parts[0].vertices.contains(&n)))
        .collect();
    let at = |z: f64| -> Vec<usize> {
        (0..mesh.num_nodes())
            .filter(|&n| (mesh.nodes()[n].z - z).abs() < 1e-9)
            .collect()
    };
    let (bottom, top) = (at(-thickness), at(GAP + thickness));
    let problem = Problem::builder(mesh)
        .method(Method::MixedP1)
        .material(Material::from_young_poisson(YOUNG, NU, 1000.0).expect("a valid material"))
        .clamp(bottom)
        .dirichlet(Dirichlet {
            nodes: top,
            axes: [true; 3],
            motion: Motion::Translate(Vec3::new(0.1 * GAP, 0.0, -0.4 * GAP)),
            curve: None,
        })
        .build()
        .expect("a valid problem");
    (problem, bodies)
}

fn contact_spec(bodies: Vec<usize>) -> SurfaceContactSpec {
    SurfaceContactSpec {
        dhat: DHAT,
        self_contact: false,
        node_bodies: bodies,
    }
}

fn friction_spec() -> FrictionSpec {
    FrictionSpec {
        epsv: EPSV,
        obstacles: Vec::new(),
        surfaces: Some(SurfaceFrictionSpec {
            friction: MU,
            pairs: Vec::new(),
        }),
    }
}

/// One quasi-static step of the slabs, with contact and friction if `contact`.
fn solve(problem: Problem, bodies: Vec<usize>, contact: bool) -> RunSummary {
    let mut sim = Simulation::new(problem, Settings::default()).expect("a valid simulation");
    if contact {
        sim.set_surface_contact(contact_spec(bodies))
            .expect("valid contact");
        sim.set_friction(friction_spec()).expect("valid friction");
    }
    sim.run(Stepping::quasi_static(1), |_| {})
        .expect("the slabs converge")
}

fn ms(d: Duration) -> f64 {
    d.as_secs_f64() * 1e3
}

/// The split of the solve per Newton iteration, printed.
fn print_split(summary: &RunSummary, tets: usize) {
    let n = summary.newton_iterations().max(1) as u32;
    let mut t = isochor_solvers::Timings::default();
    let mut wall = Duration::ZERO;
    for r in &summary.reports {
        t += r.timings;
        wall += r.wall_time;
    }
    let rebuilds: usize = summary.reports.iter().map(|r| r.pattern_rebuilds).sum();
    let lags: usize = summary.reports.iter().map(|r| r.friction_lags).sum();
    eprintln!(
        "{tets} tets, {} Newton iterations, {rebuilds} pattern rebuilds, {lags} friction lags; \
         per iteration (ms): step {:.1}, assembly {:.1} (contact {:.1}), \
         factorization {:.1}, solve {:.1}, line search {:.1} (CCD {:.1}); contact / step \
         {:.1}%, CCD / line search {:.1}%",
        summary.newton_iterations(),
        ms(wall / n),
        ms(t.assembly / n),
        ms(t.contact / n),
        ms(t.factorization / n),
        ms(t.solve / n),
        ms(t.line_search / n),
        ms(t.ccd / n),
        100.0 * t.contact.as_secs_f64() / wall.as_secs_f64(),
        100.0 * t.ccd.as_secs_f64() / t.line_search.as_secs_f64(),
    );
}

fn bench(c: &mut Criterion) {
    let cells = std::env::var("ISOCHOR_BENCH_CELLS")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(48);
    let (problem, bodies) = slabs(cells);
    let mesh = problem.mesh.clone();
    let tets = mesh.num_elements();
    let contact = std::env::var("ISOCHOR_BENCH_CONTACT").as_deref() != Ok("off");
    let summary = solve(problem, bodies.clone(), contact);
    print_split(&summary, tets);
    if !contact {
        return;
    }

    // The contact terms on their own, built as the model builds them, at the solved state.
    let rest = mesh.nodes().to_vec();
    let x = summary.final_state.positions.clone();
    let surface = ContactSurface::from_element_surface(&mesh.boundary().expect("a boundary"));
    let h = (6.0 * mesh.corners().rest_volume() / tets as f64).cbrt();
    let mu = YOUNG / (2.0 * (1.0 + NU));
    let contact = SurfaceContact::new(
        contact_spec(bodies.clone()),
        surface.clone(),
        rest.clone(),
        mu * h,
    )
    .expect("a valid contact term");
    contact.update(&x);
    let friction = SurfaceFriction::new(friction_spec().surfaces.expect("surface friction"), EPSV);
    friction.lag(
        &rest,
        &contact.friction_lag(&x, &LoadLevel::quasi_static(0.0)),
    );
    let level = LoadLevel::quasi_static(1.0);
    eprintln!(
        "{} surface triangles, {} pairs within dhat, {} friction pairs",
        surface.triangles().len(),
        contact.num_pairs(),
        friction.num_pairs()
    );

    let mut group = c.benchmark_group("contact");
    group.sample_size(10);
    group.bench_function("broad phase", |b| {
        b.iter(|| contact_candidates(&surface, &x, None, DHAT, PairFilter::BetweenBodies(&bodies)))
    });
    for (name, term) in [
        ("barrier gradient and Hessian", &contact as &dyn EnergyTerm),
        ("friction gradient and Hessian", &friction),
    ] {
        let mut g = vec![0.0; 3 * x.len()];
        let mut hessian = vec![0.0; term.hessian_pattern().len()];
        group.bench_function(name, |b| {
            b.iter(|| term.evaluate(&x, &level, Some(&mut g), Some(&mut hessian)))
        });
    }
    let direction: Vec<f64> = x
        .iter()
        .zip(&rest)
        .flat_map(|(x, r)| (x - r).iter().copied().collect::<Vec<_>>())
        .collect();
    group.bench_function("CCD of the step", |b| {
        b.iter(|| contact.max_step(&rest, &direction))
    });
    group.bench_function("barrier and friction energies (a line-search trial)", |b| {
        b.iter(|| {
            contact.evaluate(&x, &level, None, None).expect("finite")
                + friction.evaluate(&x, &level, None, None).expect("finite")
        })
    });
    group.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
