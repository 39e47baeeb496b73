//! The obstacle-surface readers against random triangle soups: the same triangles written as
//! OBJ (with positive or negative indices and quads), ASCII STL and binary STL read back to
//! the same geometry, and STL's repeated vertices are welded to the distinct positions.

use isochor_mesh::io::{read_surface, TriangleSurface};
use isochor_mesh::Vec3;
use proptest::prelude::*;
use std::collections::BTreeSet;
use std::fmt::Write;

/// The triangles as sorted corner bit patterns, for comparing surfaces numbered differently.
fn geometry(s: &TriangleSurface) -> Vec<[[u64; 3]; 3]> {
    let mut t: Vec<[[u64; 3]; 3]> = s
        .triangles
        .iter()
        .map(|t| {
            let mut c = t.map(|v| {
                let p = s.vertices[v];
                [p.x, p.y, p.z].map(|c| (c + 0.0).to_bits())
            });
            c.sort_unstable();
            c
        })
        .collect();
    t.sort_unstable();
    t
}

fn write(name: &str, bytes: &[u8]) -> std::path::PathBuf {
    let path = std::env::temp_dir().join(format!("isochor-surface-{}-{name}", std::process::id()));
    std::fs::write(&path, bytes).unwrap();
    path
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(32))]

    #[test]
    fn obj_and_both_stls_read_back_the_same_triangles(
        // Coordinates exact in f32, so that binary STL holds them exactly too.
        grid in proptest::collection::vec((-8i32..8, -8i32..8, -8i32..8), 3..12),
        picks in proptest::collection::vec((0usize..100, 0usize..100, 0usize..100), 1..16),
        negative in any::<bool>(),
    ) {
        let points: Vec<Vec3> = grid
            .iter()
            .map(|&(x, y, z)| Vec3::new(f64::from(x) * 0.25, f64::from(y) * 0.5, f64::from(z)))
            .collect();
        let n = points.len();
        let triangles: Vec<[usize; 3]> = picks
            .iter()
            .map(|&(a, b, c)| [a % n, b % n, c % n])
            .filter(|t| t[0] != t[1] && t[1] != t[2] && t[0] != t[2])
            .collect();
        prop_assume!(!triangles.is_empty());
        let mut obj = String::new();
        for p in &points {
            writeln!(obj, "v {:?} {:?} {:?}", p.x, p.y, p.z).unwrap();
        }
        for t in &triangles {
            let index = |v: usize| if negative { v as i64 - n as i64 } else { v as i64 + 1 };
            writeln!(obj, "f {} {} {}", index(t[0]), index(t[1]), index(t[2])).unwrap();
        }
        let mut ascii = String::from("solid soup\n");
        let mut binary = vec![0u8; 80];
        binary.extend((triangles.len() as u32).to_le_bytes());
        for t in &triangles {
            ascii.push_str("facet normal 0 0 0\nouter loop\n");
            binary.extend([0u8; 12]);
            for &v in t {
                let p = points[v];
                writeln!(ascii, "vertex {:?} {:?} {:?}", p.x, p.y, p.z).unwrap();
                for c in [p.x, p.y, p.z] {
                    binary.extend((c as f32).to_le_bytes());
                }
            }
            ascii.push_str("endloop\nendfacet\n");
            binary.extend([0u8; 2]);
        }
        ascii.push_str("endsolid soup\n");
        let paths = [write("soup.obj", obj.as_bytes()), write("ascii.stl", ascii.as_bytes()), write("binary.stl", &binary)];
        let read: Vec<TriangleSurface> = paths.iter().map(|p| read_surface(p).unwrap()).collect();
        for p in &paths {
            std::fs::remove_file(p).unwrap();
        }
        let expected = geometry(&TriangleSurface { vertices: points.clone(), triangles: triangles.clone() });
        let used: BTreeSet<[u64; 3]> = triangles
            .iter()
            .flatten()
            .map(|&v| [points[v].x, points[v].y, points[v].z].map(|c| (c + 0.0).to_bits()))
            .collect();
        for (s, what) in read.iter().zip(["obj", "ascii stl", "binary stl"]) {
            prop_assert_eq!(&geometry(s), &expected, "{}", what);
        }
        // STL welds every repeated position into one vertex.
        for s in &read[1..] {
            prop_assert_eq!(s.vertices.len(), used.len());
        }
    }
}
