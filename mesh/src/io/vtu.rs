//! VTK XML UnstructuredGrid (`.vtu`) files of linear or quadratic tets (VTK cell types 10 and
//! 24; quadratic tetra nodes in VTK's order, see [`TetElement::vtk_order`]), ASCII, full `f64`
//! precision, with named point and cell data: a writer readable by ParaView and meshio, and a
//! reader for the files it writes (and other ASCII VTU files of one of these cell types).

use super::atomic::write_atomic;
use super::read_text;
use crate::element::TetElement;
use crate::{ElementMesh, MeshError, TetMesh, Vec3};
use std::io::{self, Write};
use std::path::Path;
use std::str::FromStr;

/// VTK cell type of a tet element: `VTK_TETRA` (10) or `VTK_QUADRATIC_TETRA` (24).
fn vtk_type(kind: TetElement) -> usize {
    match kind {
        TetElement::Tet4 => 10,
        TetElement::Tet10 => 24,
    }
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
}

/// A named data array.
#[derive(Debug, Clone, PartialEq)]
pub struct Field {
    pub name: String,
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
    pub points: Vec<Vec3>,
    /// The kind of every cell.
    pub element: TetElement,
    /// `element.num_nodes()` point indices per cell, in our node order.
    pub cells: Vec<usize>,
    pub point_data: Vec<Field>,
    pub cell_data: Vec<Field>,
}

/// Writes an ASCII VTU file of the linear tets `tets` over `points`, with `point_data` (one
/// tuple per point) and `cell_data` (one per tet); see [`write_vtu_elements`].
pub fn write_vtu(
    path: impl AsRef<Path>,
    points: &[Vec3],
    tets: &[[usize; 4]],
    point_data: &[Field],
    cell_data: &[Field],
) -> Result<(), MeshError> {
    write_vtu_elements(
        path,
        points,
        TetElement::Tet4,
        tets.as_flattened(),
        point_data,
        cell_data,
    )
}

/// Writes an ASCII VTU file of `kind` elements over `points` (`cells` lists
/// `kind.num_nodes()` point indices per element in our node order; for an [`ElementMesh`],
/// its nodes, kind and connectivity), with `point_data` (one tuple per point) and `cell_data`
/// (one per element). Quadratic tets are written as VTK quadratic tetra (cell type 24), which
/// ParaView draws curved. Reals are written in the shortest form that reads back to the same
/// `f64`; non-finite values are written as `NaN`/`inf` (which meshio and this reader accept).
/// The write is atomic.
pub fn write_vtu_elements(
    path: impl AsRef<Path>,
    points: &[Vec3],
    kind: TetElement,
    cells: &[usize],
    point_data: &[Field],
    cell_data: &[Field],
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
    write_atomic(path, |w: &mut dyn Write| {
        writeln!(w, r#"<?xml version="1.0"?>"#)?;
        writeln!(
            w,
            r#"<VTKFile type="UnstructuredGrid" version="1.0" byte_order="LittleEndian" header_type="UInt64">"#
        )?;
        writeln!(w, "  <UnstructuredGrid>")?;
        writeln!(
            w,
            r#"    <Piece NumberOfPoints="{}" NumberOfCells="{}">"#,
            points.len(),
            num_cells
        )?;
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
    })
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

fn write_array(w: &mut dyn Write, name: &str, values: &FieldValues) -> io::Result<()> {
    // One-component arrays omit NumberOfComponents (default 1), so meshio reads them as
    // flat arrays.
    let (kind, components) = match values {
        FieldValues::Scalar(_) => ("Float64", ""),
        FieldValues::Vector(_) => ("Float64", r#" NumberOfComponents="3""#),
        FieldValues::Int(_) => ("Int32", ""),
    };
    writeln!(
        w,
        r#"        <DataArray type="{kind}" Name="{}"{components} format="ascii">"#,
        escape(name)
    )?;
    match values {
        FieldValues::Scalar(v) => v.iter().try_for_each(|x| writeln!(w, "{x:?}"))?,
        FieldValues::Vector(v) => v
            .iter()
            .try_for_each(|x| writeln!(w, "{:?} {:?} {:?}", x.x, x.y, x.z))?,
        FieldValues::Int(v) => v.iter().try_for_each(|x| writeln!(w, "{x}"))?,
    }
    writeln!(w, "        </DataArray>")
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
    let file = parse(path, &read_text(path)?, false, false)?;
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
    let file = parse(path, &read_text(path)?, false, true)?;
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
    parse(path, &read_text(path)?, true, true)
}

/// A `<DataArray>` found in the file.
struct Array<'a> {
    parent: &'a str,
    attributes: Vec<(&'a str, String)>,
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

/// Line of the `i`-th value of array `a` (or of its tag if there are fewer values).
fn token_line(text: &str, a: &Array, i: usize) -> usize {
    a.content
        .split_ascii_whitespace()
        .nth(i)
        .map_or(a.line, |t| {
            line_of(text, t.as_ptr() as usize - text.as_ptr() as usize)
        })
}

/// 1-based line of byte `offset`.
fn line_of(text: &str, offset: usize) -> usize {
    text.as_bytes()[..offset.min(text.len())]
        .iter()
        .filter(|&&b| b == b'\n')
        .count()
        + 1
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
    text: &str,
    with_fields: bool,
    quadratic: bool,
) -> Result<VtuFile, MeshError> {
    let err =
        |offset: usize, message: String| MeshError::parse(path, line_of(text, offset), message);
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
        let attrs = attributes(path, line_of(text, start), attribute_text)?;
        let attr = |key: &str| {
            attrs
                .iter()
                .find(|(k, _)| *k == key)
                .map(|(_, v)| v.as_str())
        };
        match name {
            "VTKFile" if attr("type") != Some("UnstructuredGrid") => {
                return Err(err(
                    start,
                    format!(
                        "expected a VTKFile of type \"UnstructuredGrid\", found {:?}",
                        attr("type").unwrap_or("none")
                    ),
                ))
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
                return Err(err(
                    start,
                    "appended (binary) data is not supported: write the file in ASCII".into(),
                ))
            }
            "DataArray" if !self_closing => {
                let format = attr("format").unwrap_or("ascii");
                if format != "ascii" {
                    return Err(err(
                        start,
                        format!(
                        "DataArray format \"{format}\" is not supported: write the file in ASCII"
                    ),
                    ));
                }
                let close = text[pos..]
                    .find("</DataArray>")
                    .ok_or_else(|| err(start, "expected </DataArray>".into()))?;
                arrays.push(Array {
                    parent: stack.last().copied().unwrap_or(""),
                    attributes: attrs,
                    content: &text[pos..pos + close],
                    line: line_of(text, start),
                });
            }
            _ => {}
        }
        if !self_closing {
            stack.push(name);
        }
    }
    if let Some(open) = stack.last() {
        return Err(err(
            text.len(),
            format!("unexpected end of file: expected </{open}>"),
        ));
    }
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
    let coords: Vec<f64> = values(path, text, points_array, num_coords)?;
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
    let types: Vec<usize> = values(path, text, types_array, num_cells)?;
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
    let offsets: Vec<usize> = values(path, text, offsets_array, num_cells)?;
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
    let connectivity: Vec<usize> = values(path, text, connectivity_array, num_indices)?;
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
            .map(|a| field(path, text, a, count))
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
fn field(path: &Path, text: &str, a: &Array, count: usize) -> Result<Field, MeshError> {
    let kind = a.attribute("type").unwrap_or("");
    let components = a.components(path)?;
    let name = a.name().to_string();
    let values = match (kind, components) {
        ("Float32" | "Float64", 1) => FieldValues::Scalar(values(path, text, a, count)?),
        ("Float32" | "Float64", 3) => FieldValues::Vector(
            values::<f64>(path, text, a, 3 * count)?
                .chunks_exact(3)
                .map(Vec3::from_column_slice)
                .collect(),
        ),
        (k, 1) if k.starts_with("Int") || k.starts_with("UInt") => {
            FieldValues::Int(values(path, text, a, count)?)
        }
        _ => {
            return Err(MeshError::parse(
                path,
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

/// Exactly `expected` whitespace-separated values of an array, or an error at the line of the
/// offending token.
fn values<T: FromStr>(
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
