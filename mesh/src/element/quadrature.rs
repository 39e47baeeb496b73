//! Quadrature rules on the reference tetrahedron and triangle, each with its degree of
//! exactness and its source. Every rule is fully symmetric with positive weights (a negative
//! weight would let a sum of pointwise convex energy terms lose convexity), and its weights
//! add up to the measure of the reference element (1/6 and 1/2), so that
//! `sum_q w_q f(xi_q)` approximates the integral of `f` over the reference element.

use crate::{MeshError, Vec3};
use nalgebra::Vector2;

/// A quadrature rule on the reference tetrahedron `{xi, eta, zeta >= 0, xi + eta + zeta <= 1}`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum TetQuadrature {
    /// 1 point (the centroid), exact for degree 1.
    Degree1,
    /// 4 points, exact for degree 2 (Hammer, Marlowe and Stroud, "Numerical integration over
    /// simplexes and cones", Math. Tables Aids Comput. 10, 1956).
    Degree2,
    /// 8 points on two orbits, exact for degree 3: the face centroids `(1/3, 1/3, 1/3, 0)` with
    /// total weight `0.36` and the orbit `(1/8, 1/8, 1/8, 5/8)` with `0.64` (fractions of the
    /// volume). A fully symmetric rule is exact to degree 3 when it integrates `1`,
    /// `sum_i lambda_i^2` and `sum_i lambda_i^3` exactly (averages `2/5` and `1/5`); on the
    /// orbit `(a, a, a, 1 - 3a)` these sums are `12a^2 - 6a + 1` and `-24a^3 + 27a^2 - 9a + 1`,
    /// and the two orbits above are a rational pair that meets both with positive weights
    /// (a centroid would need a negative weight, Stroud's 5-point rule). Half the points of
    /// the degree-5 rule, for the element (P0) and zonal rows on 10-node tets.
    Degree3,
    /// 15 points, exact for degree 5 (Keast, "Moderate-degree tetrahedral quadrature
    /// formulas", Comput. Methods Appl. Mech. Engrg. 55, 1986: the degree-5 rule with the
    /// centroid, face centroids, the orbit `(1/11, 1/11, 1/11, 8/11)` and the orbit
    /// `(a, a, 1/2 - a, 1/2 - a)`, `a = 1/4 - sqrt(91)/52`). It serves degree 4 too: Keast's
    /// 11-point degree-4 rule has a negative weight, and the positive 15-point rule costs only
    /// 4 points more.
    Degree5,
}

/// A quadrature rule on the reference triangle `{xi, eta >= 0, xi + eta <= 1}`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum TriQuadrature {
    /// 1 point (the centroid), exact for degree 1.
    Degree1,
    /// 3 interior points `(1/6, 1/6)`, `(2/3, 1/6)`, `(1/6, 2/3)`, exact for degree 2
    /// (Dunavant, "High degree efficient symmetrical Gaussian quadrature rules for the
    /// triangle", Int. J. Numer. Meth. Engng. 21, 1985).
    Degree2,
    /// 6 points on two orbits `(a, a, 1 - 2a)`, exact for degree 4 (Dunavant 1985, the
    /// degree-4 rule).
    Degree4,
}

/// The four points with barycentric coordinates a permutation of `(1 - 3a, a, a, a)`, as
/// reference coordinates `(lambda_1, lambda_2, lambda_3)`.
const fn s31(a: f64) -> [Vec3; 4] {
    let b = 1.0 - 3.0 * a;
    [
        Vec3::new(a, a, a),
        Vec3::new(b, a, a),
        Vec3::new(a, b, a),
        Vec3::new(a, a, b),
    ]
}

/// The six points with barycentric coordinates a permutation of `(a, a, 1/2 - a, 1/2 - a)`.
const fn s22(a: f64) -> [Vec3; 6] {
    let b = 0.5 - a;
    [
        Vec3::new(a, b, b),
        Vec3::new(b, a, b),
        Vec3::new(b, b, a),
        Vec3::new(a, a, b),
        Vec3::new(a, b, a),
        Vec3::new(b, a, a),
    ]
}

/// The three points with barycentric coordinates a permutation of `(1 - 2a, a, a)`.
const fn s21(a: f64) -> [Vector2<f64>; 3] {
    let b = 1.0 - 2.0 * a;
    [Vector2::new(a, a), Vector2::new(b, a), Vector2::new(a, b)]
}

const TET1_POINTS: [Vec3; 1] = [Vec3::new(0.25, 0.25, 0.25)];
const TET1_WEIGHTS: [f64; 1] = [1.0 / 6.0];

/// `(5 - sqrt 5) / 20`.
const TET2_A: f64 = 0.138_196_601_125_010_5;
const TET2_POINTS: [Vec3; 4] = s31(TET2_A);
const TET2_WEIGHTS: [f64; 4] = [1.0 / 24.0; 4];

const TET3_POINTS: [Vec3; 8] = {
    let f = s31(1.0 / 3.0);
    let v = s31(1.0 / 8.0);
    [f[0], f[1], f[2], f[3], v[0], v[1], v[2], v[3]]
};
/// `0.36 / 4` and `0.64 / 4` of the reference volume 1/6.
const TET3_WEIGHTS: [f64; 8] = {
    let f = 0.09 / 6.0;
    let v = 0.16 / 6.0;
    [f, f, f, f, v, v, v, v]
};

/// `1/4 - sqrt(91) / 52`.
const KEAST5_A: f64 = 0.066_550_153_573_664_3;
const TET5_POINTS: [Vec3; 15] = {
    let f = s31(1.0 / 3.0);
    let v = s31(1.0 / 11.0);
    let e = s22(KEAST5_A);
    [
        Vec3::new(0.25, 0.25, 0.25),
        f[0],
        f[1],
        f[2],
        f[3],
        v[0],
        v[1],
        v[2],
        v[3],
        e[0],
        e[1],
        e[2],
        e[3],
        e[4],
        e[5],
    ]
};
/// Keast's weights (normalized to the unit volume there) times the reference volume 1/6.
const TET5_WEIGHTS: [f64; 15] = {
    let c = 6544.0 / 36015.0 / 6.0;
    let f = 81.0 / 2240.0 / 6.0;
    let v = 161051.0 / 2304960.0 / 6.0;
    let e = 338.0 / 5145.0 / 6.0;
    [c, f, f, f, f, v, v, v, v, e, e, e, e, e, e]
};

const TRI1_POINTS: [Vector2<f64>; 1] = [Vector2::new(1.0 / 3.0, 1.0 / 3.0)];
const TRI1_WEIGHTS: [f64; 1] = [0.5];

const TRI2_POINTS: [Vector2<f64>; 3] = s21(1.0 / 6.0);
const TRI2_WEIGHTS: [f64; 3] = [1.0 / 6.0; 3];

/// Dunavant's degree-4 orbits, `a = (8 - sqrt 10 +- sqrt(38 - 44 sqrt(2/5))) / 18`, with
/// weights `(620 +- sqrt(213125 - 53320 sqrt 10)) / 3720` times the reference area 1/2.
const TRI4_A: f64 = 0.445_948_490_915_964_9;
const TRI4_B: f64 = 0.091_576_213_509_770_74;
const TRI4_WA: f64 = 0.111_690_794_839_005_74;
const TRI4_WB: f64 = 0.054_975_871_827_660_935;
const TRI4_POINTS: [Vector2<f64>; 6] = {
    let a = s21(TRI4_A);
    let b = s21(TRI4_B);
    [a[0], a[1], a[2], b[0], b[1], b[2]]
};
const TRI4_WEIGHTS: [f64; 6] = [TRI4_WA, TRI4_WA, TRI4_WA, TRI4_WB, TRI4_WB, TRI4_WB];

/// The error of a degree no tabulated rule reaches.
fn too_high(degree: usize, highest: usize) -> MeshError {
    MeshError::parameter(
        "quadrature degree",
        degree,
        format!("the highest tabulated degree is {highest}"),
    )
}

impl TetQuadrature {
    /// Every rule, by increasing degree.
    pub const ALL: [TetQuadrature; 4] = [
        TetQuadrature::Degree1,
        TetQuadrature::Degree2,
        TetQuadrature::Degree3,
        TetQuadrature::Degree5,
    ];

    /// The cheapest rule exact for polynomials of total degree `degree`; fails above 5.
    pub fn for_degree(degree: usize) -> Result<Self, MeshError> {
        Self::ALL
            .into_iter()
            .find(|rule| rule.degree() >= degree)
            .ok_or_else(|| too_high(degree, 5))
    }

    /// The highest total degree integrated exactly.
    pub const fn degree(self) -> usize {
        match self {
            TetQuadrature::Degree1 => 1,
            TetQuadrature::Degree2 => 2,
            TetQuadrature::Degree3 => 3,
            TetQuadrature::Degree5 => 5,
        }
    }

    /// Number of points.
    pub fn num_points(self) -> usize {
        self.points().len()
    }

    /// The points `xi_q` in reference coordinates.
    pub fn points(self) -> &'static [Vec3] {
        match self {
            TetQuadrature::Degree1 => &TET1_POINTS,
            TetQuadrature::Degree2 => &TET2_POINTS,
            TetQuadrature::Degree3 => &TET3_POINTS,
            TetQuadrature::Degree5 => &TET5_POINTS,
        }
    }

    /// The weights `w_q`, adding up to the reference volume 1/6.
    pub fn weights(self) -> &'static [f64] {
        match self {
            TetQuadrature::Degree1 => &TET1_WEIGHTS,
            TetQuadrature::Degree2 => &TET2_WEIGHTS,
            TetQuadrature::Degree3 => &TET3_WEIGHTS,
            TetQuadrature::Degree5 => &TET5_WEIGHTS,
        }
    }
}

impl TriQuadrature {
    /// Every rule, by increasing degree.
    pub const ALL: [TriQuadrature; 3] = [
        TriQuadrature::Degree1,
        TriQuadrature::Degree2,
        TriQuadrature::Degree4,
    ];

    /// The cheapest rule exact for polynomials of total degree `degree`; fails above 4.
    pub fn for_degree(degree: usize) -> Result<Self, MeshError> {
        Self::ALL
            .into_iter()
            .find(|rule| rule.degree() >= degree)
            .ok_or_else(|| too_high(degree, 4))
    }

    /// The highest total degree integrated exactly.
    pub const fn degree(self) -> usize {
        match self {
            TriQuadrature::Degree1 => 1,
            TriQuadrature::Degree2 => 2,
            TriQuadrature::Degree4 => 4,
        }
    }

    /// Number of points.
    pub fn num_points(self) -> usize {
        self.points().len()
    }

    /// The points `xi_q` in reference coordinates.
    pub fn points(self) -> &'static [Vector2<f64>] {
        match self {
            TriQuadrature::Degree1 => &TRI1_POINTS,
            TriQuadrature::Degree2 => &TRI2_POINTS,
            TriQuadrature::Degree4 => &TRI4_POINTS,
        }
    }

    /// The weights `w_q`, adding up to the reference area 1/2.
    pub fn weights(self) -> &'static [f64] {
        match self {
            TriQuadrature::Degree1 => &TRI1_WEIGHTS,
            TriQuadrature::Degree2 => &TRI2_WEIGHTS,
            TriQuadrature::Degree4 => &TRI4_WEIGHTS,
        }
    }
}
