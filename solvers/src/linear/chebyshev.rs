//! The Chebyshev polynomial smoother of the multigrid cycle (Adams, Brezina, Hu and
//! Tuminaro 2003, "Parallel multigrid smoothing: polynomial versus Gauss-Seidel"): a few
//! steps of Chebyshev iteration on `D^-1 A` aimed at the upper part `[rho / 30, g]` of its
//! spectrum (`rho` the spectral radius estimated by power iteration, `g` Gershgorin's bound),
//! which multigrid leaves to the coarse levels below. The residual polynomial is below one in
//! magnitude on all of `(0, g]`, and `g` bounds the spectrum for certain (an estimate of
//! `rho` alone may fall short of it and amplify the top modes), so for SPD `A` the smoother
//! converges in the energy norm. A polynomial in `D^-1 A` times `D^-1` is symmetric, so the
//! same smoother before and after the coarse correction keeps the cycle symmetric, as CG
//! needs.

use rayon::prelude::*;
use sprs::CsMat;

/// Polynomial degree (matrix-vector products per smoothing).
const DEGREE: usize = 3;

/// The lower end of the smoothed part of the spectrum, `rho / RATIO`.
const RATIO: f64 = 30.0;

/// Power iterations for the spectral radius of `D^-1 A`.
const POWER_ITERATIONS: usize = 15;

/// Rows of a matrix-vector product per parallel task: smaller products stay on one thread,
/// where the synchronization of a parallel loop would cost more than it saves (and far more
/// on a machine whose cores are busy with other work).
const ROWS_PER_TASK: usize = 16_384;

/// `y = A x` for a CSR matrix, in parallel over blocks of rows.
pub fn multiply(a: &CsMat<f64>, x: &[f64], y: &mut [f64]) {
    let indptr = a.indptr();
    let indptr = indptr.raw_storage();
    let (indices, data) = (a.indices(), a.data());
    y.par_iter_mut()
        .enumerate()
        .with_min_len(ROWS_PER_TASK)
        .for_each(|(i, yi)| {
            *yi = (indptr[i]..indptr[i + 1])
                .map(|p| data[p] * x[indices[p]])
                .sum();
        });
}

/// The Chebyshev smoother of one level.
#[derive(Debug, Clone)]
pub struct Chebyshev {
    inverse_diagonal: Vec<f64>,
    /// The estimated spectral radius of `D^-1 A`.
    rho: f64,
    /// Centre and half-width of the smoothed interval.
    theta: f64,
    delta: f64,
}

impl Chebyshev {
    /// The smoother of `a` with the inverse of its (positive) diagonal, and the spectral
    /// radius `rho` of `D^-1 A` estimated by power iteration.
    pub fn new(a: &CsMat<f64>, inverse_diagonal: Vec<f64>) -> Self {
        let rho = spectral_radius(a, &inverse_diagonal);
        let upper = gershgorin(a, &inverse_diagonal).max(rho);
        let lower = rho / RATIO;
        Chebyshev {
            inverse_diagonal,
            rho,
            theta: 0.5 * (upper + lower),
            delta: 0.5 * (upper - lower),
        }
    }

    /// The estimated spectral radius of `D^-1 A`.
    pub fn spectral_radius(&self) -> f64 {
        self.rho
    }

    /// `DEGREE` Chebyshev steps on `A x = b` from the given `x` (Saad, "Iterative Methods
    /// for Sparse Linear Systems", 2nd ed., algorithm 12.1, preconditioned by `D`).
    pub fn smooth(&self, a: &CsMat<f64>, b: &[f64], x: &mut [f64]) {
        let n = b.len();
        let mut r = vec![0.0; n];
        multiply(a, x, &mut r);
        r.iter_mut().zip(b).for_each(|(ri, bi)| *ri = bi - *ri);
        let sigma = self.theta / self.delta;
        let mut rho = 1.0 / sigma;
        let mut d: Vec<f64> = r
            .iter()
            .zip(&self.inverse_diagonal)
            .map(|(ri, di)| ri * di / self.theta)
            .collect();
        let mut ad = vec![0.0; n];
        for step in 0..DEGREE {
            x.iter_mut().zip(&d).for_each(|(xi, di)| *xi += di);
            if step + 1 == DEGREE {
                break;
            }
            multiply(a, &d, &mut ad);
            r.iter_mut().zip(&ad).for_each(|(ri, adi)| *ri -= adi);
            let next = 1.0 / (2.0 * sigma - rho);
            for ((di, ri), inv) in d.iter_mut().zip(&r).zip(&self.inverse_diagonal) {
                *di = next * rho * *di + 2.0 * next / self.delta * ri * inv;
            }
            rho = next;
        }
    }
}

/// Gershgorin's bound on the spectrum of `D^-1 A`: `max_i sum_j |A_ij| / A_ii`.
fn gershgorin(a: &CsMat<f64>, inverse_diagonal: &[f64]) -> f64 {
    a.outer_iterator()
        .zip(inverse_diagonal)
        .map(|(row, inv)| row.iter().map(|(_, v)| v.abs()).sum::<f64>() * inv)
        .fold(0.0, f64::max)
}

/// Spectral radius of `D^-1 A`: power iteration with Rayleigh quotients on the similar,
/// symmetric `S A S` (`S = D^-1/2`) from a deterministic, non-smooth start.
fn spectral_radius(a: &CsMat<f64>, inverse_diagonal: &[f64]) -> f64 {
    let n = inverse_diagonal.len();
    let scale: Vec<f64> = inverse_diagonal.iter().map(|d| d.sqrt()).collect();
    let mut v: Vec<f64> = (0..n)
        .map(|i| 1.0 + ((i * 7919) % 13) as f64 / 13.0)
        .collect();
    let norm = v.iter().map(|x| x * x).sum::<f64>().sqrt();
    v.iter_mut().for_each(|x| *x /= norm);
    let (mut scaled, mut w) = (vec![0.0; n], vec![0.0; n]);
    let mut estimate = 0.0;
    for _ in 0..POWER_ITERATIONS {
        scaled
            .iter_mut()
            .zip(&v)
            .zip(&scale)
            .for_each(|((y, x), s)| *y = x * s);
        multiply(a, &scaled, &mut w);
        w.iter_mut().zip(&scale).for_each(|(y, s)| *y *= s);
        estimate = v.iter().zip(&w).map(|(x, y)| x * y).sum();
        let norm = w.iter().map(|x| x * x).sum::<f64>().sqrt();
        if norm == 0.0 {
            break;
        }
        v.iter_mut().zip(&w).for_each(|(x, y)| *x = y / norm);
    }
    estimate
}
