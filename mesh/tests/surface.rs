//! The triangle-surface readers of rigid obstacles against the files of `tests/data`.

use isochor_mesh::io::{read_gmsh, read_surface, TriangleSurface};
use isochor_mesh::Vec3;
use std::collections::HashMap;
use std::path::{Path, PathBuf};

fn data(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/data")
        .join(name)
}

/// The triangles as sets of corner positions, for comparing surfaces numbered differently.
fn geometry(s: &TriangleSurface) -> Vec<[[u64; 3]; 3]> {
    let mut t: Vec<[[u64; 3]; 3]> = s
        .triangles
        .iter()
        .map(|t| {
            let mut c = t.map(|v| {
                let p: Vec3 = s.vertices[v];
                [p.x, p.y, p.z].map(|c| (c + 0.0).to_bits())
            });
            c.sort_unstable();
            c
        })
        .collect();
    t.sort_unstable();
    t
}

#[test]
fn obj_and_ascii_stl_plates_are_the_same_two_triangles() {
    let obj = read_surface(data("plate.obj")).unwrap();
    let stl = read_surface(data("plate.stl")).unwrap();
    assert_eq!(obj.vertices.len(), 4);
    assert_eq!(
        stl.vertices.len(),
        4,
        "the STL's repeated vertices are welded"
    );
    assert_eq!(obj.triangles.len(), 2);
    assert_eq!(geometry(&obj), geometry(&stl));
}

#[test]
fn gmsh_surfaces_are_the_boundary_of_the_tets() {
    for name in ["unit-cube-v22.msh", "unit-cube-v41.msh"] {
        let surface = read_surface(data(name)).unwrap();
        let mesh = read_gmsh(data(name)).unwrap();
        let boundary = mesh.boundary().unwrap();
        assert_eq!(
            surface.triangles.len(),
            boundary.triangles().len(),
            "{name}"
        );
        // Closed: every edge is shared by two triangles.
        let mut edges = HashMap::new();
        for t in &surface.triangles {
            for (a, b) in [(t[0], t[1]), (t[1], t[2]), (t[2], t[0])] {
                *edges.entry((a.min(b), a.max(b))).or_insert(0) += 1;
            }
        }
        assert!(edges.values().all(|&n| n == 2), "{name}");
    }
}

#[test]
fn unknown_extension_is_refused() {
    let e = read_surface(data("plate.ply")).unwrap_err().to_string();
    assert!(e.contains("plate.ply") && e.contains(".obj"), "{e}");
}
