//! The scalar functions of IPC contact (Li et al. 2020) that the solvers' contact energy
//! builds on, over the geometry of `isochor_mesh::contact`: the log barrier on squared
//! distances with its derivatives, the adaptive barrier stiffness, the smoothed lagged
//! friction with the tangent basis of a pair, and the barrier potential of a candidate set
//! (energy, gradient, PSD-projected Hessian triplets). Beside the analytic-obstacle term of
//! `terms::contact`, which it does not change.

mod barrier;
mod friction;
mod potential;
mod stiffness;

pub use barrier::{barrier, barrier_first_derivative, barrier_second_derivative, normal_force};
pub use friction::{friction_f0, friction_f1, plane_basis, tangent_basis, FrictionPair};
pub use potential::{BarrierPotential, HessianBlocks, PairForce, WriteBlock};
pub use stiffness::{initial_barrier_stiffness, update_barrier_stiffness, StiffnessBounds};
