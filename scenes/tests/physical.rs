//! Gmsh physical groups as selections: the second-order tube of the mesh crate's test data
//! (`tube-tet10-v41.msh`: radii 0.02 and 0.03 m, z from 0 to 0.06 m, surface groups
//! `inner`, `outer`, `bottom`, `top` and volume group `tube`) clamped by its `bottom` group
//! and inflated through its `inner` group, as the same run with geometric selections.

use crate::common::scratch;
use isochor_scenes::resolve::mesh_with_groups;
use isochor_scenes::resolve::Selections;
use isochor_scenes::{load_scene, run_scene, RunOptions, Scene, SceneError};
use std::path::{Path, PathBuf};

fn tube_mesh() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../mesh/tests/data/tube-tet10-v41.msh")
}

/// The tube scene with `mesh` (a TOML table body) and `selections` (TOML tables for
/// `base` and `cavity`), written to `dir` and loaded.
fn write_scene(dir: &Path, file: &str, mesh: &str, selections: &str) -> Result<Scene, SceneError> {
    let text = format!(
        r#"name = "physical-tube"
method = "mixed-p1"
element = "tet4"

[mesh]
{mesh}

[material]
young = 90e3
nu = 0.49
rho = 1070.0

{selections}

[[dirichlet]]
selection = "base"

[[loads.pressure]]
selection = "cavity"
pressure = 2e3

[stepping]
mode = "quasi-static"
steps = 2
increments = "fixed"

[probes.volume_change]
kind = "volume-change"
"#
    );
    let path = dir.join(file);
    std::fs::write(&path, text).unwrap();
    load_scene(path.to_str().unwrap(), None, &[])
}

fn file_mesh() -> String {
    format!(
        "generator = \"file\"\npath = {:?}",
        tube_mesh().to_str().unwrap()
    )
}

const PHYSICAL: &str = r#"[selections.base]
physical = "bottom"

[selections.cavity]
physical = "inner"
"#;

#[test]
fn physical_groups_clamp_and_pressurize_like_geometric_selections() {
    let dir = scratch("physical-run");
    let physical = write_scene(&dir, "physical.toml", &file_mesh(), PHYSICAL).unwrap();
    let geometric = write_scene(
        &dir,
        "geometric.toml",
        &file_mesh(),
        "[selections.base]\nplane = { point = [0.0, 0.0, 0.0], normal = [0.0, 0.0, 1.0] }\n\n\
         [selections.cavity]\nradial = { max = 0.02 }\n",
    )
    .unwrap();
    let (a, _) = run_scene(&physical, &RunOptions::default()).unwrap();
    let (b, _) = run_scene(&geometric, &RunOptions::default()).unwrap();
    assert!(a.converged && b.converged, "{:?} {:?}", a.error, b.error);
    assert_eq!(a.steps, 2);
    // A 10-node file run on its corners says so (before: not a word).
    assert!(
        a.warnings
            .iter()
            .any(|w| w.contains("holds 10-node tets") && w.contains("corners only")),
        "{:?}",
        a.warnings
    );
    let (va, vb) = (a.probes["volume_change"], b.probes["volume_change"]);
    eprintln!("physical-tube: volume change {va:e} (geometric selections: {vb:e})");
    assert!(va.abs() < 1e-2, "nearly incompressible: {va}");
    assert!((va - vb).abs() <= 1e-9 * va.abs().max(1e-12), "{va} {vb}");
    assert_eq!(a.newton_iterations, b.newton_iterations);
    std::fs::remove_dir_all(&dir).unwrap();
}

/// On 10-node tets a surface group holds every node of its 6-node faces; a volume group
/// with `surface = true` selects the boundary faces of its tets.
#[test]
fn physical_selections_on_quadratic_tets() {
    let dir = scratch("physical-tet10");
    let selections = format!(
        "{PHYSICAL}\n[selections.skin]\nphysical = \"tube\"\nsurface = true\n\n\
         [selections.body]\nphysical = \"tube\"\n"
    );
    let mut scene = write_scene(&dir, "tet10.toml", &file_mesh(), &selections).unwrap();
    scene.element = isochor_scenes::format::ElementName(isochor_mesh::element::TetElement::Tet10);
    let resolved = mesh_with_groups(scene.mesh.as_ref().unwrap(), scene.element(), true).unwrap();
    assert!(
        resolved.notices.is_empty(),
        "every node used: nothing to say"
    );
    let s = Selections::new(&resolved, &scene.selections).unwrap();
    let mesh = &resolved.mesh;
    let x = mesh.nodes();
    let boundary = mesh.boundary().unwrap();
    let bottom: Vec<usize> = {
        let mut n: Vec<usize> = (0..boundary.len())
            .filter(|&f| boundary.face(f).iter().all(|&i| x[i].z.abs() < 1e-12))
            .flat_map(|f| boundary.face(f).to_vec())
            .collect();
        n.sort_unstable();
        n.dedup();
        n
    };
    assert_eq!(s.faces("base").unwrap().len(), 111);
    assert_eq!(s.nodes("base").unwrap(), bottom);
    assert!(s.nodes("base").unwrap().len() > s.vertices("base").unwrap().len());
    assert_eq!(s.faces("skin").unwrap().len(), boundary.len());
    assert_eq!(s.tets("body").unwrap().len(), 2257);
    assert_eq!(s.vertices("body").unwrap().len(), mesh.num_vertices());
    let e = s.tets("cavity").unwrap_err().to_string();
    assert!(e.contains("'cavity'") && e.contains("surface group"), "{e}");
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn missing_groups_and_generated_meshes_are_errors() {
    let dir = scratch("physical-errors");
    let missing = PHYSICAL.replace("\"inner\"", "\"chamber\"");
    let scene = write_scene(&dir, "missing.toml", &file_mesh(), &missing).unwrap();
    let e = run_scene(&scene, &RunOptions::default())
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("selection 'cavity'")
            && e.contains("no physical group \"chamber\"")
            && e.contains("tube-tet10-v41.msh")
            && e.contains("groups: bottom, inner, outer, top, tube"),
        "{e}"
    );
    let generated =
        "generator = \"tube\"\ninner_radius = 0.02\nouter_radius = 0.03\nheight = 0.06\nres = 1";
    let scene = write_scene(&dir, "generated.toml", generated, PHYSICAL).unwrap();
    let e = run_scene(&scene, &RunOptions::default())
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("selection 'base'")
            && e.contains("needs a mesh with named groups")
            && e.contains("generated mesh"),
        "{e}"
    );
    std::fs::remove_dir_all(&dir).unwrap();
}

/// A group name that two dimensions use is reported as ambiguous with its dimensions, and
/// a curve group is found and refused as one. Before: both were "no physical group".
#[test]
fn ambiguous_and_curve_groups_say_what_they_are() {
    let dir = scratch("physical-ambiguous");
    let gmsh = Path::new(env!("CARGO_MANIFEST_DIR")).join("../mesh/tests/data/two-groups-v22.msh");
    let text = std::fs::read_to_string(gmsh)
        .unwrap()
        .replace("2 1 \"base\"", "2 1 \"all\"");
    let mesh = dir.join("two-groups.msh");
    std::fs::write(&mesh, text).unwrap();
    let mesh_table = format!("generator = \"file\"\npath = \"{}\"", mesh.display());
    let select = |base: &str| {
        let scene = write_scene(
            &dir,
            "scene.toml",
            &mesh_table,
            &format!(
                "[selections.base]\nphysical = \"{base}\"\n\n[selections.cavity]\nphysical = \"3:all\"\n"
            ),
        )
        .unwrap();
        let resolved =
            mesh_with_groups(scene.mesh.as_ref().unwrap(), scene.element(), true).unwrap();
        let s = Selections::new(&resolved, &scene.selections).unwrap();
        s.vertices("base").map(|_| ())
    };
    let err = select("all").unwrap_err().to_string();
    assert!(
        err.contains("ambiguous")
            && err.contains("dimensions 2 and 3")
            && err.contains("\"2:all\""),
        "{err}"
    );
    let err = select("edge").unwrap_err().to_string();
    assert!(err.contains("curves (dimension 1)"), "{err}");
    assert!(select("2:all").is_ok());
    std::fs::remove_dir_all(&dir).unwrap();
}
