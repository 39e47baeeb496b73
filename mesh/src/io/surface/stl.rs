//! STL surfaces, ASCII (`solid ... facet normal ... outer loop vertex x y z (x3) endloop
//! endfacet ... endsolid`) or binary (an 80-byte header, a little-endian `u32` triangle
//! count, then 50 bytes per triangle: normal, three vertices as `f32`, a 2-byte attribute).
//! A file starting with `solid` is read as ASCII unless its size is exactly that of a binary
//! STL of its declared count or it holds a zero byte (a binary header may start with
//! `solid` too; its count and coordinates nearly always hold a zero byte). STL repeats every vertex in each triangle: vertices with exactly equal
//! coordinates are welded into one; facet normals are ignored.

use super::{TriangleSurface, Welder};
use crate::io::read_regular_file;
use crate::io::text::{excerpt, Fields, Lines};
use crate::{MeshError, Vec3};
use std::path::Path;

/// Bytes of a binary STL's header and count.
const HEADER: usize = 84;
/// Bytes of a binary STL triangle.
const TRIANGLE: usize = 50;

/// Reads an ASCII or binary STL file (see the module docs).
pub fn read_stl(path: impl AsRef<Path>) -> Result<TriangleSurface, MeshError> {
    let path = path.as_ref();
    let bytes = read_regular_file(path)?;
    let declared = bytes
        .get(80..HEADER)
        .map(|c| u32::from_le_bytes([c[0], c[1], c[2], c[3]]) as usize);
    let binary_size = declared.and_then(|n| n.checked_mul(TRIANGLE)?.checked_add(HEADER));
    let ascii = binary_size != Some(bytes.len())
        && !bytes.contains(&0)
        && bytes.trim_ascii_start().starts_with(b"solid");
    if ascii {
        return read_ascii(path, &String::from_utf8_lossy(&bytes));
    }
    read_binary(path, &bytes)
}

fn read_binary(path: &Path, bytes: &[u8]) -> Result<TriangleSurface, MeshError> {
    let error = |offset: usize, message: String| MeshError::Format {
        path: path.into(),
        message: format!("binary STL, byte {offset}: {message}"),
    };
    if bytes.len() < HEADER {
        return Err(error(
            bytes.len(),
            format!(
                "truncated: the file has {} bytes, less than the {HEADER}-byte header and triangle count (nor is it an ASCII STL starting with `solid`)",
                bytes.len()
            ),
        ));
    }
    let count = u32::from_le_bytes([bytes[80], bytes[81], bytes[82], bytes[83]]) as usize;
    let body = bytes.len() - HEADER;
    if body / TRIANGLE < count {
        return Err(error(
            HEADER + (body / TRIANGLE) * TRIANGLE,
            format!(
                "truncated: the header declares {count} triangles but the file holds {} bytes of triangles, room for {}",
                body,
                body / TRIANGLE
            ),
        ));
    }
    if body != count * TRIANGLE {
        return Err(error(
            HEADER + count * TRIANGLE,
            format!(
                "{} bytes after the {count} declared triangles",
                body - count * TRIANGLE
            ),
        ));
    }
    let mut welder = Welder::default();
    let mut triangles = Vec::with_capacity(count);
    for (t, record) in bytes[HEADER..].chunks_exact(TRIANGLE).enumerate() {
        let offset = HEADER + t * TRIANGLE;
        let mut corner = [0; 3];
        for (k, c) in corner.iter_mut().enumerate() {
            // Past the 12-byte normal, 12 bytes per vertex.
            let start = 12 + 12 * k;
            let coordinate = |a: usize| {
                let b = &record[start + 4 * a..start + 4 * a + 4];
                f64::from(f32::from_le_bytes([b[0], b[1], b[2], b[3]]))
            };
            let p = Vec3::new(coordinate(0), coordinate(1), coordinate(2));
            if !p.iter().all(|v| v.is_finite()) {
                return Err(error(
                    offset + start,
                    format!(
                        "vertex {} of triangle {} has a non-finite coordinate {:?}",
                        k + 1,
                        t + 1,
                        [p.x, p.y, p.z]
                    ),
                ));
            }
            *c = welder.index(p);
        }
        triangles.push(corner);
    }
    TriangleSurface::compact(path, &welder.vertices, triangles)
}

fn read_ascii(path: &Path, text: &str) -> Result<TriangleSurface, MeshError> {
    let mut lines = Lines::new(path, text, None);
    let keyword = |f: &mut Fields, expected: &str| -> Result<(), MeshError> {
        match f.word() {
            Some(w) if w == expected => Ok(()),
            Some(w) => Err(f.error(format!("expected `{expected}`, found `{}`", excerpt(w)))),
            None => Err(f.error(format!("expected `{expected}`, found end of line"))),
        }
    };
    keyword(&mut lines.fields("`solid`")?, "solid")?;
    let mut welder = Welder::default();
    let mut triangles = Vec::new();
    loop {
        let mut f = lines.fields("`facet normal` or `endsolid`")?;
        match f.word().unwrap_or_default() {
            "endsolid" => break,
            "facet" => {}
            w => {
                return Err(f.error(format!(
                    "expected `facet normal` or `endsolid`, found `{}`",
                    excerpt(w)
                )))
            }
        }
        let mut outer = lines.fields("`outer loop`")?;
        keyword(&mut outer, "outer")?;
        keyword(&mut outer, "loop")?;
        outer.end("`outer loop`")?;
        let mut corner = [0; 3];
        for c in &mut corner {
            let mut v = lines.fields("`vertex x y z`")?;
            keyword(&mut v, "vertex")?;
            let p = Vec3::new(
                v.f64("x coordinate")?,
                v.f64("y coordinate")?,
                v.f64("z coordinate")?,
            );
            v.end("`vertex x y z`")?;
            *c = welder.index(p);
        }
        for end in ["endloop", "endfacet"] {
            let mut f = lines.fields(&format!("`{end}`"))?;
            keyword(&mut f, end)?;
            f.end(&format!("`{end}`"))?;
        }
        triangles.push(corner);
    }
    TriangleSurface::compact(path, &welder.vertices, triangles)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn read(name: &str, bytes: &[u8]) -> Result<TriangleSurface, MeshError> {
        let path =
            std::env::temp_dir().join(format!("isochor-stl-{}-{name}.stl", std::process::id()));
        std::fs::write(&path, bytes).unwrap();
        let result = read_stl(&path);
        std::fs::remove_file(&path).unwrap();
        result
    }

    /// A binary STL of `triangles` (their vertices), with a header starting with `solid`.
    fn binary(triangles: &[[[f32; 3]; 3]]) -> Vec<u8> {
        let mut bytes = b"solid but binary".to_vec();
        bytes.resize(80, b' ');
        bytes.extend((triangles.len() as u32).to_le_bytes());
        for t in triangles {
            bytes.extend([0u8; 12]);
            for v in t {
                for c in v {
                    bytes.extend(c.to_le_bytes());
                }
            }
            bytes.extend([0u8; 2]);
        }
        bytes
    }

    #[test]
    fn binary_square_welds_its_shared_vertices() {
        let square = [
            [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [1.0, 1.0, 0.0]],
            [[0.0, 0.0, -0.0], [1.0, 1.0, 0.0], [0.0, 1.0, 0.0]],
        ];
        let s = read("square", &binary(&square)).unwrap();
        assert_eq!(s.vertices.len(), 4);
        assert_eq!(s.triangles, [[0, 1, 2], [0, 2, 3]]);
    }

    #[test]
    fn bad_binary_files_name_the_byte() {
        let message = |bytes: &[u8]| match read("bad", bytes) {
            Err(MeshError::Format { message, .. }) => message,
            other => panic!("expected a format error, got {other:?}"),
        };
        let one = binary(&[[[0.0; 3], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]]]);
        assert!(message(&one[..100]).contains("truncated"));
        // An absurd count is refused from the file's size, before any allocation.
        let mut absurd = one.clone();
        absurd[80..84].copy_from_slice(&u32::MAX.to_le_bytes());
        assert!(message(&absurd).contains("4294967295 triangles"));
        let mut nan = one.clone();
        nan[84 + 12 + 12 + 4..84 + 12 + 12 + 8].copy_from_slice(&f32::NAN.to_le_bytes());
        assert!(message(&nan).contains("byte 108"), "{}", message(&nan));
        assert!(message(&binary(&[])).contains("no triangles"));
    }

    #[test]
    fn ascii_reads_and_names_the_line() {
        let text = "solid plate\nfacet normal 0 0 1\n outer loop\n  vertex 0 0 0\n  vertex 1 0 0\n  vertex 0 1 0\n endloop\nendfacet\nendsolid plate\n";
        let s = read("ascii", text.as_bytes()).unwrap();
        assert_eq!((s.vertices.len(), s.triangles.len()), (3, 1));
        let line = |text: &str| match read("ascii-bad", text.as_bytes()) {
            Err(MeshError::Parse { line, .. }) => line,
            other => panic!("expected a parse error, got {other:?}"),
        };
        assert_eq!(line(&text.replace("vertex 1 0 0", "vertex 1 inf 0")), 5);
        assert_eq!(line(&text.replace("endloop", "endloop x")), 7);
        assert_eq!(line(&text.replace("endsolid plate\n", "")), 9);
        assert!(matches!(
            read("empty", b"solid x\nendsolid x\n"),
            Err(MeshError::Format { .. })
        ));
    }
}
