//! Speed of the contact geometry: the broad phase (barrier candidates within `dhat`, and
//! swept boxes for the CCD) and every candidate pair's squared distance with its gradient
//! and Hessian, on two balls about 9,600 surface triangles in all, 1% of their radius
//! apart; and the CCD over the 3,409 benchmark queries of Wang et al. 2021.

use criterion::{criterion_group, criterion_main, Criterion};
use isochor_mesh::contact::{
    contact_candidates, edge_edge_distance_kind, point_triangle_distance_kind, read_ccd_queries,
    CcdQuery, CcdSettings, ContactSurface, PairFilter, QueryKind,
};
use isochor_mesh::generate::ball;
use isochor_mesh::{BoundarySurface, Vec3};
use std::hint::black_box;
use std::path::Path;

/// Two unit balls at `res` (`48 res^2` surface triangles each), `gap` apart.
fn two_balls(res: usize, gap: f64) -> (ContactSurface, Vec<Vec3>) {
    let one = ball(1.0, res).expect("ball");
    let n = one.num_vertices();
    let mut x = one.positions().to_vec();
    x.extend(
        one.positions()
            .iter()
            .map(|p| p + Vec3::new(2.0 + gap, 0.0, 0.0)),
    );
    let surface = BoundarySurface::new(&one).expect("surface");
    let mut triangles = surface.triangles().to_vec();
    triangles.extend(surface.triangles().iter().map(|t| t.map(|v| v + n)));
    (ContactSurface::from_triangles(triangles), x)
}

fn queries() -> Vec<CcdQuery> {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/ccd-queries");
    let mut all = Vec::new();
    for set in std::fs::read_dir(root).expect("data").flatten() {
        for kind in ["vertex-face", "edge-edge"] {
            let Ok(files) = std::fs::read_dir(set.path().join(kind)) else {
                continue;
            };
            for file in files.flatten() {
                let path = file.path();
                all.extend(read_ccd_queries(&path, QueryKind::from_path(&path)).expect("queries"));
            }
        }
    }
    all
}

fn bench(c: &mut Criterion) {
    let (surface, x) = two_balls(10, 0.01);
    let dhat = 0.02;
    let candidates = contact_candidates(&surface, &x, None, dhat, PairFilter::All);
    let moved: Vec<Vec3> = x
        .iter()
        .enumerate()
        .map(|(i, p)| {
            if i * 2 < x.len() {
                p + Vec3::new(0.005, 0.0, 0.0)
            } else {
                *p
            }
        })
        .collect();
    let swept = contact_candidates(&surface, &x, Some(&moved), 0.0, PairFilter::All);
    eprintln!(
        "two balls: {} triangles, {} edges, {} vertices; within dhat: {} point-triangle, {} edge-edge pairs; swept: {} pairs",
        surface.triangles().len(),
        surface.edges().len(),
        surface.vertices().len(),
        candidates.point_triangle.len(),
        candidates.edge_edge.len(),
        swept.len()
    );
    c.bench_function("broad phase within dhat (9.6k triangles)", |b| {
        b.iter(|| {
            black_box(contact_candidates(
                &surface,
                &x,
                None,
                dhat,
                PairFilter::All,
            ))
        })
    });
    c.bench_function("broad phase swept (9.6k triangles)", |b| {
        b.iter(|| {
            black_box(contact_candidates(
                &surface,
                &x,
                Some(&moved),
                0.0,
                PairFilter::All,
            ))
        })
    });
    let tris = surface.triangles();
    let edges = surface.edges();
    c.bench_function("distance derivatives of the candidates", |b| {
        b.iter(|| {
            let mut sum = 0.0;
            for &[p, t] in &candidates.point_triangle {
                let y = [x[p], x[tris[t][0]], x[tris[t][1]], x[tris[t][2]]];
                let kind = point_triangle_distance_kind(&y[0], &y[1], &y[2], &y[3]);
                sum += kind.derivatives(&y).hessian[(0, 0)];
            }
            for &[i, j] in &candidates.edge_edge {
                let y = [
                    x[edges[i][0]],
                    x[edges[i][1]],
                    x[edges[j][0]],
                    x[edges[j][1]],
                ];
                let kind = edge_edge_distance_kind(&y[0], &y[1], &y[2], &y[3]);
                sum += kind.derivatives(&y).hessian[(0, 0)];
            }
            black_box(sum)
        })
    });
    let queries = queries();
    eprintln!("{} CCD queries", queries.len());
    let settings = CcdSettings::default();
    c.bench_function("CCD over the benchmark queries", |b| {
        b.iter(|| {
            black_box(
                queries
                    .iter()
                    .filter(|q| q.time_of_impact(&settings).is_some())
                    .count(),
            )
        })
    });
}

criterion_group! {
    name = benches;
    config = Criterion::default().sample_size(10);
    targets = bench
}
criterion_main!(benches);
