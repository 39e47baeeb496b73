//! File I/O: VTU round trip, PVD, the sample Gmsh files, TetGen, and malformed input.

use isochor_mesh::generate::box_grid;
use isochor_mesh::io::{
    read_gmsh, read_mesh, read_tetgen, read_vtu, read_vtu_file, write_pvd, write_vtu, Field,
    FieldValues,
};
use isochor_mesh::{MeshError, Vec3};
use std::fs;
use std::path::{Path, PathBuf};

/// A fresh, empty scratch directory for one test.
fn scratch(test: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("isochor-mesh-{}-{test}", std::process::id()));
    let _ = fs::remove_dir_all(&dir);
    fs::create_dir_all(&dir).unwrap();
    dir
}

fn data(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/data")
        .join(name)
}

/// The line and message of a parse error, after checking it names `path`.
fn parse_error(result: Result<impl std::fmt::Debug, MeshError>, path: &Path) -> (usize, String) {
    match result {
        Err(MeshError::Parse {
            path: p,
            line,
            message,
        }) => {
            assert_eq!(p, path);
            (line, message)
        }
        other => panic!("expected a parse error, got {other:?}"),
    }
}

#[test]
fn vtu_round_trip_is_exact() {
    let dir = scratch("vtu");
    let mesh = box_grid(
        Vec3::new(0.1, 0.2, 0.3),
        Vec3::new(1.0 / 3.0, 1.0, 2.0),
        [2, 3, 2],
    )
    .unwrap();
    let n = mesh.num_vertices();
    let m = mesh.num_tets();
    let displacement: Vec<Vec3> = (0..n)
        .map(|i| Vec3::new(i as f64 * 0.1, -1e-300, 1.0 / (i + 1) as f64))
        .collect();
    let pressure: Vec<f64> = (0..n)
        .map(|i| (i as f64).sqrt() * 1e7 + 0.1 + 0.2)
        .collect();
    let j: Vec<f64> = (0..m)
        .map(|e| {
            if e == 3 {
                f64::NAN
            } else {
                1.0 - e as f64 * 1e-17
            }
        })
        .collect();
    let zone: Vec<i32> = (0..m).map(|e| e as i32 % 3 - 1).collect();
    let point_data = [
        Field::vector("displacement", displacement),
        Field::scalar("p <kPa> & \"x\"", pressure),
    ];
    let cell_data = [Field::scalar("J", j.clone()), Field::int("zone", zone)];
    let path = dir.join("frame.vtu");
    write_vtu(
        &path,
        mesh.positions(),
        mesh.tets(),
        &point_data,
        &cell_data,
    )
    .unwrap();
    let file = read_vtu_file(&path).unwrap();
    assert_eq!(file.points, mesh.positions());
    assert_eq!(file.cells, mesh.tets().as_flattened());
    assert_eq!(file.point_data, point_data);
    assert_eq!(file.cell_data.len(), 2);
    assert_eq!(file.cell_data[1], cell_data[1]);
    let FieldValues::Scalar(read_j) = &file.cell_data[0].values else {
        panic!("J is scalar")
    };
    assert!(read_j[3].is_nan());
    assert!(read_j
        .iter()
        .zip(&j)
        .enumerate()
        .all(|(e, (a, b))| e == 3 || a == b));
    let back = read_mesh(&path).unwrap();
    assert_eq!(back.rest_volumes(), mesh.rest_volumes());
    // Atomic writes leave no temporary behind.
    assert_eq!(fs::read_dir(&dir).unwrap().count(), 1);
    // Mismatched data lengths are refused before anything is written.
    let short = [Field::scalar("p", vec![0.0; n - 1])];
    assert!(matches!(
        write_vtu(
            dir.join("bad.vtu"),
            mesh.positions(),
            mesh.tets(),
            &short,
            &[]
        ),
        Err(MeshError::InvalidParameter { .. })
    ));
    assert!(!dir.join("bad.vtu").exists());
    fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn malformed_vtu_files_name_the_line() {
    let dir = scratch("vtu-bad");
    let mesh = box_grid(Vec3::zeros(), Vec3::repeat(1.0), [1, 1, 1]).unwrap();
    let good = dir.join("good.vtu");
    write_vtu(&good, mesh.positions(), mesh.tets(), &[], &[]).unwrap();
    let text = fs::read_to_string(&good).unwrap();
    let line_of = |needle: &str| text[..text.find(needle).unwrap()].matches('\n').count() + 1;
    let case = |name: &str, text: &str| {
        let path = dir.join(name);
        fs::write(&path, text).unwrap();
        parse_error(read_vtu(&path), &path)
    };
    let (line, m) = case("nan.vtu", &text.replacen("1.0 1.0 1.0", "1.0 NaN 1.0", 1));
    assert_eq!(line, line_of("1.0 1.0 1.0"));
    assert!(m.contains("non-finite"), "{m}");
    let (line, m) = case("range.vtu", &text.replacen("0 1 3 7", "0 1 3 8", 1));
    assert_eq!(line, line_of("0 1 3 7"));
    assert!(m.contains("point 8"), "{m}");
    let (line, m) = case("type.vtu", &text.replacen("\n10\n", "\n12\n", 1));
    assert_eq!(line, line_of("\n10\n") + 1);
    assert!(m.contains("cell type 12"), "{m}");
    let (line, m) = case("truncated.vtu", &text[..text.len() / 2]);
    assert!(line > 1);
    assert!(m.contains("expected"), "{m}");
    let (_, m) = case(
        "binary.vtu",
        &text.replacen("format=\"ascii\"", "format=\"binary\"", 1),
    );
    assert!(m.contains("binary"), "{m}");
    let (line, m) = case("word.vtu", &text.replacen("\n4\n", "\nfour\n", 1));
    assert_eq!(line, line_of("\"offsets\"") + 1);
    assert!(m.contains("`four`"), "{m}");
    let (_, m) = case(
        "huge.vtu",
        &text.replacen(
            "NumberOfCells=\"6\"",
            "NumberOfCells=\"18446744073709551615\"",
            1,
        ),
    );
    assert!(m.contains("more cells"), "{m}");
    fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn pvd_lists_the_frames() {
    let dir = scratch("pvd");
    let path = dir.join("series.pvd");
    write_pvd(&path, &[(0.0, "f0.vtu".into()), (0.25, "f1.vtu".into())]).unwrap();
    let text = fs::read_to_string(&path).unwrap();
    assert!(text.contains(r#"<DataSet timestep="0.25" group="" part="0" file="f1.vtu"/>"#));
    assert!(text.contains(r#"type="Collection""#));
    assert!(write_pvd(&path, &[(f64::NAN, "x.vtu".into())]).is_err());
    fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn sample_gmsh_files_match_their_readme() {
    for (file, vertices, tets, volume, tolerance) in [
        ("unit-cube-v22.msh", 341, 1140, 1.0, 1e-12),
        ("unit-cube-v41.msh", 341, 1140, 1.0, 1e-12),
        ("cylinder-v22.msh", 249, 780, 1.22096e-4, 1e-9),
        ("cylinder-v41.msh", 249, 780, 1.22096e-4, 1e-9),
    ] {
        let mesh = read_mesh(data(file)).unwrap();
        assert_eq!(
            (mesh.num_vertices(), mesh.num_tets()),
            (vertices, tets),
            "{file}"
        );
        assert_eq!(mesh.reoriented(), 0, "{file}");
        assert!(
            (mesh.rest_volume() - volume).abs() < tolerance,
            "{file}: {}",
            mesh.rest_volume()
        );
        let surface = mesh.boundary().unwrap();
        surface.check_closed().unwrap();
        assert!(
            (surface.enclosed_volume(mesh.positions()) - mesh.rest_volume()).abs() < 1e-12 * volume
        );
    }
    let v22 = read_gmsh(data("unit-cube-v22.msh")).unwrap();
    let v41 = read_gmsh(data("unit-cube-v41.msh")).unwrap();
    assert_eq!(v22.positions(), v41.positions());
    assert_eq!(v22.tets(), v41.tets());
}

#[test]
fn damaged_gmsh_files_name_the_line() {
    let dir = scratch("gmsh-bad");
    let original = fs::read_to_string(data("unit-cube-v41.msh")).unwrap();
    let lines: Vec<&str> = original.lines().collect();
    let case = |name: &str, text: String| {
        let path = dir.join(name);
        fs::write(&path, text).unwrap();
        parse_error(read_gmsh(&path), &path)
    };
    // Truncated in the middle of $Elements.
    let keep = lines.len() - 100;
    let (line, m) = case("truncated.msh", lines[..keep].join("\n"));
    assert_eq!(line, keep + 1);
    assert!(m.contains("unexpected end of file"), "{m}");
    // The last tet refers to a node that does not exist.
    let mut edited = lines.clone();
    let last_tet = lines.len() - 2;
    let replaced = format!(
        "{} 999 1 2 3",
        lines[last_tet].split_whitespace().next().unwrap()
    );
    edited[last_tet] = &replaced;
    let (line, m) = case("range.msh", edited.join("\n"));
    assert_eq!(line, last_tet + 1);
    assert!(m.contains("node tag 999"), "{m}");
    // A NaN coordinate in the first node block.
    let coord = lines.iter().position(|l| *l == "0 0 1").unwrap();
    let mut edited = lines.clone();
    edited[coord] = "0 nan 1";
    let (line, m) = case("nan.msh", edited.join("\n"));
    assert_eq!(line, coord + 1);
    assert!(m.contains("finite y coordinate"), "{m}");
    // The volume block declared as hexahedra.
    let block = lines.iter().position(|l| l.starts_with("3 1 4 ")).unwrap();
    let mut edited = lines.clone();
    let hex = lines[block].replacen("3 1 4 ", "3 1 5 ", 1);
    edited[block] = &hex;
    let (line, m) = case("hex.msh", edited.join("\n"));
    assert_eq!(line, block + 1);
    assert!(m.contains("hexahedron"), "{m}");
    // A binary file.
    let (line, m) = case("binary.msh", original.replacen("4.1 0 8", "4.1 1 8", 1));
    assert_eq!(line, 2);
    assert!(m.contains("binary"), "{m}");
    fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn tetgen_pair_and_dispatch() {
    let dir = scratch("tetgen");
    let mesh = box_grid(Vec3::zeros(), Vec3::new(2.0, 1.0, 1.0), [2, 1, 1]).unwrap();
    let mut node = format!("# generated\n{} 3 0 1\n", mesh.num_vertices());
    for (i, p) in mesh.positions().iter().enumerate() {
        node += &format!("{} {:?} {:?} {:?} 1\n", i + 1, p.x, p.y, p.z);
    }
    let mut ele = format!("{} 4 1\n", mesh.num_tets());
    for (e, t) in mesh.tets().iter().enumerate() {
        // TetGen's own orientation is the opposite of ours: the reader re-orients.
        ele += &format!(
            "{} {} {} {} {} 5\n",
            e + 1,
            t[0] + 1,
            t[1] + 1,
            t[3] + 1,
            t[2] + 1
        );
    }
    fs::write(dir.join("box.node"), &node).unwrap();
    fs::write(dir.join("box.ele"), &ele).unwrap();
    let back = read_tetgen(dir.join("box.node")).unwrap();
    assert_eq!(back.num_tets(), mesh.num_tets());
    assert_eq!(back.reoriented(), mesh.num_tets());
    assert!((back.rest_volume() - 2.0).abs() < 1e-15);
    assert_eq!(
        read_mesh(dir.join("box.ele")).unwrap().num_vertices(),
        mesh.num_vertices()
    );
    // Missing .ele file: an I/O error naming it.
    fs::remove_file(dir.join("box.ele")).unwrap();
    match read_mesh(dir.join("box.node")) {
        Err(MeshError::Io { path, .. }) => assert_eq!(path, dir.join("box.ele")),
        other => panic!("expected an I/O error, got {other:?}"),
    }
    assert!(matches!(
        read_mesh(dir.join("box.stl")),
        Err(MeshError::Format { .. })
    ));
    fs::remove_dir_all(&dir).unwrap();
}
