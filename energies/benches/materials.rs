//! Throughput of the energy layer: `Psi + P + dP/dF` per material, and tet element
//! energy + gradient + Hessian (the assembly hot path), 4-node (one point) and 10-node (the
//! 4-point rule of the elastic terms).

use criterion::{criterion_group, criterion_main, Criterion, Throughput};
use isochor_energies::kernel::{self, RestPoints};
use isochor_energies::{
    constrained_neo_hookean, quadratic_neo_hookean, standard_neo_hookean, tet, BonetWood,
    DistortionalNeoHookean, FbarNeoHookean, Hyperelastic, Lame, Mooney, MooneyRivlin,
    StableNeoHookean, Yeoh,
};
use isochor_mesh::element::TetQuadrature;
use isochor_mesh::{ElementMesh, TetMesh};
use nalgebra::{Matrix3, Vector3};
use std::hint::black_box;
use std::time::Duration;

const BATCH: usize = 64;

/// Deterministic, mildly deformed `F`s with `det F > 0` (a cheap LCG, no rand dependency).
fn samples() -> Vec<Matrix3<f64>> {
    let mut state = 0x2545_f491_4f6c_dd1d_u64;
    let mut next = move || {
        state = state
            .wrapping_mul(6_364_136_223_846_793_005)
            .wrapping_add(1);
        ((state >> 11) as f64 / (1u64 << 53) as f64 - 0.5) * 0.6
    };
    (0..BATCH)
        .map(|_| Matrix3::identity() + Matrix3::from_fn(|_, _| next()))
        .collect()
}

fn materials() -> Vec<Box<dyn Hyperelastic>> {
    let lame = Lame::from_young_poisson(1e5, 0.45).unwrap();
    vec![
        Box::new(Mooney::new(lame.mu).unwrap()),
        Box::new(DistortionalNeoHookean::new(lame.mu).unwrap()),
        Box::new(BonetWood::new(lame.mu).unwrap()),
        Box::new(StableNeoHookean::from_linear_lame(lame).unwrap()),
        Box::new(FbarNeoHookean::new(lame.mu, 0.1).unwrap()),
        Box::new(MooneyRivlin::new(0.35 * lame.mu, 0.15 * lame.mu).unwrap()),
        Box::new(Yeoh::new(0.5 * lame.mu, -0.05 * lame.mu, 0.01 * lame.mu).unwrap()),
        Box::new(standard_neo_hookean(lame).unwrap()),
        Box::new(quadratic_neo_hookean(lame).unwrap()),
        Box::new(constrained_neo_hookean(lame.mu, 1e5, 1.0, 0.1).unwrap()),
    ]
}

fn densities(c: &mut Criterion) {
    let fs = samples();
    let mut group = c.benchmark_group("psi+P+dPdF");
    group.throughput(Throughput::Elements(BATCH as u64));
    for m in materials() {
        group.bench_function(m.name(), |b| {
            b.iter(|| {
                for f in &fs {
                    let f = black_box(f);
                    black_box(m.energy_density(f).unwrap());
                    black_box(m.pk1(f).unwrap());
                    black_box(m.pk1_derivative(f).unwrap());
                }
            })
        });
    }
    group.finish();
}

fn tet_hessians(c: &mut Criterion) {
    let rest = [
        Vector3::new(0.0, 0.0, 0.0),
        Vector3::new(1.0, 0.1, 0.0),
        Vector3::new(0.2, 0.9, 0.1),
        Vector3::new(0.1, 0.2, 1.1),
    ];
    let dm = Matrix3::from_columns(&[rest[1] - rest[0], rest[2] - rest[0], rest[3] - rest[0]]);
    let (dm_inv, volume) = (dm.try_inverse().unwrap(), dm.determinant() / 6.0);
    let xs: Vec<[Vector3<f64>; 4]> = samples().iter().map(|f| rest.map(|v| f * v)).collect();
    let lame = Lame::from_young_poisson(1e5, 0.45).unwrap();
    let standard = standard_neo_hookean(lame).unwrap();
    let cnh = constrained_neo_hookean(lame.mu, 1e5, 1.0, 0.1).unwrap();

    let mut group = c.benchmark_group("tet element");
    group.throughput(Throughput::Elements(BATCH as u64));
    group.bench_function("energy+gradient+Hessian, standard neo-Hookean", |b| {
        b.iter(|| {
            for x in &xs {
                black_box(
                    tet::energy_gradient_hessian(&standard, black_box(x), &dm_inv, volume).unwrap(),
                );
            }
        })
    });
    group.bench_function("energy+gradient+Hessian, constrained neo-Hookean", |b| {
        b.iter(|| {
            for x in &xs {
                black_box(
                    tet::energy_gradient_hessian(&cnh, black_box(x), &dm_inv, volume).unwrap(),
                );
            }
        })
    });
    let dynamic: &dyn Hyperelastic = &cnh;
    group.bench_function("Hessian, constrained neo-Hookean via &dyn", |b| {
        b.iter(|| {
            for x in &xs {
                black_box(tet::hessian(dynamic, black_box(x), &dm_inv, volume).unwrap());
            }
        })
    });
    // Reference: the same Hessian through the dense 9x12 dF/dx product.
    let d = tet::deformation_jacobian(&dm_inv);
    group.bench_function(
        "Hessian, constrained neo-Hookean, dense dF/dx (reference)",
        |b| {
            b.iter(|| {
                for x in &xs {
                    let f = tet::deformation_gradient(black_box(x), &dm_inv);
                    let a = cnh.pk1_derivative(&f).unwrap();
                    black_box(d.transpose() * a * d * volume);
                }
            })
        },
    );
    // The same element as a straight 10-node tet with the 4-point rule.
    let mesh = ElementMesh::quadratic(TetMesh::new(rest.to_vec(), vec![[0, 1, 2, 3]]).unwrap());
    let geometry = mesh.rest_geometry(TetQuadrature::Degree2).unwrap();
    let points = RestPoints {
        weights: geometry.element_weights(0),
        gradients: geometry.element_gradients(0),
    };
    let nodes = mesh.element(0);
    let x10: Vec<Vec<Vector3<f64>>> = samples()
        .iter()
        .map(|f| mesh.nodes().iter().map(|v| f * v).collect())
        .collect();
    let (mut g, mut h) = (vec![0.0; 30], vec![0.0; 900]);
    for (name, m) in [
        ("standard", &standard as &dyn Hyperelastic),
        ("constrained", &cnh),
    ] {
        group.bench_function(
            format!("energy+gradient+Hessian, {name} neo-Hookean, tet10 4-point rule"),
            |b| {
                b.iter(|| {
                    for x in &x10 {
                        let (g, h) = (Some(g.as_mut_slice()), Some(h.as_mut_slice()));
                        black_box(kernel::evaluate(m, black_box(x), nodes, points, g, h).unwrap());
                    }
                })
            },
        );
    }
    group.finish();
}

fn config() -> Criterion {
    Criterion::default()
        .warm_up_time(Duration::from_millis(300))
        .measurement_time(Duration::from_secs(1))
        .sample_size(20)
}

criterion_group! {
    name = benches;
    config = config();
    targets = densities, tet_hessians
}
criterion_main!(benches);
