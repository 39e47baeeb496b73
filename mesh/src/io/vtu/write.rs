//! The VTU writers: ASCII, or zlib-compressed binary appended after the XML.

use super::super::atomic::write_atomic;
use super::super::vtk_binary::append_compressed;
use super::types::{Field, FieldValues, VtuEncoding};
use super::vtk_type;
use crate::element::TetElement;
use crate::{MeshError, Vec3};
use std::io::{self, Write};
use std::path::Path;

/// Writes a VTU file of the linear tets `tets` over `points`, with `point_data` (one tuple
/// per point) and `cell_data` (one per tet), in `encoding`; see [`write_vtu_elements`].
pub fn write_vtu(
    path: impl AsRef<Path>,
    points: &[Vec3],
    tets: &[[usize; 4]],
    point_data: &[Field],
    cell_data: &[Field],
    encoding: VtuEncoding,
) -> Result<(), MeshError> {
    write_vtu_elements(
        path,
        points,
        TetElement::Tet4,
        tets.as_flattened(),
        point_data,
        cell_data,
        encoding,
    )
}

/// Writes a VTU file of `kind` elements over `points` (`cells` lists `kind.num_nodes()`
/// point indices per element in our node order; for an [`ElementMesh`](crate::ElementMesh), its nodes, kind and
/// connectivity), with `point_data` (one tuple per point) and `cell_data` (one per element),
/// in `encoding`. Quadratic tets are written as VTK quadratic tetra (cell type 24), which
/// ParaView draws curved. Reals are `Float64`, connectivity and offsets `Int64`, cell types
/// `UInt8`. In ASCII, reals are written in the shortest form that reads back to the same
/// `f64`, non-finite values as `NaN`/`inf` (which meshio and this reader accept); binary
/// files hold the exact bits. The write is atomic.
pub fn write_vtu_elements(
    path: impl AsRef<Path>,
    points: &[Vec3],
    kind: TetElement,
    cells: &[usize],
    point_data: &[Field],
    cell_data: &[Field],
    encoding: VtuEncoding,
) -> Result<(), MeshError> {
    let path = path.as_ref();
    let n = kind.num_nodes();
    if cells.len() % n != 0 {
        return Err(MeshError::parameter(
            "cells",
            cells.len(),
            format!("must hold {n} point indices per element"),
        ));
    }
    let num_cells = cells.len() / n;
    if let Some(i) = cells.iter().position(|&v| v >= points.len()) {
        return Err(MeshError::IndexOutOfRange {
            tet: i / n,
            index: cells[i],
            vertices: points.len(),
        });
    }
    for (fields, expected, kind) in [
        (point_data, points.len(), "point"),
        (cell_data, num_cells, "cell"),
    ] {
        if let Some(f) = fields.iter().find(|f| f.len() != expected) {
            return Err(MeshError::parameter(
                "field",
                &f.name,
                format!("{kind} data has {} tuples, expected {expected}", f.len()),
            ));
        }
    }
    write_atomic(path, |w: &mut dyn Write| match encoding {
        VtuEncoding::Ascii => write_ascii(w, points, kind, cells, point_data, cell_data),
        VtuEncoding::Binary => write_binary(w, points, kind, cells, point_data, cell_data),
    })
}

/// The XML declaration and the opening `<VTKFile>`, `<UnstructuredGrid>` and `<Piece>`.
fn write_start(w: &mut dyn Write, compressor: &str, points: usize, cells: usize) -> io::Result<()> {
    writeln!(w, r#"<?xml version="1.0"?>"#)?;
    writeln!(
        w,
        r#"<VTKFile type="UnstructuredGrid" version="1.0" byte_order="LittleEndian" header_type="UInt64"{compressor}>"#
    )?;
    writeln!(w, "  <UnstructuredGrid>")?;
    writeln!(
        w,
        r#"    <Piece NumberOfPoints="{points}" NumberOfCells="{cells}">"#
    )
}

fn write_ascii(
    w: &mut dyn Write,
    points: &[Vec3],
    kind: TetElement,
    cells: &[usize],
    point_data: &[Field],
    cell_data: &[Field],
) -> io::Result<()> {
    let n = kind.num_nodes();
    let num_cells = cells.len() / n;
    write_start(w, "", points.len(), num_cells)?;
    write_section(w, "PointData", point_data)?;
    write_section(w, "CellData", cell_data)?;
    writeln!(w, "      <Points>")?;
    write_array(w, "Points", &FieldValues::Vector(points.to_vec()))?;
    writeln!(w, "      </Points>")?;
    writeln!(w, "      <Cells>")?;
    writeln!(
        w,
        r#"        <DataArray type="Int64" Name="connectivity" format="ascii">"#
    )?;
    for cell in cells.chunks_exact(n) {
        let vtk: Vec<String> = kind
            .vtk_order()
            .iter()
            .map(|&a| cell[a].to_string())
            .collect();
        writeln!(w, "{}", vtk.join(" "))?;
    }
    writeln!(w, "        </DataArray>")?;
    writeln!(
        w,
        r#"        <DataArray type="Int64" Name="offsets" format="ascii">"#
    )?;
    for e in 1..=num_cells {
        writeln!(w, "{}", n * e)?;
    }
    writeln!(w, "        </DataArray>")?;
    writeln!(
        w,
        r#"        <DataArray type="UInt8" Name="types" format="ascii">"#
    )?;
    let cell_type = vtk_type(kind);
    for _ in 0..num_cells {
        writeln!(w, "{cell_type}")?;
    }
    writeln!(w, "        </DataArray>")?;
    writeln!(w, "      </Cells>")?;
    writeln!(w, "    </Piece>")?;
    writeln!(w, "  </UnstructuredGrid>")?;
    writeln!(w, "</VTKFile>")
}

fn write_section(w: &mut dyn Write, section: &str, fields: &[Field]) -> io::Result<()> {
    if fields.is_empty() {
        return Ok(());
    }
    writeln!(w, "      <{section}>")?;
    for f in fields {
        write_array(w, &f.name, &f.values)?;
    }
    writeln!(w, "      </{section}>")
}

/// The `type`, `Name` and `NumberOfComponents` attributes of an array. One-component arrays
/// omit NumberOfComponents (default 1), so meshio reads them as flat arrays.
fn array_attributes(name: &str, values: &FieldValues) -> String {
    let (kind, components) = match values {
        FieldValues::Scalar(_) => ("Float64", ""),
        FieldValues::Vector(_) => ("Float64", r#" NumberOfComponents="3""#),
        FieldValues::Int(_) => ("Int32", ""),
        FieldValues::Tensor(_) => ("Float64", r#" NumberOfComponents="9""#),
    };
    format!(r#"type="{kind}" Name="{}"{components}"#, escape(name))
}

fn write_array(w: &mut dyn Write, name: &str, values: &FieldValues) -> io::Result<()> {
    writeln!(
        w,
        r#"        <DataArray {} format="ascii">"#,
        array_attributes(name, values)
    )?;
    match values {
        FieldValues::Scalar(v) => v.iter().try_for_each(|x| writeln!(w, "{x:?}"))?,
        FieldValues::Vector(v) => v
            .iter()
            .try_for_each(|x| writeln!(w, "{:?} {:?} {:?}", x.x, x.y, x.z))?,
        FieldValues::Int(v) => v.iter().try_for_each(|x| writeln!(w, "{x}"))?,
        FieldValues::Tensor(v) => v.iter().try_for_each(|t| {
            let row_major: Vec<String> = t.transpose().iter().map(|x| format!("{x:?}")).collect();
            writeln!(w, "{}", row_major.join(" "))
        })?,
    }
    writeln!(w, "        </DataArray>")
}

/// Writes the XML with `format="appended"` arrays, then the `<AppendedData>` block of their
/// compressed bytes.
fn write_binary(
    w: &mut dyn Write,
    points: &[Vec3],
    kind: TetElement,
    cells: &[usize],
    point_data: &[Field],
    cell_data: &[Field],
) -> io::Result<()> {
    let n = kind.num_nodes();
    let num_cells = cells.len() / n;
    write_start(
        w,
        r#" compressor="vtkZLibDataCompressor""#,
        points.len(),
        num_cells,
    )?;
    let mut data = Vec::new();
    let mut array = |w: &mut dyn Write, attributes: &str, bytes: &[u8]| {
        writeln!(
            w,
            r#"        <DataArray {attributes} format="appended" offset="{}"/>"#,
            data.len()
        )?;
        append_compressed(&mut data, bytes)
    };
    for (section, fields) in [("PointData", point_data), ("CellData", cell_data)] {
        if fields.is_empty() {
            continue;
        }
        writeln!(w, "      <{section}>")?;
        for f in fields {
            let attributes = array_attributes(&f.name, &f.values);
            array(w, &attributes, &le_bytes(&f.values))?;
        }
        writeln!(w, "      </{section}>")?;
    }
    writeln!(w, "      <Points>")?;
    let coordinates = FieldValues::Vector(points.to_vec());
    array(
        w,
        &array_attributes("Points", &coordinates),
        &le_bytes(&coordinates),
    )?;
    writeln!(w, "      </Points>")?;
    writeln!(w, "      <Cells>")?;
    let connectivity: Vec<u8> = cells
        .chunks_exact(n)
        .flat_map(|c| kind.vtk_order().iter().map(move |&a| c[a] as i64))
        .flat_map(i64::to_le_bytes)
        .collect();
    array(w, r#"type="Int64" Name="connectivity""#, &connectivity)?;
    let offsets: Vec<u8> = (1..=num_cells)
        .flat_map(|e| ((n * e) as i64).to_le_bytes())
        .collect();
    array(w, r#"type="Int64" Name="offsets""#, &offsets)?;
    let types = vec![vtk_type(kind) as u8; num_cells];
    array(w, r#"type="UInt8" Name="types""#, &types)?;
    writeln!(w, "      </Cells>")?;
    writeln!(w, "    </Piece>")?;
    writeln!(w, "  </UnstructuredGrid>")?;
    writeln!(w, r#"  <AppendedData encoding="raw">"#)?;
    w.write_all(b"   _")?;
    w.write_all(&data)?;
    writeln!(w, "\n  </AppendedData>")?;
    writeln!(w, "</VTKFile>")
}

/// The values of an array as little-endian bytes.
fn le_bytes(values: &FieldValues) -> Vec<u8> {
    match values {
        FieldValues::Scalar(v) => v.iter().flat_map(|x| x.to_le_bytes()).collect(),
        FieldValues::Vector(v) => v
            .iter()
            .flat_map(|x| [x.x, x.y, x.z])
            .flat_map(f64::to_le_bytes)
            .collect(),
        FieldValues::Int(v) => v.iter().flat_map(|x| x.to_le_bytes()).collect(),
        FieldValues::Tensor(v) => v
            .iter()
            .flat_map(|t| t.transpose().iter().copied().collect::<Vec<_>>())
            .flat_map(f64::to_le_bytes)
            .collect(),
    }
}

/// XML-escapes an attribute value.
pub(crate) fn escape(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
        .replace('\'', "&apos;")
}
