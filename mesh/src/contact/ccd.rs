//! Continuous collision detection of point-triangle and edge-edge pairs under linear motion
//! over a step `t in [0, 1]`, with a minimum separation: the inclusion-based root finding of
//! Wang et al. 2021 ("A Large-Scale Benchmark and an Inclusion-Based Algorithm for
//! Continuous Collision Detection", ACM TOG 40(5), sec. 4), with outward-rounded interval
//! arithmetic in place of their error filter.
//!
//! A pair touches at time `t` when `F(t, u, v) = 0`, with `F` the vector between a point of
//! one primitive and a point of the other: `p(t) - a(t) - u (b(t) - a(t)) - v (c(t) - a(t))`
//! over `u, v >= 0, u + v <= 1` for a point and a triangle, `a0(t) + u (a1(t) - a0(t)) - b0(t)
//! - v (b1(t) - b0(t))` over `[0, 1]^2` for two edges. `F` is affine in each of `t, u, v`
//! separately, so its range over a box of parameters is spanned by its values at the box's
//! eight corners (their inclusion, Wang et al. 2021 sec. 4.1); computed with outward rounding,
//! that range contains every exact value. Boxes whose range misses the cube
//! `[-min_separation, min_separation]^3` are discarded, the others are split (the parameter
//! whose width moves `F` most first), earliest time first; the first box whose range lies
//! inside the cube of half-side `1.1 min_separation + tolerance` reports contact at its
//! earliest time (with no separation, a box narrower than `tolerance` on every axis; with
//! one, a coarse box near the separation: the 10% slack keeps the thick contact region of a
//! separation from being refined everywhere to `tolerance`).
//!
//! Before any box, a pair whose points never become coplanar is let go: with no separation
//! asked, touching needs the point in the triangle's plane (the two edges in one plane), so a
//! signed volume `det(X, Y, Z)` of the pair's three difference vectors that keeps one strict
//! sign over the step rules contact out. Each vector is linear in `t`, so the volume is a
//! cubic whose Bernstein coefficients are sums of determinants of the end vectors (the
//! polarization of the trilinear `det`), bounded with the same rounding; four of one strict
//! sign keep the cubic off zero on `[0, 1]` (the filter of Provot 1997 and Bridson et al.
//! 2002, made conservative). It settles pairs that slide past each other at a small gap,
//! whose boxes would otherwise be refined along the whole motion.
//!
//! The guarantee, in floating point: when a pair comes within `min_separation` (in the
//! largest coordinate, which holds the Euclidean ball) at some time `t* < t_max`, a time of
//! impact `toi <= t*` is returned; no pair closer than that is missed. A reported time may be a
//! false positive, but only of two kinds: the pair does come within `1.1 min_separation +
//! tolerance` (per coordinate) at some time of the reporting box, or the iteration limit was
//! reached (then the earliest time still undecided is returned).

use super::interval::Interval;
use crate::Vec3;
use std::cmp::Ordering;
use std::collections::BinaryHeap;

/// A box every point of which is within `(1 + SEPARATION_SLACK) min_separation + tolerance`
/// reports contact: with a separation, coarse boxes then settle a thick contact region.
const SEPARATION_SLACK: f64 = 0.1;

/// The parameters of a CCD query.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CcdSettings {
    /// The distance (per coordinate) the primitives must keep; 0 detects actual contact.
    pub min_separation: f64,
    /// How much farther than `1.1 min_separation` (per coordinate) a pair may be reported;
    /// the default is
    /// `1e-6`, for coordinates of unit size: scale it with the scene (see
    /// [`CcdSettings::for_scale`]).
    pub tolerance: f64,
    /// Boxes examined at most per query before the earliest undecided time is returned.
    pub max_iterations: usize,
    /// The end of the searched times, in `(0, 1]`: an impact at or after it is not looked
    /// for (`None` is returned). A caller that wants the earliest impact of many pairs passes
    /// the earliest found so far, and the later queries stop there.
    pub t_max: f64,
}

impl Default for CcdSettings {
    fn default() -> Self {
        CcdSettings {
            min_separation: 0.0,
            tolerance: 1e-6,
            max_iterations: 100_000,
            t_max: 1.0,
        }
    }
}

impl CcdSettings {
    /// `min_separation` with a tolerance of `1e-6 length` (`length` e.g. the scene's
    /// bounding-box diagonal).
    pub fn for_scale(min_separation: f64, length: f64) -> Self {
        CcdSettings {
            min_separation,
            tolerance: 1e-6 * length,
            ..CcdSettings::default()
        }
    }
}

/// The earliest time in `[0, 1]` at which point `p` comes within the minimum separation of
/// triangle `(a, b, c)`, all moving linearly from the `*0` to the `*1` positions; `None` when
/// the whole step is safe. The pair keeps its separation over `[0, toi)`.
#[allow(clippy::too_many_arguments)]
pub fn point_triangle_ccd(
    p0: &Vec3,
    a0: &Vec3,
    b0: &Vec3,
    c0: &Vec3,
    p1: &Vec3,
    a1: &Vec3,
    b1: &Vec3,
    c1: &Vec3,
    settings: &CcdSettings,
) -> Option<f64> {
    // F = (p - a) - u (b - a) - v (c - a)
    let pair = Pair {
        start: [*p0, *a0, *b0, *c0],
        end: [*p1, *a1, *b1, *c1],
        base: [0, 1],
        first: ([2, 1], -1.0),
        second: ([3, 1], -1.0),
        triangle: true,
    };
    pair.time_of_impact(settings)
}

/// The earliest time in `[0, 1]` at which edges `(a0, a1)` and `(b0, b1)` come within the
/// minimum separation, moving linearly from the `*_t0` to the `*_t1` positions; `None` when the
/// whole step is safe.
#[allow(clippy::too_many_arguments)]
pub fn edge_edge_ccd(
    a0_t0: &Vec3,
    a1_t0: &Vec3,
    b0_t0: &Vec3,
    b1_t0: &Vec3,
    a0_t1: &Vec3,
    a1_t1: &Vec3,
    b0_t1: &Vec3,
    b1_t1: &Vec3,
    settings: &CcdSettings,
) -> Option<f64> {
    // F = (a0 - b0) + u (a1 - a0) - v (b1 - b0)
    let pair = Pair {
        start: [*a0_t0, *a1_t0, *b0_t0, *b1_t0],
        end: [*a0_t1, *a1_t1, *b0_t1, *b1_t1],
        base: [0, 2],
        first: ([1, 0], 1.0),
        second: ([3, 2], -1.0),
        triangle: false,
    };
    pair.time_of_impact(settings)
}

/// `F(t, u, v) = (x_i - x_j) + s_u u (x_k - x_l) + s_v v (x_m - x_n)` for the vertex index
/// pairs `base = [i, j]`, `first = ([k, l], s_u)`, `second = ([m, n], s_v)`.
struct Pair {
    start: [Vec3; 4],
    end: [Vec3; 4],
    base: [usize; 2],
    first: ([usize; 2], f64),
    second: ([usize; 2], f64),
    /// `u + v <= 1` (a triangle) rather than `v <= 1` (an edge).
    triangle: bool,
}

/// A box of parameters `[t0, t1] x [u0, u1] x [v0, v1]`; its bounds are dyadic, so halving
/// is exact.
#[derive(Debug, Clone, Copy, PartialEq)]
struct ParameterBox {
    t: [f64; 2],
    u: [f64; 2],
    v: [f64; 2],
}

impl Eq for ParameterBox {}

impl Ord for ParameterBox {
    /// Earliest start time first (in a max-heap).
    fn cmp(&self, other: &Self) -> Ordering {
        other.t[0].total_cmp(&self.t[0])
    }
}

impl PartialOrd for ParameterBox {
    fn partial_cmp(&self, other: &Self) -> Option<Ordering> {
        Some(self.cmp(other))
    }
}

impl Pair {
    /// Whether the signed volume of the pair's difference vectors (`F`'s constant part and
    /// its two directions) keeps one strict sign over the whole step, rounding included: then
    /// the pair is never coplanar and cannot touch.
    fn never_coplanar(&self) -> bool {
        let ([k, l], _) = self.first;
        let ([m, n], _) = self.second;
        let difference = |x: &[Vec3; 4], [i, j]: [usize; 2]| -> [Interval; 3] {
            std::array::from_fn(|a| Interval::point(x[i][a]).sub(Interval::point(x[j][a])))
        };
        let ends = [&self.start, &self.end];
        let vectors: [[[Interval; 3]; 3]; 2] = std::array::from_fn(|e| {
            [
                difference(ends[e], self.base),
                difference(ends[e], [k, l]),
                difference(ends[e], [m, n]),
            ]
        });
        // det with factor f taken at end `choice[f]` (0: start, 1: end).
        let det = |choice: [usize; 3]| {
            let [x, y, z] = [
                vectors[choice[0]][0],
                vectors[choice[1]][1],
                vectors[choice[2]][2],
            ];
            let cross = |i: usize, j: usize| y[i].mul(z[j]).sub(y[j].mul(z[i]));
            x[0].mul(cross(1, 2))
                .add(x[1].mul(cross(2, 0)))
                .add(x[2].mul(cross(0, 1)))
        };
        let sum = |choices: &[[usize; 3]]| {
            choices[1..]
                .iter()
                .fold(det(choices[0]), |acc, &c| acc.add(det(c)))
        };
        let coefficients = [
            det([0, 0, 0]),
            sum(&[[1, 0, 0], [0, 1, 0], [0, 0, 1]]),
            sum(&[[0, 1, 1], [1, 0, 1], [1, 1, 0]]),
            det([1, 1, 1]),
        ];
        coefficients.iter().all(|c| c.lo > 0.0) || coefficients.iter().all(|c| c.hi < 0.0)
    }

    /// The positions at the exact time `t`, per vertex and axis.
    fn at(&self, motion: &[[Interval; 3]; 4], t: f64) -> [[Interval; 3]; 4] {
        std::array::from_fn(|i| {
            std::array::from_fn(|a| Interval::point(self.start[i][a]).add(motion[i][a].scale(t)))
        })
    }

    /// The range of every coordinate of `F` over the box.
    fn range(&self, motion: &[[Interval; 3]; 4], b: &ParameterBox) -> [Interval; 3] {
        let mut range = [Interval {
            lo: f64::INFINITY,
            hi: f64::NEG_INFINITY,
        }; 3];
        let ([k, l], su) = self.first;
        let ([m, n], sv) = self.second;
        for t in b.t {
            let x = self.at(motion, t);
            for (a, out) in range.iter_mut().enumerate() {
                let base = x[self.base[0]][a].sub(x[self.base[1]][a]);
                let e1 = x[k][a].sub(x[l][a]);
                let e2 = x[m][a].sub(x[n][a]);
                for u in b.u {
                    let partial = base.add(e1.scale(su * u));
                    for v in b.v {
                        let f = partial.add(e2.scale(sv * v));
                        out.lo = out.lo.min(f.lo);
                        out.hi = out.hi.max(f.hi);
                    }
                }
            }
        }
        range
    }

    /// How far `F` can move per unit of `t`, `u` and `v` (largest coordinate), to choose the
    /// parameter to split.
    fn sensitivities(&self) -> [f64; 3] {
        let amax = |v: Vec3| v.amax();
        let motion = (0..4)
            .map(|i| amax(self.end[i] - self.start[i]))
            .fold(0.0, f64::max);
        let edge = |[i, j]: [usize; 2]| {
            amax(self.start[i] - self.start[j]).max(amax(self.end[i] - self.end[j]))
        };
        [2.0 * motion, edge(self.first.0), edge(self.second.0)]
    }

    fn time_of_impact(&self, settings: &CcdSettings) -> Option<f64> {
        let finite = |x: &[Vec3; 4]| x.iter().all(|p| p.iter().all(|c| c.is_finite()));
        if !finite(&self.start) || !finite(&self.end) {
            return Some(0.0);
        }
        let motion: [[Interval; 3]; 4] = std::array::from_fn(|i| {
            std::array::from_fn(|a| {
                Interval::point(self.end[i][a]).sub(Interval::point(self.start[i][a]))
            })
        });
        let ms = settings.min_separation;
        if ms == 0.0 && self.never_coplanar() {
            return None;
        }
        let sensitivity = self.sensitivities();
        let mut heap = BinaryHeap::new();
        heap.push(ParameterBox {
            t: [0.0, 1.0],
            u: [0.0, 1.0],
            v: [0.0, 1.0],
        });
        let mut iterations = 0;
        while let Some(b) = heap.pop() {
            // Earliest first: every box left starts at or after this one.
            if b.t[0] >= settings.t_max {
                return None;
            }
            if self.triangle && b.u[0] + b.v[0] > 1.0 {
                continue;
            }
            let range = self.range(&motion, &b);
            if range.iter().any(|r| r.lo > ms || r.hi < -ms) {
                continue;
            }
            iterations += 1;
            // Every point of the box is within the reach: contact, or as good as.
            let reach = ms * (1.0 + SEPARATION_SLACK) + settings.tolerance;
            if range.iter().all(|r| r.lo >= -reach && r.hi <= reach)
                || iterations >= settings.max_iterations
            {
                return Some(b.t[0]);
            }
            let widths = [
                (b.t[1] - b.t[0]) * sensitivity[0],
                (b.u[1] - b.u[0]) * sensitivity[1],
                (b.v[1] - b.v[0]) * sensitivity[2],
            ];
            let split = (0..3).fold(0, |best, d| if widths[d] > widths[best] { d } else { best });
            let (mut low, mut high) = (b, b);
            let (lo_side, hi_side, [a, z]) = match split {
                0 => (&mut low.t, &mut high.t, b.t),
                1 => (&mut low.u, &mut high.u, b.u),
                _ => (&mut low.v, &mut high.v, b.v),
            };
            let mid = 0.5 * (a + z);
            lo_side[1] = mid;
            hi_side[0] = mid;
            heap.push(low);
            heap.push(high);
        }
        None
    }
}
