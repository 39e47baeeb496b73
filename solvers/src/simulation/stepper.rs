//! How the load parameter or time advances: increments between fixed levels (the frames, and
//! in quasi-static stepping the corners of the load curves), halved when a step fails and
//! doubled again after easy steps.

use super::stepping::Stepping;
use crate::error::SolverError;
use crate::problem::schedule::LoadLevel;

/// How quasi-static increments are chosen.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum StepControl {
    /// One solve per frame level; a failed solve ends the run.
    Fixed,
    /// Increments adapt between the frame levels.
    Adaptive(Adaptive),
}

/// Adaptive increments: try `first`, halve after a failed step (from the last converged
/// state), double after a step that took at most `easy_iterations` Newton iterations, never
/// step past a frame level, and stop below `min`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Adaptive {
    /// First increment, as a fraction of the run (1: the full load at once).
    pub first: f64,
    /// Smallest increment tried, as a fraction of the run.
    pub min: f64,
    /// Newton iterations at or below which a step counts as easy.
    pub easy_iterations: usize,
}

impl Default for Adaptive {
    /// The full load first, at most 9 halvings of it (`min = 1e-3`), growth after 8 iterations or
    /// fewer.
    fn default() -> Self {
        Adaptive {
            first: 1.0,
            min: 1e-3,
            easy_iterations: 8,
        }
    }
}

/// The smallest `Adaptive::min` a run accepts, as a fraction of the run: 30 halvings of the
/// whole load. Below it a failing step would be halved hundreds of times (each attempt up to
/// the Newton limit) before its error, for increments that no longer change the load at
/// double precision near the end of the run.
pub const MIN_INCREMENT_FLOOR: f64 = 1e-9;

/// Smallest substep of dynamics, as a fraction of the frame's time step: 10 halvings.
const MIN_SUBSTEP: f64 = 1.0 / 1024.0;

/// Where a run stands: what a checkpoint must hold beside the state to continue it exactly.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Progress {
    /// Load parameter or time reached.
    pub t: f64,
    /// Accepted steps so far.
    pub steps: usize,
    /// Levels reached so far (frames and, in quasi-static stepping, curve corners).
    pub levels: usize,
    /// The next increment to try.
    pub increment: f64,
}

impl Progress {
    /// The start of a run.
    pub fn start(stepping: &Stepping) -> Self {
        let increment = match *stepping {
            Stepping::QuasiStatic {
                control: StepControl::Adaptive(a),
                ..
            } => a.first,
            Stepping::QuasiStatic { steps, .. } => 1.0 / steps as f64,
            Stepping::ImplicitEuler { dt, .. } => dt,
        };
        Progress {
            t: 0.0,
            steps: 0,
            levels: 0,
            increment,
        }
    }
}

/// A level the stepping stops at.
#[derive(Debug, Clone, Copy)]
struct Level {
    level: LoadLevel,
    /// The frame it is (from 1), if any.
    frame: Option<usize>,
    /// The exact increment from the previous level (the time step in dynamics).
    spacing: f64,
}

/// One attempt: the level to reach and the increment it takes.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Attempt {
    /// Where the loads stand at the end of the step.
    pub level: LoadLevel,
    /// The increment of the load parameter or time.
    pub increment: f64,
    /// The frame reached, if the step ends on one.
    pub frame: Option<usize>,
}

/// The increment control of one run.
#[derive(Debug, Clone)]
pub struct Stepper {
    levels: Vec<Level>,
    dynamic: bool,
    duration: f64,
    control: StepControl,
    max_increment: f64,
    min_increment: f64,
}

impl Stepper {
    /// The levels of `stepping` and the corners `corners` of the load curves (their
    /// abscissae; used in quasi-static stepping only).
    pub fn new(stepping: &Stepping, corners: &[f64]) -> Self {
        match *stepping {
            Stepping::QuasiStatic { steps, control } => {
                let frames = (1..=steps).map(|k| (k as f64 / steps as f64, Some(k)));
                let inner = corners
                    .iter()
                    .filter(|&&c| c > 0.0 && c < 1.0)
                    .map(|&c| (c, None));
                let mut points: Vec<(f64, Option<usize>)> = frames.chain(inner).collect();
                points.sort_by(|a, b| a.0.total_cmp(&b.0).then(b.1.cmp(&a.1)));
                points.dedup_by(|b, a| b.0 == a.0);
                let mut previous = 0.0;
                let levels = points
                    .into_iter()
                    .map(|(t, frame)| {
                        let spacing = t - previous;
                        previous = t;
                        Level {
                            level: LoadLevel::quasi_static(t),
                            frame,
                            spacing,
                        }
                    })
                    .collect();
                let min_increment = match control {
                    StepControl::Fixed => f64::INFINITY,
                    StepControl::Adaptive(a) => a.min,
                };
                Stepper {
                    levels,
                    dynamic: false,
                    duration: 1.0,
                    control,
                    max_increment: 1.0,
                    min_increment,
                }
            }
            Stepping::ImplicitEuler { dt, frames } => Stepper {
                levels: (1..=frames)
                    .map(|k| Level {
                        level: LoadLevel {
                            t: k as f64 * dt,
                            ramp: 1.0,
                            fraction: k as f64 / frames as f64,
                        },
                        frame: Some(k),
                        spacing: dt,
                    })
                    .collect(),
                dynamic: true,
                duration: frames as f64 * dt,
                control: StepControl::Adaptive(Adaptive {
                    first: dt,
                    min: dt * MIN_SUBSTEP,
                    easy_iterations: 0,
                }),
                max_increment: dt,
                min_increment: dt * MIN_SUBSTEP,
            },
        }
    }

    /// Checks that `progress` (read from a checkpoint) is a point this stepping can reach:
    /// `levels` at most the levels there are, `t` finite and between the last level reached
    /// and the next one (the end of the run once all are reached), at least one step per level
    /// reached, and a finite positive increment. The message names the field at fault.
    pub fn check_progress(&self, progress: &Progress) -> Result<(), String> {
        let Progress {
            t,
            steps,
            levels,
            increment,
        } = *progress;
        let total = self.levels.len();
        if levels > total {
            return Err(format!(
                "levels = {levels}, but this stepping has {total} levels (frames and load-curve corners)"
            ));
        }
        if steps < levels {
            return Err(format!(
                "steps = {steps} is fewer than the levels reached ({levels})"
            ));
        }
        let reached = levels
            .checked_sub(1)
            .map_or(0.0, |i| self.levels[i].level.t);
        let in_range = if levels == total {
            t == reached
        } else {
            t >= reached && t < self.levels[levels].level.t
        };
        if !(t.is_finite() && in_range) {
            return Err(match self.levels.get(levels) {
                Some(next) => format!(
                    "progress_t = {t} does not lie between the last level reached ({reached}) and the next ({})",
                    next.level.t
                ),
                None => format!("progress_t = {t}, but all levels are reached: it must be the end, {reached}"),
            });
        }
        if !(increment > 0.0 && increment.is_finite() && increment <= self.max_increment) {
            return Err(format!(
                "increment = {increment} must lie in (0, {}]",
                self.max_increment
            ));
        }
        Ok(())
    }

    /// Whether every level has been reached.
    pub fn finished(&self, progress: &Progress) -> bool {
        progress.levels >= self.levels.len()
    }

    /// The next step from `progress`: to the next level if the increment reaches it (up to
    /// rounding), else by the increment.
    pub fn next(&self, progress: &Progress) -> Attempt {
        let next = self.levels[progress.levels];
        let previous = progress
            .levels
            .checked_sub(1)
            .map_or(0.0, |i| self.levels[i].level.t);
        let remaining = next.level.t - progress.t;
        if progress.t == previous && progress.increment >= next.spacing {
            return Attempt {
                level: next.level,
                increment: next.spacing,
                frame: next.frame,
            };
        }
        if progress.increment >= remaining * (1.0 - 1e-9) {
            return Attempt {
                level: next.level,
                increment: remaining,
                frame: next.frame,
            };
        }
        Attempt {
            level: self.level(progress.t + progress.increment),
            increment: progress.increment,
            frame: None,
        }
    }

    /// The level at load parameter or time `t`.
    pub fn level(&self, t: f64) -> LoadLevel {
        if self.dynamic {
            LoadLevel::dynamic(t, self.duration)
        } else {
            LoadLevel::quasi_static(t)
        }
    }

    /// `progress` after `attempt` converged in `iterations` Newton iterations.
    pub fn accept(&self, progress: &Progress, attempt: &Attempt, iterations: usize) -> Progress {
        let reached = attempt.level.t == self.levels[progress.levels].level.t;
        let easy = match self.control {
            StepControl::Adaptive(a) => iterations <= a.easy_iterations,
            StepControl::Fixed => false,
        };
        // A dynamic substep grows back towards the frame's time step after each success.
        let grow = easy || self.dynamic;
        Progress {
            t: attempt.level.t,
            steps: progress.steps + 1,
            levels: progress.levels + usize::from(reached),
            increment: if grow {
                (2.0 * progress.increment).min(self.max_increment)
            } else {
                progress.increment
            },
        }
    }

    /// The load level of the state `progress` stands at.
    pub fn level_at(&self, progress: &Progress) -> LoadLevel {
        if self.dynamic {
            LoadLevel::dynamic(progress.t, self.duration)
        } else {
            LoadLevel::quasi_static(progress.t)
        }
    }

    /// `progress` after `attempt` failed with `error`: half its increment, or the error if
    /// that is below the smallest increment.
    pub fn cut(
        &self,
        progress: &Progress,
        attempt: &Attempt,
        error: SolverError,
    ) -> Result<Progress, SolverError> {
        let increment = 0.5 * attempt.increment;
        if increment < self.min_increment {
            if let StepControl::Fixed = self.control {
                return Err(error);
            }
            return Err(SolverError::IncrementTooSmall {
                t: progress.t,
                increment,
                min: self.min_increment,
                error: Box::new(error),
            });
        }
        Ok(Progress {
            increment,
            ..*progress
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn adaptive(steps: usize) -> Stepping {
        Stepping::QuasiStatic {
            steps,
            control: StepControl::Adaptive(Adaptive::default()),
        }
    }

    #[test]
    fn fixed_and_easy_adaptive_steps_hit_the_frame_levels_exactly() {
        for stepping in [Stepping::quasi_static(10), adaptive(10)] {
            let stepper = Stepper::new(&stepping, &[]);
            let mut progress = Progress::start(&stepping);
            let mut ts = Vec::new();
            while !stepper.finished(&progress) {
                let attempt = stepper.next(&progress);
                assert_eq!(attempt.frame, Some(ts.len() + 1));
                ts.push(attempt.level.t);
                progress = stepper.accept(&progress, &attempt, 3);
            }
            let expected: Vec<f64> = (1..=10).map(|k| k as f64 / 10.0).collect();
            assert_eq!(ts, expected);
        }
    }

    #[test]
    fn cuts_halve_and_easy_steps_grow_back() {
        let stepping = adaptive(1);
        let stepper = Stepper::new(&stepping, &[]);
        let mut progress = Progress::start(&stepping);
        let error = || SolverError::NonFinite("test");
        let first = stepper.next(&progress);
        assert_eq!(first.level.t, 1.0);
        progress = stepper.cut(&progress, &first, error()).unwrap();
        progress = stepper
            .cut(&progress, &stepper.next(&progress), error())
            .unwrap();
        let quarter = stepper.next(&progress);
        assert_eq!((quarter.level.t, quarter.frame), (0.25, None));
        progress = stepper.accept(&progress, &quarter, 2);
        assert_eq!(progress.increment, 0.5);
        let next = stepper.next(&progress);
        assert_eq!(next.level.t, 0.75);
        progress = stepper.accept(&progress, &next, 20);
        assert_eq!(progress.increment, 0.5, "a hard step does not grow");
        let last = stepper.next(&progress);
        assert_eq!(
            (last.level.t, last.frame, last.increment),
            (1.0, Some(1), 0.25)
        );
        progress = stepper.accept(&progress, &last, 2);
        assert!(stepper.finished(&progress));
        assert_eq!(progress.steps, 3);
    }

    #[test]
    fn increments_below_the_minimum_end_with_a_typed_error() {
        let stepping = adaptive(1);
        let stepper = Stepper::new(&stepping, &[]);
        let mut progress = Progress::start(&stepping);
        let cut = loop {
            let attempt = stepper.next(&progress);
            match stepper.cut(&progress, &attempt, SolverError::NonFinite("test")) {
                Ok(p) => progress = p,
                Err(e) => break e,
            }
        };
        assert!(
            matches!(cut, SolverError::IncrementTooSmall { .. }),
            "{cut}"
        );
        assert!(progress.increment >= 1e-3 && progress.increment < 2e-3);
        let fixed = Stepping::quasi_static(4);
        let stepper = Stepper::new(&fixed, &[]);
        let start = Progress::start(&fixed);
        let e = stepper.cut(&start, &stepper.next(&start), SolverError::NonFinite("x"));
        assert!(matches!(e, Err(SolverError::NonFinite(_))));
    }

    #[test]
    fn curve_corners_are_levels_without_frames() {
        let stepping = adaptive(1);
        let stepper = Stepper::new(&stepping, &[0.0, 0.5, 1.0, 2.0]);
        let progress = Progress::start(&stepping);
        let attempt = stepper.next(&progress);
        assert_eq!((attempt.level.t, attempt.frame), (0.5, None));
        let progress = stepper.accept(&progress, &attempt, 1);
        let attempt = stepper.next(&progress);
        assert_eq!((attempt.level.t, attempt.frame), (1.0, Some(1)));
    }

    #[test]
    fn dynamics_take_exact_time_steps_and_substeps_after_a_failure() {
        let stepping = Stepping::ImplicitEuler {
            dt: 0.01,
            frames: 3,
        };
        let stepper = Stepper::new(&stepping, &[]);
        let mut progress = Progress::start(&stepping);
        let a = stepper.next(&progress);
        assert_eq!(
            (a.increment, a.level.t, a.level.fraction),
            (0.01, 0.01, 1.0 / 3.0)
        );
        progress = stepper.accept(&progress, &a, 30);
        let b = stepper.next(&progress);
        progress = stepper
            .cut(&progress, &b, SolverError::NonFinite("x"))
            .unwrap();
        let half = stepper.next(&progress);
        assert_eq!((half.increment, half.frame), (0.005, None));
        progress = stepper.accept(&progress, &half, 30);
        let rest = stepper.next(&progress);
        assert_eq!((rest.level.t, rest.frame), (0.02, Some(2)));
        assert!((rest.increment - 0.005).abs() < 1e-15);
        progress = stepper.accept(&progress, &rest, 30);
        let c = stepper.next(&progress);
        assert_eq!((c.increment, c.frame), (0.01, Some(3)));
    }
}
