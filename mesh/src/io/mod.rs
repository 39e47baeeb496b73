//! File I/O: VTU/PVD for ParaView and meshio, Gmsh `.msh` (2.2 and 4.1 ASCII) and TetGen
//! `.node`/`.ele` readers. Readers never panic on malformed input: they return
//! [`MeshError::Parse`] with the path, the line and what was expected. Writers are atomic.

mod atomic;
mod gmsh;
mod pvd;
mod tetgen;
mod text;
mod vtu;

pub use gmsh::read_gmsh;
pub use pvd::write_pvd;
pub use tetgen::read_tetgen;
pub use vtu::{read_vtu, read_vtu_file, write_vtu, Field, FieldValues, VtuFile};

use crate::{MeshError, TetMesh, Vec3};
use std::path::Path;

/// Reads a mesh file chosen by its extension: `.msh` (Gmsh), `.vtu`, `.node` or `.ele`
/// (TetGen; the other file of the pair is found next to it).
pub fn read_mesh(path: impl AsRef<Path>) -> Result<TetMesh, MeshError> {
    let path = path.as_ref();
    let extension = path
        .extension()
        .and_then(|e| e.to_str())
        .map(str::to_ascii_lowercase);
    match extension.as_deref() {
        Some("msh") => read_gmsh(path),
        Some("vtu") => read_vtu(path),
        Some("node" | "ele") => read_tetgen(path),
        _ => Err(MeshError::Format {
            path: path.into(),
            message: "unknown mesh format: expected a .msh, .vtu, .node or .ele file".into(),
        }),
    }
}

/// Reads a whole file as text (invalid UTF-8 is replaced, and then fails to parse).
fn read_text(path: &Path) -> Result<String, MeshError> {
    let bytes = std::fs::read(path).map_err(|e| MeshError::io(path, e))?;
    Ok(String::from_utf8_lossy(&bytes).into_owned())
}

/// Builds a mesh from parsed vertices and tets, dropping vertices no tet uses (renumbering
/// the rest in order). A tet the constructor rejects is reported at its line `tet_lines[e]`
/// of `path`.
fn assemble(
    path: &Path,
    positions: Vec<Vec3>,
    mut tets: Vec<[usize; 4]>,
    tet_lines: &[usize],
) -> Result<TetMesh, MeshError> {
    if tets.is_empty() {
        return Err(MeshError::Format {
            path: path.into(),
            message: "the file contains no linear tetrahedra".into(),
        });
    }
    let mut new_index = vec![usize::MAX; positions.len()];
    tets.iter().flatten().for_each(|&v| new_index[v] = 0);
    let mut kept = Vec::new();
    for (v, p) in positions.into_iter().enumerate() {
        if new_index[v] == 0 {
            new_index[v] = kept.len();
            kept.push(p);
        }
    }
    tets.iter_mut().for_each(|t| *t = t.map(|v| new_index[v]));
    TetMesh::new(kept, tets).map_err(|e| {
        let tet = match e {
            MeshError::RepeatedVertex { tet, .. } | MeshError::Degenerate { tet, .. } => tet,
            other => return other,
        };
        let line = tet_lines.get(tet).copied().unwrap_or(0);
        MeshError::parse(path, line, e.to_string())
    })
}
