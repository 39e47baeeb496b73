//! Errors of the constraint layer.

/// Why a constraint set could not be evaluated or built.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum ConstraintError {
    /// A tet has non-positive volume where the logarithmic measure needs `v_e > 0`.
    #[error(
        "tet {tet} has volume {volume:e} <= 0, outside the domain of the logarithmic constraint"
    )]
    NonPositiveVolume { tet: usize, volume: f64 },
    /// An invalid construction parameter.
    #[error("invalid constraint parameter {name} = {value}: {reason}")]
    InvalidParameter {
        name: &'static str,
        value: f64,
        reason: &'static str,
    },
    /// A buffer or position array has the wrong length for this constraint set.
    #[error("{what} has length {actual}, expected {expected}")]
    DimensionMismatch {
        what: &'static str,
        expected: usize,
        actual: usize,
    },
    /// A zone refers to a tet that is not in the mesh, or is empty.
    #[error("zone {zone}: {reason}")]
    InvalidZone { zone: usize, reason: String },
}
