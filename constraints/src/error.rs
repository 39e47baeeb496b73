//! Errors of the constraint layer.

/// Why a constraint set could not be evaluated or built.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum ConstraintError {
    /// An element has a volume ratio `J <= 0` at a quadrature point, where the logarithmic
    /// measure needs `J > 0`.
    #[error(
        "element {element} has J = {j:e} <= 0 at a quadrature point, outside the domain of the logarithmic constraint"
    )]
    NonPositiveVolumeRatio {
        /// Index of the element.
        element: usize,
        /// The volume ratio found.
        j: f64,
    },
    /// The rest geometry of the mesh could not be evaluated (a folded element).
    #[error("invalid mesh: {reason}")]
    InvalidMesh {
        /// Why.
        reason: String,
    },
    /// An invalid construction parameter.
    #[error("invalid constraint parameter {name} = {value}: {reason}")]
    InvalidParameter {
        /// The parameter's name.
        name: &'static str,
        /// The value given.
        value: f64,
        /// Why.
        reason: &'static str,
    },
    /// A buffer or position array has the wrong length for this constraint set.
    #[error("{what} has length {actual}, expected {expected}")]
    DimensionMismatch {
        /// The array.
        what: &'static str,
        /// The length expected.
        expected: usize,
        /// The length given.
        actual: usize,
    },
    /// A zone refers to a tet that is not in the mesh, or is empty.
    #[error("zone {zone}: {reason}")]
    InvalidZone {
        /// Index of the zone.
        zone: usize,
        /// Why.
        reason: String,
    },
}
