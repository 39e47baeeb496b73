//! The bending energy of discrete shells (Grinspun et al. 2003, eq. 3) on one hinge: two
//! triangles `(x0, x1, x2)` and `(x1, x0, x3)` sharing the edge `x0 x1`,
//! `E_b = (D / 2) |e_0|^2 / (A_1 + A_2) (theta - theta_0)^2`, with `D` the plate bending
//! stiffness ([`Fabric::bending_stiffness`]), `theta` the signed dihedral angle (0 when flat)
//! and the rest values `|e_0|`, `A_1 + A_2`, `theta_0`.
//!
//! The weight makes the sum over a mesh tend to the plate energy `(D / 2) int kappa^2 dA` of a
//! cylindrical bend on a regular mesh whose hinges lie along the axis: there `theta` is the
//! hinge spacing times the curvature. (Grinspun et al. write the weight `3 |e|^2 / A` with
//! `A = A_1 + A_2` and leave the stiffness free: ours is theirs with `k_b = D / 6`.)
//!
//! With `e = x1 - x0`, `a = x2 - x0`, `b = x3 - x0` and the normals `n1 = e x a`, `n2 = b x e`,
//! `theta = atan2(Y, X)` where `X = n1 . n2 = (e.a)(e.b) - |e|^2 (a.b)` (Binet-Cauchy) and
//! `Y = (n1 x n2) . e / |e| = -|e| e . (a x b)`: polynomials in `(e, a, b)` but for `|e|`, so
//! the gradient and Hessian follow by the chain rule from those of `X` and `Y`.

use super::Fabric;
use nalgebra::{Matrix3, SMatrix, SVector, Vector3};

/// A 12-vector: the coordinates of the hinge's four vertices, node-major.
pub type Vector12 = SVector<f64, 12>;
/// A 12x12 matrix over the hinge's vertex coordinates.
pub type Matrix12 = SMatrix<f64, 12, 12>;

/// Rest data of a hinge: the weight `(D / 2) |e_0|^2 / (A_1 + A_2)` and the rest angle.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RestHinge {
    weight: f64,
    rest_angle: f64,
}

/// Energy, gradient and Hessian of one hinge.
#[derive(Debug, Clone, PartialEq)]
pub struct HingeTerms {
    /// `E_b`.
    pub energy: f64,
    /// Gradient with respect to the 12 vertex coordinates.
    pub gradient: Vector12,
    /// The exact Hessian (symmetric, indefinite away from the rest angle).
    pub hessian: Matrix12,
}

impl RestHinge {
    /// From the rest positions `[x0, x1, x2, x3]`; `None` when either rest triangle is
    /// degenerate (zero or non-finite area).
    pub fn new(fabric: &Fabric, rest: &[Vector3<f64>; 4]) -> Option<Self> {
        let e = rest[1] - rest[0];
        let areas =
            0.5 * (e.cross(&(rest[2] - rest[0])).norm() + (rest[3] - rest[0]).cross(&e).norm());
        let rest_angle = dihedral_angle(rest)?;
        let weight = 0.5 * fabric.bending_stiffness() * e.norm_squared() / areas;
        (weight.is_finite() && areas > 0.0).then_some(RestHinge { weight, rest_angle })
    }

    /// `theta_0`.
    pub fn rest_angle(&self) -> f64 {
        self.rest_angle
    }

    /// Energy, gradient and Hessian at `x`; `None` when a triangle of the hinge is degenerate
    /// (its angle is undefined).
    pub fn energy_gradient_hessian(&self, x: &[Vector3<f64>; 4]) -> Option<HingeTerms> {
        let angle = Angle::at(x)?;
        let delta = angle.theta - self.rest_angle;
        let gradient = angle.gradient * (2.0 * self.weight * delta);
        let hessian = (angle.gradient * angle.gradient.transpose() + angle.hessian * delta)
            * (2.0 * self.weight);
        Some(HingeTerms {
            energy: self.weight * delta * delta,
            gradient,
            hessian,
        })
    }
}

/// The signed dihedral angle `theta` of the hinge `[x0, x1, x2, x3]` in `(-pi, pi]` (0 when
/// flat, positive when `x3` lies on the side of `-n1`, `n1 = (x1 - x0) x (x2 - x0)`); `None` when a
/// triangle is degenerate.
pub fn dihedral_angle(x: &[Vector3<f64>; 4]) -> Option<f64> {
    let (e, a, b) = (x[1] - x[0], x[2] - x[0], x[3] - x[0]);
    let cos = e.dot(&a) * e.dot(&b) - e.norm_squared() * a.dot(&b);
    let sin = -e.norm() * e.dot(&a.cross(&b));
    (cos * cos + sin * sin > 0.0 && (cos + sin).is_finite()).then(|| sin.atan2(cos))
}

/// `theta` with its gradient and Hessian over the 12 coordinates.
struct Angle {
    theta: f64,
    gradient: Vector12,
    hessian: Matrix12,
}

/// A function of `(e, a, b)` with its gradient (9) and Hessian (9x9), in that block order.
struct Polynomial {
    value: f64,
    gradient: SVector<f64, 9>,
    hessian: SMatrix<f64, 9, 9>,
}

impl Angle {
    fn at(x: &[Vector3<f64>; 4]) -> Option<Angle> {
        let (e, a, b) = (x[1] - x[0], x[2] - x[0], x[3] - x[0]);
        let (cos, sin) = (cos_term(&e, &a, &b), sin_term(&e, &a, &b));
        let r2 = cos.value * cos.value + sin.value * sin.value;
        if !(r2 > 0.0 && r2.is_finite()) {
            return None;
        }
        // theta = atan2(Y, X): d theta = (X dY - Y dX) / r^2, and its derivative.
        let g = (sin.gradient * cos.value - cos.gradient * sin.value) / r2;
        let h = (sin.hessian * cos.value - cos.hessian * sin.value
            + sin.gradient * cos.gradient.transpose()
            - cos.gradient * sin.gradient.transpose())
            / r2
            - g * (cos.gradient * cos.value + sin.gradient * sin.value).transpose() * (2.0 / r2);
        let h = (h + h.transpose()) * 0.5;
        // (e, a, b) = (x1 - x0, x2 - x0, x3 - x0): the map to the vertices.
        let mut map = SMatrix::<f64, 9, 12>::zeros();
        for block in 0..3 {
            for k in 0..3 {
                map[(3 * block + k, k)] = -1.0;
                map[(3 * block + k, 3 * (block + 1) + k)] = 1.0;
            }
        }
        Some(Angle {
            theta: sin.value.atan2(cos.value),
            gradient: map.transpose() * g,
            hessian: map.transpose() * h * map,
        })
    }
}

/// `X = (e.a)(e.b) - |e|^2 (a.b)`.
fn cos_term(e: &Vector3<f64>, a: &Vector3<f64>, b: &Vector3<f64>) -> Polynomial {
    let (ea, eb, ab, ee) = (e.dot(a), e.dot(b), a.dot(b), e.norm_squared());
    let mut gradient = SVector::<f64, 9>::zeros();
    gradient
        .fixed_rows_mut::<3>(0)
        .copy_from(&(a * eb + b * ea - e * (2.0 * ab)));
    gradient
        .fixed_rows_mut::<3>(3)
        .copy_from(&(e * eb - b * ee));
    gradient
        .fixed_rows_mut::<3>(6)
        .copy_from(&(e * ea - a * ee));
    let id = Matrix3::identity();
    let ee_block = a * b.transpose() + b * a.transpose() - id * (2.0 * ab);
    let ea_block = b * e.transpose() + id * eb - e * b.transpose() * 2.0;
    let eb_block = a * e.transpose() + id * ea - e * a.transpose() * 2.0;
    let ab_block = e * e.transpose() - id * ee;
    let mut hessian = SMatrix::<f64, 9, 9>::zeros();
    set_symmetric(&mut hessian, 0, 0, &ee_block);
    set_symmetric(&mut hessian, 0, 1, &ea_block);
    set_symmetric(&mut hessian, 0, 2, &eb_block);
    set_symmetric(&mut hessian, 1, 2, &ab_block);
    Polynomial {
        value: ea * eb - ee * ab,
        gradient,
        hessian,
    }
}

/// `Y = -|e| T` with the triple product `T = e . (a x b)`.
fn sin_term(e: &Vector3<f64>, a: &Vector3<f64>, b: &Vector3<f64>) -> Polynomial {
    let length = e.norm();
    let unit = e / length;
    let triple = e.dot(&a.cross(b));
    let mut triple_gradient = SVector::<f64, 9>::zeros();
    triple_gradient
        .fixed_rows_mut::<3>(0)
        .copy_from(&a.cross(b));
    triple_gradient
        .fixed_rows_mut::<3>(3)
        .copy_from(&b.cross(e));
    triple_gradient
        .fixed_rows_mut::<3>(6)
        .copy_from(&e.cross(a));
    let mut triple_hessian = SMatrix::<f64, 9, 9>::zeros();
    set_symmetric(&mut triple_hessian, 0, 1, &(-b.cross_matrix()));
    set_symmetric(&mut triple_hessian, 0, 2, &a.cross_matrix());
    set_symmetric(&mut triple_hessian, 1, 2, &(-e.cross_matrix()));
    let mut length_gradient = SVector::<f64, 9>::zeros();
    length_gradient.fixed_rows_mut::<3>(0).copy_from(&unit);
    let mut length_hessian = SMatrix::<f64, 9, 9>::zeros();
    length_hessian
        .fixed_view_mut::<3, 3>(0, 0)
        .copy_from(&((Matrix3::identity() - unit * unit.transpose()) / length));
    Polynomial {
        value: -length * triple,
        gradient: -(length_gradient * triple + triple_gradient * length),
        hessian: -(length_hessian * triple
            + length_gradient * triple_gradient.transpose()
            + triple_gradient * length_gradient.transpose()
            + triple_hessian * length),
    }
}

/// Writes `block` at block position `(i, j)` of a 9x9 matrix of 3x3 blocks, and its transpose
/// at `(j, i)`.
fn set_symmetric(m: &mut SMatrix<f64, 9, 9>, i: usize, j: usize, block: &Matrix3<f64>) {
    m.fixed_view_mut::<3, 3>(3 * i, 3 * j).copy_from(block);
    m.fixed_view_mut::<3, 3>(3 * j, 3 * i)
        .copy_from(&block.transpose());
}
