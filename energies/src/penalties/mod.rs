//! Volumetric penalties `U(J)`, each scaled by `lambda` where it is used
//! (see [`Composed`](crate::Composed)).

mod log;
mod quadratic;
mod sheen;
mod snh2;
mod stvk;

pub use log::LogPenalty;
pub use quadratic::QuadraticPenalty;
pub use sheen::SheenPenalty;
pub use snh2::Snh2Penalty;
pub use stvk::StvkPenalty;
