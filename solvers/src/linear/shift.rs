//! Diagonal shifts `K + tau I` for Newton steps whose stiffness is not positive definite
//! (or whose saddle-point matrix has the wrong inertia): try `tau = 0`, then a growing
//! sequence of shifts, until a factorization succeeds.

use super::LinearError;
use faer::sparse::SparseColMatRef;

/// A growing sequence of diagonal shifts, relative to a scale of `K` (for instance
/// [`max_abs_diagonal`]): `0, initial * scale, initial * growth * scale, ...`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ShiftSchedule {
    /// First nonzero shift, relative to the scale.
    pub initial: f64,
    /// Factor between consecutive shifts (> 1).
    pub growth: f64,
    /// Attempts in total, the unshifted one included.
    pub max_attempts: usize,
}

impl Default for ShiftSchedule {
    fn default() -> Self {
        Self {
            initial: 1e-8,
            growth: 10.0,
            max_attempts: 10,
        }
    }
}

impl ShiftSchedule {
    /// The unshifted attempt only: a failure is reported as
    /// [`LinearError::RegularizationFailed`] after one attempt.
    pub const NONE: Self = Self {
        initial: 1e-8,
        growth: 10.0,
        max_attempts: 1,
    };

    /// The absolute shifts to try, starting with zero.
    pub fn shifts(&self, scale: f64) -> impl Iterator<Item = f64> + '_ {
        (0..self.max_attempts).map(move |k| match k {
            0 => 0.0,
            _ => self.initial * scale * self.growth.powi(k as i32 - 1),
        })
    }

    /// Runs `attempt(shift)` for each shift of the schedule until it succeeds or fails
    /// with an error that a shift cannot cure ([`LinearError::is_regularizable`]).
    /// Returns the result and the shift that worked.
    pub fn retry<T>(
        &self,
        scale: f64,
        mut attempt: impl FnMut(f64) -> Result<T, LinearError>,
    ) -> Result<(T, f64), LinearError> {
        let mut last = LinearError::RegularizationFailed {
            attempts: 0,
            last_shift: 0.0,
            last_error: Box::new(LinearError::NotFactorized),
        };
        let mut attempts = 0;
        let mut last_shift = 0.0;
        for shift in self.shifts(scale) {
            attempts += 1;
            last_shift = shift;
            match attempt(shift) {
                Ok(value) => return Ok((value, shift)),
                Err(e) if e.is_regularizable() => last = e,
                Err(e) => return Err(e),
            }
        }
        Err(LinearError::RegularizationFailed {
            attempts,
            last_shift,
            last_error: Box::new(last),
        })
    }
}

/// The largest `|A_ii|`, a natural scale for diagonal shifts (1 if the diagonal is zero).
pub fn max_abs_diagonal(a: SparseColMatRef<'_, usize, f64>) -> f64 {
    let rows = a.symbolic().row_idx();
    let vals = a.val();
    let max = (0..a.ncols())
        .flat_map(|j| a.col_range(j).filter(move |&p| rows[p] == j))
        .map(|p| vals[p].abs())
        .fold(0.0, f64::max);
    if max > 0.0 {
        max
    } else {
        1.0
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn retry_stops_at_first_success_and_passes_on_fatal_errors() {
        let schedule = ShiftSchedule {
            initial: 1e-3,
            growth: 10.0,
            max_attempts: 5,
        };
        let (v, shift) = schedule
            .retry(2.0, |s| {
                if s < 0.01 {
                    Err(LinearError::NotPositiveDefinite { pivot: 0 })
                } else {
                    Ok(s)
                }
            })
            .unwrap();
        assert_eq!(v, shift);
        assert!((shift - 0.02).abs() < 1e-15);
        let fatal = schedule.retry(1.0, |_| -> Result<(), _> {
            Err(LinearError::NonFiniteSolution)
        });
        assert_eq!(fatal, Err(LinearError::NonFiniteSolution));
        let exhausted = schedule.retry(1.0, |_| -> Result<(), _> {
            Err(LinearError::Singular { pivot: 1 })
        });
        assert!(matches!(
            exhausted,
            Err(LinearError::RegularizationFailed { attempts: 5, .. })
        ));
    }
}
