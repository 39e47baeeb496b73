//! A scene's mesh: generated or read, with the named groups of its source, built once.

use crate::error::SceneError;
use crate::format::{Generated, GroupSpec, MeshSpec};
use isochor_mesh::element::TetElement;
use isochor_mesh::io::{
    read_gmsh_with_groups, read_tetgen_with_regions, PhysicalGroup, PhysicalGroups,
};
use isochor_mesh::{ElementMesh, Vec3};
use std::collections::BTreeMap;
use std::path::Path;

/// A scene's mesh and the named groups its selections may take (`physical`).
pub struct SceneMesh {
    /// The mesh, of the scene's element.
    pub mesh: ElementMesh,
    /// The named groups of the generator or the mesh file, if it has any (and, for a file,
    /// if they were asked for).
    pub groups: Option<PhysicalGroups>,
    /// What the mesh is, for errors about groups.
    pub source: String,
    /// What a user should know about how the mesh was taken (printed with the run's
    /// warnings), e.g. a 10-node file run on its corners.
    pub notices: Vec<String>,
}

/// Generates, reads or takes the mesh, with elements of `element`: a linear mesh (generated,
/// read or explicit) becomes 10-node by adding mid-edge nodes, on the true surface for the
/// curved generators (cylinder, puck, tube, ball) and at edge midpoints otherwise (a file's
/// true surface is unknown); a 10-node file or explicit mesh is used as it is, or reduced to
/// its corners for `tet4`.
pub fn build_mesh(spec: &MeshSpec, element: TetElement) -> Result<ElementMesh, SceneError> {
    Ok(mesh_with_groups(spec, element, false)?.mesh)
}

/// The mesh of [`build_mesh`] with the named groups of its source: a generator's (from the
/// same generation), or, when `file_groups`, a mesh file's physical groups or regions.
pub fn mesh_with_groups(
    spec: &MeshSpec,
    element: TetElement,
    file_groups: bool,
) -> Result<SceneMesh, SceneError> {
    let generated = match spec {
        MeshSpec::File { path } => return file_mesh(path, element, file_groups),
        MeshSpec::Explicit {
            positions,
            tets,
            groups,
        } => return explicit_mesh(positions, tets, groups, element),
        generator => generator.generate()?,
    };
    let Generated {
        mesh,
        groups,
        surface,
    } = generated;
    let source = if groups.is_some() {
        "a generated mesh with groups"
    } else {
        "a generated mesh"
    };
    Ok(SceneMesh {
        mesh: match (element, surface) {
            (TetElement::Tet4, _) => ElementMesh::linear(mesh),
            (TetElement::Tet10, None) => ElementMesh::quadratic(mesh),
            (TetElement::Tet10, Some(surface)) => ElementMesh::quadratic_on_surface(mesh, surface)?,
        },
        groups,
        source: source.to_string(),
        notices: Vec::new(),
    })
}

/// A mesh file's mesh, of `element` (a 10-node file reduced to its corners for `tet4`, a
/// 4-node one given mid-edge nodes for `tet10`), with its groups when `file_groups`.
fn file_mesh(path: &Path, element: TetElement, file_groups: bool) -> Result<SceneMesh, SceneError> {
    let source = format!("the mesh file {}", path.display());
    let (mesh, notices) = of_element(read_mesh_file(path)?, element, &source);
    Ok(SceneMesh {
        mesh,
        groups: if file_groups {
            file_groups_of(path)?
        } else {
            None
        },
        source,
        notices,
    })
}

/// A mesh read or given as it is, of `element` (10-node tets reduced to their corners for
/// `tet4`, 4-node ones given mid-edge nodes for `tet10`), with the notice of a reduction.
fn of_element(mesh: ElementMesh, element: TetElement, source: &str) -> (ElementMesh, Vec<String>) {
    match (element, mesh.kind()) {
        (TetElement::Tet4, TetElement::Tet10) => (
            ElementMesh::linear(mesh.into_corners()),
            vec![format!(
                "{source} holds 10-node tets; element = \"tet4\" runs on their corners only (element = \"tet10\" uses every node)"
            )],
        ),
        (TetElement::Tet10, TetElement::Tet4) => {
            (ElementMesh::quadratic(mesh.into_corners()), Vec::new())
        }
        _ => (mesh, Vec::new()),
    }
}

/// An explicit mesh (`generator = "explicit"`) of `element`, numbered as given, with its
/// named groups.
fn explicit_mesh(
    positions: &[[f64; 3]],
    tets: &[Vec<usize>],
    groups: &BTreeMap<String, GroupSpec>,
    element: TetElement,
) -> Result<SceneMesh, SceneError> {
    let invalid = |key: String, message: String| SceneError::Invalid {
        origin: "the explicit mesh".into(),
        key,
        message,
    };
    let kind = match tets.first().map(Vec::len) {
        Some(10) => TetElement::Tet10,
        _ => TetElement::Tet4,
    };
    if let Some(t) = tets.iter().position(|t| t.len() != kind.num_nodes()) {
        return Err(invalid(
            format!("mesh.tets.{t}"),
            format!(
                "has {} nodes, but tet 0 has {} (4 or 10 each, all alike)",
                tets[t].len(),
                kind.num_nodes()
            ),
        ));
    }
    let nodes: Vec<Vec3> = positions
        .iter()
        .map(|p| Vec3::new(p[0], p[1], p[2]))
        .collect();
    let connectivity = tets.iter().flatten().copied().collect();
    let mesh = ElementMesh::from_nodes(kind, nodes.clone(), connectivity)?;
    if mesh.nodes() != nodes.as_slice() {
        return Err(invalid(
            "mesh.positions".into(),
            "every node must be a tet's, the corners listed before the mid-edge nodes (the numbering `vertices` and the groups refer to)".into(),
        ));
    }
    let nv = mesh.num_vertices();
    let mut physical = Vec::new();
    for (tag, (name, g)) in groups.iter().enumerate() {
        let key = |what: &str| format!("mesh.groups.{name}{what}");
        let dimension = match (g.faces.is_empty(), g.tets.is_empty()) {
            (false, true) => 2,
            (true, false) => 3,
            _ => {
                return Err(invalid(
                    key(""),
                    "a group holds faces or tets (exactly one of the two)".into(),
                ))
            }
        };
        if let Some(&v) = g.faces.iter().flatten().find(|&&v| v >= nv) {
            return Err(invalid(
                key(".faces"),
                format!("node {v} is not a tet's corner (the mesh has {nv} corners)"),
            ));
        }
        if let Some(&t) = g.tets.iter().find(|&&t| t >= tets.len()) {
            return Err(invalid(
                key(".tets"),
                format!("tet {t} is out of range (the mesh has {} tets)", tets.len()),
            ));
        }
        physical.push(PhysicalGroup {
            dimension,
            tag: tag as i64 + 1,
            name: Some(name.clone()),
            faces: g.faces.clone(),
            tets: g.tets.clone(),
        });
    }
    let source = "the explicit mesh";
    let (mesh, notices) = of_element(mesh, element, source);
    Ok(SceneMesh {
        mesh,
        groups: (!physical.is_empty()).then(|| PhysicalGroups::new(physical)),
        source: source.into(),
        notices,
    })
}

/// The physical groups (Gmsh) or regions (TetGen) of a mesh file; `None` for a format
/// without them (`.vtu`).
fn file_groups_of(path: &Path) -> Result<Option<PhysicalGroups>, SceneError> {
    let extension = path
        .extension()
        .map(|e| e.to_string_lossy().to_ascii_lowercase());
    Ok(match extension.as_deref() {
        Some("msh") => Some(read_gmsh_with_groups(path)?.1),
        Some("node" | "ele") => Some(read_tetgen_with_regions(path)?.1),
        _ => None,
    })
}

/// Reads a mesh file of 4- or 10-node tets by its extension; a missing file or a folder is
/// said to be one.
pub fn read_mesh_file(path: &Path) -> Result<ElementMesh, SceneError> {
    const VALID: &str = ".msh (Gmsh), .node/.ele (TetGen), .vtu";
    let check = |p: &Path| -> Result<(), SceneError> {
        let message = if p.is_dir() {
            "is a directory, not a mesh file"
        } else if p.is_file() {
            return Ok(());
        } else {
            "mesh file not found"
        };
        Err(SceneError::io(
            p,
            std::io::Error::new(std::io::ErrorKind::NotFound, message),
        ))
    };
    let ext = path
        .extension()
        .and_then(|e| e.to_str())
        .unwrap_or("")
        .to_ascii_lowercase();
    match ext.as_str() {
        "node" | "ele" => {
            check(&path.with_extension("node"))?;
            check(&path.with_extension("ele"))?;
        }
        "msh" | "vtu" => check(path)?,
        _ if path.is_dir() => check(path)?,
        _ => {
            return Err(SceneError::Invalid {
                origin: path.display().to_string(),
                key: "mesh.path".into(),
                message: format!(
                    "unknown mesh file type '.{}' (valid: {VALID})",
                    isochor_mesh::io::excerpt(&ext)
                ),
            })
        }
    }
    Ok(isochor_mesh::io::read_mesh_elements(path)?)
}
