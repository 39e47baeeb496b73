//! Errors of the mesh layer: every variant names the element, vertex, file or line at fault.

use std::path::PathBuf;

/// Why a mesh could not be built, read or written.
#[derive(Debug, thiserror::Error)]
pub enum MeshError {
    /// Tet `tet`: vertex index `index` is out of range (the mesh has `vertices` vertices).
    #[error("tet {tet}: vertex index {index} is out of range (the mesh has {vertices} vertices)")]
    IndexOutOfRange {
        /// Index of the tet.
        tet: usize,
        /// The vertex index out of range.
        index: usize,
        /// Number of vertices of the mesh.
        vertices: usize,
    },
    /// Tet `tet`: vertex `vertex` appears more than once in `indices`.
    #[error("tet {tet}: vertex {vertex} appears more than once in {indices:?}")]
    RepeatedVertex {
        /// Index of the tet.
        tet: usize,
        /// Index of the vertex.
        vertex: usize,
        /// The tet's vertex indices.
        indices: [usize; 4],
    },
    /// Tet `tet` is degenerate: |volume| = `volume` is below `threshold` (relative to its longest edge cubed).
    #[error("tet {tet} is degenerate: |volume| = {volume:e} is below {threshold:e} (relative to its longest edge cubed)")]
    Degenerate {
        /// Index of the tet.
        tet: usize,
        /// Its signed volume.
        volume: f64,
        /// The degeneracy threshold.
        threshold: f64,
    },
    /// Tet `tet` is negatively oriented (volume `volume`) and the mesh was built with strict orientation.
    #[error("tet {tet} is negatively oriented (volume {volume:e}) and the mesh was built with strict orientation")]
    Inverted {
        /// Index of the tet.
        tet: usize,
        /// Its signed volume.
        volume: f64,
    },
    /// Vertex `vertex` has a non-finite coordinate `coords`.
    #[error("vertex {vertex} has a non-finite coordinate {coords:?}")]
    NonFiniteVertex {
        /// Index of the vertex.
        vertex: usize,
        /// Its coordinates.
        coords: [f64; 3],
    },
    /// Element `element`: det(dX/dxi) = `determinant` at reference point `point` is not positive: the (curved) element is folded or inverted.
    #[error("element {element}: det(dX/dxi) = {determinant:e} at reference point {point:?} is not positive: the (curved) element is folded or inverted")]
    FoldedElement {
        /// Index of the element.
        element: usize,
        /// The reference point.
        point: [f64; 3],
        /// The determinant found.
        determinant: f64,
    },
    /// Element `element`: node `node` `reason`.
    #[error("element {element}: node {node} {reason}")]
    MidEdgeNode {
        /// Index of the element.
        element: usize,
        /// The node (or, for a face, the first vertex of its edge).
        node: usize,
        /// Why.
        reason: String,
    },
    /// The mesh has no tetrahedra.
    #[error("the mesh has no tetrahedra")]
    Empty,
    /// Tet index `tet` is out of range (the mesh has `tets` tets).
    #[error("tet index {tet} is out of range (the mesh has {tets} tets)")]
    TetOutOfRange {
        /// Index of the tet.
        tet: usize,
        /// Number of tets of the mesh.
        tets: usize,
    },
    /// Vertex index `vertex` is out of range (the mesh has `vertices` vertices).
    #[error("vertex index {vertex} is out of range (the mesh has {vertices} vertices)")]
    VertexOutOfRange {
        /// Index of the vertex.
        vertex: usize,
        /// Number of vertices of the mesh.
        vertices: usize,
    },
    /// Face `face` is shared by `count` tets (a conforming mesh shares a face by at most 2).
    #[error(
        "face {face:?} is shared by {count} tets (a conforming mesh shares a face by at most 2)"
    )]
    NonManifoldFace {
        /// The face's vertex indices.
        face: [usize; 3],
        /// How many share it.
        count: usize,
    },
    /// Surface edge `edge` belongs to one triangle only: the surface is open there.
    #[error("surface edge {edge:?} belongs to one triangle only: the surface is open there")]
    OpenBoundary {
        /// The edge's vertex indices.
        edge: [usize; 2],
    },
    /// Surface edge `edge` is shared by `count` triangles (a closed manifold surface needs exactly 2).
    #[error("surface edge {edge:?} is shared by {count} triangles (a closed manifold surface needs exactly 2)")]
    NonManifoldEdge {
        /// The edge's vertex indices.
        edge: [usize; 2],
        /// How many share it.
        count: usize,
    },
    /// Surface edge `edge` is traversed in the same direction by both of its triangles: their orientations disagree.
    #[error("surface edge {edge:?} is traversed in the same direction by both of its triangles: their orientations disagree")]
    InconsistentOrientation {
        /// The edge's vertex indices.
        edge: [usize; 2],
    },
    /// Selection "`name`" is empty: its region contains no vertex or boundary face of the mesh.
    #[error(
        "selection \"{name}\" is empty: its region contains no vertex or boundary face of the mesh"
    )]
    EmptySelection {
        /// The selection's name.
        name: String,
    },
    /// Point `point` lies outside the mesh.
    #[error("point {point:?} lies outside the mesh")]
    PointOutside {
        /// The rest point.
        point: [f64; 3],
    },
    /// Zone `zone` is empty.
    #[error("zone {zone} is empty")]
    EmptyZone {
        /// Index of the zone.
        zone: usize,
    },
    /// Invalid `name` = `value`: `reason`.
    #[error("invalid {name} = {value}: {reason}")]
    InvalidParameter {
        /// The parameter's name.
        name: &'static str,
        /// The value given.
        value: String,
        /// Why.
        reason: String,
    },
    /// `path`:`line`: `message`.
    #[error("{path}:{line}: {message}")]
    Parse {
        /// The file.
        path: PathBuf,
        /// The line, from 1.
        line: usize,
        /// What is wrong.
        message: String,
    },
    /// `path`: `source`.
    #[error("{path}: {source}")]
    Io {
        /// The file.
        path: PathBuf,
        /// The underlying I/O error.
        #[source]
        source: std::io::Error,
    },
    /// `path`: `message`.
    #[error("{path}: {message}")]
    Format {
        /// The file.
        path: PathBuf,
        /// What is wrong.
        message: String,
    },
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
