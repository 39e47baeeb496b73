//! Bodies of several materials: `[[regions]]` on the bilayer mesh of the mesh crate's test
//! data (`bilayer-v41.msh`, Gmsh output: a 0.06 x 0.02 x 0.012 m block, a soft body over a
//! 2 mm strain-limiting layer at z in [0, 0.002], volume groups `soft` and `stiff layer`,
//! surface group `clamped` at x = 0), and `isochor check`.

use isochor_scenes::check::check_scene;
use isochor_scenes::{load_scene, run_scene, RunOptions, Scene, SceneError};
use std::path::{Path, PathBuf};

fn bilayer_mesh() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../mesh/tests/data/bilayer-v41.msh")
}

/// A fresh scratch folder for one test.
fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("isochor-regions-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// The bilayer clamped on its `clamped` group, bending under its own weight, with body
/// Young's modulus `young` and the extra TOML `regions`.
fn bilayer(dir: &Path, file: &str, young: f64, regions: &str) -> Result<Scene, SceneError> {
    let text = format!(
        r#"name = "bilayer"
method = "mixed-p1"

[mesh]
generator = "file"
path = {mesh:?}

[material]
young = {young:e}
nu = 0.49
rho = 1070.0

[selections.clamped]
physical = "clamped"

[selections.layer]
physical = "stiff layer"

[selections.layer_box]
box = {{ min = [-1.0, -1.0, -1.0], max = [1.0, 1.0, 0.002] }}

[selections.tip]
plane = {{ point = [0.06, 0.0, 0.0], normal = [1.0, 0.0, 0.0] }}

{regions}

[[dirichlet]]
selection = "clamped"

[loads]
gravity = [0.0, 0.0, -9.8]

[stepping]
mode = "quasi-static"
steps = 1

[probes.sag]
kind = "displacement"
selection = "tip"
component = "z"
scale = -1.0
"#,
        mesh = bilayer_mesh()
    );
    let path = dir.join(file);
    std::fs::write(&path, text).unwrap();
    load_scene(path.to_str().unwrap(), None, &[])
}

fn sag(scene: &Scene) -> f64 {
    let (result, _) = run_scene(scene, &RunOptions::default()).unwrap();
    assert!(result.converged, "{:?}", result.error);
    result.probes["sag"]
}

const SOFT: f64 = 100e3;

const STIFF_LAYER: &str = r#"[[regions]]
name = "stiff layer"
selection = "layer"
material = { young = 10e6 }"#;

/// A layer 100 times stiffer than the body: the bilayer sags less than the soft body and
/// more than a body made wholly of the stiff material; a region given by a box equals the
/// one given by the physical volume group, and a region of the body's material is no region.
#[test]
fn a_stiff_layer_sags_between_the_soft_and_the_stiff_body() {
    let dir = scratch("order");
    let soft = sag(&bilayer(&dir, "soft.toml", SOFT, "").unwrap());
    let layered = sag(&bilayer(&dir, "layered.toml", SOFT, STIFF_LAYER).unwrap());
    let stiff = sag(&bilayer(&dir, "stiff.toml", 100.0 * SOFT, "").unwrap());
    let boxed = sag(&bilayer(
        &dir,
        "boxed.toml",
        SOFT,
        &STIFF_LAYER.replace("\"layer\"", "\"layer_box\""),
    )
    .unwrap());
    let same = sag(&bilayer(
        &dir,
        "same.toml",
        SOFT,
        &STIFF_LAYER.replace("young = 10e6", ""),
    )
    .unwrap());
    eprintln!(
        "sag soft {soft:e}, layered {layered:e}, stiff {stiff:e}, boxed {boxed:e}, same {same:e}"
    );
    // A region of the body's own material changes nothing.
    assert!((same - soft).abs() <= 1e-9 * soft, "{same:e} vs {soft:e}");
    assert!(soft > 0.0 && stiff > 0.0);
    // Nearly linear in 1/E: the stiff body sags 100 times less than the soft one.
    assert!((soft / stiff - 100.0).abs() < 5.0, "{}", soft / stiff);
    assert!(layered < 0.5 * soft && layered > 2.0 * stiff, "{layered:e}");
    assert!(
        (boxed - layered).abs() <= 1e-9 * layered,
        "{boxed:e} vs {layered:e}"
    );
}

/// `isochor check` sizes the regions: their volumes are the layer's 0.06 x 0.02 x 0.002 and
/// the body's 0.06 x 0.02 x 0.010 (flat faces, so the tets fill them exactly), with the
/// element counts Gmsh reports for the two volume groups.
#[test]
fn check_reports_the_region_volumes_of_the_mesh() {
    let dir = scratch("check");
    let scene = bilayer(&dir, "layered.toml", SOFT, STIFF_LAYER).unwrap();
    let vtu = dir.join("check.vtu");
    let report = check_scene(&scene, Some(&vtu)).unwrap();
    let text = report.to_text();
    eprintln!("{text}");
    let region = |name: &str| report.regions.iter().find(|r| r.name == name).unwrap();
    let (body, layer) = (region("body"), region("stiff layer"));
    assert_eq!((body.tets, layer.tets), (2508, 1151));
    assert!((layer.volume - 0.06 * 0.02 * 0.002).abs() < 1e-12 * 2.4e-6 * 1e3);
    assert!((body.volume - 0.06 * 0.02 * 0.010).abs() < 1e-12 * 1.2e-5 * 1e3);
    assert_eq!(layer.young, 10e6);
    let clamped = report
        .selections
        .iter()
        .find(|s| s.name == "clamped")
        .unwrap();
    assert_eq!(clamped.faces, Ok(96));
    assert!(clamped.tets.is_err(), "a surface group selects no tets");
    let written = isochor_mesh::io::read_vtu_file(&vtu).unwrap();
    let regions = written
        .cell_data
        .iter()
        .find(|f| f.name == "region")
        .unwrap();
    assert_eq!(regions.len(), 3659);
}

/// Errors name the region: an unknown material key, a bad value, an empty selection.
#[test]
fn bad_regions_are_named_errors() {
    let dir = scratch("errors");
    let unknown = bilayer(
        &dir,
        "unknown.toml",
        SOFT,
        &STIFF_LAYER.replace("young = 10e6", "yung = 10e6"),
    )
    .and_then(|s| check_scene(&s, None).map(|_| ()))
    .unwrap_err()
    .to_string();
    assert!(
        unknown.contains("regions.0.material") && unknown.contains("yung"),
        "{unknown}"
    );
    let bad = bilayer(
        &dir,
        "bad.toml",
        SOFT,
        &STIFF_LAYER.replace("young = 10e6", "nu = 0.7"),
    )
    .and_then(|s| check_scene(&s, None).map(|_| ()))
    .unwrap_err()
    .to_string();
    assert!(
        bad.contains("regions.0.material") && bad.contains("nu"),
        "{bad}"
    );
    let overlap = format!(
        "{STIFF_LAYER}\n\n{}",
        STIFF_LAYER.replace("\"stiff layer\"", "\"again\"")
    );
    let twice = bilayer(&dir, "twice.toml", SOFT, &overlap)
        .and_then(|s| check_scene(&s, None).map(|_| ()))
        .unwrap_err()
        .to_string();
    assert!(
        twice.contains("region 'again'") && twice.contains("stiff layer"),
        "{twice}"
    );
}
