//! The contact geometry of IPC (`isochor_mesh::contact`) and its scalar functions
//! (`isochor_solvers::contact`): every squared distance in each closest-feature case (with
//! the kind fixed, as a Newton iteration uses it) against central differences of itself, its
//! classification and value against a brute-force search, near-degenerate configurations
//! (nearly parallel edges, a point almost on an edge or a vertex, exactly parallel edges);
//! the mollifier, the barrier near `dhat` and near 0, the friction potential; the CCD on
//! hand-made cases and on the benchmark of Wang et al. 2021 (no false negative); the broad
//! phase against all pairs; the tet10 contact surface; the intersection check.

use isochor_mesh::contact::*;
use isochor_mesh::element::ElementMesh;
use isochor_mesh::generate::ball;
use isochor_mesh::{check_closed_manifold, BoundarySurface, Vec3};
use isochor_solvers::contact::*;
use nalgebra::{DMatrix, SMatrix, SVector};
use proptest::prelude::*;
use std::path::{Path, PathBuf};

/// Central-difference step on coordinates of unit size.
const STEP: f64 = 1e-6;

/// Agreement required between a derivative and its central differences, relative to the
/// derivative's size (max norm; the truncation error is `STEP^2` times the third
/// derivative, the rounding error `1e-16 / STEP` times the function).
const TOLERANCE: f64 = 1e-5;

fn vec3() -> impl Strategy<Value = Vec3> {
    (-1.0..1.0f64, -1.0..1.0f64, -1.0..1.0f64).prop_map(|(x, y, z)| Vec3::new(x, y, z))
}

fn stack(x: &[Vec3; 4]) -> SVector<f64, 12> {
    SVector::from_iterator(x.iter().flat_map(|p| p.iter().copied()))
}

fn unstack(v: &SVector<f64, 12>) -> [Vec3; 4] {
    std::array::from_fn(|i| Vec3::new(v[3 * i], v[3 * i + 1], v[3 * i + 2]))
}

/// Central differences of a scalar function of four vertices (divided by the step as
/// rounded, `(x + h) - (x - h)`).
fn fd_gradient(f: impl Fn(&[Vec3; 4]) -> f64, x: &[Vec3; 4], h: f64) -> SVector<f64, 12> {
    let x0 = stack(x);
    SVector::from_fn(|k, _| {
        let (mut p, mut m) = (x0, x0);
        p[k] += h;
        m[k] -= h;
        (f(&unstack(&p)) - f(&unstack(&m))) / (p[k] - m[k])
    })
}

/// Central differences of a gradient of four vertices.
fn fd_hessian(
    g: impl Fn(&[Vec3; 4]) -> SVector<f64, 12>,
    x: &[Vec3; 4],
    h: f64,
) -> SMatrix<f64, 12, 12> {
    let x0 = stack(x);
    let mut m = SMatrix::<f64, 12, 12>::zeros();
    for k in 0..12 {
        let (mut p, mut q) = (x0, x0);
        p[k] += h;
        q[k] -= h;
        m.set_column(k, &((g(&unstack(&p)) - g(&unstack(&q))) / (2.0 * h)));
    }
    m
}

/// `max |a - b| <= TOLERANCE max(|a|, floor)`, with a message.
fn close<const R: usize, const C: usize>(
    what: &str,
    a: &SMatrix<f64, R, C>,
    b: &SMatrix<f64, R, C>,
    floor: f64,
) -> Result<(), TestCaseError> {
    let error = (a - b).amax();
    let scale = a.amax().max(floor);
    prop_assert!(
        error <= TOLERANCE * scale,
        "{what}: error {error:e} against scale {scale:e}"
    );
    Ok(())
}

/// The derivatives of the distance of `kind` (fixed) against central differences.
fn check_kind(kind: DistanceKind, x: &[Vec3; 4]) -> Result<(), TestCaseError> {
    check_kind_with_step(kind, x, STEP)
}

/// The same with a gradient step of `step` (nearly parallel lines, whose third derivative
/// grows like `1 / angle^3`, need one proportional to the angle) and a Hessian step of
/// `1e-3 sqrt(step)` (a compromise between that growth and the rounding of a gradient whose
/// closest points are solved with a determinant of `angle^2`).
fn check_kind_with_step(kind: DistanceKind, x: &[Vec3; 4], step: f64) -> Result<(), TestCaseError> {
    let d = kind.derivatives(x);
    prop_assert!((d.value - kind.squared_distance(x)).abs() <= 1e-14 * d.value.max(1e-300));
    // The gradient `2 w r` is as small as the distance, the differences' truncation error
    // (STEP^2 times the O(1) third derivative) is not: near contact the step shrinks with
    // the distance (down to 1e-10, where rounding still costs below 1e-6 of the gradient).
    let h = step.min(1e-2 * d.value.sqrt()).max(1e-10);
    let fd_g = fd_gradient(|y| kind.squared_distance(y), x, h);
    close("gradient", &d.gradient, &fd_g, d.value.sqrt())?;
    let fd_h = fd_hessian(
        |y| kind.derivatives(y).gradient,
        x,
        STEP.min(step.sqrt() * 1e-3),
    );
    close("hessian", &d.hessian, &fd_h, 1.0)?;
    prop_assert!((d.hessian - d.hessian.transpose()).amax() <= 1e-12 * d.hessian.amax());
    Ok(())
}

/// The smallest squared distance between points of the two primitives on a grid of their
/// parameters (`triangle`: point `x0` and triangle `x1, x2, x3`; else edges `x0 x1`, `x2 x3`).
fn brute_force(x: &[Vec3; 4], triangle: bool) -> f64 {
    let n = 300;
    let mut best = f64::INFINITY;
    for i in 0..=n {
        for j in 0..=n {
            let (s, t) = (i as f64 / n as f64, j as f64 / n as f64);
            let d = if triangle {
                if s + t > 1.0 {
                    continue;
                }
                x[0] - (x[1] + (x[2] - x[1]) * s + (x[3] - x[1]) * t)
            } else {
                (x[0] + (x[1] - x[0]) * s) - (x[2] + (x[3] - x[2]) * t)
            };
            best = best.min(d.norm_squared());
        }
    }
    best
}

/// The classified distance is the minimum: never above the grid's, and the grid's is above
/// it by at most what its spacing allows.
fn check_minimum(d: f64, x: &[Vec3; 4], triangle: bool) -> Result<(), TestCaseError> {
    let grid = brute_force(x, triangle);
    let size: f64 = x.iter().map(|p| p.norm()).fold(0.0, f64::max) + 1.0;
    prop_assert!(
        d <= grid + 1e-12,
        "classified {d:e} above the grid's {grid:e}"
    );
    let spacing = 3.0 * size / 300.0;
    prop_assert!(
        grid.sqrt() <= d.sqrt() + spacing,
        "grid {grid:e} far above the classified {d:e}"
    );
    Ok(())
}

/// A triangle far from degenerate, with its unit normal.
fn triangle() -> impl Strategy<Value = ([Vec3; 3], Vec3)> {
    (vec3(), vec3(), vec3())
        .prop_filter("well shaped", |(a, b, c)| {
            let n = (b - a).cross(&(c - a));
            n.norm() > 0.2 * (b - a).norm_squared().max((c - a).norm_squared())
                && (b - a).norm() > 0.2
        })
        .prop_map(|(a, b, c)| {
            let n = (b - a).cross(&(c - a)).normalize();
            ([a, b, c], n)
        })
}

/// A height above a plane: far, near, or very near contact.
fn height() -> impl Strategy<Value = f64> {
    prop_oneof![0.05..1.0f64, 1e-4..1e-2f64, -1.0..-0.05f64, 1e-9..1e-7f64]
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(96))]

    #[test]
    fn point_plane(([a, b, c], n) in triangle(), l1 in 0.05..0.9f64, l2 in 0.05..0.9f64, h in height()) {
        prop_assume!(l1 + l2 < 0.95);
        let p = a + (b - a) * l1 + (c - a) * l2 + n * h;
        let x = [p, a, b, c];
        prop_assert_eq!(point_triangle_distance_kind(&p, &a, &b, &c), DistanceKind::PointPlane);
        let d = point_triangle_squared_distance(&p, &a, &b, &c);
        prop_assert!((d - h * h).abs() <= 1e-12 * (1.0 + h * h), "{} against {}", d, h * h);
        check_kind(DistanceKind::PointPlane, &x)?;
    }

    #[test]
    fn point_edge_of_a_triangle(([a, b, c], n) in triangle(), s in 0.05..0.95f64, out in 0.05..1.0f64, h in height()) {
        // Across edge (a, b) from c, its foot inside the edge: the edge's Voronoi region.
        let e = (b - a).normalize();
        let inward = (c - a) - e * e.dot(&(c - a));
        let p = a + (b - a) * s - inward.normalize() * out + n * h;
        let x = [p, a, b, c];
        let kind = point_triangle_distance_kind(&p, &a, &b, &c);
        prop_assert_eq!(kind, DistanceKind::PointEdge(0, 1, 2));
        check_minimum(point_triangle_squared_distance(&p, &a, &b, &c), &x, true)?;
        check_kind(kind, &x)?;
    }

    #[test]
    fn point_vertex_of_a_triangle(([a, b, c], _n) in triangle(), v in vec3()) {
        prop_assume!(v.dot(&(b - a)) < -0.01 && v.dot(&(c - a)) < -0.01);
        let p = a + v;
        let x = [p, a, b, c];
        let kind = point_triangle_distance_kind(&p, &a, &b, &c);
        prop_assert_eq!(kind, DistanceKind::PointPoint(0, 1));
        prop_assert!((point_triangle_squared_distance(&p, &a, &b, &c) - v.norm_squared()).abs() <= 1e-14);
        check_kind(kind, &x)?;
    }

    #[test]
    fn point_triangle_any(p in vec3(), a in vec3(), b in vec3(), c in vec3()) {
        let x = [p, a, b, c];
        let kind = point_triangle_distance_kind(&p, &a, &b, &c);
        check_minimum(point_triangle_squared_distance(&p, &a, &b, &c), &x, true)?;
        check_kind(kind, &x)?;
    }

    #[test]
    fn point_almost_on_an_edge(a in vec3(), b in vec3(), s in 0.01..0.99f64, off in vec3(), tiny in 1e-12..1e-6f64) {
        prop_assume!((b - a).norm() > 0.1);
        let p = a + (b - a) * s + off.cross(&(b - a)).normalize() * tiny;
        prop_assume!(p.iter().all(|v| v.is_finite()));
        prop_assert_eq!(point_edge_distance_kind(&p, &a, &b), DistanceKind::PointEdge(0, 1, 2));
        let d = point_edge_squared_distance_derivatives(&p, &a, &b);
        prop_assert!((d.value.sqrt() - tiny).abs() <= 1e-9 * tiny + 1e-15);
        check_kind(DistanceKind::PointEdge(0, 1, 2), &[p, a, b, Vec3::zeros()])?;
        // Collinear, beyond an end: the end point.
        let beyond = b + (b - a) * (0.5 + s);
        prop_assert_eq!(point_edge_distance_kind(&beyond, &a, &b), DistanceKind::PointPoint(0, 2));
        // On a vertex: distance 0, the end point.
        prop_assert_eq!(point_edge_squared_distance(&a, &a, &b), 0.0);
        let pp = point_point_squared_distance_derivatives(&p, &a);
        prop_assert_eq!(pp.value, point_point_squared_distance(&p, &a));
        check_kind(DistanceKind::PointPoint(0, 1), &[p, a, Vec3::zeros(), Vec3::zeros()])?;
    }

    #[test]
    fn line_line(a0 in vec3(), u in vec3(), v in vec3(), s in 0.05..0.95f64, t in 0.05..0.95f64, h in height()) {
        prop_assume!(u.norm() > 0.2 && v.norm() > 0.2 && u.cross(&v).norm() > 0.05 * u.norm() * v.norm());
        let n = u.cross(&v).normalize();
        let b0 = a0 + u * s + n * h - v * t;
        let x = [a0, a0 + u, b0, b0 + v];
        prop_assert_eq!(edge_edge_distance_kind(&x[0], &x[1], &x[2], &x[3]), DistanceKind::LineLine);
        let d = edge_edge_squared_distance(&x[0], &x[1], &x[2], &x[3]);
        prop_assert!((d - h * h).abs() <= 1e-10 * (1.0 + h * h), "{} against {}", d, h * h);
        check_kind(DistanceKind::LineLine, &x)?;
    }

    #[test]
    fn nearly_parallel_edges(a0 in vec3(), u in vec3(), w in vec3(), angle in 1e-3..3e-2f64, s in 0.2..0.8f64, t in 0.2..0.8f64, h in 0.01..1.0f64) {
        prop_assume!(u.norm() > 0.3 && w.cross(&u).norm() > 0.1 * w.norm() * u.norm());
        let side = u.cross(&w).normalize();
        let v = (u.normalize() + side.cross(&u.normalize()) * angle) * u.norm();
        let n = u.cross(&v).normalize();
        let b0 = a0 + u * s + n * h - v * t;
        let x = [a0, a0 + u, b0, b0 + v];
        let kind = edge_edge_distance_kind(&x[0], &x[1], &x[2], &x[3]);
        prop_assert_eq!(kind, DistanceKind::LineLine);
        check_kind_with_step(kind, &x, STEP * angle)?;
        // The mollifier is active (below eps_x) and its derivatives hold.
        let eps = edge_edge_mollifier_threshold(&x[0], &x[1], &x[2], &x[3]);
        let c = edge_edge_cross_squared_derivatives(&x);
        prop_assert!(c.value < eps);
        check_mollifier(&x, eps)?;
    }

    #[test]
    fn edge_edge_any(a0 in vec3(), a1 in vec3(), b0 in vec3(), b1 in vec3()) {
        let x = [a0, a1, b0, b1];
        let kind = edge_edge_distance_kind(&a0, &a1, &b0, &b1);
        check_minimum(edge_edge_squared_distance(&a0, &a1, &b0, &b1), &x, false)?;
        check_kind(kind, &x)?;
        let eps = edge_edge_mollifier_threshold(&a0, &a1, &b0, &b1);
        check_mollifier(&x, eps * 1e3 * 0.5)?;
    }

    #[test]
    fn parallel_and_collinear_edges(a0 in vec3(), u in vec3(), off in vec3(), shift in -1.5..1.5f64, scale in 0.2..2.0f64) {
        prop_assume!(u.norm() > 0.2);
        // Exactly parallel (scaled copies of u, offset and shifted): never the lines.
        for offset in [off, Vec3::zeros()] {
            let b0 = a0 + offset + u * shift;
            let x = [a0, a0 + u, b0, b0 + u * scale];
            let kind = edge_edge_distance_kind(&x[0], &x[1], &x[2], &x[3]);
            prop_assert!(kind != DistanceKind::LineLine);
            check_minimum(edge_edge_squared_distance(&x[0], &x[1], &x[2], &x[3]), &x, false)?;
            prop_assert!(edge_edge_mollifier(&x, 1.0) < 1e-12);
        }
    }
}

/// The mollifier and the squared cross product against central differences.
fn check_mollifier(x: &[Vec3; 4], eps: f64) -> Result<(), TestCaseError> {
    let c = edge_edge_cross_squared_derivatives(x);
    let fd = fd_gradient(|y| edge_edge_cross_squared_derivatives(y).value, x, STEP);
    close("cross gradient", &c.gradient, &fd, 1.0)?;
    let fd = fd_hessian(|y| edge_edge_cross_squared_derivatives(y).gradient, x, STEP);
    close("cross hessian", &c.hessian, &fd, 1.0)?;
    let m = edge_edge_mollifier_derivatives(x, eps);
    prop_assert_eq!(m.value, edge_edge_mollifier(x, eps));
    // The mollifier is C1 at c = eps_x: stay off the kink by 100 steps.
    prop_assume!((c.value - eps).abs() > 100.0 * STEP * c.gradient.amax());
    let fd = fd_gradient(|y| edge_edge_mollifier(y, eps), x, STEP);
    close("mollifier gradient", &m.gradient, &fd, 1.0 / eps)?;
    let fd = fd_hessian(
        |y| edge_edge_mollifier_derivatives(y, eps).gradient,
        x,
        STEP,
    );
    close("mollifier hessian", &m.hessian, &fd, 1.0 / eps)?;
    Ok(())
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(256))]

    #[test]
    fn barrier_near_dhat_and_near_zero(dhat in 1e-4..1.0f64, r in prop_oneof![0.9..0.999f64, 1e-8..1e-4f64, 0.01..0.9f64]) {
        let dhat_sq = dhat * dhat;
        let d = r * dhat_sq;
        let h = 1e-5 * d;
        let fd1 = (barrier(d + h, dhat_sq) - barrier(d - h, dhat_sq)) / (2.0 * h);
        let b1 = barrier_first_derivative(d, dhat_sq);
        prop_assert!((fd1 - b1).abs() <= 1e-6 * b1.abs().max(dhat_sq), "b' {} against {}", b1, fd1);
        let fd2 = (barrier_first_derivative(d + h, dhat_sq) - barrier_first_derivative(d - h, dhat_sq)) / (2.0 * h);
        let b2 = barrier_second_derivative(d, dhat_sq);
        prop_assert!((fd2 - b2).abs() <= 1e-6 * b2.abs().max(1.0), "b'' {} against {}", b2, fd2);
        prop_assert!(barrier(d, dhat_sq) > 0.0 && b1 < 0.0 && b2 > 0.0);
        prop_assert_eq!(barrier(dhat_sq, dhat_sq), 0.0);
        prop_assert_eq!(barrier_first_derivative(dhat_sq * 1.5, dhat_sq), 0.0);
        prop_assert!(barrier(0.0, dhat_sq).is_infinite());
        let lambda = normal_force(2.0, d, dhat_sq);
        let fd = -(barrier((d.sqrt() + h).powi(2), dhat_sq) - barrier((d.sqrt() - h).powi(2), dhat_sq)) / (2.0 * h) * 2.0;
        prop_assert!((lambda - fd).abs() <= 1e-4 * lambda.abs().max(dhat), "{} against {}", lambda, fd);
    }

    #[test]
    fn friction_f1_is_the_derivative_of_f0(epsv in 1e-6..1e-1f64, r in prop_oneof![0.0..0.999f64, 1.001..10.0f64]) {
        let y = r * epsv;
        let h = 1e-6 * epsv;
        let fd = (friction_f0(y + h, epsv) - friction_f0((y - h).max(0.0), epsv)) / (y + h - (y - h).max(0.0));
        prop_assert!((fd - friction_f1(y, epsv)).abs() <= 1e-5);
        prop_assert!((0.0..=1.0).contains(&friction_f1(y, epsv)));
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(96))]

    #[test]
    fn friction_potential(p in vec3(), a in vec3(), b in vec3(), c in vec3(), u in vec3(), w in vec3(), epsv in 1e-3..1.0f64, slip in prop_oneof![1e-3..0.9f64, 1.1..10.0f64], mu_lambda in 0.1..10.0f64) {
        let x = [p, a, b, c];
        let kind = point_triangle_distance_kind(&p, &a, &b, &c);
        prop_assume!(kind.squared_distance(&x) > 1e-4);
        let pair = FrictionPair::new(kind, &x, mu_lambda, epsv);
        // The basis is orthonormal and orthogonal to the normal direction.
        let t = pair.basis;
        prop_assert!((t.transpose() * t - nalgebra::Matrix2::identity()).amax() <= 1e-12);
        let normal: Vec3 = (0..4).map(|i| x[i] * pair.weights[i]).sum();
        prop_assert!((t.transpose() * normal).amax() <= 1e-9 * normal.norm().max(1e-9));
        // Motions with a tangential slip of `slip epsv`.
        let base = [u * 0.3, w * 0.2, u * 0.1 - w * 0.2, w * 0.05];
        let y = pair.tangential_motion(&base).norm();
        prop_assume!(y > 1e-6);
        let motion = base.map(|m| m * (slip * epsv / y));
        let d = pair.derivatives(&motion);
        prop_assert!((d.value - pair.potential(&motion)).abs() <= 1e-12 * d.value.abs().max(1.0));
        let h = STEP * epsv;
        let fd = fd_gradient(|m| pair.potential(m), &motion, h);
        close("friction gradient", &d.gradient, &fd, mu_lambda)?;
        let fd = fd_hessian(|m| pair.derivatives(m).gradient, &motion, h);
        close("friction hessian", &d.hessian, &fd, mu_lambda / epsv)?;
        let smallest = d.hessian.symmetric_eigenvalues().min();
        prop_assert!(smallest >= -1e-9 * d.hessian.amax(), "not PSD: {}", smallest);
    }
}

fn settings(min_separation: f64) -> CcdSettings {
    CcdSettings {
        min_separation,
        ..CcdSettings::default()
    }
}

#[test]
fn ccd_point_through_a_triangle() {
    let (a, b, c) = (
        Vec3::new(-1.0, -1.0, 0.0),
        Vec3::new(2.0, -1.0, 0.0),
        Vec3::new(-1.0, 2.0, 0.0),
    );
    let (p0, p1) = (Vec3::new(0.1, 0.2, 1.0), Vec3::new(0.1, 0.2, -1.0));
    // Contact at t = 0.5; with a separation of 0.1 at t = 0.45, reported from 0.11 (the
    // 10% slack) at t = 0.445.
    for (ms, exact, earliest) in [(0.0, 0.5, 0.5), (0.1, 0.45, 0.445)] {
        let toi = point_triangle_ccd(&p0, &a, &b, &c, &p1, &a, &b, &c, &settings(ms)).unwrap();
        assert!(toi <= exact && toi > earliest - 1e-5, "ms {ms}: toi {toi}");
    }
    // The same, the triangle moving instead.
    let up = Vec3::new(0.0, 0.0, 2.0);
    let toi = point_triangle_ccd(
        &p0,
        &a,
        &b,
        &c,
        &p0,
        &(a + up),
        &(b + up),
        &(c + up),
        &settings(0.0),
    );
    assert!(toi.is_some_and(|t| t <= 0.5 && t > 0.5 - 1e-5));
    // Passing beside the triangle: safe.
    let (q0, q1) = (Vec3::new(3.0, 3.0, 1.0), Vec3::new(3.0, 3.0, -1.0));
    assert_eq!(
        point_triangle_ccd(&q0, &a, &b, &c, &q1, &a, &b, &c, &settings(0.0)),
        None
    );
}

#[test]
fn ccd_parallel_edges_sliding() {
    let (a0, a1) = (Vec3::new(0.0, 0.0, 0.0), Vec3::new(1.0, 0.0, 0.0));
    let slide = Vec3::new(2.0, 0.0, 0.0);
    for (gap, touching) in [(1e-3, false), (0.0, true)] {
        let (b0, b1) = (Vec3::new(-0.5, 0.0, gap), Vec3::new(0.5, 0.0, gap));
        let toi = edge_edge_ccd(
            &a0,
            &a1,
            &b0,
            &b1,
            &a0,
            &a1,
            &(b0 + slide),
            &(b1 + slide),
            &settings(0.0),
        );
        assert_eq!(toi.is_some(), touching, "gap {gap}: {toi:?}");
        // Kept apart by more than the gap: contact from the start.
        let toi = edge_edge_ccd(
            &a0,
            &a1,
            &b0,
            &b1,
            &a0,
            &a1,
            &(b0 + slide),
            &(b1 + slide),
            &settings(2e-3),
        );
        assert_eq!(toi, Some(0.0));
    }
}

#[test]
fn ccd_zero_motion_and_start_at_the_separation() {
    let (a, b, c) = (
        Vec3::zeros(),
        Vec3::new(1.0, 0.0, 0.0),
        Vec3::new(0.0, 1.0, 0.0),
    );
    let p = Vec3::new(0.2, 0.2, 0.1);
    // No motion, apart: safe; closer than the separation: contact at once.
    assert_eq!(
        point_triangle_ccd(&p, &a, &b, &c, &p, &a, &b, &c, &settings(0.05)),
        None
    );
    assert_eq!(
        point_triangle_ccd(&p, &a, &b, &c, &p, &a, &b, &c, &settings(0.2)),
        Some(0.0)
    );
    // Starting exactly at the separation and moving closer: no safe step at all.
    let p1 = Vec3::new(0.2, 0.2, -0.5);
    let toi = point_triangle_ccd(&p, &a, &b, &c, &p1, &a, &b, &c, &settings(0.1)).unwrap();
    assert!(toi < 1e-5, "{toi}");
    // Moving away from the separation: safe.
    let away = Vec3::new(0.2, 0.2, 0.5);
    assert_eq!(
        point_triangle_ccd(&p, &a, &b, &c, &away, &a, &b, &c, &settings(0.099)),
        None
    );
    // Non-finite input: no safe step.
    let nan = Vec3::new(f64::NAN, 0.0, 0.0);
    assert_eq!(
        point_triangle_ccd(&nan, &a, &b, &c, &p, &a, &b, &c, &settings(0.0)),
        Some(0.0)
    );
}

/// The benchmark's folders, each a set with a `vertex-face` and/or an `edge-edge` folder.
fn benchmark_root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../mesh/tests/data/ccd-queries")
}

#[test]
fn ccd_benchmark_has_no_false_negative() {
    let mut total = CcdTally::default();
    let mut sets: Vec<PathBuf> = std::fs::read_dir(benchmark_root())
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.is_dir())
        .collect();
    sets.sort();
    for set in sets {
        for kind in ["vertex-face", "edge-edge"] {
            let folder = set.join(kind);
            let Ok(entries) = std::fs::read_dir(&folder) else {
                continue;
            };
            let mut files: Vec<PathBuf> = entries.map(|e| e.unwrap().path()).collect();
            files.sort();
            let mut tally = CcdTally::default();
            for file in files {
                let queries = read_ccd_queries(&file, QueryKind::from_path(&file)).unwrap();
                assert!(
                    queries.iter().all(|q| q.rounding == 0.0),
                    "{file:?}: inexact"
                );
                tally = tally.plus(CcdTally::of(&queries, &CcdSettings::default()));
            }
            println!(
                "{}/{kind}: {tally}",
                set.file_name().unwrap().to_string_lossy()
            );
            total = total.plus(tally);
        }
    }
    println!(
        "all: {total} (false-positive rate {:.2}% of the non-touching queries)",
        100.0 * total.false_positives as f64 / (total.queries - total.touching) as f64
    );
    assert_eq!(total.queries, 3409);
    assert_eq!(total.touching, 296);
    assert_eq!(total.false_negatives, 0);
}

#[test]
fn rationals_round_and_report_their_error() {
    assert_eq!(rational_to_f64(3, 4), Some((0.75, 0.0)));
    assert_eq!(
        rational_to_f64(-4194305, 8388608),
        Some((-4194305.0 / 8388608.0, 0.0))
    );
    let (third, error) = rational_to_f64(1, 3).unwrap();
    assert!(error > 0.0 && (third - 1.0 / 3.0).abs() <= error);
    // 2^60 + 1 is not a double: rounded, with an error bound.
    let (v, e) = rational_to_f64((1 << 60) + 1, 1).unwrap();
    assert!(e >= 1.0 && v == (1u64 << 60) as f64);
    assert_eq!(rational_to_f64(1, 0), None);
    let bad = parse_ccd_queries("1,2,3\n", Path::new("q.csv"), QueryKind::VertexFace);
    assert_eq!(
        bad.unwrap_err().to_string(),
        "q.csv:1: 3 columns, expected 7"
    );
}

/// Two balls of radius 1 whose centres are `gap + 2` apart, as one contact surface with a
/// body per node.
fn two_balls(res: usize, gap: f64) -> (ContactSurface, Vec<Vec3>, Vec<usize>) {
    let one = ball(1.0, res).unwrap();
    let n = one.num_vertices();
    let mut x = one.positions().to_vec();
    x.extend(
        one.positions()
            .iter()
            .map(|p| p + Vec3::new(2.0 + gap, 0.0, 0.0)),
    );
    let surface = BoundarySurface::new(&one).unwrap();
    let mut triangles = surface.triangles().to_vec();
    triangles.extend(surface.triangles().iter().map(|t| t.map(|v| v + n)));
    let bodies = (0..2 * n).map(|v| v / n).collect();
    (ContactSurface::from_triangles(triangles), x, bodies)
}

#[test]
fn broad_phase_finds_every_close_pair() {
    let (surface, x, bodies) = two_balls(2, 0.05);
    let dhat = 0.3;
    for filter in [PairFilter::All, PairFilter::BetweenBodies(&bodies)] {
        let candidates = contact_candidates(&surface, &x, None, dhat, filter);
        let keep = |a: usize, b: usize| match filter {
            PairFilter::All => true,
            PairFilter::BetweenBodies(bodies) => bodies[a] != bodies[b],
        };
        let mut expected = Vec::new();
        for &v in surface.vertices() {
            for (t, tri) in surface.triangles().iter().enumerate() {
                let [a, b, c] = tri.map(|n| x[n]);
                if !tri.contains(&v)
                    && keep(v, tri[0])
                    && point_triangle_squared_distance(&x[v], &a, &b, &c) < dhat * dhat
                {
                    expected.push([v, t]);
                }
            }
        }
        assert!(!expected.is_empty());
        for pair in &expected {
            assert!(
                candidates.point_triangle.binary_search(pair).is_ok(),
                "{pair:?} missed"
            );
        }
        let edges = surface.edges();
        let mut close_edges = 0;
        for i in 0..edges.len() {
            for j in i + 1..edges.len() {
                let (a, b) = (edges[i], edges[j]);
                if a.iter().any(|n| b.contains(n)) || !keep(a[0], b[0]) {
                    continue;
                }
                let d = edge_edge_squared_distance(&x[a[0]], &x[a[1]], &x[b[0]], &x[b[1]]);
                if d < dhat * dhat {
                    close_edges += 1;
                    assert!(candidates.edge_edge.binary_search(&[i, j]).is_ok());
                }
            }
        }
        assert!(close_edges > 0);
        // No pair shares a node; between bodies, every pair joins the two balls.
        for &[v, t] in &candidates.point_triangle {
            assert!(!surface.triangles()[t].contains(&v));
            assert!(keep(v, surface.triangles()[t][0]));
        }
    }
}

#[test]
fn tet10_contact_surface_splits_each_face_in_four() {
    let mesh = ElementMesh::quadratic(ball(1.0, 2).unwrap());
    let faces = mesh.boundary().unwrap();
    let surface = ContactSurface::from_element_surface(&faces);
    assert_eq!(surface.triangles().len(), 4 * faces.len());
    check_closed_manifold(surface.triangles()).unwrap();
    assert_eq!(surface.vertices(), faces.nodes().as_slice());
    // Closed: V - E + F = 2, and the split keeps the enclosed volume.
    let (v, e, f) = (
        surface.vertices().len(),
        surface.edges().len(),
        surface.triangles().len(),
    );
    assert_eq!(v + f, e + 2);
    let linear = ContactSurface::from_boundary(&BoundarySurface::new(mesh.corners()).unwrap());
    assert_eq!(linear.triangles().len(), faces.len());
}

/// The triangle as references.
fn refs(s: &[Vec3; 3]) -> [&Vec3; 3] {
    [&s[0], &s[1], &s[2]]
}

#[test]
fn intersection_check() {
    let (surface, x, _) = two_balls(2, 0.05);
    assert!(intersecting_triangles(&surface, &x).is_empty());
    let (surface, x, _) = two_balls(2, -0.2);
    assert!(!intersecting_triangles(&surface, &x).is_empty());
    // Crossing, touching at a vertex, coplanar overlapping, coplanar apart.
    let t = [
        Vec3::zeros(),
        Vec3::new(1.0, 0.0, 0.0),
        Vec3::new(0.0, 1.0, 0.0),
    ];
    let tri = |a: Vec3, b: Vec3, c: Vec3| [a, b, c];
    let crossing = tri(
        Vec3::new(0.2, 0.2, -1.0),
        Vec3::new(0.2, 0.2, 1.0),
        Vec3::new(2.0, 2.0, 0.0),
    );
    let apart = tri(
        Vec3::new(0.2, 0.2, 0.1),
        Vec3::new(1.2, 0.2, 0.1),
        Vec3::new(0.2, 1.2, 0.1),
    );
    let coplanar = tri(
        Vec3::new(0.2, 0.2, 0.0),
        Vec3::new(2.0, 0.2, 0.0),
        Vec3::new(0.2, 2.0, 0.0),
    );
    let coplanar_apart = tri(
        Vec3::new(2.0, 2.0, 0.0),
        Vec3::new(3.0, 2.0, 0.0),
        Vec3::new(2.0, 3.0, 0.0),
    );
    assert!(triangles_intersect(refs(&t), refs(&crossing)));
    assert!(!triangles_intersect(refs(&t), refs(&apart)));
    assert!(triangles_intersect(refs(&t), refs(&coplanar)));
    assert!(!triangles_intersect(refs(&t), refs(&coplanar_apart)));
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(16))]

    #[test]
    fn barrier_potential_gradient_and_psd_hessian(gap in 0.02..0.08f64, kappa in 0.1..10.0f64, shift in vec3()) {
        let (surface, rest, bodies) = two_balls(2, gap);
        let x: Vec<Vec3> = rest.iter().enumerate().map(|(i, p)| {
            let s = shift * 0.01;
            if bodies[i] == 1 { p + s } else { *p }
        }).collect();
        let potential = BarrierPotential { dhat: 0.1, kappa };
        let candidates = contact_candidates(&surface, &x, None, 0.3, PairFilter::BetweenBodies(&bodies));
        let energy = |y: &[Vec3]| potential.energy(&surface, &candidates, &rest, y);
        prop_assert!(energy(&x) > 0.0);
        let mut g = vec![0.0; 3 * x.len()];
        potential.add_gradient(&surface, &candidates, &rest, &x, &mut g);
        // Central differences along a few node coordinates with a non-zero gradient.
        let h = 1e-7;
        let mut checked = 0;
        for k in (0..g.len()).filter(|&k| g[k].abs() > 1e-3 * g.iter().fold(0.0f64, |m, v| m.max(v.abs()))).take(12) {
            let (mut p, mut m) = (x.clone(), x.clone());
            p[k / 3][k % 3] += h;
            m[k / 3][k % 3] -= h;
            let fd = (energy(&p) - energy(&m)) / (2.0 * h);
            prop_assert!((fd - g[k]).abs() <= 1e-5 * g[k].abs(), "{} against {}", g[k], fd);
            checked += 1;
        }
        prop_assert!(checked > 0);
        let triplets = potential.hessian_triplets(&surface, &candidates, &rest, &x);
        let mut dense = DMatrix::<f64>::zeros(g.len(), g.len());
        for (i, j, v) in triplets {
            dense[(i, j)] += v;
        }
        let eigen = dense.symmetric_eigenvalues();
        // Each pair's block is PSD up to 1e-12 of its own scale (at most kappa / dhat^2 here).
        prop_assert!(eigen.min() >= -1e-9 * (eigen.amax() + kappa), "eigenvalues {:e} to {:e}", eigen.min(), eigen.max());
        prop_assert!(BarrierPotential::min_distance(&surface, &candidates, &rest, &x) > 0.0);
    }
}

#[test]
fn barrier_stiffness_bounds_start_and_growth() {
    let bounds = StiffnessBounds::new(1.0, 1e-3, 1.0);
    assert!(bounds.min > 0.0 && bounds.max == 100.0 * bounds.min);
    // The balancing stiffness, clamped.
    let (ge, gb) = ([1.0, -2.0], [-1.0, 2.0]);
    let inside = StiffnessBounds {
        min: 0.1,
        max: 10.0,
    };
    assert_eq!(initial_barrier_stiffness(&ge, &gb, &inside), 1.0);
    assert_eq!(initial_barrier_stiffness(&ge, &[0.0, 0.0], &inside), 0.1);
    assert_eq!(initial_barrier_stiffness(&[-5.0, 10.0], &gb, &inside), 0.1);
    // Doubling only while the smallest distance keeps shrinking below 1e-9 of the scene.
    assert_eq!(
        update_barrier_stiffness(1.0, 5e-10, 4e-10, 1.0, &inside),
        2.0
    );
    assert_eq!(
        update_barrier_stiffness(1.0, 5e-10, 6e-10, 1.0, &inside),
        1.0
    );
    assert_eq!(update_barrier_stiffness(1.0, 5e-9, 4e-9, 1.0, &inside), 1.0);
    assert_eq!(
        update_barrier_stiffness(8.0, 5e-10, 4e-10, 1.0, &inside),
        10.0
    );
}
