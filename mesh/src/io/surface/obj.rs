//! Wavefront OBJ surfaces: `v x y z [w]` vertices and `f` faces of three or more vertices
//! (`i`, `i/t`, `i//n` or `i/t/n`; 1-based, negative indices counting back from the latest
//! vertex), each polygon split into a fan of triangles from its first vertex. Every other
//! statement (normals, texture coordinates, groups, materials, lines) is ignored.

use super::TriangleSurface;
use crate::io::read_text;
use crate::io::text::{excerpt, Fields, Lines};
use crate::{MeshError, Vec3};
use std::path::Path;

/// Reads an OBJ file's triangles (see the module docs).
pub fn read_obj(path: impl AsRef<Path>) -> Result<TriangleSurface, MeshError> {
    let path = path.as_ref();
    let text = read_text(path)?;
    let mut lines = Lines::new(path, &text, Some('#'));
    let mut vertices = Vec::new();
    let mut triangles = Vec::new();
    while let Some(mut f) = lines.next_fields() {
        match f.word() {
            Some("v") => {
                vertices.push(Vec3::new(
                    f.f64("x coordinate")?,
                    f.f64("y coordinate")?,
                    f.f64("z coordinate")?,
                ));
            }
            Some("f") => {
                let corners = face(&mut f, vertices.len())?;
                if corners.len() < 3 {
                    return Err(f.error(format!(
                        "a face needs at least 3 vertices, found {}",
                        corners.len()
                    )));
                }
                for k in 1..corners.len() - 1 {
                    triangles.push([corners[0], corners[k], corners[k + 1]]);
                }
            }
            _ => {}
        }
    }
    TriangleSurface::compact(path, &vertices, triangles)
}

/// The 0-based vertex indices of a face's fields, `count` vertices read so far.
fn face(f: &mut Fields, count: usize) -> Result<Vec<usize>, MeshError> {
    let mut corners = Vec::new();
    while let Some(token) = f.word() {
        let first = token.split('/').next().unwrap_or("");
        let index: i64 = first.parse().map_err(|_| {
            f.error(format!(
                "expected a vertex index (an integer), found `{}`",
                excerpt(token)
            ))
        })?;
        // 1-based from the first vertex, or negative from the latest.
        let resolved = match index {
            i if i > 0 => usize::try_from(i - 1).ok(),
            i if i < 0 => usize::try_from(-i)
                .ok()
                .and_then(|back| count.checked_sub(back)),
            _ => None,
        };
        match resolved.filter(|&v| v < count) {
            Some(v) => corners.push(v),
            None => {
                return Err(f.error(format!(
                    "vertex index {index} is out of range: {count} vertices are defined above this line"
                )))
            }
        }
    }
    Ok(corners)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn read(text: &str) -> Result<TriangleSurface, MeshError> {
        let path = std::env::temp_dir().join(format!(
            "isochor-obj-{}-{}.obj",
            std::process::id(),
            text.len()
        ));
        std::fs::write(&path, text).unwrap();
        let result = read_obj(&path);
        std::fs::remove_file(&path).unwrap();
        result
    }

    #[test]
    fn a_quad_is_two_triangles_and_negative_indices_count_back() {
        let s = read(
            "# a square\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvn 0 0 1\nf 1//1 2//1 3//1 4//1\n",
        )
        .unwrap();
        assert_eq!(s.triangles, [[0, 1, 2], [0, 2, 3]]);
        let s = read("v 0 0 0\nv 1 0 0\nv 1 1 0\nf -3 -2 -1\n").unwrap();
        assert_eq!(s.triangles, [[0, 1, 2]]);
    }

    #[test]
    fn bad_files_name_the_line() {
        let line = |text: &str| match read(text) {
            Err(MeshError::Parse { line, message, .. }) => (line, message),
            other => panic!("expected a parse error, got {other:?}"),
        };
        assert_eq!(line("v 0 0 0\nv 1 0 nan\n").0, 2);
        assert_eq!(line("v 0 0 0\nv 1 0 0\nv 0 1 0\n\nf 1 2 4\n").0, 5);
        assert_eq!(line("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 -4\n").0, 4);
        assert_eq!(line("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 0\n").0, 4);
        assert_eq!(line("v 0 0 0\nv 1 0 0\nf 1 2\n").0, 3);
        assert!(line("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 x\n")
            .1
            .contains("`x`"));
        assert!(matches!(read("v 0 0 0\n"), Err(MeshError::Format { .. })));
    }
}
