//! Errors of the mesh layer: every variant names the element, vertex, file or line at fault.

use std::path::PathBuf;

/// Why a mesh could not be built, read or written.
#[derive(Debug, thiserror::Error)]
pub enum MeshError {
    #[error("tet {tet}: vertex index {index} is out of range (the mesh has {vertices} vertices)")]
    IndexOutOfRange {
        tet: usize,
        index: usize,
        vertices: usize,
    },
    #[error("tet {tet}: vertex {vertex} appears more than once in {indices:?}")]
    RepeatedVertex {
        tet: usize,
        vertex: usize,
        indices: [usize; 4],
    },
    #[error("tet {tet} is degenerate: |volume| = {volume:e} is below {threshold:e} (relative to its longest edge cubed)")]
    Degenerate {
        tet: usize,
        volume: f64,
        threshold: f64,
    },
    #[error("tet {tet} is negatively oriented (volume {volume:e}) and the mesh was built with strict orientation")]
    Inverted { tet: usize, volume: f64 },
    #[error("vertex {vertex} has a non-finite coordinate {coords:?}")]
    NonFiniteVertex { vertex: usize, coords: [f64; 3] },
    #[error("element {element}: det(dX/dxi) = {determinant:e} at reference point {point:?} is not positive: the (curved) element is folded or inverted")]
    FoldedElement {
        element: usize,
        point: [f64; 3],
        determinant: f64,
    },
    #[error("element {element}: node {node} {reason}")]
    MidEdgeNode {
        element: usize,
        node: usize,
        reason: String,
    },
    #[error("the mesh has no tetrahedra")]
    Empty,
    #[error("tet index {tet} is out of range (the mesh has {tets} tets)")]
    TetOutOfRange { tet: usize, tets: usize },
    #[error("vertex index {vertex} is out of range (the mesh has {vertices} vertices)")]
    VertexOutOfRange { vertex: usize, vertices: usize },
    #[error(
        "face {face:?} is shared by {count} tets (a conforming mesh shares a face by at most 2)"
    )]
    NonManifoldFace { face: [usize; 3], count: usize },
    #[error("surface edge {edge:?} belongs to one triangle only: the surface is open there")]
    OpenBoundary { edge: [usize; 2] },
    #[error("surface edge {edge:?} is shared by {count} triangles (a closed manifold surface needs exactly 2)")]
    NonManifoldEdge { edge: [usize; 2], count: usize },
    #[error("surface edge {edge:?} is traversed in the same direction by both of its triangles: their orientations disagree")]
    InconsistentOrientation { edge: [usize; 2] },
    #[error(
        "selection \"{name}\" is empty: its region contains no vertex or boundary face of the mesh"
    )]
    EmptySelection { name: String },
    #[error("point {point:?} lies outside the mesh")]
    PointOutside { point: [f64; 3] },
    #[error("zone {zone} is empty")]
    EmptyZone { zone: usize },
    #[error("invalid {name} = {value}: {reason}")]
    InvalidParameter {
        name: &'static str,
        value: String,
        reason: String,
    },
    #[error("{path}:{line}: {message}")]
    Parse {
        path: PathBuf,
        line: usize,
        message: String,
    },
    #[error("{path}: {source}")]
    Io {
        path: PathBuf,
        #[source]
        source: std::io::Error,
    },
    #[error("{path}: {message}")]
    Format { path: PathBuf, message: String },
}

impl MeshError {
    /// An I/O error on `path`.
    pub fn io(path: impl Into<PathBuf>, source: std::io::Error) -> Self {
        MeshError::Io {
            path: path.into(),
            source,
        }
    }

    /// A parse error at `line` (1-based) of `path`.
    pub fn parse(path: impl Into<PathBuf>, line: usize, message: impl Into<String>) -> Self {
        MeshError::Parse {
            path: path.into(),
            line,
            message: message.into(),
        }
    }

    /// An invalid generator or constructor parameter.
    pub fn parameter(name: &'static str, value: impl ToString, reason: impl Into<String>) -> Self {
        MeshError::InvalidParameter {
            name,
            value: value.to_string(),
            reason: reason.into(),
        }
    }
}
