//! The surface-contact and surface-friction terms evaluate their pairs in parallel (rayon);
//! their energy, gradient and Hessian values must not depend on the number of threads. Two
//! slabs a fraction of `dhat` apart, perturbed, with hundreds of barrier and friction pairs,
//! evaluated in a one-thread and a two-thread pool: the same bits.

use isochor_mesh::contact::ContactSurface;
use isochor_mesh::generate::box_grid;
use isochor_mesh::{ElementMesh, Vec3};
use isochor_solvers::terms::{EnergyTerm, SurfaceContact, SurfaceContactSpec, SurfaceFriction};
use isochor_solvers::{LoadLevel, SurfaceFrictionSpec};

const DHAT: f64 = 1e-3;

/// Two `8 x 8 x 1`-cell slabs of side 0.1 m, the upper `DHAT / 2` above the lower, as one
/// mesh, with the body of every node.
fn slabs() -> (ElementMesh, Vec<usize>) {
    let slab = |z0: f64| {
        box_grid(
            Vec3::new(0.0, 0.0, z0),
            Vec3::new(0.1, 0.1, z0 + 0.01),
            [8, 8, 1],
        )
        .unwrap()
    };
    let (mesh, parts) =
        ElementMesh::disjoint_union(vec![slab(-0.01).into(), slab(0.5 * DHAT).into()]).unwrap();
    let mut bodies = vec![0; mesh.num_nodes()];
    parts[1].nodes().for_each(|n| bodies[n] = 1);
    (mesh, bodies)
}

/// `rest` moved by a smooth field of `scale` (no symmetry left between the pairs).
fn moved(rest: &[Vec3], scale: f64) -> Vec<Vec3> {
    rest.iter()
        .enumerate()
        .map(|(i, p)| {
            let t = i as f64;
            p + Vec3::new((1.3 * t).sin(), (0.7 * t).cos(), (2.1 * t).sin()) * scale
        })
        .collect()
}

/// A term's energy alone, energy with gradient, and energy, gradient and Hessian values in
/// its pattern at `x`, as bits.
fn values(term: &dyn EnergyTerm, x: &[Vec3]) -> Vec<u64> {
    let level = LoadLevel::quasi_static(1.0);
    let alone = term.evaluate(x, &level, None, None).unwrap();
    let mut g = vec![0.0; 3 * x.len()];
    let with_gradient = term.evaluate(x, &level, Some(&mut g), None).unwrap();
    let mut gradient = vec![0.0; 3 * x.len()];
    let mut hessian = vec![0.0; term.hessian_pattern().len()];
    let all = term
        .evaluate(x, &level, Some(&mut gradient), Some(&mut hessian))
        .unwrap();
    assert!(
        alone > 0.0 && alone.is_finite(),
        "{}: energy {alone}",
        term.name()
    );
    // The three paths share one kernel: the same energy, and the same gradient.
    assert_eq!(alone.to_bits(), with_gradient.to_bits(), "{}", term.name());
    assert_eq!(alone.to_bits(), all.to_bits(), "{}", term.name());
    assert_eq!(g, gradient, "{}", term.name());
    assert!(hessian.iter().any(|&v| v != 0.0), "{}", term.name());
    [alone]
        .into_iter()
        .chain(gradient)
        .chain(hessian)
        .map(f64::to_bits)
        .collect()
}

/// The barrier's and the friction's values at a perturbed state, in a pool of `threads`.
fn evaluated(threads: usize) -> (usize, usize, Vec<u64>, Vec<u64>) {
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .unwrap();
    pool.install(|| {
        let (mesh, bodies) = slabs();
        let rest = mesh.nodes().to_vec();
        let surface = ContactSurface::from_element_surface(&mesh.boundary().unwrap());
        let spec = SurfaceContactSpec {
            dhat: DHAT,
            self_contact: false,
            node_bodies: bodies,
        };
        let contact = SurfaceContact::new(spec, surface, rest.clone(), 1e4).unwrap();
        let lagged = moved(&rest, 0.1 * DHAT);
        contact.update(&lagged);
        let friction = SurfaceFriction::new(
            SurfaceFrictionSpec {
                friction: 0.5,
                pairs: Vec::new(),
            },
            1e-6,
        );
        friction.lag(
            &rest,
            &contact.friction_lag(&lagged, &LoadLevel::quasi_static(0.0)),
        );
        let x = moved(&lagged, 0.02 * DHAT);
        contact.update(&x);
        (
            contact.num_pairs(),
            friction.num_pairs(),
            values(&contact, &x),
            values(&friction, &x),
        )
    })
}

#[test]
fn contact_values_have_the_same_bits_on_one_and_two_threads() {
    let one = evaluated(1);
    let two = evaluated(2);
    eprintln!("{} barrier pairs, {} friction pairs", one.0, one.1);
    assert!(
        one.0 >= 300 && one.1 >= 100,
        "{} and {} pairs",
        one.0,
        one.1
    );
    assert_eq!(one.0, two.0);
    assert_eq!(one.1, two.1);
    assert!(one.2 == two.2, "the barrier's values differ");
    assert!(one.3 == two.3, "the friction's values differ");
}
