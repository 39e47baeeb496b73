//! Richardson extrapolation of a series' values over the mesh size.

/// A Richardson extrapolation from three runs of one series.
#[derive(Debug, Clone, PartialEq)]
pub struct Richardson {
    /// The method.
    pub method: String,
    /// The element.
    pub element: String,
    /// Resolutions of the three runs, coarse to fine.
    pub resolutions: [f64; 3],
    /// Their probe values.
    pub values: [f64; 3],
    /// Observed order of convergence in `h`.
    pub order: f64,
    /// The extrapolated limit.
    pub limit: f64,
    /// `|limit - finest value|`.
    pub finest_gap: f64,
    /// `|limit - limit of the previous triple|`, with four or more runs.
    pub previous_gap: Option<f64>,
}

impl Richardson {
    /// The estimated error of the limit: the previous gap, or the finest gap without one.
    pub fn estimate(&self) -> f64 {
        self.previous_gap.unwrap_or(self.finest_gap)
    }

    /// [`Richardson::estimate`] relative to the limit.
    pub fn relative_estimate(&self) -> f64 {
        self.estimate() / self.limit.abs()
    }
}

/// Extrapolates `f(h) = f_inf + C h^p` through three (resolution, value) pairs, coarse to
/// fine. `None` if the values do not converge monotonically (oscillate or diverge) or the
/// order is outside (0.05, 20).
pub fn richardson(points: [(f64, f64); 3]) -> Option<(f64, f64)> {
    let h = points.map(|(r, _)| 1.0 / r);
    let f = points.map(|(_, v)| v);
    let (d1, d2) = (f[0] - f[1], f[1] - f[2]);
    let ordered = h[0] > h[1] && h[1] > h[2] && h[2] > 0.0;
    let ratio = d1 / d2;
    // Monotone: differences of one sign (a zero d2 gives inf or NaN); whether they shrink
    // fast enough for a positive order is decided by the bracket below.
    if !ordered || !ratio.is_finite() || ratio <= 0.0 {
        return None;
    }
    let g = |p: f64| (h[0].powf(p) - h[1].powf(p)) / (h[1].powf(p) - h[2].powf(p)) - ratio;
    let (mut lo, mut hi) = (0.05, 20.0);
    if g(lo) > 0.0 || g(hi) < 0.0 {
        return None;
    }
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if g(mid) < 0.0 {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    let p = 0.5 * (lo + hi);
    let c = d2 / (h[1].powf(p) - h[2].powf(p));
    Some((p, f[2] - c * h[2].powf(p)))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn richardson_recovers_order_and_limit() {
        // f = 2 - 3 h^1.5 at h = 1/2, 1/4, 1/8 and at a non-constant ratio.
        let f = |r: f64| 2.0 - 3.0 * (1.0 / r).powf(1.5);
        for rs in [[2.0, 4.0, 8.0], [2.0, 3.0, 5.0]] {
            let (p, l) = richardson(rs.map(|r| (r, f(r)))).unwrap();
            assert!((p - 1.5).abs() < 1e-8, "{p}");
            assert!((l - 2.0).abs() < 1e-10, "{l}");
        }
        // Oscillating or diverging values are not extrapolated.
        assert!(richardson([(1.0, 1.0), (2.0, 2.0), (4.0, 1.5)]).is_none());
        assert!(richardson([(1.0, 1.0), (2.0, 1.1), (4.0, 1.3)]).is_none());
    }
}
