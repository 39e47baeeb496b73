//! What the sections share: the vector type and the defaults and skip tests of their serde
//! attributes.

/// A point or vector `[x, y, z]`.
pub type Vector = [f64; 3];

pub(super) fn is_false(b: &bool) -> bool {
    !*b
}

pub(super) fn is_zero(x: &f64) -> bool {
    *x == 0.0
}

pub(super) fn one() -> usize {
    1
}

pub(super) fn yes() -> bool {
    true
}

pub(super) fn z_axis() -> Vector {
    [0.0, 0.0, 1.0]
}
