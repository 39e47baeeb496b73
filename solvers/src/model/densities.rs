//! The elastic energy density each method puts on a material: the whole energy for
//! `standard`, the model's distortional part for the methods whose volume response comes from
//! constraints, that part plus `lambda U(J; beta)` of Sheen et al. 2021 for `zonal`.

use crate::error::SolverError;
use crate::problem::material::{Material, ZonalEnergy};
use crate::problem::material_model::DensityForm;
use crate::problem::method::Method;
use isochor_energies::{
    constrained_neo_hookean, standard_neo_hookean, Composed, DistortionalNeoHookean,
    DistortionalStableNeoHookean, Hyperelastic, LogPenalty, Matrix9, OutOfDomain, SheenPenalty,
    StableNeoHookean,
};
use nalgebra::Matrix3;
use std::sync::Arc;

/// The density of `material` under `method`, composed as the model's [`DensityForm`] says.
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
    Ok(match material.model.density_form_with(mu)? {
        DensityForm::NeoHookean if coupled => Arc::new(standard_neo_hookean(material.lame()?)?),
        DensityForm::NeoHookean if method == Method::Zonal => Arc::new(constrained_neo_hookean(
            mu,
            material.zonal_lambda,
            material.beta,
            material.epsilon,
        )?),
        DensityForm::NeoHookean => Arc::new(DistortionalNeoHookean::new(mu)?),
        DensityForm::StableNeoHookean if coupled => {
            Arc::new(StableNeoHookean::from_linear_lame(material.lame()?)?)
        }
        DensityForm::StableNeoHookean => with_penalty(
            Arc::new(DistortionalStableNeoHookean::new(4.0 / 3.0 * mu)?),
            method,
            material,
            "Stable neo-Hookean",
        )?,
        DensityForm::Isochoric(density) => isochoric(density, coupled, method, material)?,
    })
}

/// An isochoric density `W(Ib1, Ib2)` completed by `kappa/2 (log J)^2` when `coupled`, else
/// as [`with_penalty`].
fn isochoric(
    density: Arc<dyn Hyperelastic>,
    coupled: bool,
    method: Method,
    material: &Material,
) -> Result<Arc<dyn Hyperelastic>, SolverError> {
    if coupled {
        // The bulk modulus of (E, nu); an error naming nu at nu = 0.5.
        let lame = material.lame()?;
        let kappa = lame.lambda + 2.0 / 3.0 * lame.mu;
        let name = density.name();
        return Ok(Arc::new(Composed::new(
            Shared(density),
            kappa,
            LogPenalty,
            name,
        )?));
    }
    let name = density.name();
    with_penalty(density, method, material, name)
}

/// A distortional density with `lambda U(J; beta)` added for `zonal` (eq. 13 of Sheen et al.
/// 2021), alone for the methods with volume constraints.
fn with_penalty(
    density: Arc<dyn Hyperelastic>,
    method: Method,
    material: &Material,
    name: &'static str,
) -> Result<Arc<dyn Hyperelastic>, SolverError> {
    Ok(if method == Method::Zonal {
        Arc::new(Composed::new(
            Shared(density),
            material.zonal_lambda,
            SheenPenalty::new(material.beta)?,
            name,
        )?)
    } else {
        density
    })
}

/// A shared density as the distortional part of a [`Composed`] one.
#[derive(Debug)]
struct Shared(Arc<dyn Hyperelastic>);

impl Hyperelastic for Shared {
    fn name(&self) -> &'static str {
        self.0.name()
    }

    fn energy_density(&self, f: &Matrix3<f64>) -> Result<f64, OutOfDomain> {
        self.0.energy_density(f)
    }

    fn pk1(&self, f: &Matrix3<f64>) -> Result<Matrix3<f64>, OutOfDomain> {
        self.0.pk1(f)
    }

    fn pk1_derivative(&self, f: &Matrix3<f64>) -> Result<Matrix9, OutOfDomain> {
        self.0.pk1_derivative(f)
    }

    fn is_defined_at(&self, j: f64) -> bool {
        self.0.is_defined_at(j)
    }
}
