//! File I/O: VTU (ASCII or zlib-compressed binary) and PVD for ParaView and meshio, Gmsh
//! `.msh` (2.2 and 4.1 ASCII) and TetGen `.node`/`.ele` readers, and triangle surfaces of
//! rigid obstacles (OBJ, STL, Gmsh triangles: [`read_surface`]). Readers never panic on
//! malformed input: they return [`MeshError::Parse`] with the path, the line and what was
//! expected. Writers are atomic.
//!
//! Gmsh and VTU files may hold 4- or 10-node tets: [`read_mesh_elements`] (and
//! [`read_gmsh_elements`], [`read_vtu_elements`]) return an [`ElementMesh`] of the file's
//! order; [`read_mesh`] (and [`read_gmsh`], [`read_vtu`]) return the linear [`TetMesh`] of a
//! linear file and refuse a quadratic one, naming the line or cell, rather than silently
//! dropping its curved geometry (its corner mesh is `read_mesh_elements(path)?.corners()`).
//!
//! [`read_gmsh_with_groups`] also returns the Gmsh physical groups of surfaces and volumes
//! ([`PhysicalGroups`]), numbered as the mesh.

mod atomic;
mod gmsh;
mod pvd;
mod surface;
mod tetgen;
mod text;
mod vtk_binary;
mod vtp;
mod vtu;

pub use crate::groups::{PhysicalGroup, PhysicalGroups};
pub use gmsh::{read_gmsh, read_gmsh_elements, read_gmsh_with_groups};
pub use pvd::{write_pvd, write_pvd_parts};
pub use surface::{read_gmsh_surface, read_obj, read_stl, read_surface, TriangleSurface};
pub use tetgen::{read_tetgen, read_tetgen_with_regions};
pub use text::excerpt;
pub use vtp::write_vtp_triangles;
pub use vtu::{
    read_vtu, read_vtu_elements, read_vtu_file, write_vtu, write_vtu_elements, Field, FieldValues,
    VtuEncoding, VtuFile,
};

use crate::element::{Labels, TetElement};
use crate::{ElementMesh, MeshError, TetMesh, Vec3};
use std::path::Path;

/// Reads a mesh file chosen by its extension: `.msh` (Gmsh), `.vtu`, `.node` or `.ele`
/// (TetGen; the other file of the pair is found next to it).
pub fn read_mesh(path: impl AsRef<Path>) -> Result<TetMesh, MeshError> {
    let path = path.as_ref();
    match extension(path).as_deref() {
        Some("msh") => read_gmsh(path),
        Some("vtu") => read_vtu(path),
        Some("node" | "ele") => read_tetgen(path),
        _ => Err(unknown_format(path)),
    }
}

/// Reads a mesh file of 4- or 10-node tets chosen by its extension, like [`read_mesh`]: a
/// TetGen pair gives a 4-node mesh.
pub fn read_mesh_elements(path: impl AsRef<Path>) -> Result<ElementMesh, MeshError> {
    let path = path.as_ref();
    match extension(path).as_deref() {
        Some("msh") => read_gmsh_elements(path),
        Some("vtu") => read_vtu_elements(path),
        Some("node" | "ele") => Ok(ElementMesh::linear(read_tetgen(path)?)),
        _ => Err(unknown_format(path)),
    }
}

/// The lower-case extension of `path`.
fn extension(path: &Path) -> Option<String> {
    path.extension()
        .and_then(|e| e.to_str())
        .map(str::to_ascii_lowercase)
}

fn unknown_format(path: &Path) -> MeshError {
    MeshError::Format {
        path: path.into(),
        message: "unknown mesh format: expected a .msh, .vtu, .node or .ele file".into(),
    }
}

/// Reads a whole file as text (invalid UTF-8 is replaced, and then fails to parse).
fn read_text(path: &Path) -> Result<String, MeshError> {
    let bytes = read_regular_file(path)?;
    Ok(String::from_utf8_lossy(&bytes).into_owned())
}

/// Reads a whole regular file; a device (`/dev/zero`, `/dev/urandom`), FIFO or socket, or a
/// link to one, is refused before it is opened (reading one would never end, or block).
pub(crate) fn read_regular_file(path: &Path) -> Result<Vec<u8>, MeshError> {
    check_regular_file(path)?;
    std::fs::read(path).map_err(|e| MeshError::io(path, e))
}

/// Refuses a `path` that is a device, FIFO or socket (symbolic links followed) without
/// opening it; a missing path or a folder is left to the reader, which says so.
pub fn check_regular_file(path: &Path) -> Result<(), MeshError> {
    match std::fs::metadata(path) {
        Ok(m) if !m.is_file() && !m.is_dir() => Err(MeshError::Format {
            path: path.into(),
            message: format!(
                "is a {}, not a regular file: refused before reading",
                file_kind(&m.file_type())
            ),
        }),
        _ => Ok(()),
    }
}

/// What a file that is not regular is, for messages.
fn file_kind(kind: &std::fs::FileType) -> &'static str {
    #[cfg(unix)]
    {
        use std::os::unix::fs::FileTypeExt;
        if kind.is_char_device() || kind.is_block_device() {
            return "device";
        }
        if kind.is_fifo() {
            return "FIFO (named pipe)";
        }
        if kind.is_socket() {
            return "socket";
        }
    }
    #[cfg(not(unix))]
    let _ = kind;
    "special file"
}

/// The elements read from a file: their kind, `kind.num_nodes()` node indices per element, and
/// the tag (number in the file) and line of each.
struct Cells {
    kind: TetElement,
    connectivity: Vec<usize>,
    tags: Vec<usize>,
    lines: Vec<usize>,
}

/// Parsed nodes: positions and the tag (number in the file) of each.
struct FileNodes {
    positions: Vec<Vec3>,
    tags: Vec<usize>,
}

/// Builds a mesh from parsed nodes and elements with [`ElementMesh::from_nodes`] (which drops
/// nodes no element uses and renumbers the rest, corners first, in order). An element the
/// constructor rejects is reported at its line of `path`, with nodes and elements numbered by
/// their tags in the file.
fn assemble(path: &Path, nodes: FileNodes, cells: Cells) -> Result<ElementMesh, MeshError> {
    if cells.connectivity.is_empty() {
        return Err(MeshError::Format {
            path: path.into(),
            message: "the file contains no tetrahedra".into(),
        });
    }
    let labels = Labels {
        nodes: Some(&nodes.tags),
        elements: Some(&cells.tags),
    };
    ElementMesh::from_labelled_nodes(cells.kind, nodes.positions, cells.connectivity, labels)
        .map_err(|e| {
            let tag = match e {
                MeshError::RepeatedVertex { tet, .. } | MeshError::Degenerate { tet, .. } => tet,
                MeshError::FoldedElement { element, .. }
                | MeshError::MidEdgeNode { element, .. } => element,
                other => return other,
            };
            let line = cells
                .tags
                .iter()
                .position(|&t| t == tag)
                .and_then(|e| cells.lines.get(e).copied())
                .unwrap_or(0);
            MeshError::parse(path, line, format!("{e} (numbered as in the file)"))
        })
}
