//! Cloth sheets in a problem, their nodes among the bodies':
//! - a falling sheet's mass and weight: its gravity potential (and, at its rest size, its
//!   kinetic energy) after one implicit Euler step equal those of the lumped mass
//!   `rho h A_0` (`A_0` the rest area, the placed one times `rest_scale^2`);
//! - a sheet dropped onto a block in barrier contact rests on it, and no triangle of either
//!   crosses another;
//! - a band on a rigid cylinder (frictionless): a cloth band of rest circumference `L0` placed
//!   just outside an analytic cylinder of radius `R` and circumference `C = 2 pi R > L0`
//!   settles on it at `C`. Its hoop tension follows the plane-stress Saint Venant-Kirchhoff
//!   membrane at the hoop stretch `lambda_1 = C / L0` with the axial direction free
//!   (`S_22 = 0`, so `S_11 = E E_11`): `T = h lambda_1 S_11 / lambda_2` per unit deformed width,
//!   and the contact force the cylinder carries integrates to Laplace's `p = T / R`.
//!
//! The mesh of a problem needs a tet: a clamped cube beside the sheet stands in for a solid
//! body (it touches nothing).

use isochor_energies::cloth::Fabric;
use isochor_mesh::contact::{intersecting_triangles, ContactSurface};
use isochor_mesh::io::TriangleSurface;
use isochor_mesh::{generate, TetMesh, Vec3};
use isochor_solvers::{
    ClothSheet, Dirichlet, Method, Motion, Obstacle, Problem, Settings, Shape, Simulation,
    Stepping, SurfaceContactSpec,
};
use std::f64::consts::PI;

const RADIUS: f64 = 0.1;
const WIDTH: f64 = 0.05;
/// The band is placed at this multiple of the cylinder's radius...
const PLACED: f64 = 1.02;
/// ...with rest lengths this fraction of the placed ones: `C / L0 = 1 / (0.9 * 1.02)`.
const REST_SCALE: f64 = 0.9;
const YOUNG: f64 = 1e6;
const POISSON: f64 = 0.3;
const THICKNESS: f64 = 5e-4;

/// What the settled band shows.
#[derive(Debug)]
pub struct Settled {
    /// Triangles of the band.
    pub triangles: usize,
    /// Mean distance of its nodes from the axis, over `R`.
    pub radius_ratio: f64,
    /// Its measured hoop and axial stretches against the rest band.
    pub stretches: [f64; 2],
    /// The closed-form hoop tension (N/m) at `C / L0`.
    pub tension: f64,
    /// The contact pressure: the radial contact force over the band's deformed area.
    pub pressure: f64,
}

/// The closed-form stretches `[lambda_1, lambda_2]` and tension `T` of the band on the
/// cylinder: `lambda_1 = C / L0`, `E_22 = -lambda_s E_11 / (2 mu + lambda_s)` from
/// `S_22 = 0`, `S_11 = 2 mu E_11 + lambda_s (E_11 + E_22)`.
fn closed_form(fabric: &Fabric) -> ([f64; 2], f64) {
    let hoop = 1.0 / (REST_SCALE * PLACED);
    let e11 = (hoop * hoop - 1.0) / 2.0;
    let (mu, lambda) = (fabric.mu(), fabric.lambda_s());
    let e22 = -lambda * e11 / (2.0 * mu + lambda);
    let axial = (1.0 + 2.0 * e22).sqrt();
    let s11 = 2.0 * mu * e11 + lambda * (e11 + e22);
    ([hoop, axial], fabric.thickness() * hoop * s11 / axial)
}

/// A clamped block's mesh (the box `[min, max]` of `cells`) with the vertices of `sheet`
/// after its own, the first of them, and the sheet's triangles in that numbering.
fn beside_a_block(
    sheet: &TriangleSurface,
    [min, max]: [Vec3; 2],
    cells: [usize; 3],
) -> (TetMesh, usize, Vec<[usize; 3]>) {
    let block = generate::box_grid(min, max, cells).unwrap();
    let first = block.num_vertices();
    let mut positions = block.positions().to_vec();
    positions.extend(&sheet.vertices);
    let mesh = TetMesh::new(positions, block.tets().to_vec()).unwrap();
    let triangles = sheet
        .triangles
        .iter()
        .map(|t| t.map(|v| v + first))
        .collect();
    (mesh, first, triangles)
}

/// A 2 cm cube away from the sheets of the tests that need no solid.
const ASIDE: [Vec3; 2] = [Vec3::new(0.2, 0.0, 0.0), Vec3::new(0.22, 0.02, 0.02)];

/// A 3 x 2 grid of squares 2 cm wide in the plane z = 0 (12 triangles).
fn flat_sheet() -> TriangleSurface {
    let (nx, ny, h) = (3, 2, 0.02);
    let vertices = (0..=ny)
        .flat_map(|j| (0..=nx).map(move |i| Vec3::new(i as f64 * h, j as f64 * h, 0.0)))
        .collect();
    let index = |i: usize, j: usize| j * (nx + 1) + i;
    let triangles = generate::split_quads(nx, ny, index);
    TriangleSurface {
        vertices,
        triangles,
    }
}

/// A free sheet falls for one step of implicit Euler. Its internal forces add up to zero, so
/// its momentum is `M g dt` and its gravity potential `-M |g|^2 dt^2`, of the lumped mass
/// `M = rho h A_0`; at its rest size (`rest_scale = 1`) it only translates, at velocity
/// `g dt`, with kinetic energy `M |g dt|^2 / 2`. A sheet placed larger than its rest
/// (`rest_scale = 0.8`) also contracts, and its potential tells its mass from its rest area.
#[test]
fn a_falling_sheet_has_the_mass_of_its_rest_area() {
    let (density, dt) = (300.0, 1e-2);
    let g = Vec3::new(0.0, 0.0, -9.81);
    for rest_scale in [1.0, 0.8] {
        let sheet = flat_sheet();
        let (mesh, first, triangles) = beside_a_block(&sheet, ASIDE, [1, 1, 1]);
        let problem = Problem::builder(mesh)
            .method(Method::Standard)
            .clamp(0..first)
            .gravity(g)
            .cloth(ClothSheet {
                name: "sheet".into(),
                triangles,
                fabric: Fabric::new(YOUNG, POISSON, THICKNESS).unwrap(),
                density,
                rest_scale,
            })
            .build()
            .unwrap();
        let mass = density * THICKNESS * (0.06 * 0.04) * rest_scale * rest_scale;
        let mut energies = None;
        let mut sim = Simulation::new(problem, Settings::default()).unwrap();
        sim.run(Stepping::ImplicitEuler { dt, frames: 1 }, |frame| {
            energies = Some(frame.energies);
        })
        .unwrap();
        let energies = energies.unwrap();
        let external = -mass * g.norm_squared() * dt * dt;
        assert!(
            (energies.external / external - 1.0).abs() < 1e-6,
            "rest_scale {rest_scale}: external {} against {external}",
            energies.external
        );
        if rest_scale == 1.0 {
            let kinetic = mass * (g.norm() * dt).powi(2) / 2.0;
            assert!(
                (energies.kinetic / kinetic - 1.0).abs() < 1e-6,
                "kinetic {} against {kinetic}",
                energies.kinetic
            );
        }
    }
}

/// A sheet dropped 2 mm onto a clamped block (barrier contact, `dhat = 1 mm`, the sheet's
/// self-contact on) comes to rest on it, within `dhat` of its top, and no triangle of the
/// sheet or the block crosses another in any accepted state (the independent check of
/// `isochor_mesh::contact::intersecting_triangles` on the block's boundary and the sheet).
#[test]
fn a_dropped_sheet_rests_on_a_block_without_crossing_it() {
    let dhat = 1e-3;
    let mut sheet = flat_sheet();
    sheet.vertices.iter_mut().for_each(|p| p.z = 2e-3);
    let block = [Vec3::new(-0.01, -0.01, -0.02), Vec3::new(0.07, 0.05, 0.0)];
    let (mesh, first, triangles) = beside_a_block(&sheet, block, [4, 3, 1]);
    let mut surface = ContactSurface::from_boundary(&mesh.boundary().unwrap())
        .triangles()
        .to_vec();
    surface.extend(&triangles);
    let surface = ContactSurface::from_triangles(surface);
    let nodes = mesh.num_vertices();
    let problem = Problem::builder(mesh)
        .method(Method::Standard)
        .clamp(0..first)
        .gravity(Vec3::new(0.0, 0.0, -9.81))
        .cloth(ClothSheet {
            name: "sheet".into(),
            triangles,
            fabric: Fabric::new(YOUNG, POISSON, THICKNESS).unwrap(),
            density: 300.0,
            rest_scale: 1.0,
        })
        .build()
        .unwrap();
    let mut sim = Simulation::new(problem, Settings::default()).unwrap();
    sim.set_surface_contact(SurfaceContactSpec {
        dhat,
        self_contact: true,
        node_bodies: (0..nodes).map(|v| usize::from(v >= first)).collect(),
    })
    .unwrap();
    let mut heights = Vec::new();
    sim.run(
        Stepping::ImplicitEuler {
            dt: 5e-3,
            frames: 10,
        },
        |frame| {
            let x = &frame.state.positions;
            let crossing = intersecting_triangles(&surface, x);
            assert!(
                crossing.is_empty(),
                "t {}: {crossing:?} cross",
                frame.state.t
            );
            heights = x[first..].iter().map(|p| p.z).collect();
        },
    )
    .unwrap();
    for z in heights {
        assert!(z > 0.0 && z <= dhat, "a node of the sheet rests at z = {z}");
    }
}

/// Settles the band of `res` cells across its width on the cylinder.
pub fn settle(res: usize) -> Settled {
    let fabric = Fabric::new(YOUNG, POISSON, THICKNESS).unwrap();
    let band = generate::band(PLACED * RADIUS, WIDTH, res).unwrap();
    let (mesh, first, triangles) = beside_a_block(&band, ASIDE, [1, 1, 1]);
    let around = band.vertices.len() / (res + 1);
    // The bottom ring held axially (the band contracts freely across its width), and its
    // vertex on the x axis tangentially (the rotation about the axis).
    let bottom: Vec<usize> = (first..first + around).collect();
    let held = |nodes: Vec<usize>, axes| Dirichlet {
        nodes,
        axes,
        motion: Motion::Fixed,
        curve: None,
    };
    let problem = Problem::builder(mesh)
        .method(Method::Standard)
        .clamp(0..first)
        .dirichlet(held(bottom, [false, false, true]))
        .dirichlet(held(vec![first], [false, true, false]))
        .obstacle(Obstacle::fixed(Shape::Cylinder {
            point: Vec3::zeros(),
            axis: Vec3::z(),
            radius: RADIUS,
        }))
        .cloth(ClothSheet {
            name: "band".into(),
            triangles,
            fabric,
            density: 300.0,
            rest_scale: REST_SCALE,
        })
        .build()
        .unwrap();
    let mut sim = Simulation::new(problem, Settings::default()).unwrap();
    let mut settled = None;
    sim.run(Stepping::adaptive(1), |frame| {
        let x = &frame.state.positions;
        let nodes = first..x.len();
        let radial = |v: usize| x[v].xy().norm();
        let radius = nodes.clone().map(radial).sum::<f64>() / nodes.len() as f64;
        let force: f64 = nodes
            .clone()
            .map(|v| frame.contact_forces[v].xy().dot(&x[v].xy()) / radial(v))
            .sum();
        // The middle ring's polygon against the rest one, and the band's deformed width.
        let ring = |j: usize| (0..around).map(move |i| first + j * around + i);
        let middle: Vec<usize> = ring(res / 2).collect();
        let chords: f64 = (0..around)
            .map(|i| (x[middle[(i + 1) % around]] - x[middle[i]]).norm())
            .sum();
        let rest_chords =
            REST_SCALE * around as f64 * 2.0 * PLACED * RADIUS * (PI / around as f64).sin();
        let width = ring(res).map(|v| x[v].z).sum::<f64>() / around as f64;
        let (_, tension) = closed_form(&fabric);
        settled = Some(Settled {
            triangles: band.triangles.len(),
            radius_ratio: radius / RADIUS,
            stretches: [chords / rest_chords, width / (REST_SCALE * WIDTH)],
            tension,
            pressure: force / (2.0 * PI * RADIUS * width),
        });
    })
    .unwrap();
    settled.unwrap()
}

/// At 2 cells across (26 around, 104 triangles) the band lies on the cylinder, at the
/// closed-form stretches, and carries Laplace's pressure within 2%.
#[test]
fn band_on_a_rigid_cylinder_carries_laplace_pressure() {
    let s = settle(2);
    let fabric = Fabric::new(YOUNG, POISSON, THICKNESS).unwrap();
    let (stretches, tension) = closed_form(&fabric);
    let laplace = tension / RADIUS;
    eprintln!("{s:?}, closed-form stretches {stretches:?}, Laplace {laplace}");
    assert!((s.radius_ratio - 1.0).abs() < 1e-5, "{s:?}");
    for (measured, expected) in s.stretches.iter().zip(stretches) {
        assert!((measured / expected - 1.0).abs() < 1e-5, "{s:?}");
    }
    assert!(
        (s.pressure / laplace - 1.0).abs() < 0.02,
        "{s:?} against {laplace}"
    );
}

/// The docs' table (docs/cloth.md): `T`, `p` and Laplace's `T / R` at 2, 4 and 8 cells
/// across the band. Run with `cargo test --workspace --locked --test validation --
/// cloth_sheets::band_table --ignored --nocapture`.
#[test]
#[ignore = "a study for the docs' table"]
fn band_table() {
    println!("| triangles | T (N/m) | p (Pa) | T / R (Pa) | error |");
    println!("|---|---|---|---|---|");
    for res in [2, 4, 8] {
        let s = settle(res);
        let laplace = s.tension / RADIUS;
        println!(
            "| {} | {:.3} | {:.2} | {:.2} | {:+.3}% |",
            s.triangles,
            s.tension,
            s.pressure,
            laplace,
            100.0 * (s.pressure / laplace - 1.0)
        );
    }
}
