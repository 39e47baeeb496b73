//! Hyperelastic energy densities, one per file with its equation number.

mod bonet_wood;
mod distortional_neo_hookean;
mod distortional_stable_neo_hookean;
mod fbar_neo_hookean;
mod mooney;
mod mooney_rivlin;
mod ogden;
mod yeoh;

pub use bonet_wood::BonetWood;
pub use distortional_neo_hookean::DistortionalNeoHookean;
pub use distortional_stable_neo_hookean::DistortionalStableNeoHookean;
pub use fbar_neo_hookean::FbarNeoHookean;
pub use mooney::Mooney;
pub use mooney_rivlin::MooneyRivlin;
pub use ogden::Ogden;
pub use yeoh::Yeoh;
