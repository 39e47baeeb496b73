//! How loads, prescribed motions and obstacles follow the run: by default loads ramp with the
//! load parameter (quasi-static) or stay constant (dynamics) and motions follow the fraction of
//! the run; a [`Curve`] replaces either by a piecewise-linear function of the load parameter
//! (quasi-static) or of time in seconds (dynamics), so that a chamber can be inflated, held
//! and deflated, or an obstacle can squeeze and release.

use crate::error::SolverError;

/// A piecewise-linear function `y(s)` through points with increasing `s`, constant beyond the
/// first and last point.
#[derive(Debug, Clone, PartialEq)]
pub struct Curve {
    points: Vec<(f64, f64)>,
}

impl Curve {
    /// A curve through `points` (`(s, y)` pairs): at least one, finite, with strictly
    /// increasing `s`.
    pub fn new(points: Vec<(f64, f64)>) -> Result<Self, SolverError> {
        let bad = |what: String| Err(SolverError::InvalidProblem(format!("load curve: {what}")));
        if points.is_empty() {
            return bad("needs at least one point".into());
        }
        if let Some((i, p)) = points
            .iter()
            .enumerate()
            .find(|(_, p)| !(p.0.is_finite() && p.1.is_finite()))
        {
            return bad(format!("point {i} = [{}, {}] is not finite", p.0, p.1));
        }
        if let Some(i) = (1..points.len()).find(|&i| points[i].0 <= points[i - 1].0) {
            return bad(format!(
                "the abscissae must increase: point {i} has s = {} after s = {}",
                points[i].0,
                points[i - 1].0
            ));
        }
        Ok(Curve { points })
    }

    /// The points `(s, y)`.
    pub fn points(&self) -> &[(f64, f64)] {
        &self.points
    }

    /// `y(s)`, linear between points and constant outside them.
    pub fn value(&self, s: f64) -> f64 {
        let p = &self.points;
        let after = p.partition_point(|q| q.0 <= s);
        match after {
            0 => p[0].1,
            n if n == p.len() => p[n - 1].1,
            n => {
                let ((s0, y0), (s1, y1)) = (p[n - 1], p[n]);
                y0 + (s - s0) / (s1 - s0) * (y1 - y0)
            }
        }
    }
}

/// Where the loads stand at one step: the argument of the curves and the defaults of what
/// has none.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LoadLevel {
    /// Load parameter in `[0, 1]` (quasi-static) or time in seconds (dynamics): the
    /// argument of every [`Curve`].
    pub t: f64,
    /// Scale of a load without a curve: `t` (quasi-static ramp) or 1 (dynamics).
    pub ramp: f64,
    /// Parameter of a motion or obstacle without a curve: the fraction of the run, `t`
    /// (quasi-static) or `time / duration` (dynamics).
    pub fraction: f64,
}

impl LoadLevel {
    /// Full load at the end of a run: every default is 1.
    pub const FULL: LoadLevel = LoadLevel {
        t: 1.0,
        ramp: 1.0,
        fraction: 1.0,
    };

    /// Quasi-static level at load parameter `t`.
    pub fn quasi_static(t: f64) -> Self {
        LoadLevel {
            t,
            ramp: t,
            fraction: t,
        }
    }

    /// Dynamic level at `time` of a run lasting `duration` seconds.
    pub fn dynamic(time: f64, duration: f64) -> Self {
        LoadLevel {
            t: time,
            ramp: 1.0,
            fraction: time / duration,
        }
    }

    /// The scale of a load following `curve` (or the default ramp).
    pub fn load_scale(&self, curve: Option<&Curve>) -> f64 {
        curve.map_or(self.ramp, |c| c.value(self.t))
    }

    /// The parameter of a motion or obstacle following `curve` (or the fraction of the run).
    pub fn motion_parameter(&self, curve: Option<&Curve>) -> f64 {
        curve.map_or(self.fraction, |c| c.value(self.t))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn curves_interpolate_and_hold_their_ends() {
        let c = Curve::new(vec![(0.0, 0.0), (0.5, 1.0), (1.0, 0.0)]).unwrap();
        assert_eq!(c.value(-1.0), 0.0);
        assert_eq!(c.value(0.25), 0.5);
        assert_eq!(c.value(0.5), 1.0);
        assert_eq!(c.value(0.75), 0.5);
        assert_eq!(c.value(2.0), 0.0);
        assert_eq!(Curve::new(vec![(0.3, 2.0)]).unwrap().value(0.0), 2.0);
    }

    #[test]
    fn bad_curves_are_refused() {
        assert!(Curve::new(vec![]).is_err());
        assert!(Curve::new(vec![(0.0, 1.0), (0.0, 2.0)]).is_err());
        assert!(Curve::new(vec![(0.0, f64::NAN)]).is_err());
    }

    #[test]
    fn defaults_ramp_in_quasi_statics_and_hold_in_dynamics() {
        let q = LoadLevel::quasi_static(0.3);
        assert_eq!((q.load_scale(None), q.motion_parameter(None)), (0.3, 0.3));
        let d = LoadLevel::dynamic(0.5, 2.0);
        assert_eq!((d.load_scale(None), d.motion_parameter(None)), (1.0, 0.25));
        let c = Curve::new(vec![(0.0, 0.0), (1.0, 2.0)]).unwrap();
        assert_eq!(d.load_scale(Some(&c)), 1.0);
    }
}
