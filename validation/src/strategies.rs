//! Proptest strategies shared by the test suites: deformation gradients and perturbed meshes.

use nalgebra::Matrix3;
use proptest::prelude::*;

/// Random `F = I + M` with entries of `M` in `[-spread, spread]`.
pub fn near_identity(spread: f64) -> impl Strategy<Value = Matrix3<f64>> {
    proptest::array::uniform9(-spread..spread)
        .prop_map(|m| Matrix3::identity() + Matrix3::from_column_slice(&m))
}

/// Random `F` with `det F` in `[j_min, j_max]`: a random rotation-free shape of unit
/// determinant scaled by `J^(1/3)` with `J` drawn log-uniformly; with `inverted`, one
/// axis is reflected so that `det F = -J`.
pub fn with_determinant(j_min: f64, j_max: f64, inverted: bool) -> impl Strategy<Value = Matrix3<f64>> {
    (
        proptest::array::uniform9(-0.4..0.4f64),
        j_min.ln()..j_max.ln(),
    )
        .prop_filter_map("shape matrix must be invertible", move |(m, log_j)| {
            let shape = Matrix3::identity() + Matrix3::from_column_slice(&m);
            let d = shape.determinant();
            if d < 0.2 {
                return None;
            }
            let unit = shape / d.cbrt();
            let mut f = unit * log_j.exp().cbrt();
            if inverted {
                f.column_mut(2).neg_mut();
            }
            Some(f)
        })
}
