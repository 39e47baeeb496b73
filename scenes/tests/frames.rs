//! The VTU frames' convention, read back with the mesh crate's reader: the points are the
//! rest positions and `displacement` is the field to warp them by (ParaView's Warp By
//! Vector), or with `output.points = "deformed"` the points are the deformed positions.

use crate::common::scratch;
use isochor_mesh::io::{read_vtu_file, FieldValues};
use isochor_mesh::Vec3;
use isochor_scenes::resolve::build;
use isochor_scenes::{builtin, load_scene, run_named, Override};
use std::path::Path;

/// The reduced stretch cube's overrides with `extra`.
fn sets(extra: &[&str]) -> Vec<Override> {
    let reduced = builtin::reduced("stretch-cube").unwrap();
    reduced
        .iter()
        .chain(extra)
        .map(|s| Override::parse(s).unwrap())
        .collect()
}

/// The points and the `displacement` field of the last frame of a run into `out`.
fn last_frame(out: &Path, extra: &[&str]) -> (Vec<Vec3>, Vec<Vec3>) {
    let (r, _) = run_named("stretch-cube", None, &sets(extra), Some(out), false, None).unwrap();
    assert!(r.converged, "{:?}", r.error);
    let file = read_vtu_file(out.join(format!("frame_{:05}.vtu", r.steps_requested))).unwrap();
    let displacement = file
        .point_data
        .iter()
        .find(|f| f.name == "displacement")
        .map(|f| match &f.values {
            FieldValues::Vector(v) => v.clone(),
            other => panic!("displacement is {other:?}"),
        })
        .expect("a displacement field");
    (file.points, displacement)
}

#[test]
fn frames_hold_rest_points_and_the_displacement_to_warp_by() {
    let rest_nodes = build(&load_scene("stretch-cube", None, &sets(&[])).unwrap())
        .unwrap()
        .problem
        .mesh
        .nodes()
        .to_vec();
    let dir = scratch("frames-points");
    let (rest, u) = last_frame(&dir.join("rest"), &["vtu_encoding=binary"]);
    assert_eq!(rest, rest_nodes, "the points are the rest nodes");
    assert!(u.iter().any(|d| d.norm() > 1e-3), "the cube is stretched");
    let (deformed, u_deformed) = last_frame(
        &dir.join("deformed"),
        &["vtu_encoding=binary", "output.points=deformed"],
    );
    assert_eq!(
        u_deformed, u,
        "the displacement does not depend on the points"
    );
    // Binary frames store every number exactly: rest + displacement is the deformed
    // position up to the rounding of the subtraction that made the displacement.
    for ((x, r), d) in deformed.iter().zip(&rest).zip(&u) {
        assert!(
            (r + d - x).norm() <= 1e-15 * x.norm().max(1.0),
            "{x} != {r} + {d}"
        );
    }
    let e = load_scene("stretch-cube", None, &sets(&["output.points=warped"]))
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("output.points") && e.contains("`rest` or `deformed`"),
        "{e}"
    );
    let _ = std::fs::remove_dir_all(&dir);
}
