//! Mesh files through the mesh crate's readers, chosen by extension.

use crate::SceneError;
use isochor_mesh::TetMesh;
use std::path::Path;

/// Reads `path` (extension `ext`, lower case: msh, node, ele or vtu; the file exists).
pub fn read(path: &Path, ext: &str) -> Result<TetMesh, SceneError> {
    // TODO(mesh io): call isochor_mesh's Gmsh / TetGen / VTU readers once they land.
    Err(SceneError::Invalid {
        origin: path.display().to_string(),
        key: "mesh.path".into(),
        message: format!("reading .{ext} meshes is not available yet in isochor-mesh"),
    })
}
