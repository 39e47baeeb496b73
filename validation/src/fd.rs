//! Central finite differences and a relative error measure, used by every derivative test.

use nalgebra::{DMatrix, DVector};

/// Central difference step relative to the scale of the input.
pub const STEP: f64 = 1e-6;

/// Gradient of `f` at `x` by central differences with step `h`.
pub fn gradient(f: impl Fn(&DVector<f64>) -> f64, x: &DVector<f64>, h: f64) -> DVector<f64> {
    let mut g = DVector::zeros(x.len());
    let mut xp = x.clone();
    for i in 0..x.len() {
        let xi = x[i];
        xp[i] = xi + h;
        let fp = f(&xp);
        xp[i] = xi - h;
        let fm = f(&xp);
        xp[i] = xi;
        g[i] = (fp - fm) / (2.0 * h);
    }
    g
}

/// Jacobian of a vector function `f` at `x` by central differences: column `j` is `d f / d x_j`.
pub fn jacobian(
    f: impl Fn(&DVector<f64>) -> DVector<f64>,
    x: &DVector<f64>,
    h: f64,
) -> DMatrix<f64> {
    let m = f(x).len();
    let mut jac = DMatrix::zeros(m, x.len());
    let mut xp = x.clone();
    for j in 0..x.len() {
        let xj = x[j];
        xp[j] = xj + h;
        let fp = f(&xp);
        xp[j] = xj - h;
        let fm = f(&xp);
        xp[j] = xj;
        jac.set_column(j, &((fp - fm) / (2.0 * h)));
    }
    jac
}

/// Relative error `|a - b| / max(|a|, |b|, floor)` in the max norm, where `floor` keeps the
/// measure meaningful when both are near zero (pass the natural scale of the quantity).
pub fn relative_error(a: &DMatrix<f64>, b: &DMatrix<f64>, floor: f64) -> f64 {
    assert_eq!(a.shape(), b.shape(), "shapes differ");
    let diff = (a - b).amax();
    let scale = a.amax().max(b.amax()).max(floor);
    diff / scale
}

/// [`relative_error`] for vectors.
pub fn relative_error_vec(a: &DVector<f64>, b: &DVector<f64>, floor: f64) -> f64 {
    assert_eq!(a.len(), b.len(), "lengths differ");
    let diff = (a - b).amax();
    let scale = a.amax().max(b.amax()).max(floor);
    diff / scale
}
