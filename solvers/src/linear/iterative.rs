//! Matrix-free Krylov solvers (sec. 8 of Francu et al. 2021, where conjugate residuals
//! and CG solved eq. 21/24 with Jacobi scaling): preconditioned CG for SPD systems and
//! preconditioned MINRES (Paige and Saunders 1975) for the symmetric indefinite
//! saddle-point operator [`super::SaddlePoint`], each with any SPD [`Preconditioner`].

use super::operator::{norm, LinearOperator};
use super::{relative_residual, LinearError, Preconditioner};
use std::time::{Duration, Instant};

/// Stopping rule of the Krylov solvers.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct IterativeOptions {
    /// Target relative residual `|b - A x| / |b|`.
    pub tolerance: f64,
    /// Most iterations.
    pub max_iterations: usize,
}

impl Default for IterativeOptions {
    fn default() -> Self {
        Self {
            tolerance: 1e-10,
            max_iterations: 10_000,
        }
    }
}

/// Outcome of a converged Krylov solve.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct IterativeReport {
    /// Iterations performed (operator applications after the initial residual).
    pub iterations: usize,
    /// Final relative residual `|b - A x| / |b|`, recomputed from `x`.
    pub residual: f64,
    /// Wall time.
    pub time: Duration,
}

fn check_dims(
    a: &dyn LinearOperator,
    m: &dyn Preconditioner,
    b: &[f64],
    x: &[f64],
) -> Result<(), LinearError> {
    let n = LinearError::square("operator", a.nrows(), a.ncols())?;
    for (what, got) in [
        ("right-hand side", b.len()),
        ("initial guess", x.len()),
        ("preconditioner", m.dim()),
    ] {
        if got != n {
            return Err(LinearError::DimensionMismatch {
                what,
                expected: n,
                got,
            });
        }
    }
    if b.iter().chain(x.iter()).any(|v| !v.is_finite()) {
        return Err(LinearError::NonFiniteInput {
            what: "right-hand side or initial guess",
        });
    }
    Ok(())
}

/// Checks the inputs; for `b = 0` sets `x = 0` and returns the finished report.
fn prologue(
    a: &dyn LinearOperator,
    m: &dyn Preconditioner,
    b: &[f64],
    x: &mut [f64],
    start: Instant,
) -> Result<Option<IterativeReport>, LinearError> {
    check_dims(a, m, b, x)?;
    if norm(b) > 0.0 {
        return Ok(None);
    }
    x.fill(0.0);
    Ok(Some(IterativeReport {
        iterations: 0,
        residual: 0.0,
        time: start.elapsed(),
    }))
}

fn dot(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| x * y).sum()
}

/// Preconditioned conjugate gradients for SPD `A`: solves `A x = b` starting from the
/// `x` given. A non-positive curvature `p^T A p <= 0` is a [`LinearError::Breakdown`]
/// (the operator is not SPD); running out of iterations is [`LinearError::NotConverged`].
pub fn cg(
    a: &dyn LinearOperator,
    m: &dyn Preconditioner,
    b: &[f64],
    x: &mut [f64],
    options: IterativeOptions,
) -> Result<IterativeReport, LinearError> {
    const METHOD: &str = "CG";
    let start = Instant::now();
    if let Some(done) = prologue(a, m, b, x, start)? {
        return Ok(done);
    }
    let n = b.len();
    let b_norm = norm(b);
    let mut r = vec![0.0; n];
    a.apply(x, &mut r);
    r.iter_mut().zip(b).for_each(|(ri, bi)| *ri = bi - *ri);
    let mut z = vec![0.0; n];
    m.apply(&r, &mut z);
    let mut p = z.clone();
    let mut ap = vec![0.0; n];
    let mut rz = dot(&r, &z);
    let mut iterations = 0;
    while norm(&r) / b_norm > options.tolerance {
        if iterations >= options.max_iterations {
            return Err(LinearError::NotConverged {
                method: METHOD,
                iterations,
                residual: relative_residual(a, x, b),
                tolerance: options.tolerance,
            });
        }
        iterations += 1;
        a.apply(&p, &mut ap);
        let pap = dot(&p, &ap);
        if pap <= 0.0 || pap.is_nan() {
            return Err(LinearError::Breakdown {
                method: METHOD,
                iterations,
                reason: "non-positive curvature: the operator is not positive definite",
            });
        }
        let alpha = rz / pap;
        x.iter_mut().zip(&p).for_each(|(xi, pi)| *xi += alpha * pi);
        r.iter_mut()
            .zip(&ap)
            .for_each(|(ri, api)| *ri -= alpha * api);
        m.apply(&r, &mut z);
        let rz_new = dot(&r, &z);
        let beta = rz_new / rz;
        rz = rz_new;
        p.iter_mut()
            .zip(&z)
            .for_each(|(pi, zi)| *pi = zi + beta * *pi);
    }
    Ok(IterativeReport {
        iterations,
        residual: relative_residual(a, x, b),
        time: start.elapsed(),
    })
}

/// Preconditioned MINRES for symmetric (possibly indefinite) `A` with an SPD
/// preconditioner, such as the KKT operator with the block-diagonal
/// [`super::BlockDiagonal`] or the absolute-value Jacobi scaling of
/// [`super::saddle_point_diagonal`]. Solves `A x = b` starting from the `x` given.
///
/// MINRES minimizes the `M^-1`-norm of the residual; its estimate drives the
/// iteration and the true residual `|b - A x| / |b|` is checked before returning.
pub fn minres(
    a: &dyn LinearOperator,
    m: &dyn Preconditioner,
    b: &[f64],
    x: &mut [f64],
    options: IterativeOptions,
) -> Result<IterativeReport, LinearError> {
    const METHOD: &str = "MINRES";
    let start = Instant::now();
    if let Some(done) = prologue(a, m, b, x, start)? {
        return Ok(done);
    }
    let n = b.len();
    let mut r1 = vec![0.0; n];
    a.apply(x, &mut r1);
    r1.iter_mut().zip(b).for_each(|(ri, bi)| *ri = bi - *ri);
    let mut y = vec![0.0; n];
    m.apply(&r1, &mut y);
    let beta1 = dot(&r1, &y).sqrt();
    let mut iterations = 0;
    let done = |x: &[f64]| relative_residual(a, x, b);
    if beta1 == 0.0 {
        return Ok(IterativeReport {
            iterations,
            residual: done(x),
            time: start.elapsed(),
        });
    }
    // Lanczos vectors and the QR factorization of the tridiagonal matrix, as in the
    // reference implementation (Paige and Saunders; SciPy's minres).
    let mut r2 = r1.clone();
    let (mut oldb, mut beta) = (0.0, beta1);
    let (mut dbar, mut epsln, mut phibar) = (0.0, 0.0, beta1);
    let (mut cs, mut sn) = (-1.0f64, 0.0f64);
    let mut w = vec![0.0; n];
    let mut w2 = vec![0.0; n];
    let mut v = vec![0.0; n];
    let mut target = options.tolerance;
    loop {
        if iterations >= options.max_iterations {
            return Err(LinearError::NotConverged {
                method: METHOD,
                iterations,
                residual: done(x),
                tolerance: options.tolerance,
            });
        }
        iterations += 1;
        let s = 1.0 / beta;
        v.iter_mut().zip(&y).for_each(|(vi, yi)| *vi = s * yi);
        a.apply(&v, &mut y);
        if iterations >= 2 {
            let f = beta / oldb;
            y.iter_mut().zip(&r1).for_each(|(yi, ri)| *yi -= f * ri);
        }
        let alfa = dot(&v, &y);
        let f = alfa / beta;
        y.iter_mut().zip(&r2).for_each(|(yi, ri)| *yi -= f * ri);
        std::mem::swap(&mut r1, &mut r2);
        r2.copy_from_slice(&y);
        m.apply(&r2, &mut y);
        oldb = beta;
        let beta2 = dot(&r2, &y);
        if beta2 < 0.0 || beta2.is_nan() {
            return Err(LinearError::Breakdown {
                method: METHOD,
                iterations,
                reason: "the preconditioner is not positive definite",
            });
        }
        beta = beta2.sqrt();
        // Apply the previous rotation, then compute and apply the next one.
        let oldeps = epsln;
        let delta = cs * dbar + sn * alfa;
        let gbar = sn * dbar - cs * alfa;
        epsln = sn * beta;
        dbar = -cs * beta;
        let gamma = gbar.hypot(beta).max(f64::EPSILON);
        cs = gbar / gamma;
        sn = beta / gamma;
        let phi = cs * phibar;
        phibar *= sn;
        // w = (v - oldeps w1 - delta w2) / gamma with w1 the previous w2.
        for i in 0..n {
            let w1 = w2[i];
            w2[i] = w[i];
            w[i] = (v[i] - oldeps * w1 - delta * w2[i]) / gamma;
            x[i] += phi * w[i];
        }
        if phibar / beta1 <= target || beta == 0.0 {
            let residual = done(x);
            if residual <= options.tolerance {
                return Ok(IterativeReport {
                    iterations,
                    residual,
                    time: start.elapsed(),
                });
            }
            if beta == 0.0 {
                return Err(LinearError::NotConverged {
                    method: METHOD,
                    iterations,
                    residual,
                    tolerance: options.tolerance,
                });
            }
            // The preconditioned estimate is met but the true residual is not:
            // tighten the estimate's target and continue.
            target *= (options.tolerance / residual).max(1e-3);
        }
    }
}
