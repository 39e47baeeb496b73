//! The VTU reader: a file of linear or quadratic tets with its point and cell data (ASCII,
//! inline base64 or appended raw binary, compressed with zlib or not, `UInt32` or `UInt64`
//! headers). It never panics on malformed input and never trusts a declared size beyond the
//! bytes present.

use super::scan::{error_at, scan, split_appended, Array, Scan};
use super::types::{Field, FieldValues, VtuFile};
use super::values::{token_line, values, Source};
use super::vtk_type;
use crate::element::TetElement;
use crate::{ElementMesh, MeshError, TetMesh, Vec3};
use nalgebra::Matrix3;
use std::path::Path;

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
    super::super::read_regular_file(path)
}

/// Builds the file contents from the XML scan; with `quadratic` false, quadratic tets are
/// refused.
fn parse(
    path: &Path,
    bytes: &[u8],
    with_fields: bool,
    quadratic: bool,
) -> Result<VtuFile, MeshError> {
    let (xml, appended) = split_appended(path, bytes)?;
    let text = String::from_utf8_lossy(xml);
    let text: &str = &text;
    let Scan {
        layout,
        unsupported_compressor,
        piece,
        grid,
        arrays,
    } = scan(path, text, appended.is_some())?;
    let src = Source {
        path,
        text,
        appended,
        layout,
        unsupported_compressor,
    };
    let Some((num_points, num_cells)) = piece.filter(|_| grid) else {
        return Err(error_at(
            path,
            text,
            text.len(),
            "expected an <UnstructuredGrid> with a <Piece>".into(),
        ));
    };
    let arrays = Arrays {
        src: &src,
        arrays: &arrays,
    };
    let points = read_points(&arrays, num_points)?;
    let (element, cells) = read_cells(&arrays, num_points, num_cells, quadratic)?;
    let fields = |parent: &str, count: usize| -> Result<Vec<Field>, MeshError> {
        if !with_fields {
            return Ok(Vec::new());
        }
        arrays
            .arrays
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

/// The data arrays of a file, found by their parent element and name.
struct Arrays<'s> {
    src: &'s Source<'s>,
    arrays: &'s [Array<'s>],
}

impl<'s> Arrays<'s> {
    /// The first array in `<parent>` (named `name`, if given).
    fn find(&self, parent: &str, name: Option<&str>) -> Result<&'s Array<'s>, MeshError> {
        self.arrays
            .iter()
            .find(|a| a.parent == parent && name.is_none_or(|n| a.name() == n))
            .ok_or_else(|| {
                let what = name.map_or(String::new(), |n| format!(" \"{n}\""));
                self.error(
                    self.src.text.len(),
                    format!("expected a DataArray{what} in <{parent}>"),
                )
            })
    }

    /// The error at byte `offset` of the XML.
    fn error(&self, offset: usize, message: String) -> MeshError {
        error_at(self.src.path, self.src.text, offset, message)
    }

    /// The error at the `i`-th value of array `a`.
    fn at(&self, a: &Array, i: usize, message: String) -> MeshError {
        MeshError::parse(self.src.path, token_line(self.src.text, a, i), message)
    }

    /// The error of a `<Piece>` that declares more `what` than memory can hold.
    fn too_many(&self, what: &str) -> MeshError {
        self.error(
            0,
            format!("<Piece> declares more {what} than memory can hold"),
        )
    }
}

/// The `num_points` points of the `<Points>` array, every coordinate finite.
fn read_points(arrays: &Arrays, num_points: usize) -> Result<Vec<Vec3>, MeshError> {
    let points_array = arrays.find("Points", None)?;
    let num_coords = num_points
        .checked_mul(3)
        .ok_or_else(|| arrays.too_many("points"))?;
    let coords: Vec<f64> = values(arrays.src, points_array, num_coords)?;
    if let Some(i) = coords.iter().position(|c| !c.is_finite()) {
        return Err(arrays.at(
            points_array,
            i,
            format!("point {} has a non-finite coordinate", i / 3),
        ));
    }
    Ok(coords
        .chunks_exact(3)
        .map(Vec3::from_column_slice)
        .collect())
}

/// The kind of the `num_cells` cells and their point indices in our node order: one VTK
/// cell type (a linear tet, or with `quadratic` a quadratic one), consecutive offsets, and
/// points in range.
fn read_cells(
    arrays: &Arrays,
    num_points: usize,
    num_cells: usize,
    quadratic: bool,
) -> Result<(TetElement, Vec<usize>), MeshError> {
    // The largest cell has 10 points.
    num_cells
        .checked_mul(10)
        .ok_or_else(|| arrays.too_many("cells"))?;
    let types_array = arrays.find("Cells", Some("types"))?;
    let types: Vec<usize> = values(arrays.src, types_array, num_cells)?;
    let element = cell_kind(arrays, types_array, &types, quadratic)?;
    let first = vtk_type(element);
    let n = element.num_nodes();
    let offsets_array = arrays.find("Cells", Some("offsets"))?;
    let offsets: Vec<usize> = values(arrays.src, offsets_array, num_cells)?;
    for e in 0..num_cells {
        if types[e] != first {
            return Err(arrays.at(
                types_array,
                e,
                format!(
                    "cell {e}: VTK cell type {} after cells of type {first}: cells of one type only are supported",
                    types[e]
                ),
            ));
        }
        if offsets[e] != n * (e + 1) {
            return Err(arrays.at(
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
    let connectivity_array = arrays.find("Cells", Some("connectivity"))?;
    let connectivity: Vec<usize> = values(arrays.src, connectivity_array, num_cells * n)?;
    if let Some(i) = connectivity.iter().position(|&v| v >= num_points) {
        return Err(arrays.at(
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
    Ok((element, cells))
}

/// The tet kind of the first cell's VTK type (with `quadratic` false, linear tets only).
fn cell_kind(
    arrays: &Arrays,
    types_array: &Array,
    types: &[usize],
    quadratic: bool,
) -> Result<TetElement, MeshError> {
    let kinds = if quadratic {
        &[TetElement::Tet4, TetElement::Tet10][..]
    } else {
        &[TetElement::Tet4][..]
    };
    let first = types.first().copied().unwrap_or(10);
    if let Some(&element) = kinds.iter().find(|&&k| vtk_type(k) == first) {
        return Ok(element);
    }
    let hint = if first == vtk_type(TetElement::Tet10) {
        ": this file holds quadratic tetrahedra, read it with read_vtu_elements"
    } else {
        ""
    };
    Err(arrays.at(
        types_array,
        0,
        format!(
            "cell 0: VTK cell type {first} is not supported{hint} (isochor reads tetrahedra, \
             type 10, and quadratic tetrahedra, type 24)"
        ),
    ))
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
