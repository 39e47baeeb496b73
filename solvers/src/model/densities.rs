//! The elastic energy density each method puts on a material: the whole energy for
//! `standard`, the distortional part for the methods whose volume response comes from
//! constraints, the constrained energy of Sheen et al. 2021 for `zonal`.

use super::{Material, Method, ZonalEnergy};
use crate::SolverError;
use isochor_energies::{
    constrained_neo_hookean, standard_neo_hookean, DistortionalNeoHookean, Hyperelastic,
};
use std::sync::Arc;

/// The density of `material` under `method`: for `standard` the standard neo-Hookean
/// (eq. 6 of Francu et al. 2021); for `zonal` the constrained neo-Hookean (eq. 12-13 of
/// Sheen et al. 2021) or the standard one; for the mixed, condensed and dual methods the
/// distortional neo-Hookean (eq. 32), whose volume change the constraints govern.
pub(super) fn elastic_density(
    method: Method,
    material: &Material,
) -> Result<Arc<dyn Hyperelastic>, SolverError> {
    let mu = material.mu;
    Ok(match method {
        Method::Standard => Arc::new(standard_neo_hookean(material.lame()?)?),
        Method::Zonal => match material.zonal_energy {
            ZonalEnergy::Constrained => Arc::new(constrained_neo_hookean(
                mu,
                material.zonal_lambda,
                material.beta,
                material.epsilon,
            )?),
            ZonalEnergy::Standard => Arc::new(standard_neo_hookean(material.lame()?)?),
        },
        _ => Arc::new(DistortionalNeoHookean::new(mu)?),
    })
}
