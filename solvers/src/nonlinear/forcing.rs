//! Forcing terms of inexact Newton: the relative residual `eta_k` each iterative linear
//! solve is asked for, loose far from the solution and tight near it, so the Krylov solver
//! does not over-solve early Newton steps (Eisenstat and Walker 1996, "Choosing the forcing
//! terms in an inexact Newton method", choice 2 with its safeguard; Kelley 1995, "Iterative
//! Methods for Linear and Nonlinear Equations", eq. 6.20 for the end-game safeguard).

/// `gamma` of choice 2.
const GAMMA: f64 = 0.9;
/// The exponent of choice 2 (Eisenstat and Walker's recommended 2).
const EXPONENT: f64 = 2.0;
/// The largest forcing term, and the first one. Eisenstat and Walker use 0.9 and 0.5; the
/// saddle-point right-hand side mixes forces and volumes in one norm, so a loose solve may
/// leave the smaller block unresolved: 0.1 keeps every solve within a digit of it.
const ETA_MAX: f64 = 0.1;

/// The forcing-term sequence of one Newton solve (one load step).
#[derive(Debug, Clone, Copy)]
pub struct Forcing {
    /// The user's tolerance: the smallest term ever returned.
    floor: f64,
    /// `|F|` and `eta` of the previous iteration.
    previous: Option<(f64, f64)>,
}

impl Forcing {
    /// A new sequence whose terms never go below `floor`.
    pub fn new(floor: f64) -> Self {
        Forcing {
            floor,
            previous: None,
        }
    }

    /// The relative tolerance of the solve at a Newton residual of norm `residual`, for a
    /// nonlinear tolerance `target` on that norm (0 when no single norm has one):
    /// `eta = gamma (|F_k| / |F_k-1|)^2`, raised to `gamma eta_k-1^2` when that exceeds 0.1
    /// (choice 2's safeguard), and to `0.5 target / |F_k|` (no solve tighter than the
    /// nonlinear tolerance needs), then clamped to `[floor, ETA_MAX]`.
    pub fn next(&mut self, residual: f64, target: f64) -> f64 {
        let mut eta = match self.previous {
            None => ETA_MAX,
            Some((previous, eta_previous)) => {
                let eta = GAMMA * (residual / previous).powf(EXPONENT);
                let safeguard = GAMMA * eta_previous.powf(EXPONENT);
                if safeguard > 0.1 {
                    eta.max(safeguard)
                } else {
                    eta
                }
            }
        };
        if residual > 0.0 {
            eta = eta.max(0.5 * target / residual);
        }
        let eta = eta.min(ETA_MAX).max(self.floor);
        self.previous = Some((residual, eta));
        eta
    }
}
