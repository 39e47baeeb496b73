//! The adaptive barrier stiffness of IPC (Li et al. 2020, sec. 4.3 and supplement B): a
//! start value that balances the barrier's gradient against the rest of the energy's, bounds
//! from the scene's size, and doubling while the smallest distance keeps shrinking near
//! zero.

use super::barrier::barrier_second_derivative;

/// Lower and upper bounds of the barrier stiffness.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StiffnessBounds {
    /// The smallest stiffness: at a distance `d0 = min(1e-8 bbox_diagonal, dhat / 2)` the
    /// barrier's curvature along the distance, `4 d0^2 b''(d0^2)` (per unit stiffness),
    /// times `kappa_min`, is `1e11` times the average mass.
    pub min: f64,
    /// `100 min`.
    pub max: f64,
}

impl StiffnessBounds {
    /// The bounds for a scene of bounding-box diagonal `bbox_diagonal`, barrier reach `dhat`
    /// (a distance) and average nodal mass `average_mass` (in quasi-static problems, the
    /// average diagonal entry of the elastic Hessian takes its place).
    pub fn new(bbox_diagonal: f64, dhat: f64, average_mass: f64) -> Self {
        let d0 = (1e-8 * bbox_diagonal).min(0.5 * dhat);
        let d0_sq = d0 * d0;
        let curvature = 4.0 * d0_sq * barrier_second_derivative(d0_sq, dhat * dhat);
        let min = 1e11 * average_mass / curvature;
        StiffnessBounds {
            min,
            max: 100.0 * min,
        }
    }
}

/// The start stiffness `kappa = -(g_b . g_E) / (g_b . g_b)` that makes the barrier's
/// gradient `g_b` (per unit stiffness) best cancel the gradient `g_E` of the rest of the
/// energy, clamped to the bounds (`min` when the barrier has no gradient).
pub fn initial_barrier_stiffness(
    energy_gradient: &[f64],
    barrier_gradient: &[f64],
    bounds: &StiffnessBounds,
) -> f64 {
    let dot = |a: &[f64], b: &[f64]| a.iter().zip(b).map(|(x, y)| x * y).sum::<f64>();
    let gb = dot(barrier_gradient, barrier_gradient);
    let kappa = -dot(barrier_gradient, energy_gradient) / gb;
    if kappa.is_finite() {
        kappa.clamp(bounds.min, bounds.max)
    } else {
        bounds.min
    }
}

/// The stiffness for the next iteration: doubled (up to `bounds.max`) when the smallest
/// distance `min_distance` is below `1e-9 bbox_diagonal` and smaller than the previous
/// one `previous_min_distance` (distances, not squared), else unchanged.
pub fn update_barrier_stiffness(
    kappa: f64,
    previous_min_distance: f64,
    min_distance: f64,
    bbox_diagonal: f64,
    bounds: &StiffnessBounds,
) -> f64 {
    if previous_min_distance < 1e-9 * bbox_diagonal && min_distance < previous_min_distance {
        (2.0 * kappa).min(bounds.max)
    } else {
        kappa
    }
}
