//! VTK XML UnstructuredGrid (`.vtu`) files of linear or quadratic tets (VTK cell types 10 and
//! 24; quadratic tetra nodes in VTK's order, see [`TetElement::vtk_order`]) with named point
//! and cell data, at full `f64` precision: a writer readable by ParaView and meshio, in ASCII
//! or zlib-compressed appended binary ([`VtuEncoding`]), and a reader for the files it writes
//! and other VTU files of one of these cell types (ASCII, inline base64 or appended raw
//! binary, compressed with zlib or not, `UInt32` or `UInt64` headers).

use super::atomic::write_atomic;
use super::vtk_binary::{append_compressed, decode_base64, Layout, Number, Scalar};
use crate::element::TetElement;
use crate::{ElementMesh, MeshError, TetMesh, Vec3};
use nalgebra::Matrix3;
use std::borrow::Cow;
use std::io::{self, Write};
use std::path::Path;

/// VTK cell type of a tet element: `VTK_TETRA` (10) or `VTK_QUADRATIC_TETRA` (24).
fn vtk_type(kind: TetElement) -> usize {
    match kind {
        TetElement::Tet4 => 10,
        TetElement::Tet10 => 24,
    }
}

/// How a VTU writer stores the data arrays.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum VtuEncoding {
    /// Text, one tuple per line: readable and diffable.
    Ascii,
    /// Little-endian binary appended after the XML (`<AppendedData encoding="raw">`),
    /// compressed with zlib in blocks of 32 KiB as VTK's `vtkZLibDataCompressor` does, with
    /// `UInt64` headers: several times smaller and faster to write than ASCII.
    Binary,
}

/// Values of a data array: one per point or one per cell.
#[derive(Debug, Clone, PartialEq)]
pub enum FieldValues {
    /// `Float64`, one component (pressure, J, ...).
    Scalar(Vec<f64>),
    /// `Float64`, three components (displacement, velocity, force, ...).
    Vector(Vec<Vec3>),
    /// `Int32`, one component (zone id, flags, ...).
    Int(Vec<i32>),
    /// `Float64`, nine components in row-major order, as VTK stores tensors (stress).
    Tensor(Vec<Matrix3<f64>>),
}

/// A named data array.
#[derive(Debug, Clone, PartialEq)]
pub struct Field {
    /// The array's name (`Name` attribute).
    pub name: String,
    /// Its values.
    pub values: FieldValues,
}

impl Field {
    /// A scalar `Float64` array.
    pub fn scalar(name: impl Into<String>, values: Vec<f64>) -> Self {
        Field {
            name: name.into(),
            values: FieldValues::Scalar(values),
        }
    }

    /// A 3-vector `Float64` array.
    pub fn vector(name: impl Into<String>, values: Vec<Vec3>) -> Self {
        Field {
            name: name.into(),
            values: FieldValues::Vector(values),
        }
    }

    /// A 3x3 tensor `Float64` array.
    pub fn tensor(name: impl Into<String>, values: Vec<Matrix3<f64>>) -> Self {
        Field {
            name: name.into(),
            values: FieldValues::Tensor(values),
        }
    }

    /// An `Int32` array.
    pub fn int(name: impl Into<String>, values: Vec<i32>) -> Self {
        Field {
            name: name.into(),
            values: FieldValues::Int(values),
        }
    }

    /// Number of tuples (points or cells).
    pub fn len(&self) -> usize {
        match &self.values {
            FieldValues::Scalar(v) => v.len(),
            FieldValues::Vector(v) => v.len(),
            FieldValues::Int(v) => v.len(),
            FieldValues::Tensor(v) => v.len(),
        }
    }

    /// Whether the array has no tuples.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }
}

/// The contents of a VTU file.
#[derive(Debug, Clone, PartialEq)]
pub struct VtuFile {
    /// The point coordinates.
    pub points: Vec<Vec3>,
    /// The kind of every cell.
    pub element: TetElement,
    /// `element.num_nodes()` point indices per cell, in our node order.
    pub cells: Vec<usize>,
    /// The arrays with one value (or tuple) per point.
    pub point_data: Vec<Field>,
    /// The arrays with one value (or tuple) per cell.
    pub cell_data: Vec<Field>,
}

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
/// point indices per element in our node order; for an [`ElementMesh`], its nodes, kind and
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

fn unescape(s: &str) -> String {
    s.replace("&lt;", "<")
        .replace("&gt;", ">")
        .replace("&quot;", "\"")
        .replace("&apos;", "'")
        .replace("&amp;", "&")
}

/// Reads the linear mesh of a VTU file of linear tets (its data arrays are not interpreted);
/// a file of quadratic tets is refused at its first cell: read it with [`read_vtu_elements`].
pub fn read_vtu(path: impl AsRef<Path>) -> Result<TetMesh, MeshError> {
    let path = path.as_ref();
    let file = parse(path, &read_bytes(path)?, false, false)?;
    let tets = file
        .cells
        .chunks_exact(4)
        .map(|c| [c[0], c[1], c[2], c[3]])
        .collect();
    TetMesh::new(file.points, tets).map_err(|e| format_error(path, e))
}

/// Reads the mesh of a VTU file of linear or quadratic tets as an [`ElementMesh`] (see
/// [`ElementMesh::from_nodes`]: points no cell uses are dropped; a file written from an
/// `ElementMesh` reads back with the same numbering).
pub fn read_vtu_elements(path: impl AsRef<Path>) -> Result<ElementMesh, MeshError> {
    let path = path.as_ref();
    let file = parse(path, &read_bytes(path)?, false, true)?;
    ElementMesh::from_nodes(file.element, file.points, file.cells)
        .map_err(|e| format_error(path, e))
}

/// A mesh error of the contents of file `path`.
fn format_error(path: &Path, e: MeshError) -> MeshError {
    MeshError::Format {
        path: path.into(),
        message: e.to_string(),
    }
}

/// Reads a VTU file of linear or quadratic tets with its point and cell data (`Float32/64`
/// arrays of 1 or 3 components, integer arrays of 1 component).
pub fn read_vtu_file(path: impl AsRef<Path>) -> Result<VtuFile, MeshError> {
    let path = path.as_ref();
    parse(path, &read_bytes(path)?, true, true)
}

fn read_bytes(path: &Path) -> Result<Vec<u8>, MeshError> {
    std::fs::read(path).map_err(|e| MeshError::io(path, e))
}

/// A `<DataArray>` found in the file.
struct Array<'a> {
    parent: &'a str,
    attributes: Vec<(&'a str, String)>,
    /// The text after the tag and any child elements: ASCII values or base64.
    content: &'a str,
    line: usize,
}

impl Array<'_> {
    fn attribute(&self, key: &str) -> Option<&str> {
        self.attributes
            .iter()
            .find(|(k, _)| *k == key)
            .map(|(_, v)| v.as_str())
    }

    fn name(&self) -> &str {
        self.attribute("Name").unwrap_or("")
    }

    /// `ascii`, `binary` (inline base64) or `appended`.
    fn format(&self) -> &str {
        self.attribute("format").unwrap_or("ascii")
    }

    fn components(&self, path: &Path) -> Result<usize, MeshError> {
        self.attribute("NumberOfComponents").map_or(Ok(1), |c| {
            c.parse().map_err(|_| {
                MeshError::parse(
                    path,
                    self.line,
                    format!("expected NumberOfComponents to be an integer, found `{c}`"),
                )
            })
        })
    }
}

/// Line of the `i`-th value of array `a` (or of its tag if there are fewer values, or if it
/// is binary).
fn token_line(text: &str, a: &Array, i: usize) -> usize {
    if a.format() != "ascii" {
        return a.line;
    }
    a.content
        .split_ascii_whitespace()
        .nth(i)
        .map_or(a.line, |t| {
            line_of(
                text.as_bytes(),
                t.as_ptr() as usize - text.as_ptr() as usize,
            )
        })
}

/// 1-based line of byte `offset`.
fn line_of(bytes: &[u8], offset: usize) -> usize {
    bytes[..offset.min(bytes.len())]
        .iter()
        .filter(|&&b| b == b'\n')
        .count()
        + 1
}

/// The first non-blank run of `content` outside its child elements: the values of a
/// `<DataArray>`, which VTK may precede or follow with `<InformationKey>` elements.
fn own_text(content: &str) -> &str {
    let mut depth = 0usize;
    let mut pos = 0;
    loop {
        let next = content[pos..].find('<').map_or(content.len(), |i| pos + i);
        let run = &content[pos..next];
        if depth == 0 && !run.trim().is_empty() {
            return run;
        }
        if next == content.len() {
            return "";
        }
        let end = content[next..]
            .find('>')
            .map_or(content.len(), |i| next + i + 1);
        let tag = &content[next..end];
        if tag.starts_with("</") {
            depth = depth.saturating_sub(1);
        } else if !(tag.ends_with("/>") || tag.starts_with("<?") || tag.starts_with("<!")) {
            depth += 1;
        }
        pos = end;
    }
}

/// Splits a file at its `<AppendedData>` tag: the XML up to the end of that tag, and the raw
/// bytes after the `_` that starts the data (offsets of appended arrays count from there).
fn split_appended<'b>(
    path: &Path,
    bytes: &'b [u8],
) -> Result<(&'b [u8], Option<&'b [u8]>), MeshError> {
    const TAG: &[u8] = b"<AppendedData";
    let Some(start) = bytes.windows(TAG.len()).position(|w| w == TAG) else {
        return Ok((bytes, None));
    };
    let err = |message: &str| MeshError::parse(path, line_of(bytes, start), message);
    let end = bytes[start..]
        .iter()
        .position(|&b| b == b'>')
        .map(|i| start + i + 1)
        .ok_or_else(|| err("unterminated <AppendedData> tag: expected `>`"))?;
    let underscore = bytes[end..]
        .iter()
        .position(|b| !b.is_ascii_whitespace())
        .map(|i| end + i)
        .filter(|&i| bytes[i] == b'_')
        .ok_or_else(|| err("expected `_` to start the data after <AppendedData>"))?;
    if !bytes.trim_ascii_end().ends_with(b"</VTKFile>") {
        return Err(err(
            "the file ends before </VTKFile> after its appended data: it is truncated",
        ));
    }
    Ok((&bytes[..end], Some(&bytes[underscore + 1..])))
}

/// Parses `key="value"` pairs of a tag.
fn attributes<'a>(
    path: &Path,
    line: usize,
    text: &'a str,
) -> Result<Vec<(&'a str, String)>, MeshError> {
    let mut out = Vec::new();
    let mut rest = text.trim();
    while !rest.is_empty() {
        let bad = || {
            MeshError::parse(
                path,
                line,
                format!("expected attributes `key=\"value\"`, found `{rest}`"),
            )
        };
        let eq = rest.find('=').ok_or_else(bad)?;
        let key = rest[..eq].trim();
        let after = rest[eq + 1..].trim_start();
        let quote = after
            .chars()
            .next()
            .filter(|&c| c == '"' || c == '\'')
            .ok_or_else(bad)?;
        let close = after[1..].find(quote).ok_or_else(bad)?;
        out.push((key, unescape(&after[1..1 + close])));
        rest = after[close + 2..].trim_start();
    }
    Ok(out)
}

/// Scans the XML for the piece size and the data arrays, then builds the file contents; with
/// `quadratic` false, quadratic tets are refused.
fn parse(
    path: &Path,
    bytes: &[u8],
    with_fields: bool,
    quadratic: bool,
) -> Result<VtuFile, MeshError> {
    let (xml, appended) = split_appended(path, bytes)?;
    let text = String::from_utf8_lossy(xml);
    let text: &str = &text;
    let err = |offset: usize, message: String| {
        MeshError::parse(path, line_of(text.as_bytes(), offset), message)
    };
    let mut layout = Layout {
        big_endian: false,
        header64: false,
        zlib: false,
    };
    let mut unsupported_compressor = None;
    let mut stack: Vec<&str> = Vec::new();
    let mut arrays = Vec::new();
    let mut piece = None;
    let mut grid = false;
    let mut pos = 0;
    while let Some(rel) = text[pos..].find('<') {
        let start = pos + rel;
        let rest = &text[start..];
        let (skip_to, terminator) = if rest.starts_with("<?") {
            (Some("?>"), "?>")
        } else if rest.starts_with("<!--") {
            (Some("-->"), "-->")
        } else {
            (None, ">")
        };
        let end = rest
            .find(terminator)
            .ok_or_else(|| err(start, format!("unterminated tag: expected `{terminator}`")))?;
        pos = start + end + terminator.len();
        if skip_to.is_some() {
            continue;
        }
        let tag = &rest[1..end];
        if let Some(name) = tag.strip_prefix('/') {
            match stack.pop() {
                Some(open) if open == name.trim() => continue,
                Some(open) => {
                    return Err(err(
                        start,
                        format!("expected </{open}>, found </{}>", name.trim()),
                    ))
                }
                None => {
                    return Err(err(
                        start,
                        format!("unexpected closing tag </{}>", name.trim()),
                    ))
                }
            }
        }
        let self_closing = tag.ends_with('/');
        let tag = tag.trim_end_matches('/');
        let (name, attribute_text) = tag.split_once(char::is_whitespace).unwrap_or((tag, ""));
        let attrs = attributes(path, line_of(text.as_bytes(), start), attribute_text)?;
        let attr = |key: &str| {
            attrs
                .iter()
                .find(|(k, _)| *k == key)
                .map(|(_, v)| v.as_str())
        };
        match name {
            "VTKFile" => {
                if attr("type") != Some("UnstructuredGrid") {
                    return Err(err(
                        start,
                        format!(
                            "expected a VTKFile of type \"UnstructuredGrid\", found {:?}",
                            attr("type").unwrap_or("none")
                        ),
                    ));
                }
                layout.big_endian = match attr("byte_order") {
                    None | Some("LittleEndian") => false,
                    Some("BigEndian") => true,
                    Some(other) => {
                        return Err(err(
                            start,
                            format!("byte_order \"{other}\" is neither LittleEndian nor BigEndian"),
                        ))
                    }
                };
                layout.header64 = match attr("header_type") {
                    None | Some("UInt32") => false,
                    Some("UInt64") => true,
                    Some(other) => {
                        return Err(err(
                            start,
                            format!("header_type \"{other}\" is neither UInt32 nor UInt64"),
                        ))
                    }
                };
                match attr("compressor") {
                    None | Some("") => {}
                    Some("vtkZLibDataCompressor") => layout.zlib = true,
                    Some(other) => unsupported_compressor = Some(other.to_string()),
                }
            }
            "UnstructuredGrid" => grid = true,
            "Piece" if piece.is_some() => {
                return Err(err(
                    start,
                    "files with several <Piece> elements are not supported".into(),
                ))
            }
            "Piece" => {
                let count = |key: &str| {
                    attr(key)
                        .and_then(|v| v.parse::<usize>().ok())
                        .ok_or_else(|| {
                            err(start, format!("expected <Piece> to have an integer {key}"))
                        })
                };
                piece = Some((count("NumberOfPoints")?, count("NumberOfCells")?));
            }
            "AppendedData" => {
                let encoding = attr("encoding").unwrap_or("none");
                if encoding != "raw" {
                    return Err(err(
                        start,
                        format!(
                            "AppendedData encoding \"{encoding}\" is not supported (isochor \
                             reads raw appended data)"
                        ),
                    ));
                }
            }
            "DataArray" => {
                let format = attr("format").unwrap_or("ascii");
                if !matches!(format, "ascii" | "binary" | "appended") {
                    return Err(err(
                        start,
                        format!(
                            "DataArray format \"{format}\" is not supported (expected ascii, \
                             binary or appended)"
                        ),
                    ));
                }
                let content = if self_closing {
                    ""
                } else {
                    let close = text[pos..]
                        .find("</DataArray>")
                        .ok_or_else(|| err(start, "expected </DataArray>".into()))?;
                    own_text(&text[pos..pos + close])
                };
                arrays.push(Array {
                    parent: stack.last().copied().unwrap_or(""),
                    attributes: attrs,
                    content,
                    line: line_of(text.as_bytes(), start),
                });
            }
            _ => {}
        }
        if !self_closing {
            stack.push(name);
        }
    }
    match stack.last() {
        // The XML ends at the <AppendedData> tag; the raw data follows.
        Some(&"AppendedData") if appended.is_some() => {}
        Some(open) => {
            return Err(err(
                text.len(),
                format!("unexpected end of file: expected </{open}>"),
            ))
        }
        None => {}
    }
    let src = Source {
        path,
        text,
        appended,
        layout,
        unsupported_compressor,
    };
    let Some((num_points, num_cells)) = piece.filter(|_| grid) else {
        return Err(err(
            text.len(),
            "expected an <UnstructuredGrid> with a <Piece>".into(),
        ));
    };
    let find = |parent: &str, name: Option<&str>| {
        arrays
            .iter()
            .find(|a| a.parent == parent && name.is_none_or(|n| a.name() == n))
            .ok_or_else(|| {
                let what = name.map_or(String::new(), |n| format!(" \"{n}\""));
                err(
                    text.len(),
                    format!("expected a DataArray{what} in <{parent}>"),
                )
            })
    };
    let points_array = find("Points", None)?;
    let too_many = |what: &str| {
        err(
            0,
            format!("<Piece> declares more {what} than memory can hold"),
        )
    };
    let num_coords = num_points
        .checked_mul(3)
        .ok_or_else(|| too_many("points"))?;
    let coords: Vec<f64> = values(&src, points_array, num_coords)?;
    if let Some(i) = coords.iter().position(|c| !c.is_finite()) {
        let line = token_line(text, points_array, i);
        return Err(MeshError::parse(
            path,
            line,
            format!("point {} has a non-finite coordinate", i / 3),
        ));
    }
    let points: Vec<Vec3> = coords
        .chunks_exact(3)
        .map(Vec3::from_column_slice)
        .collect();

    // The largest cell has 10 points.
    num_cells.checked_mul(10).ok_or_else(|| too_many("cells"))?;
    let types_array = find("Cells", Some("types"))?;
    let types: Vec<usize> = values(&src, types_array, num_cells)?;
    let at =
        |a: &Array, i: usize, what: String| MeshError::parse(path, token_line(text, a, i), what);
    let kinds = if quadratic {
        &[TetElement::Tet4, TetElement::Tet10][..]
    } else {
        &[TetElement::Tet4][..]
    };
    let first = types.first().copied().unwrap_or(10);
    let Some(&element) = kinds.iter().find(|&&k| vtk_type(k) == first) else {
        let hint = if first == vtk_type(TetElement::Tet10) {
            ": this file holds quadratic tetrahedra, read it with read_vtu_elements"
        } else {
            ""
        };
        return Err(at(
            types_array,
            0,
            format!(
                "cell 0: VTK cell type {first} is not supported{hint} (isochor reads tetrahedra, \
                 type 10, and quadratic tetrahedra, type 24)"
            ),
        ));
    };
    let n = element.num_nodes();
    let num_indices = num_cells * n;
    let offsets_array = find("Cells", Some("offsets"))?;
    let offsets: Vec<usize> = values(&src, offsets_array, num_cells)?;
    for e in 0..num_cells {
        if types[e] != first {
            return Err(at(
                types_array,
                e,
                format!(
                    "cell {e}: VTK cell type {} after cells of type {first}: cells of one type only are supported",
                    types[e]
                ),
            ));
        }
        if offsets[e] != n * (e + 1) {
            return Err(at(
                offsets_array,
                e,
                format!(
                    "cell {e}: expected offset {} ({n} points per cell of type {first}), found {}",
                    n * (e + 1),
                    offsets[e]
                ),
            ));
        }
    }
    let connectivity_array = find("Cells", Some("connectivity"))?;
    let connectivity: Vec<usize> = values(&src, connectivity_array, num_indices)?;
    if let Some(i) = connectivity.iter().position(|&v| v >= num_points) {
        return Err(at(
            connectivity_array,
            i,
            format!(
                "cell {}: point {} is out of range (the piece has {num_points} points)",
                i / n,
                connectivity[i]
            ),
        ));
    }
    let cells = connectivity
        .chunks_exact(n)
        .flat_map(|c| element.vtk_order().iter().map(|&a| c[a]))
        .collect();

    let fields = |parent: &str, count: usize| -> Result<Vec<Field>, MeshError> {
        if !with_fields {
            return Ok(Vec::new());
        }
        arrays
            .iter()
            .filter(|a| a.parent == parent)
            .map(|a| field(&src, a, count))
            .collect()
    };
    Ok(VtuFile {
        points,
        element,
        cells,
        point_data: fields("PointData", num_points)?,
        cell_data: fields("CellData", num_cells)?,
    })
}

/// One point or cell data array.
fn field(src: &Source, a: &Array, count: usize) -> Result<Field, MeshError> {
    let kind = a.attribute("type").unwrap_or("");
    let components = a.components(src.path)?;
    let name = a.name().to_string();
    let values = match (kind, components) {
        ("Float32" | "Float64", 1) => FieldValues::Scalar(values(src, a, count)?),
        ("Float32" | "Float64", 3) => FieldValues::Vector(
            values::<f64>(src, a, 3 * count)?
                .chunks_exact(3)
                .map(Vec3::from_column_slice)
                .collect(),
        ),
        ("Float32" | "Float64", 9) => FieldValues::Tensor(
            values::<f64>(src, a, 9 * count)?
                .chunks_exact(9)
                .map(Matrix3::from_row_slice)
                .collect(),
        ),
        (k, 1) if k.starts_with("Int") || k.starts_with("UInt") => {
            FieldValues::Int(values(src, a, count)?)
        }
        _ => {
            return Err(MeshError::parse(
                src.path,
                a.line,
                format!(
                "data array \"{name}\": type {kind} with {components} components is not supported \
                 (expected Float32/Float64 with 1 or 3 components, or an integer type with 1)"
            ),
            ))
        }
    };
    Ok(Field { name, values })
}

/// The file being read: its XML text and the bytes of its `<AppendedData>`.
struct Source<'a> {
    path: &'a Path,
    text: &'a str,
    appended: Option<&'a [u8]>,
    layout: Layout,
    /// A `compressor` other than zlib, refused when a binary array is read.
    unsupported_compressor: Option<String>,
}

/// Exactly `expected` values of an array, ASCII or binary.
fn values<T: Number>(src: &Source, a: &Array, expected: usize) -> Result<Vec<T>, MeshError> {
    match a.format() {
        "ascii" => ascii_values(src.path, src.text, a, expected),
        _ => binary_values(src, a, expected),
    }
}

/// The values of an inline base64 (`binary`) or `appended` array, whose bytes must be exactly
/// `expected` values of its `type`.
fn binary_values<T: Number>(src: &Source, a: &Array, expected: usize) -> Result<Vec<T>, MeshError> {
    let fail = |message: String| {
        MeshError::parse(
            src.path,
            a.line,
            format!("data array \"{}\": {message}", a.name()),
        )
    };
    if let Some(c) = &src.unsupported_compressor {
        return Err(fail(format!(
            "compressor \"{c}\" is not supported (isochor reads vtkZLibDataCompressor or \
             uncompressed data)"
        )));
    }
    let kind = a.attribute("type").unwrap_or("");
    let scalar = Scalar::from_vtk(kind)
        .ok_or_else(|| fail(format!("type \"{kind}\" is not a numeric VTK type")))?;
    let size = expected
        .checked_mul(scalar.size())
        .ok_or_else(|| fail("more values than memory can hold".into()))?;
    let inline;
    let data: &[u8] = if a.format() == "binary" {
        inline = decode_base64(a.content)
            .map_err(|e| fail(format!("its inline binary data is not base64: {e}")))?;
        &inline
    } else {
        let offset = a
            .attribute("offset")
            .ok_or_else(|| fail("expected an offset into the appended data".into()))?;
        let offset: usize = offset.trim().parse().map_err(|_| {
            fail(format!(
                "expected offset to be an integer, found `{offset}`"
            ))
        })?;
        let appended = src
            .appended
            .ok_or_else(|| fail("the file has no <AppendedData> for this appended array".into()))?;
        appended.get(offset..).ok_or_else(|| {
            fail(format!(
                "offset {offset} is past the end of the appended data ({} bytes)",
                appended.len()
            ))
        })?
    };
    let bytes: Cow<[u8]> = src.layout.array(data, size).map_err(fail)?;
    bytes
        .chunks_exact(scalar.size())
        .enumerate()
        .map(|(i, b)| {
            let n = scalar.read(b, src.layout.big_endian);
            T::from_num(n).ok_or_else(|| {
                fail(format!(
                    "value {i} ({n}) is not a {}",
                    std::any::type_name::<T>()
                ))
            })
        })
        .collect()
}

/// Exactly `expected` whitespace-separated values of an ASCII array, or an error at the line
/// of the offending token.
fn ascii_values<T: Number>(
    path: &Path,
    text: &str,
    a: &Array,
    expected: usize,
) -> Result<Vec<T>, MeshError> {
    let mut out = Vec::new();
    for (i, token) in a.content.split_ascii_whitespace().enumerate() {
        let value = token.parse().map_err(|_| {
            MeshError::parse(
                path,
                token_line(text, a, i),
                format!(
                    "data array \"{}\": expected a {} value, found `{token}`",
                    a.name(),
                    std::any::type_name::<T>()
                ),
            )
        })?;
        if out.len() == expected {
            return Err(MeshError::parse(
                path,
                token_line(text, a, i),
                format!(
                    "data array \"{}\": more than the expected {expected} values",
                    a.name()
                ),
            ));
        }
        out.push(value);
    }
    if out.len() < expected {
        return Err(MeshError::parse(
            path,
            a.line,
            format!(
                "data array \"{}\" has {} values, expected {expected}",
                a.name(),
                out.len()
            ),
        ));
    }
    Ok(out)
}
