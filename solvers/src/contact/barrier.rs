//! The log barrier of IPC (Li et al. 2020, eq. 6) on squared distances, as IPC evaluates it:
//! `b(d) = -(d - dhat^2)^2 ln(d / dhat^2)` for `0 < d < dhat^2`, 0 beyond; `C^2` at
//! `d = dhat^2` and unbounded as `d -> 0`.

/// `b(d)` for the squared distance `d` and the squared reach `dhat_sq`; `+inf` for `d <= 0`.
pub fn barrier(d: f64, dhat_sq: f64) -> f64 {
    if d <= 0.0 {
        f64::INFINITY
    } else if d >= dhat_sq {
        0.0
    } else {
        -(d - dhat_sq).powi(2) * (d / dhat_sq).ln()
    }
}

/// `b'(d) = -2 (d - dhat^2) ln(d / dhat^2) - (d - dhat^2)^2 / d`.
pub fn barrier_first_derivative(d: f64, dhat_sq: f64) -> f64 {
    if d <= 0.0 {
        f64::NEG_INFINITY
    } else if d >= dhat_sq {
        0.0
    } else {
        let s = d - dhat_sq;
        -2.0 * s * (d / dhat_sq).ln() - s * s / d
    }
}

/// `b''(d) = -2 ln(d / dhat^2) - 4 (d - dhat^2) / d + (d - dhat^2)^2 / d^2`.
pub fn barrier_second_derivative(d: f64, dhat_sq: f64) -> f64 {
    if d <= 0.0 {
        f64::INFINITY
    } else if d >= dhat_sq {
        0.0
    } else {
        let s = d - dhat_sq;
        -2.0 * (d / dhat_sq).ln() - 4.0 * s / d + s * s / (d * d)
    }
}

/// The magnitude of the contact force of a pair at squared distance `d`, `lambda = -kappa
/// db/d(sqrt d) = -2 kappa sqrt(d) b'(d)`: what lagged friction multiplies (Li et al. 2020,
/// sec. 5).
pub fn normal_force(kappa: f64, d: f64, dhat_sq: f64) -> f64 {
    -2.0 * kappa * d.sqrt() * barrier_first_derivative(d, dhat_sq)
}
