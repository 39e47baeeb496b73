//! Outward-rounded interval arithmetic on `f64`: every operation rounds to nearest and then
//! widens by one unit in the last place on each side, so the exact result of the same
//! operation on any reals inside the operands lies inside the result (round to nearest is off
//! by at most half a unit; subnormal results too). What makes the CCD conservative in
//! floating point.

/// A closed interval `[lo, hi]`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Interval {
    pub(crate) lo: f64,
    pub(crate) hi: f64,
}

/// The next `f64` above `x` (`x` itself for `+inf` and NaN).
fn next_up(x: f64) -> f64 {
    if x.is_nan() || x == f64::INFINITY {
        x
    } else if x == 0.0 {
        f64::from_bits(1)
    } else if x > 0.0 {
        f64::from_bits(x.to_bits() + 1)
    } else {
        f64::from_bits(x.to_bits() - 1)
    }
}

/// The next `f64` below `x`.
fn next_down(x: f64) -> f64 {
    -next_up(-x)
}

impl Interval {
    /// The exact number `x`.
    pub(crate) fn point(x: f64) -> Self {
        Interval { lo: x, hi: x }
    }

    /// `self + other`, rounded outward.
    pub(crate) fn add(self, other: Self) -> Self {
        Interval {
            lo: next_down(self.lo + other.lo),
            hi: next_up(self.hi + other.hi),
        }
    }

    /// `self - other`, rounded outward.
    pub(crate) fn sub(self, other: Self) -> Self {
        Interval {
            lo: next_down(self.lo - other.hi),
            hi: next_up(self.hi - other.lo),
        }
    }

    /// `self * other`, rounded outward.
    pub(crate) fn mul(self, other: Self) -> Self {
        let products = [
            self.lo * other.lo,
            self.lo * other.hi,
            self.hi * other.lo,
            self.hi * other.hi,
        ];
        Interval {
            lo: next_down(products.iter().copied().fold(f64::INFINITY, f64::min)),
            hi: next_up(products.iter().copied().fold(f64::NEG_INFINITY, f64::max)),
        }
    }

    /// `s * self` for an exact scalar `s`, rounded outward.
    pub(crate) fn scale(self, s: f64) -> Self {
        let (a, b) = (self.lo * s, self.hi * s);
        Interval {
            lo: next_down(a.min(b)),
            hi: next_up(a.max(b)),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn widened_sums_contain_the_exact_sum() {
        // 0.1 + 0.2 is not 0.3 in floating point; the exact sum of the two doubles lies in
        // the widened interval.
        let s = Interval::point(0.1).add(Interval::point(0.2));
        assert!(s.lo < 0.1 + 0.2 && 0.1 + 0.2 < s.hi);
        assert_eq!(next_up(0.0), f64::from_bits(1));
        assert_eq!(next_down(1.0), 1.0 - f64::EPSILON / 2.0);
        assert_eq!(next_up(-1.0), -1.0 + f64::EPSILON / 2.0);
    }

    #[test]
    fn widened_products_contain_the_exact_product() {
        let p = Interval { lo: -0.1, hi: 0.3 }.mul(Interval { lo: 0.7, hi: 0.9 });
        assert!(p.lo < -0.1 * 0.9 && 0.3 * 0.9 < p.hi);
        assert!(p.lo > -0.1 * 0.9 - 1e-16 && p.hi < 0.3 * 0.9 + 1e-16);
    }
}
