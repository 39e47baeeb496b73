//! VTK XML UnstructuredGrid (`.vtu`) files of linear or quadratic tets (VTK cell types 10 and
//! 24; quadratic tetra nodes in VTK's order, see [`TetElement::vtk_order`]) with named point
//! and cell data, at full `f64` precision: a writer readable by ParaView and meshio, in ASCII
//! or zlib-compressed appended binary ([`VtuEncoding`]), and a reader for the files it writes
//! and other VTU files of one of these cell types (ASCII, inline base64 or appended raw
//! binary, compressed with zlib or not, `UInt32` or `UInt64` headers).

mod read;
mod scan;
mod types;
mod values;
mod write;

pub use read::{read_vtu, read_vtu_elements, read_vtu_file};
pub use types::{Field, FieldValues, VtuEncoding, VtuFile};
pub(crate) use write::escape;
pub use write::{write_vtu, write_vtu_elements};

use crate::element::TetElement;

/// VTK cell type of a tet element: `VTK_TETRA` (10) or `VTK_QUADRATIC_TETRA` (24).
fn vtk_type(kind: TetElement) -> usize {
    match kind {
        TetElement::Tet4 => 10,
        TetElement::Tet10 => 24,
    }
}
