//! Assembly of a cloth sheet's term (membrane of every triangle, discrete-shell bending of
//! every interior edge): energy, gradient and Hessian values of the garment's waistband
//! (`band` generator, radius 133.5 mm, width 60 mm) at res 4, 16 and 64 (448, 7,168 and
//! 114,560 triangles), drawn in by 10% and crumpled, so that the membranes are compressed
//! and the hinges off their rest angles,
//!
//! - `exact/resR`: the exact element Hessians (what Newton factorizes first);
//! - `projected/resR`: each projected onto the PSD cone (the fallback);
//! - `gradient/resR`: energy and gradient only (a line-search trial).

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion};
use isochor_energies::cloth::Fabric;
use isochor_mesh::generate::band;
use isochor_mesh::Vec3;
use isochor_solvers::terms::{Cloth, EnergyTerm};
use isochor_solvers::LoadLevel;
use std::hint::black_box;

const RESOLUTIONS: [usize; 3] = [4, 16, 64];

/// The band's term (rest scale 0.7) and a deformed state of its nodes.
fn setup(res: usize) -> (Cloth, Vec<Vec3>) {
    let surface = band(0.1335, 0.06, res).expect("band");
    let fabric = Fabric::new(4e6, 0.3, 5e-4).expect("fabric");
    let term = Cloth::new(&surface.vertices, surface.triangles, fabric, 0.7).expect("cloth");
    let x = surface
        .vertices
        .iter()
        .enumerate()
        .map(|(i, p)| {
            let wobble = 1e-3 * (i as f64 * 0.7).sin();
            Vec3::new(0.9 * p.x, 0.9 * p.y, p.z) + Vec3::new(wobble, -wobble, 0.5 * wobble)
        })
        .collect();
    (term, x)
}

fn cloth_assembly(c: &mut Criterion) {
    let mut group = c.benchmark_group("cloth");
    group.sample_size(10);
    for res in RESOLUTIONS {
        let (term, x) = setup(res);
        let entries = term.hessian_pattern().len();
        let mut gradient = vec![0.0; 3 * x.len()];
        let mut hessian = vec![0.0; entries];
        for (name, projected) in [("exact", false), ("projected", true)] {
            term.project_hessian(projected);
            group.bench_function(BenchmarkId::new(name, format!("res{res}")), |b| {
                b.iter(|| {
                    gradient.fill(0.0);
                    let e = term
                        .evaluate(
                            &x,
                            &LoadLevel::FULL,
                            Some(&mut gradient),
                            Some(&mut hessian),
                        )
                        .expect("evaluate");
                    black_box(e)
                })
            });
        }
        group.bench_function(BenchmarkId::new("gradient", format!("res{res}")), |b| {
            b.iter(|| {
                gradient.fill(0.0);
                let e = term
                    .evaluate(&x, &LoadLevel::FULL, Some(&mut gradient), None)
                    .expect("evaluate");
                black_box(e)
            })
        });
    }
    group.finish();
}

criterion_group!(benches, cloth_assembly);
criterion_main!(benches);
