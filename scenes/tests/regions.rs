//! Bodies of several materials: `[[regions]]` on the bilayer mesh of the mesh crate's test
//! data (`bilayer-v41.msh`, Gmsh output: a 0.06 x 0.02 x 0.012 m block, a soft body over a
//! 2 mm strain-limiting layer at z in [0, 0.002], volume groups `soft` and `stiff layer`,
//! surface group `clamped` at x = 0), and `isochor check`.

use crate::common::scratch;
use isochor_scenes::commands::check::check_scene;
use isochor_scenes::{load_scene, run_scene, RunOptions, Scene, SceneError};
use std::path::{Path, PathBuf};

fn bilayer_mesh() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../mesh/tests/data/bilayer-v41.msh")
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
    let dir = scratch("regions-order");
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
        &STIFF_LAYER.replace("young = 10e6", &format!("young = {SOFT:e}")),
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
    let dir = scratch("regions-check");
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

/// Errors name the region: an unknown material key, a bad value, an element in two regions,
/// a selection that does not exist.
#[test]
fn bad_regions_are_named_errors() {
    let dir = scratch("regions-errors");
    let error = |file: &str, regions: &str| {
        bilayer(&dir, file, SOFT, regions)
            .and_then(|s| check_scene(&s, None).map(|_| ()))
            .unwrap_err()
            .to_string()
    };
    let unknown = error(
        "unknown.toml",
        &STIFF_LAYER.replace("young = 10e6", "yung = 10e6"),
    );
    assert!(
        unknown.contains("regions.0.material") && unknown.contains("yung"),
        "{unknown}"
    );
    let bad = error("bad.toml", &STIFF_LAYER.replace("young = 10e6", "nu = 0.7"));
    assert!(
        bad.contains("regions.0.material") && bad.contains("nu"),
        "{bad}"
    );
    let overlap = format!(
        "{STIFF_LAYER}\n\n{}",
        STIFF_LAYER.replace("\"stiff layer\"", "\"again\"")
    );
    let twice = error("twice.toml", &overlap);
    assert!(
        twice.contains("region 'again'") && twice.contains("stiff layer"),
        "{twice}"
    );
    let missing = error(
        "missing.toml",
        &STIFF_LAYER.replace("selection = \"layer\"", "selection = \"lair\""),
    );
    assert!(
        missing.contains("regions.0.selection") && missing.contains("lair"),
        "{missing}"
    );
}

/// TetGen region attributes (the first tet attribute of the `.ele` file, TetGen's `-A`) are
/// volume groups named by their number: a region selects `physical = "2"`, and a region
/// attribute that is not an integer is an error naming the line.
#[test]
fn tetgen_region_attributes_select_regions() {
    let dir = scratch("regions-tetgen");
    let grid = isochor_mesh::generate::box_grid(
        isochor_mesh::Vec3::zeros(),
        isochor_mesh::Vec3::new(2.0, 1.0, 1.0),
        [4, 2, 2],
    )
    .unwrap();
    let mut node = format!("{} 3 0 0\n", grid.num_vertices());
    for (i, p) in grid.positions().iter().enumerate() {
        node += &format!("{} {:?} {:?} {:?}\n", i + 1, p.x, p.y, p.z);
    }
    let mut ele = format!("{} 4 1\n", grid.num_tets());
    let mut upper = 0;
    for (e, t) in grid.tets().iter().enumerate() {
        let region = if grid.centroid(e).x > 1.0 { 2 } else { 1 };
        upper += (region == 2) as usize;
        ele += &format!(
            "{} {} {} {} {} {region}\n",
            e + 1,
            t[0] + 1,
            t[1] + 1,
            t[2] + 1,
            t[3] + 1
        );
    }
    std::fs::write(dir.join("bar.node"), &node).unwrap();
    std::fs::write(dir.join("bar.ele"), &ele).unwrap();
    let text = format!(
        r#"name = "tetgen-regions"
method = "mixed-p1"

[mesh]
generator = "file"
path = {:?}

[material]
young = 1e5
nu = 0.45

[selections.far]
physical = "2"

[selections.end]
plane = {{ point = [0.0, 0.0, 0.0], normal = [1.0, 0.0, 0.0] }}

[[regions]]
name = "far half"
selection = "far"
material = {{ young = 1e6 }}

[[dirichlet]]
selection = "end"

[stepping]
mode = "quasi-static"
steps = 1
"#,
        dir.join("bar.ele")
    );
    let path = dir.join("bar.toml");
    std::fs::write(&path, text).unwrap();
    let scene = load_scene(path.to_str().unwrap(), None, &[]).unwrap();
    let report = check_scene(&scene, None).unwrap();
    let far = report
        .regions
        .iter()
        .find(|r| r.name == "far half")
        .unwrap();
    assert_eq!(far.tets, upper);
    assert!((far.volume - 1.0).abs() < 1e-12, "{}", far.volume);

    std::fs::write(dir.join("bar.ele"), ele.replacen(" 1\n", " 1.5\n", 2)).unwrap();
    let error = check_scene(&scene, None).unwrap_err().to_string();
    assert!(
        error.contains("bar.ele") && error.contains("1.5"),
        "{error}"
    );
}

/// A region may not say what it cannot mean (each was accepted silently before): both `young`
/// and `mu` (the body refuses it too), keys only the zonal method reads under another method,
/// a setting of the whole body, and `nu = 0.5` under `standard` (which the solver refused
/// without naming the region).
#[test]
fn region_keys_that_do_nothing_are_named_errors() {
    let dir = scratch("regions-questionable");
    let error = |file: &str, material: &str| {
        bilayer(
            &dir,
            file,
            SOFT,
            &STIFF_LAYER.replace("young = 10e6", material),
        )
        .and_then(|s| check_scene(&s, None).map(|_| ()))
        .unwrap_err()
        .to_string()
    };
    let both = error("both.toml", "young = 10e6, mu = 3e6");
    assert!(
        both.contains("regions.0.material")
            && both.contains("stiff layer")
            && both.contains("young or mu"),
        "{both}"
    );
    for key in ["zonal_penalty", "lambda", "beta", "epsilon"] {
        let e = error(
            &format!("{key}.toml"),
            &format!("young = 10e6, {key} = 2.0"),
        );
        assert!(
            e.contains(&format!("regions.0.material.{key}"))
                && e.contains("stiff layer")
                && e.contains("mixed-p1"),
            "{e}"
        );
    }
    let empty = error("empty.toml", "");
    assert!(
        empty.contains("regions.0.material") && empty.contains("changes nothing"),
        "{empty}"
    );
    let skin = error("skin.toml", "young = 10e6, epidermis = true");
    assert!(
        skin.contains("regions.0.material.epidermis") && skin.contains("whole body"),
        "{skin}"
    );
    let mut scene = bilayer(
        &dir,
        "incompressible.toml",
        SOFT,
        &STIFF_LAYER.replace("young = 10e6", "young = 10e6, nu = 0.5"),
    )
    .unwrap();
    scene.method = isochor_scenes::format::MethodName(isochor_solvers::Method::Standard);
    let e = isochor_scenes::resolve::build(&scene)
        .map(|_| ())
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("regions.0.material.nu") && e.contains("stiff layer"),
        "{e}"
    );
}
