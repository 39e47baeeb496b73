//! File I/O: VTU round trip, PVD, the sample Gmsh files, TetGen, and malformed input.

use isochor_mesh::element::TetElement;
use isochor_mesh::generate::{box_grid, cylinder, cylinder_surface, tube_surface};
use isochor_mesh::io::{
    read_gmsh, read_gmsh_elements, read_gmsh_with_groups, read_mesh, read_mesh_elements,
    read_tetgen, read_vtu, read_vtu_elements, read_vtu_file, write_pvd, write_vtu,
    write_vtu_elements, Field, FieldValues, VtuEncoding,
};
use isochor_mesh::{ElementMesh, MeshError, Vec3};
use std::f64::consts::PI;
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
        VtuEncoding::Ascii,
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
            &[],
            VtuEncoding::Ascii,
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
    write_vtu(
        &good,
        mesh.positions(),
        mesh.tets(),
        &[],
        &[],
        VtuEncoding::Ascii,
    )
    .unwrap();
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

/// Point and cell data with values text and binary must both keep (signed zero, subnormals,
/// extremes, infinities and `nan`) on a mesh of `points` points and `cells` cells.
fn awkward_fields(points: &[Vec3], cells: usize, nan: f64) -> (Vec<Field>, Vec<Field>) {
    let special = [-0.0, 5e-324, 1e-310, f64::MAX, f64::NEG_INFINITY, nan];
    let value = |i: usize| {
        special
            .get(i % 40)
            .copied()
            .unwrap_or((i as f64).sqrt() * 1e-7 + 0.1 + 0.2)
    };
    let displacement = points
        .iter()
        .enumerate()
        .map(|(i, p)| Vec3::new(p.x * 1e-3, value(i), -1.0 / (i + 1) as f64))
        .collect();
    let point_data = vec![
        Field::vector("displacement", displacement),
        Field::scalar("p <kPa> & \"x\"", (0..points.len()).map(value).collect()),
        Field::int(
            "flag",
            (0..points.len()).map(|i| i as i32 % 5 - 2).collect(),
        ),
    ];
    let cell_data = vec![
        Field::scalar("J", (0..cells).map(|e| 1.0 - value(e) * 1e-17).collect()),
        Field::int("zone", (0..cells).map(|e| i32::MIN + e as i32).collect()),
        Field::tensor(
            "stress",
            (0..cells)
                .map(|e| nalgebra::Matrix3::from_fn(|i, j| value(e) + 0.25 * (3 * i + j) as f64))
                .collect(),
        ),
    ];
    (point_data, cell_data)
}

/// The bits of every value of a field.
fn bits(field: &Field) -> (String, Vec<u64>) {
    let values = match &field.values {
        FieldValues::Scalar(v) => v.iter().map(|x| x.to_bits()).collect(),
        FieldValues::Vector(v) => v
            .iter()
            .flat_map(|x| [x.x, x.y, x.z])
            .map(f64::to_bits)
            .collect(),
        FieldValues::Int(v) => v.iter().map(|&x| x as u64).collect(),
        FieldValues::Tensor(v) => v
            .iter()
            .flat_map(|t| t.iter().copied().collect::<Vec<_>>())
            .map(f64::to_bits)
            .collect(),
    };
    (field.name.clone(), values)
}

fn all_bits(fields: &[Field]) -> Vec<(String, Vec<u64>)> {
    fields.iter().map(bits).collect()
}

#[test]
fn vtu_round_trips_in_ascii_and_binary_of_4_and_10_node_meshes() {
    let dir = scratch("vtu-encodings");
    let r = 0.02;
    // 2,197 points and 10,368 tets: arrays of several 32 KiB blocks.
    let linear =
        ElementMesh::linear(box_grid(Vec3::zeros(), Vec3::new(1.0, 0.5, 0.25), [12; 3]).unwrap());
    let curved =
        ElementMesh::quadratic_on_surface(cylinder(r, 0.05, 2).unwrap(), cylinder_surface(r))
            .unwrap();
    // Text keeps the canonical NaN; binary keeps any NaN payload.
    let payload_nan = f64::from_bits(0x7ff8_dead_beef_0001);
    for mesh in [&linear, &curved] {
        let mut sizes = Vec::new();
        for (encoding, nan) in [
            (VtuEncoding::Ascii, f64::NAN),
            (VtuEncoding::Binary, payload_nan),
        ] {
            let (point_data, cell_data) = awkward_fields(mesh.nodes(), mesh.num_elements(), nan);
            let path = dir.join(format!("{:?}-{encoding:?}.vtu", mesh.kind()));
            write_vtu_elements(
                &path,
                mesh.nodes(),
                mesh.kind(),
                mesh.connectivity(),
                &point_data,
                &cell_data,
                encoding,
            )
            .unwrap();
            let file = read_vtu_file(&path).unwrap();
            let what = format!("{:?} {encoding:?}", mesh.kind());
            assert_eq!(file.element, mesh.kind(), "{what}");
            assert_eq!(file.points, mesh.nodes(), "{what}");
            assert_eq!(file.cells, mesh.connectivity(), "{what}");
            assert_eq!(all_bits(&file.point_data), all_bits(&point_data), "{what}");
            assert_eq!(all_bits(&file.cell_data), all_bits(&cell_data), "{what}");
            let back = read_vtu_elements(&path).unwrap();
            assert_eq!(back.nodes(), mesh.nodes(), "{what}");
            assert_eq!(back.connectivity(), mesh.connectivity(), "{what}");
            let text = String::from_utf8_lossy(&fs::read(&path).unwrap()).into_owned();
            let binary = encoding == VtuEncoding::Binary;
            assert_eq!(text.contains(r#"format="appended""#), binary, "{what}");
            assert_eq!(text.contains(r#"format="ascii""#), !binary, "{what}");
            sizes.push(fs::metadata(&path).unwrap().len());
        }
        assert!(sizes[1] < sizes[0], "binary is smaller: {sizes:?}");
    }
    assert_eq!(
        read_mesh(dir.join("Tet4-Binary.vtu"))
            .unwrap()
            .rest_volumes(),
        linear.corners().rest_volumes()
    );
    // Atomic writes leave no temporary behind.
    assert_eq!(fs::read_dir(&dir).unwrap().count(), 4);
    fs::remove_dir_all(&dir).unwrap();
}

/// The same grid (10-node tets with point and cell data) written by VTK and meshio in other
/// layouts (see scripts/make_vtu_fixtures.py) reads back bit for bit equal to the ASCII frame
/// isochor wrote.
#[test]
fn vtu_layouts_of_vtk_and_meshio_read_alike() {
    let original = read_vtu_file(data("vtu/isochor-ascii.vtu")).unwrap();
    assert_eq!(original.element, TetElement::Tet10);
    assert_eq!((original.points.len(), original.cells.len()), (81, 24 * 10));
    let sorted = |fields: &[Field]| {
        let mut b = all_bits(fields);
        b.sort();
        b
    };
    for name in [
        "vtk-appended-zlib-uint64.vtu",
        "vtk-appended-raw-uint32-big-endian.vtu",
        "vtk-inline-zlib-uint32.vtu",
        "meshio-inline-zlib-uint32.vtu",
        "meshio-inline-raw-uint64.vtu",
    ] {
        let file = read_vtu_file(data(&format!("vtu/{name}"))).unwrap();
        assert_eq!(file.element, original.element, "{name}");
        assert_eq!(file.points, original.points, "{name}");
        assert_eq!(file.cells, original.cells, "{name}");
        assert_eq!(
            sorted(&file.point_data),
            sorted(&original.point_data),
            "{name}"
        );
        assert_eq!(
            sorted(&file.cell_data),
            sorted(&original.cell_data),
            "{name}"
        );
    }
}

/// The byte offset of the appended data (just after its `_`) in a binary VTU file.
fn appended_start(bytes: &[u8]) -> usize {
    let tag = b"<AppendedData encoding=\"raw\">";
    let at = bytes.windows(tag.len()).position(|w| w == tag).unwrap();
    at + bytes[at..].iter().position(|&b| b == b'_').unwrap() + 1
}

#[test]
fn damaged_binary_vtu_files_are_errors_not_panics() {
    let dir = scratch("vtu-binary-bad");
    let mesh = ElementMesh::linear(box_grid(Vec3::zeros(), Vec3::repeat(1.0), [3, 3, 3]).unwrap());
    let (point_data, cell_data) = awkward_fields(mesh.nodes(), mesh.num_elements(), f64::NAN);
    let good = dir.join("good.vtu");
    write_vtu_elements(
        &good,
        mesh.nodes(),
        mesh.kind(),
        mesh.connectivity(),
        &point_data,
        &cell_data,
        VtuEncoding::Binary,
    )
    .unwrap();
    let bytes = fs::read(&good).unwrap();
    let start = appended_start(&bytes);
    let tail = b"\n  </AppendedData>\n</VTKFile>\n";
    assert!(bytes.ends_with(tail));
    let end = bytes.len() - tail.len();
    let read = |name: &str, bytes: &[u8]| {
        let path = dir.join(name);
        fs::write(&path, bytes).unwrap();
        let result = read_vtu_file(&path);
        (
            parse_error(result, &path).1,
            read_vtu_elements(&path).is_err(),
        )
    };
    // Cut anywhere: in the XML, in the data, or in the closing tags (only the final newline
    // may go).
    for cut in (0..bytes.len() - 1).step_by(7) {
        let (_, elements_too) = read("truncated.vtu", &bytes[..cut]);
        assert!(elements_too, "cut at {cut}");
    }
    let (m, _) = read("truncated.vtu", &bytes[..end]);
    assert!(m.contains("truncated"), "{m}");
    // Data cut short with the closing tags kept.
    for cut in start..end {
        let damaged = [&bytes[..cut], &tail[..]].concat();
        let (m, _) = read("short.vtu", &damaged);
        assert!(m.contains("data array"), "cut at {cut}: {m}");
    }
    // The compression header of the first array ("displacement"): its words are the number of
    // blocks, the block size, the last block's size and the compressed size of each block.
    let with_word = |word: usize, value: u64| {
        let mut b = bytes.clone();
        b[start + 8 * word..start + 8 * word + 8].copy_from_slice(&value.to_le_bytes());
        b
    };
    for (word, value, needle) in [
        (0, u64::MAX, "blocks"),
        (0, 1 << 40, "blocks"),
        (0, 0, "expected"),
        (1, 0, "last block"),
        (2, 1 << 20, "last block"),
        (3, u64::MAX, "past the end"),
        (3, 1, "block 0"),
    ] {
        let (m, _) = read("header.vtu", &with_word(word, value));
        assert!(
            m.contains("\"displacement\"") && m.contains(needle),
            "word {word} = {value}: {m}"
        );
    }
    // A flipped byte in a zlib block, garbage data, an offset past the end.
    let mut flipped = bytes.clone();
    flipped[start + 40] ^= 0x55;
    let (m, _) = read("flipped.vtu", &flipped);
    assert!(m.contains("block 0"), "{m}");
    let mut garbage = bytes.clone();
    let mut state = 12345u64;
    for b in &mut garbage[start..end] {
        state = state
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        *b = (state >> 56) as u8;
    }
    read("garbage.vtu", &garbage);
    let text = String::from_utf8_lossy(&bytes[..start]).replacen(
        r#"offset="0""#,
        r#"offset="99999999""#,
        1,
    );
    let moved = [text.as_bytes(), &bytes[start..]].concat();
    let (m, _) = read("offset.vtu", &moved);
    assert!(m.contains("past the end"), "{m}");
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

#[test]
fn gmsh_ten_node_sample_reads_with_its_documented_counts() {
    let path = data("tube-tet10-v41.msh");
    let mesh = read_gmsh_elements(&path).unwrap();
    assert_eq!(mesh.kind(), TetElement::Tet10);
    assert_eq!((mesh.num_nodes(), mesh.num_elements()), (4555, 2257));
    assert_eq!(mesh.corners().reoriented(), 0);
    let surface = mesh.boundary().unwrap();
    surface.corners().check_closed().unwrap();
    // Physical groups inner 502 + outer 784 + bottom 111 + top 111 faces.
    assert_eq!(surface.len(), 502 + 784 + 111 + 111);
    let x = mesh.nodes();
    let count = |on: &dyn Fn(&Vec3) -> bool| {
        (0..surface.len())
            .filter(|&f| surface.face(f).iter().all(|&i| on(&x[i])))
            .count()
    };
    let at_radius = |r: f64| move |p: &Vec3| (p.xy().norm() - r).abs() < 1e-9 * r;
    assert_eq!(count(&at_radius(0.02)), 502);
    assert_eq!(count(&at_radius(0.03)), 784);
    assert_eq!(count(&|p: &Vec3| p.z.abs() < 1e-12), 111);
    assert_eq!(count(&|p: &Vec3| (p.z - 0.06).abs() < 1e-12), 111);
    // Radii 0.02 and 0.03, z from 0 to 0.06: the curved elements hold the true volume
    // far better than their flat corners.
    let (ri, ro, h) = (0.02, 0.03, 0.06);
    let exact = PI * (ro * ro - ri * ri) * h;
    let curved = (mesh.rest_volume() - exact).abs() / exact;
    let flat = (mesh.corners().rest_volume() - exact).abs() / exact;
    let enclosed = surface.enclosed_volume(mesh.nodes());
    eprintln!(
        "tube-tet10: volume {:.6e} (exact {exact:.6e}): relative error {curved:.2e} curved, \
         {flat:.2e} for the corner mesh; 6-node boundary encloses {enclosed:.6e}",
        mesh.rest_volume()
    );
    assert!(curved < 1e-4 && flat > 10.0 * curved, "{curved} {flat}");
    assert!((enclosed - mesh.rest_volume()).abs() < 1e-12 * exact);
    // Interior mid-edge nodes sit at their edge's midpoint; boundary ones on the curved walls
    // are where our radial projection puts them, so Gmsh's edge order is ours.
    let on_boundary: std::collections::HashSet<usize> = (0..surface.len())
        .flat_map(|f| surface.face(f)[3..].to_vec())
        .collect();
    let project = tube_surface(ri, ro);
    let nv = mesh.num_vertices();
    let (mut interior, mut boundary, mut projected): (f64, f64, f64) = (0.0, 0.0, 0.0);
    for (i, &[a, b]) in mesh.mid_edges().iter().enumerate() {
        let length = (x[b] - x[a]).norm();
        let offset = (x[nv + i] - 0.5 * (x[a] + x[b])).norm() / length;
        if on_boundary.contains(&(nv + i)) {
            boundary = boundary.max(offset);
            if let Some(p) = project(&x[a], &x[b]) {
                projected = projected.max((p - x[nv + i]).norm() / length);
            }
        } else {
            interior = interior.max(offset);
        }
    }
    eprintln!(
        "tube-tet10: max mid-edge offset from the straight midpoint / edge length: interior \
         {interior:.1e}, boundary {boundary:.1e}; distance from our wall projection {projected:.1e}"
    );
    assert!(interior < 1e-12, "{interior}");
    assert!(boundary > 1e-3 && boundary < 0.1, "{boundary}");
    assert!(projected < 1e-9, "{projected}");
    // The linear readers refuse the file at its first tet, naming the quadratic reader.
    let (line, m) = parse_error(read_gmsh(&path), &path);
    let text = fs::read_to_string(&path).unwrap();
    let first_tet = text
        .lines()
        .position(|l| l.starts_with("3 ") && l.split_whitespace().nth(2) == Some("11"))
        .unwrap();
    assert_eq!(line, first_tet + 2);
    assert!(m.contains("read_gmsh_elements"), "{m}");
    assert!(read_mesh(&path).is_err());
    assert_eq!(read_mesh_elements(&path).unwrap().num_nodes(), 4555);
}

#[test]
fn vtu_round_trip_of_curved_ten_node_tets() {
    let dir = scratch("vtu-tet10");
    let r = 0.02;
    let mesh =
        ElementMesh::quadratic_on_surface(cylinder(r, 0.05, 2).unwrap(), cylinder_surface(r))
            .unwrap();
    let height: Vec<f64> = mesh.nodes().iter().map(|p| p.z).collect();
    let point_data = [Field::scalar("z", height)];
    let cell_data = [Field::int(
        "element",
        (0..mesh.num_elements()).map(|e| e as i32).collect(),
    )];
    let path = dir.join("curved.vtu");
    write_vtu_elements(
        &path,
        mesh.nodes(),
        mesh.kind(),
        mesh.connectivity(),
        &point_data,
        &cell_data,
        VtuEncoding::Ascii,
    )
    .unwrap();
    let file = read_vtu_file(&path).unwrap();
    assert_eq!(file.element, TetElement::Tet10);
    assert_eq!(file.points, mesh.nodes());
    assert_eq!(file.cells, mesh.connectivity());
    assert_eq!(file.point_data, point_data);
    assert_eq!(file.cell_data, cell_data);
    // VTK's order: the first cell's nodes 8 and 9 are our 9 and 8.
    let text = fs::read_to_string(&path).unwrap();
    let e = mesh.element(0);
    let first = [e[0], e[1], e[2], e[3], e[4], e[5], e[6], e[7], e[9], e[8]].map(|i| i.to_string());
    assert!(text.contains(&first.join(" ")));
    assert!(text.contains("\n24\n"));
    let back = read_vtu_elements(&path).unwrap();
    assert_eq!(back.nodes(), mesh.nodes());
    assert_eq!(back.connectivity(), mesh.connectivity());
    assert_eq!(back.rest_volume(), mesh.rest_volume());
    // The linear reader refuses quadratic cells, naming the cell and the reader to use.
    let (_, m) = parse_error(read_vtu(&path), &path);
    assert!(
        m.contains("cell 0") && m.contains("read_vtu_elements"),
        "{m}"
    );
    // Linear files read as 4-node element meshes.
    let linear = dir.join("linear.vtu");
    write_vtu(
        &linear,
        mesh.corners().positions(),
        mesh.corners().tets(),
        &[],
        &[],
        VtuEncoding::Ascii,
    )
    .unwrap();
    let back = read_mesh_elements(&linear).unwrap();
    assert_eq!(back.kind(), TetElement::Tet4);
    assert_eq!(back.connectivity(), mesh.corners().tets().as_flattened());
    fs::remove_dir_all(&dir).unwrap();
}

/// The sorted corners of each face, sorted: a face set independent of listing order.
fn face_set(faces: &[[usize; 3]]) -> Vec<[usize; 3]> {
    let mut set: Vec<[usize; 3]> = faces
        .iter()
        .map(|f| {
            let mut f = *f;
            f.sort_unstable();
            f
        })
        .collect();
    set.sort_unstable();
    set
}

/// Every face of `faces` is a boundary face of `mesh`.
fn on_boundary(mesh: &ElementMesh, faces: &[[usize; 3]]) -> bool {
    let boundary = face_set(mesh.corners().boundary().unwrap().triangles());
    face_set(faces)
        .iter()
        .all(|f| boundary.binary_search(f).is_ok())
}

#[test]
fn gmsh_physical_groups_read_identically_from_both_formats() {
    for stem in ["unit-cube", "cylinder"] {
        let (m22, g22) = read_gmsh_with_groups(data(&format!("{stem}-v22.msh"))).unwrap();
        let (m41, g41) = read_gmsh_with_groups(data(&format!("{stem}-v41.msh"))).unwrap();
        assert_eq!(m22.nodes(), m41.nodes(), "{stem}");
        assert_eq!(
            g22.keys().collect::<Vec<_>>(),
            ["body", "boundary"],
            "{stem}"
        );
        assert_eq!(
            g41.keys().collect::<Vec<_>>(),
            ["body", "boundary"],
            "{stem}"
        );
        for key in ["body", "boundary"] {
            let (a, b) = (g22.get(key).unwrap(), g41.get(key).unwrap());
            assert_eq!((a.dimension, a.tag, &a.name), (b.dimension, b.tag, &b.name));
            assert_eq!(face_set(&a.faces), face_set(&b.faces), "{stem} {key}");
            assert_eq!(a.tets, b.tets, "{stem} {key}");
        }
        // "boundary" (surface 2) is the whole closed boundary; "body" (volume 1) every tet.
        let boundary = g22.get("boundary").unwrap();
        assert_eq!(boundary.dimension, 2);
        assert!(boundary.tets.is_empty());
        assert_eq!(
            face_set(&boundary.faces),
            face_set(m22.corners().boundary().unwrap().triangles())
        );
        let body = g22.get("body").unwrap();
        assert_eq!((body.dimension, body.tag), (3, 1));
        assert_eq!(body.tets, (0..m22.num_elements()).collect::<Vec<_>>());
        assert!(body.faces.is_empty());
    }
}

/// Counts per group as Gmsh reports them: format 4.1 takes an element block's groups from
/// its entity in `$Entities`. The tube's faces are 6-node triangles, read by their corners;
/// `bilayer-v41.msh` is a 0.06 x 0.02 x 0.012 block of two volume groups (a soft body over
/// a stiff layer 2 mm thick) with two named surface groups: `clamped` is the whole x = 0 end,
/// two surface entities (28 faces on the layer, 68 on the body) that both carry its tag.
#[test]
fn gmsh_physical_groups_match_gmsh_counts() {
    let (tube, groups) = read_gmsh_with_groups(data("tube-tet10-v41.msh")).unwrap();
    let count = |g: &isochor_mesh::io::PhysicalGroups, key: &str| {
        let g = g.get(key).unwrap();
        g.faces.len() + g.tets.len()
    };
    for (key, n) in [
        ("inner", 502),
        ("outer", 784),
        ("bottom", 111),
        ("top", 111),
    ] {
        assert_eq!(count(&groups, key), n, "{key}");
        assert!(on_boundary(&tube, &groups.get(key).unwrap().faces), "{key}");
    }
    assert_eq!(count(&groups, "tube"), 2257);
    let x = tube.nodes();
    assert!(groups
        .get("bottom")
        .unwrap()
        .faces
        .iter()
        .flatten()
        .all(|&v| x[v].z.abs() < 1e-12));
    let (bilayer, groups) = read_gmsh_with_groups(data("bilayer-v41.msh")).unwrap();
    assert_eq!(
        groups.keys().collect::<Vec<_>>(),
        ["clamped", "soft", "stiff layer", "top"]
    );
    for (key, n) in [
        ("clamped", 96),
        ("top", 326),
        ("soft", 2508),
        ("stiff layer", 1151),
    ] {
        assert_eq!(count(&groups, key), n, "{key}");
    }
    let clamped = &groups.get("clamped").unwrap().faces;
    assert!(on_boundary(&bilayer, clamped));
    let x = bilayer.nodes();
    let boundary = bilayer.corners().boundary().unwrap();
    let at_x0 = |f: &[usize; 3]| f.iter().all(|&v| x[v].x.abs() < 1e-12);
    let end = boundary.triangles().iter().filter(|f| at_x0(f)).count();
    assert!(clamped.iter().all(at_x0) && clamped.len() == end);
    let stiff = &groups.get("stiff layer").unwrap().tets;
    assert!(stiff
        .iter()
        .all(|&e| bilayer.element(e).iter().all(|&v| x[v].z <= 0.002 + 1e-9)));
}

#[test]
fn gmsh_physical_groups_unnamed_and_damaged() {
    let dir = scratch("gmsh-groups");
    let write = |name: &str, text: &str| {
        let path = dir.join(name);
        fs::write(&path, text).unwrap();
        path
    };
    // One tet (physical 5, unnamed) and a triangle (physical 7 and a name), format 2.2.
    let v22 =
        "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$PhysicalNames\n1\n2 7 \"lid\"\n$EndPhysicalNames\n\
        $Nodes\n4\n1 0 0 0\n2 1 0 0\n3 0 1 0\n4 0 0 1\n$EndNodes\n\
        $Elements\n2\n1 2 2 7 1 1 2 3\n2 4 2 5 1 1 2 3 4\n$EndElements\n";
    let (_, groups) = read_gmsh_with_groups(write("a.msh", v22)).unwrap();
    assert_eq!(groups.keys().collect::<Vec<_>>(), ["5", "lid"]);
    assert_eq!(groups.get("lid").unwrap().faces, [[0, 1, 2]]);
    assert_eq!(groups.get("5").unwrap().tets, [0]);
    // An unnamed surface and volume group of the same tag are told apart by dimension; the
    // curve group "x" (dimension 1, no elements read) is listed too.
    let (_, groups) = read_gmsh_with_groups(write(
        "b.msh",
        &v22.replace("2 5 1 1 2 3 4", "2 7 1 1 2 3 4")
            .replace("\"lid\"", "\"x\"")
            .replace("2 7 \"x\"", "1 7 \"x\""),
    ))
    .unwrap();
    assert_eq!(groups.keys().collect::<Vec<_>>(), ["2:7", "3:7", "x"]);
    assert_eq!(groups.get("x").unwrap().dimension, 1);
    // A triangle on a node no tet uses, and an unquoted name, are named at their line.
    let path = write(
        "c.msh",
        &v22.replace("4\n1 0 0 0", "5\n9 5 5 5\n1 0 0 0")
            .replace("1 2 2 7 1 1 2 3", "1 2 2 7 1 1 2 9"),
    );
    let (line, m) = parse_error(read_gmsh_with_groups(&path), &path);
    assert_eq!(line, 18);
    assert!(m.contains("triangle node 9 of physical group 7"), "{m}");
    let path = write("d.msh", &v22.replace("\"lid\"", "lid"));
    let (line, m) = parse_error(read_gmsh_with_groups(&path), &path);
    assert_eq!(line, 6);
    assert!(m.contains("quoted group name"), "{m}");
    fs::remove_dir_all(&dir).unwrap();
}

/// `two-groups-v22.msh` and `two-groups-v41.msh` (written by hand) hold one mesh: two tets
/// of a volume in two physical groups (`soft` and `all`), a boundary triangle in `base` and a
/// curve group `edge`. Gmsh 2.2 writes each tet once per group; it reads as one tet in both
/// groups, as in 4.1. Before: the 2.2 file was refused ("face ... is shared by 4 tets"), and
/// the curve group was not found.
#[test]
fn gmsh_22_elements_in_several_groups_read_as_in_41() {
    let (m22, g22) = read_gmsh_with_groups(data("two-groups-v22.msh")).unwrap();
    let (m41, g41) = read_gmsh_with_groups(data("two-groups-v41.msh")).unwrap();
    assert_eq!(m22.num_elements(), 2);
    assert_eq!(m22.nodes(), m41.nodes());
    assert_eq!(m22.connectivity(), m41.connectivity());
    assert_eq!(g22, g41);
    assert_eq!(
        g22.keys().collect::<Vec<_>>(),
        ["all", "base", "edge", "soft"]
    );
    for key in ["all", "soft"] {
        assert_eq!(g22.get(key).unwrap().tets, [0, 1], "{key}");
    }
    assert_eq!(g22.get("base").unwrap().faces.len(), 1);
    let edge = g22.get("edge").unwrap();
    assert_eq!((edge.dimension, edge.tag), (1, 3));
    assert!(edge.faces.is_empty() && edge.tets.is_empty());
}
