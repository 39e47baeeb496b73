//! What a VTU file holds: points, cells of one tet kind, and named point and cell data.

use crate::element::TetElement;
use crate::Vec3;
use nalgebra::Matrix3;

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
