//! Triangle surfaces for rigid obstacles: Wavefront OBJ ([`read_obj`]), STL in its ASCII and
//! binary forms ([`read_stl`]) and the 3- and 6-node triangles of a Gmsh `.msh` file
//! ([`read_gmsh_surface`]), chosen by extension in [`read_surface`]. Open surfaces are
//! allowed. A file without triangles, a non-finite coordinate, an index out of range or a
//! truncated file is an error naming the file and the line (the byte offset in binary STL);
//! no count read from a file is allocated before the file is known to hold that much.

mod obj;
mod stl;

pub use obj::read_obj;
pub use stl::read_stl;

use super::extension;
use crate::{MeshError, Vec3};
use std::collections::HashMap;
use std::path::Path;

/// Vertices and triangles (three vertex indices each) of a surface, open or closed.
#[derive(Debug, Clone, PartialEq)]
pub struct TriangleSurface {
    /// The vertex positions.
    pub vertices: Vec<Vec3>,
    /// The triangles, as indices into `vertices`.
    pub triangles: Vec<[usize; 3]>,
}

impl TriangleSurface {
    /// The surface of `triangles` with the vertices that no triangle uses dropped and the
    /// rest renumbered in their order; `path` names the file in the error when there are no
    /// triangles.
    pub(crate) fn compact(
        path: &Path,
        vertices: &[Vec3],
        triangles: Vec<[usize; 3]>,
    ) -> Result<Self, MeshError> {
        if triangles.is_empty() {
            return Err(MeshError::Format {
                path: path.into(),
                message: "the file contains no triangles".into(),
            });
        }
        let mut index = vec![usize::MAX; vertices.len()];
        let mut kept = Vec::new();
        let triangles = triangles
            .into_iter()
            .map(|t| {
                t.map(|v| {
                    if index[v] == usize::MAX {
                        index[v] = kept.len();
                        kept.push(vertices[v]);
                    }
                    index[v]
                })
            })
            .collect();
        Ok(TriangleSurface {
            vertices: kept,
            triangles,
        })
    }
}

/// Reads a triangle surface chosen by its extension: `.obj`, `.stl` or `.msh`.
pub fn read_surface(path: impl AsRef<Path>) -> Result<TriangleSurface, MeshError> {
    let path = path.as_ref();
    match extension(path).as_deref() {
        Some("obj") => read_obj(path),
        Some("stl") => read_stl(path),
        Some("msh") => read_gmsh_surface(path),
        _ => Err(MeshError::Format {
            path: path.into(),
            message: "unknown surface format: expected a .obj, .stl or .msh file".into(),
        }),
    }
}

/// Reads the triangles (3-node, and the corners of 6-node ones) of a Gmsh ASCII file,
/// format 2.2 or 4.1, with or without tetrahedra; a triangle listed more than once (format
/// 2.2 repeats an element per physical group) is kept once.
pub fn read_gmsh_surface(path: impl AsRef<Path>) -> Result<TriangleSurface, MeshError> {
    let path = path.as_ref();
    let (positions, triangles) = super::gmsh::read_triangles(path)?;
    let mut seen = HashMap::new();
    let unique = triangles
        .into_iter()
        .filter(|t| seen.insert(*t, ()).is_none())
        .collect();
    TriangleSurface::compact(path, &positions, unique)
}

/// Welds vertices with exactly equal coordinates (`-0.0` and `0.0` are equal): the index of
/// each position, assigned in order of first appearance.
#[derive(Default)]
pub(crate) struct Welder {
    index: HashMap<[u64; 3], usize>,
    /// The distinct positions.
    pub vertices: Vec<Vec3>,
}

impl Welder {
    /// The index of `p`, a new one if it was not seen before.
    pub fn index(&mut self, p: Vec3) -> usize {
        // `+ 0.0` turns -0.0 into 0.0, so the bit patterns of equal coordinates are equal.
        let key = [p.x, p.y, p.z].map(|c| (c + 0.0).to_bits());
        let next = self.vertices.len();
        *self.index.entry(key).or_insert_with(|| {
            self.vertices.push(p);
            next
        })
    }
}
