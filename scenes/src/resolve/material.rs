//! The materials of a scene in the solver's types: the body's `[material]` and each region's.

use super::bodies::SceneBodies;
use super::selections::Selections;
use crate::error::SceneError;
use crate::format::{rename_aliases, KappaName, MaterialSpec, ModelName, Scene, ZonalEnergyName};
use isochor_energies::ParameterError;
use isochor_solvers::{
    ConstantKind, Epidermis, Kappa, Material, MaterialModel, Method, Region, ZonalEnergy,
};

/// The regions of the scene, each the tets of its selection with its material; then each
/// body whose material differs from `[material]`, less the tets a region claims.
pub fn regions(
    scene: &Scene,
    selections: &Selections,
    bodies: &SceneBodies,
) -> Result<Vec<Region>, SceneError> {
    let mut regions = scene
        .regions
        .iter()
        .enumerate()
        .map(|(i, r)| {
            Ok(Region {
                name: r.name.clone(),
                elements: selections.tets(&r.selection)?.to_vec(),
                material: region_material(
                    &scene.material,
                    &r.name,
                    &r.material,
                    format!("regions.{i}.material"),
                    scene.method(),
                )?,
            })
        })
        .collect::<Result<Vec<_>, SceneError>>()?;
    let mut claimed = vec![false; bodies.parts.last().map_or(0, |p| p.elements.end)];
    regions
        .iter()
        .flat_map(|r| &r.elements)
        .for_each(|&e| claimed[e] = true);
    for (body, part) in scene.bodies().iter().zip(&bodies.parts) {
        let Some(table) = body.material.filter(|t| !t.is_empty()) else {
            continue;
        };
        let origin = body.key("material");
        let material = region_material(&scene.material, body.name, table, origin, scene.method())?;
        let elements: Vec<usize> = part.elements.clone().filter(|&e| !claimed[e]).collect();
        if !elements.is_empty() {
            regions.push(Region {
                name: body.name.to_string(),
                elements,
                material,
            });
        }
    }
    Ok(regions)
}

/// Material parameters from a scene's `[material]` table.
pub fn build_material(spec: &MaterialSpec) -> Result<Material, SceneError> {
    let invalid = |message: String| SceneError::Invalid {
        origin: "scene".into(),
        key: "material".into(),
        message,
    };
    let info = spec.model.unwrap_or_else(ModelName::neo_hookean).0;
    let model = info
        .make(spec.constants.iter().map(|(k, v)| (k.as_str(), v.into())))
        .map_err(|e| invalid(e.to_string()))?;
    model.validate().map_err(|e| {
        // A list of terms is one key; the error names the term's parameter (`mu_p`).
        match info.constants.iter().find(|c| {
            matches!(c.kind, ConstantKind::Pairs { first, second } if [first, second].contains(&e.name))
        }) {
            Some(terms) => SceneError::Invalid {
                origin: "scene".into(),
                key: format!("material.{}", terms.key),
                message: e.to_string(),
            },
            None => e.into(),
        }
    })?;
    let young = match (spec.young, spec.mu, model.shear_modulus()) {
        (None, None, Some(mu)) => 2.0 * mu * (1.0 + spec.nu),
        (Some(_), _, Some(_)) | (_, Some(_), Some(_)) => {
            return Err(invalid(format!(
                "model {} takes its stiffness from its constants: drop young and mu",
                model.name()
            )))
        }
        (Some(_), Some(_), None) => {
            return Err(invalid("give either young or mu, not both".into()))
        }
        (Some(e), None, None) => e,
        (None, Some(mu), None) => {
            // Checked as given, not as the Young's modulus it implies, so the error names mu.
            if !(mu.is_finite() && mu > 0.0) {
                return Err(ParameterError {
                    name: "mu",
                    value: mu,
                    reason: "shear modulus must be finite and positive",
                }
                .into());
            }
            2.0 * mu * (1.0 + spec.nu)
        }
        (None, None, None) => return Err(invalid("give young (E) or mu".into())),
    };
    let mut m = Material::from_young_poisson(young, spec.nu, spec.rho)?.with_model(model)?;
    if let Some(mu) = spec.mu {
        m.mu = mu;
    }
    if let Some(penalty) = spec.zonal_penalty {
        // Checked here so that the error names the scene's key (the solver's is `lambda`).
        if !(penalty.is_finite() && penalty >= 0.0) {
            return Err(ParameterError {
                name: "zonal_penalty",
                value: penalty,
                reason: "must be finite and non-negative",
            }
            .into());
        }
        m.zonal_lambda = penalty;
    }
    if let Some(beta) = spec.beta {
        m.beta = beta;
    }
    if let Some(epsilon) = spec.epsilon {
        m.epsilon = epsilon;
    }
    if let Some(kappa) = spec.kappa {
        m.kappa = match kappa {
            KappaName::Bulk => Kappa::Bulk,
            KappaName::Lambda => Kappa::Lambda,
        };
    }
    if let Some(energy) = spec.zonal_energy {
        m.zonal_energy = match energy {
            ZonalEnergyName::Constrained => ZonalEnergy::Constrained,
            ZonalEnergyName::Standard => ZonalEnergy::Standard,
        };
    }
    if let Some(nu) = spec.dual_base_nu {
        m.dual_base_nu = (nu != 0.0).then_some(nu);
    }
    if spec.epidermis {
        m.epidermis = Some(Epidermis {
            young: spec.epidermis_young.unwrap_or(young),
            poisson: spec.epidermis_nu.unwrap_or(0.45),
            gamma: spec.epidermis_gamma.unwrap_or(1.0),
        });
    }
    m.validate()?;
    Ok(m)
}

/// Keys of a region's material that only the `zonal` method reads.
const ZONAL_KEYS: [&str; 5] = ["zonal_penalty", "lambda", "beta", "epsilon", "zonal_energy"];

/// Keys of `[material]` that hold for the whole body, read from the body's material only.
const BODY_KEYS: [&str; 5] = [
    "dual_base_nu",
    "epidermis",
    "epidermis_young",
    "epidermis_nu",
    "epidermis_gamma",
];

/// The material of region or body `name` (its keys at `origin`): the scene's `[material]`
/// keys overlaid with its own. One that gives any stiffness key (`young`, `mu`, a model's
/// constants) replaces all of the scene's; a key it cannot use under `method` is an error
/// naming it.
fn region_material(
    body: &MaterialSpec,
    name: &str,
    overrides: &toml::Table,
    origin: String,
    method: Method,
) -> Result<Material, SceneError> {
    let invalid = |key: String, message: String| SceneError::Invalid {
        origin: "scene".into(),
        key,
        message,
    };
    if overrides.contains_key("young") && overrides.contains_key("mu") {
        return Err(invalid(
            origin,
            format!("region '{name}': give either young or mu, not both"),
        ));
    }
    for key in overrides.keys() {
        let message = if ZONAL_KEYS.contains(&key.as_str()) && method != Method::Zonal {
            format!(
                "region '{name}': {key} does nothing under method {}: it is a parameter of the zonal method",
                method.name()
            )
        } else if BODY_KEYS.contains(&key.as_str()) {
            format!("region '{name}': {key} is a setting of the whole body: give it in [material]")
        } else {
            continue;
        };
        return Err(invalid(format!("{origin}.{key}"), message));
    }
    let mut merged =
        toml::Table::try_from(body).map_err(|e| invalid(origin.clone(), e.to_string()))?;
    let mut stiffness = vec!["young", "mu"];
    stiffness.extend(MaterialModel::constant_keys());
    if stiffness.iter().any(|k| overrides.contains_key(*k)) {
        for key in stiffness {
            merged.remove(key);
        }
    }
    let mut overrides = overrides.clone();
    rename_aliases(&mut overrides);
    merged.extend(overrides);
    let spec: MaterialSpec = serde_path_to_error::deserialize(toml::Value::Table(merged))
        .map_err(|e| invalid(format!("{origin}.{}", e.path()), e.inner().to_string()))?;
    let material = build_material(&spec).map_err(|e| invalid(origin.clone(), e.to_string()))?;
    // The coupled energies need Lame's lambda, which nu = 0.5 does not have.
    let coupled = method == Method::Standard
        || (method == Method::Zonal && material.zonal_energy == ZonalEnergy::Standard);
    if coupled {
        material.lame().map_err(|e| {
            invalid(
                format!("{origin}.{}", e.name),
                format!("region '{name}': {e} (under method {})", method.name()),
            )
        })?;
    }
    Ok(material)
}
