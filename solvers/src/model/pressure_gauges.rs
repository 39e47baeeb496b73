//! What every pressure load reads at a state: its pressure (given, times its load scale, or
//! solved: the multiplier of its cavity's row) and the volume its faces enclose over the
//! rest volume.

use crate::problem::schedule::{Curve, LoadLevel};
use crate::terms::EnclosedVolume;
use isochor_mesh::Vec3;

/// Where a pressure load's pressure comes from.
#[derive(Debug, Clone)]
pub enum GaugedPressure {
    /// A follower pressure: `pressure` times the load scale of `curve`.
    Given {
        /// The pressure at full load.
        pressure: f64,
        /// Its scale (`None`: the default ramp).
        curve: Option<Curve>,
    },
    /// A volume-controlled cavity: the multiplier of constraint row `row`.
    Solved {
        /// The row among all the model's constraints.
        row: usize,
    },
}

/// One pressure load's gauge.
#[derive(Debug, Clone)]
pub struct PressureGauge {
    volume: EnclosedVolume,
    rest: f64,
    pressure: GaugedPressure,
}

/// A pressure load's pressure and enclosed volume ratio at one state.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PressureReading {
    /// The pressure (positive inflates).
    pub pressure: f64,
    /// The enclosed volume over the rest volume (NaN if the faces enclose none at rest).
    pub volume_ratio: f64,
}

impl PressureGauge {
    /// The gauge of the load on the faces of `volume` (body-outward) with rest positions
    /// `rest`.
    pub fn new(volume: EnclosedVolume, pressure: GaugedPressure, rest: &[Vec3]) -> Self {
        let rest = -volume.value(rest);
        PressureGauge {
            volume,
            rest,
            pressure,
        }
    }

    /// Whether the pressure is given (not solved for).
    pub fn is_given(&self) -> bool {
        matches!(self.pressure, GaugedPressure::Given { .. })
    }

    /// Moves a solved pressure's row past the `rows` constraints of the method.
    pub(crate) fn offset_row(&mut self, rows: usize) {
        if let GaugedPressure::Solved { row } = &mut self.pressure {
            *row += rows;
        }
    }

    /// The reading at positions `x`, load `level` and constraint multipliers `multipliers`.
    pub fn read(&self, x: &[Vec3], level: &LoadLevel, multipliers: &[f64]) -> PressureReading {
        let pressure = match &self.pressure {
            GaugedPressure::Given { pressure, curve } => {
                pressure * level.load_scale(curve.as_ref())
            }
            GaugedPressure::Solved { row } => multipliers.get(*row).copied().unwrap_or(f64::NAN),
        };
        let volume_ratio = if self.rest != 0.0 {
            -self.volume.value(x) / self.rest
        } else {
            f64::NAN
        };
        PressureReading {
            pressure,
            volume_ratio,
        }
    }
}
