//! A scene's mesh: generated or read, with the named groups of its source, built once.

use crate::error::SceneError;
use crate::format::{Generated, MeshSpec};
use isochor_mesh::element::TetElement;
use isochor_mesh::io::{read_gmsh_with_groups, read_tetgen_with_regions, PhysicalGroups};
use isochor_mesh::ElementMesh;
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

/// Generates or reads the mesh, with elements of `element`: a linear mesh (generated or read)
/// becomes 10-node by adding mid-edge nodes, on the true surface for the curved generators
/// (cylinder, puck, tube, ball) and at edge midpoints otherwise (a file's true surface is
/// unknown); a 10-node file is used as it is, or reduced to its corners for `tet4`.
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
    let read = read_mesh_file(path)?;
    let mut notices = Vec::new();
    if (element, read.kind()) == (TetElement::Tet4, TetElement::Tet10) {
        notices.push(format!(
            "the mesh file {} holds 10-node tets; element = \"tet4\" runs on their corners only (element = \"tet10\" uses every node)",
            path.display()
        ));
    }
    let mesh = match (element, read.kind()) {
        (TetElement::Tet4, TetElement::Tet10) => ElementMesh::linear(read.into_corners()),
        (TetElement::Tet10, TetElement::Tet4) => ElementMesh::quadratic(read.into_corners()),
        _ => read,
    };
    Ok(SceneMesh {
        mesh,
        groups: if file_groups {
            file_groups_of(path)?
        } else {
            None
        },
        source: format!("the mesh file {}", path.display()),
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
