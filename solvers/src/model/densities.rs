//! The elastic energy density each method puts on a material: the whole energy for
//! `standard`, the model's distortional part for the methods whose volume response comes from
//! constraints, that part plus `lambda U(J; beta)` of Sheen et al. 2021 for `zonal`.

use crate::error::SolverError;
use crate::problem::material::{Material, MaterialModel, ZonalEnergy};
use crate::problem::method::Method;
use isochor_energies::{
    constrained_neo_hookean, standard_neo_hookean, BonetWood, Composed, DistortionalNeoHookean,
    DistortionalStableNeoHookean, Hyperelastic, LogPenalty, MooneyRivlin, Ogden, SheenPenalty,
    StableNeoHookean, Yeoh,
};
use std::sync::Arc;

/// The density of `material` under `method`.
///
/// - Neo-Hookean: the standard neo-Hookean (eq. 6 of Francu et al. 2021) for `standard`; the
///   constrained neo-Hookean (eq. 12-13 of Sheen et al. 2021) or the standard one for
///   `zonal`; the distortional neo-Hookean (eq. 32) for the others.
/// - Stable neo-Hookean (Smith et al. 2018, matched to linear elasticity with `(mu, lambda)`):
///   the whole energy for `standard` (and the zonal `standard` energy); its distortional part,
///   with `mu' = 4/3 mu`, for the others, plus `lambda U(J; beta)` for `zonal`.
/// - The isochoric models (Mooney-Rivlin, Yeoh, Ogden, Bonet-Wood): plus `kappa/2 (log J)^2`
///   with the bulk modulus `kappa` for `standard` (the uncoupled form of FEBio), plus
///   `lambda U(J; beta)` for `zonal`, alone for the others.
pub(super) fn elastic_density(
    method: Method,
    material: &Material,
) -> Result<Arc<dyn Hyperelastic>, SolverError> {
    let mu = material.mu;
    let coupled = method == Method::Standard
        || (method == Method::Zonal && material.zonal_energy == ZonalEnergy::Standard);
    Ok(match &material.model {
        MaterialModel::NeoHookean if coupled => Arc::new(standard_neo_hookean(material.lame()?)?),
        MaterialModel::NeoHookean if method == Method::Zonal => Arc::new(constrained_neo_hookean(
            mu,
            material.zonal_lambda,
            material.beta,
            material.epsilon,
        )?),
        MaterialModel::NeoHookean => Arc::new(DistortionalNeoHookean::new(mu)?),
        MaterialModel::StableNeoHookean if coupled => {
            Arc::new(StableNeoHookean::from_linear_lame(material.lame()?)?)
        }
        MaterialModel::StableNeoHookean => with_penalty(
            DistortionalStableNeoHookean::new(4.0 / 3.0 * mu)?,
            method,
            material,
            "Stable neo-Hookean",
        )?,
        MaterialModel::BonetWood => {
            isochoric(BonetWood::new(mu)?, coupled, method, material, "Bonet-Wood")?
        }
        &MaterialModel::MooneyRivlin { c10, c01 } => isochoric(
            MooneyRivlin::new(c10, c01)?,
            coupled,
            method,
            material,
            "Mooney-Rivlin",
        )?,
        &MaterialModel::Yeoh { c10, c20, c30 } => {
            isochoric(Yeoh::new(c10, c20, c30)?, coupled, method, material, "Yeoh")?
        }
        MaterialModel::Ogden { terms } => {
            isochoric(Ogden::new(terms)?, coupled, method, material, "Ogden")?
        }
    })
}

/// An isochoric density `W(Ib1, Ib2)` completed by `kappa/2 (log J)^2` when `coupled`, else
/// as [`with_penalty`].
fn isochoric<D: Hyperelastic + 'static>(
    density: D,
    coupled: bool,
    method: Method,
    material: &Material,
    name: &'static str,
) -> Result<Arc<dyn Hyperelastic>, SolverError> {
    if coupled {
        // The bulk modulus of (E, nu); an error naming nu at nu = 0.5.
        let lame = material.lame()?;
        let kappa = lame.lambda + 2.0 / 3.0 * lame.mu;
        return Ok(Arc::new(Composed::new(density, kappa, LogPenalty, name)?));
    }
    with_penalty(density, method, material, name)
}

/// A distortional density with `lambda U(J; beta)` added for `zonal` (eq. 13 of Sheen et al.
/// 2021), alone for the methods with volume constraints.
fn with_penalty<D: Hyperelastic + 'static>(
    density: D,
    method: Method,
    material: &Material,
    name: &'static str,
) -> Result<Arc<dyn Hyperelastic>, SolverError> {
    Ok(if method == Method::Zonal {
        Arc::new(Composed::new(
            density,
            material.zonal_lambda,
            SheenPenalty::new(material.beta)?,
            name,
        )?)
    } else {
        Arc::new(density)
    })
}
