//! The limit point of a pressure-controlled cavity: past the largest pressure its wall can
//! hold (a balloon's, an inflated thin shell's), no equilibrium exists under a higher given
//! pressure, so the steps beyond it fail at every increment. Along the accepted steps, the
//! slope `dP/dV` of each given pressure against its enclosed volume falls to zero there; a
//! run whose increments are being cut while a slope has fallen below
//! [`LIMIT_SLOPE_FRACTION`] of its largest value (or turned) ends with
//! [`SolverError::PressureLimitPoint`] instead of halving its increments down to the
//! smallest (docs/stepping.md).

use crate::error::SolverError;
use crate::model::pressure_gauges::PressureReading;

/// The fraction of its largest value below which a pressure-volume slope is taken as the
/// limit point's.
pub const LIMIT_SLOPE_FRACTION: f64 = 0.1;

/// The readings of every pressure load at the accepted steps, with whether each is given.
#[derive(Debug)]
pub(super) struct PressureHistory {
    given: Vec<bool>,
    readings: Vec<Vec<PressureReading>>,
}

impl PressureHistory {
    /// A history starting from `start`; `given[k]` says whether load `k`'s pressure is given.
    pub fn new(given: Vec<bool>, start: Vec<PressureReading>) -> Self {
        PressureHistory {
            given,
            readings: vec![start],
        }
    }

    /// Adds the readings of an accepted step.
    pub fn push(&mut self, readings: Vec<PressureReading>) {
        self.readings.push(readings);
    }

    /// The limit-point error of the first given pressure whose slope along the accepted
    /// steps has fallen below [`LIMIT_SLOPE_FRACTION`] of its largest (or turned), if any.
    pub fn limit_point(&self) -> Option<SolverError> {
        (0..self.given.len())
            .filter(|&k| self.given[k])
            .find_map(|k| {
                let slopes: Vec<f64> = self
                    .readings
                    .windows(2)
                    .filter_map(|w| {
                        let (a, b) = (w[0][k], w[1][k]);
                        let dv = b.volume_ratio - a.volume_ratio;
                        (dv != 0.0 && (b.pressure - a.pressure).abs() > 0.0)
                            .then(|| (b.pressure - a.pressure) / dv)
                    })
                    .collect();
                let largest = slopes.iter().copied().fold(0.0, f64::max);
                let last = *slopes.last()?;
                let reached = self.readings.last()?[k];
                (slopes.len() >= 2 && largest > 0.0 && last < LIMIT_SLOPE_FRACTION * largest).then(
                    || SolverError::PressureLimitPoint {
                        load: k,
                        pressure: reached.pressure,
                        volume_ratio: reached.volume_ratio,
                        slope_fraction: last / largest,
                    },
                )
            })
    }
}
