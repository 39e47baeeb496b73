//! Triangles of the analytic obstacles for pictures: each shape at motion parameter `s`,
//! tessellated coarsely, the unbounded ones (half-space, cylinder) cut to a patch around the
//! bodies.

use isochor_mesh::{generate::split_quads, Vec3};
use isochor_solvers::{Obstacle, Shape};
use std::f64::consts::TAU;

/// Segments around a round shape.
const AROUND: usize = 32;

/// The triangles of `obstacle` at parameter `s`, around the bodies' box `(lo, hi)`.
pub fn obstacle_triangles(obstacle: &Obstacle, s: f64, (lo, hi): (Vec3, Vec3)) -> Vec<[Vec3; 3]> {
    let shift = s * obstacle.translate;
    let grown = |r: f64| r + s * obstacle.radius_change;
    let middle = 0.5 * (lo + hi);
    let reach = (hi - lo).norm().max(f64::MIN_POSITIVE);
    match obstacle.shape {
        Shape::HalfSpace { point, normal } => {
            let n = normal.normalize();
            let p = point + shift;
            let centre = middle - n * n.dot(&(middle - p));
            let (u, v) = basis(n);
            let corner = |a: f64, b: f64| centre + reach * (a * u + b * v);
            let c = [
                corner(-1.0, -1.0),
                corner(1.0, -1.0),
                corner(1.0, 1.0),
                corner(-1.0, 1.0),
            ];
            vec![[c[0], c[1], c[2]], [c[0], c[2], c[3]]]
        }
        Shape::Sphere { center, radius } => {
            let r = grown(radius);
            torus_like(center + shift, Vec3::z(), 0.0, r, true)
        }
        Shape::Cylinder {
            point,
            axis,
            radius,
        } => {
            let a = axis.normalize();
            let p = point + shift;
            let centre = p + a * a.dot(&(middle - p));
            let (u, v) = basis(a);
            let r = grown(radius);
            let rim = |k: usize, h: f64| {
                let phi = TAU * k as f64 / AROUND as f64;
                centre + r * (phi.cos() * u + phi.sin() * v) + h * reach * a
            };
            (0..AROUND)
                .flat_map(|k| {
                    let (a0, a1, b0, b1) =
                        (rim(k, -1.0), rim(k + 1, -1.0), rim(k, 1.0), rim(k + 1, 1.0));
                    [[a0, a1, b1], [a0, b1, b0]]
                })
                .collect()
        }
        Shape::Ring {
            center,
            axis,
            radius,
            tube,
        } => torus_like(center + shift, axis.normalize(), grown(radius), tube, false),
    }
}

/// Two unit vectors completing the unit `n` to a right-handed basis.
fn basis(n: Vec3) -> (Vec3, Vec3) {
    let helper = if n.x.abs() < 0.9 {
        Vec3::x()
    } else {
        Vec3::y()
    };
    let u = n.cross(&helper).normalize();
    (u, n.cross(&u))
}

/// The torus of tube radius `tube` about the circle of radius `big` around `axis` through
/// `centre`; with `big = 0` and `sphere`, the sphere of radius `tube` (the tube's angle
/// then runs over a half turn).
fn torus_like(centre: Vec3, axis: Vec3, big: f64, tube: f64, sphere: bool) -> Vec<[Vec3; 3]> {
    let (u, v) = basis(axis);
    let (tube_turn, rings) = if sphere {
        (0.5 * TAU, AROUND / 2)
    } else {
        (TAU, AROUND / 2)
    };
    let point = |i: usize, j: usize| {
        let phi = TAU * i as f64 / AROUND as f64;
        let theta = tube_turn * j as f64 / rings as f64 - if sphere { 0.25 * TAU } else { 0.0 };
        let radial = phi.cos() * u + phi.sin() * v;
        centre + (big + tube * theta.cos()) * radial + tube * theta.sin() * axis
    };
    split_quads(AROUND, rings, point)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn shapes_lie_on_their_surfaces() {
        let around = (Vec3::zeros(), Vec3::repeat(1.0));
        let shapes = [
            Shape::HalfSpace {
                point: Vec3::zeros(),
                normal: Vec3::z(),
            },
            Shape::Sphere {
                center: Vec3::repeat(2.0),
                radius: 0.5,
            },
            Shape::Cylinder {
                point: Vec3::zeros(),
                axis: Vec3::y(),
                radius: 0.3,
            },
            Shape::Ring {
                center: Vec3::zeros(),
                axis: Vec3::z(),
                radius: 1.0,
                tube: 0.2,
            },
        ];
        for shape in shapes {
            let obstacle = Obstacle {
                translate: Vec3::new(0.0, 0.0, 0.1),
                ..Obstacle::fixed(shape)
            };
            let triangles = obstacle_triangles(&obstacle, 1.0, around);
            assert!(!triangles.is_empty());
            for p in triangles.iter().flatten() {
                let d = obstacle.distance(p, 1.0).0;
                assert!(d.abs() < 1e-12, "{shape:?}: {d}");
            }
        }
    }
}
