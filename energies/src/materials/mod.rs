//! Hyperelastic energy densities, one per file with its equation number.

mod bonet_wood;
mod distortional_neo_hookean;
mod fbar_neo_hookean;
mod mooney;
mod scaled_invariant;
mod stable_neo_hookean;

pub use bonet_wood::BonetWood;
pub use distortional_neo_hookean::DistortionalNeoHookean;
pub use fbar_neo_hookean::FbarNeoHookean;
pub use mooney::Mooney;
pub use stable_neo_hookean::StableNeoHookean;
