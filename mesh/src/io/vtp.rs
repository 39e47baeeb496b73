//! VTK XML PolyData (`.vtp`) of a triangle surface, for the meshed obstacles of the frames.

use super::atomic::write_atomic;
use crate::{MeshError, Vec3};
use std::io::Write;
use std::path::Path;

/// Writes the triangles `triangles` over `points` as an ASCII `.vtp` file (points `Float64`,
/// the triangles as `Polys`, connectivity and offsets `Int64`; reals in the shortest form
/// that reads back to the same `f64`). The write is atomic; an index out of range is an
/// error.
pub fn write_vtp_triangles(
    path: impl AsRef<Path>,
    points: &[Vec3],
    triangles: &[[usize; 3]],
) -> Result<(), MeshError> {
    if let Some((t, &index)) = triangles
        .iter()
        .enumerate()
        .find_map(|(t, tri)| tri.iter().find(|&&v| v >= points.len()).map(|v| (t, v)))
    {
        return Err(MeshError::IndexOutOfRange {
            tet: t,
            index,
            vertices: points.len(),
        });
    }
    write_atomic(path.as_ref(), |w: &mut dyn Write| {
        writeln!(w, r#"<?xml version="1.0"?>"#)?;
        writeln!(
            w,
            r#"<VTKFile type="PolyData" version="1.0" byte_order="LittleEndian" header_type="UInt64">"#
        )?;
        writeln!(w, "  <PolyData>")?;
        writeln!(
            w,
            r#"    <Piece NumberOfPoints="{}" NumberOfPolys="{}">"#,
            points.len(),
            triangles.len()
        )?;
        writeln!(w, "      <Points>")?;
        writeln!(
            w,
            r#"        <DataArray type="Float64" NumberOfComponents="3" format="ascii">"#
        )?;
        for p in points {
            writeln!(w, "{:?} {:?} {:?}", p.x, p.y, p.z)?;
        }
        writeln!(w, "        </DataArray>")?;
        writeln!(w, "      </Points>")?;
        writeln!(w, "      <Polys>")?;
        writeln!(
            w,
            r#"        <DataArray type="Int64" Name="connectivity" format="ascii">"#
        )?;
        for [a, b, c] in triangles {
            writeln!(w, "{a} {b} {c}")?;
        }
        writeln!(w, "        </DataArray>")?;
        writeln!(
            w,
            r#"        <DataArray type="Int64" Name="offsets" format="ascii">"#
        )?;
        for t in 1..=triangles.len() {
            writeln!(w, "{}", 3 * t)?;
        }
        writeln!(w, "        </DataArray>")?;
        writeln!(w, "      </Polys>")?;
        writeln!(w, "    </Piece>")?;
        writeln!(w, "  </PolyData>")?;
        writeln!(w, "</VTKFile>")
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_triangle_is_written_and_a_bad_index_refused() {
        let path = std::env::temp_dir().join(format!("isochor-vtp-{}.vtp", std::process::id()));
        let points = [Vec3::zeros(), Vec3::x(), Vec3::y()];
        write_vtp_triangles(&path, &points, &[[0, 1, 2]]).unwrap();
        let text = std::fs::read_to_string(&path).unwrap();
        std::fs::remove_file(&path).unwrap();
        assert!(text.contains(r#"NumberOfPoints="3" NumberOfPolys="1""#));
        assert!(text.contains("\n0 1 2\n") && text.contains("\n1.0 0.0 0.0\n"));
        assert!(write_vtp_triangles(&path, &points, &[[0, 1, 3]]).is_err());
    }
}
