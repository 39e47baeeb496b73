//! The materials of a scene in the solver's types: the body's `[material]` and each region's.

use super::bodies::SceneBodies;
use super::selections::Selections;
use crate::error::SceneError;
use crate::format::{rename_aliases, KappaName, MaterialSpec, ModelName, Scene, ZonalEnergyName};
use isochor_energies::ParameterError;
use isochor_solvers::{Epidermis, Kappa, Material, MaterialModel, Region, ZonalEnergy};

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
                    &r.material,
                    format!("regions.{i}.material"),
                )?,
            })
        })
        .collect::<Result<Vec<_>, SceneError>>()?;
    let mut claimed = vec![false; bodies.parts.last().map_or(0, |p| p.elements.end)];
    regions
        .iter()
        .flat_map(|r| &r.elements)
        .for_each(|&e| claimed[e] = true);
    let own = usize::from(scene.mesh.is_some());
    for (i, (body, part)) in scene.bodies().iter().zip(&bodies.parts).enumerate() {
        let Some(table) = body.material.filter(|t| !t.is_empty()) else {
            continue;
        };
        let origin = format!("bodies.{}.material", i - own);
        let material = region_material(&scene.material, table, origin)?;
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
    let model = material_model(spec).map_err(invalid)?;
    model.validate().map_err(|e| match model {
        // The terms are one key; the error names the term's parameter.
        MaterialModel::Ogden { .. } => SceneError::Invalid {
            origin: "scene".into(),
            key: "material.ogden".into(),
            message: e.to_string(),
        },
        _ => e.into(),
    })?;
    let young = match (spec.young, spec.mu, model.shear_modulus()) {
        (None, None, Some(mu)) => 2.0 * mu * (1.0 + spec.nu),
        (Some(_), _, Some(_)) | (_, Some(_), Some(_)) => {
            return Err(invalid(format!(
                "model {} takes its stiffness from its constants: drop young and mu",
                model.name()
            )))
        }
        (Some(e), _, None) => e,
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

/// The model of a `[material]` table, its constants checked against the model.
fn material_model(spec: &MaterialSpec) -> Result<MaterialModel, String> {
    let name = spec.model.unwrap_or(ModelName::NeoHookean);
    let given: Vec<&str> = [
        ("c10", spec.c10.is_some()),
        ("c01", spec.c01.is_some()),
        ("c20", spec.c20.is_some()),
        ("c30", spec.c30.is_some()),
        ("ogden", spec.ogden.is_some()),
    ]
    .into_iter()
    .filter_map(|(key, set)| set.then_some(key))
    .collect();
    let allowed: &[&str] = match name {
        ModelName::MooneyRivlin => &["c10", "c01"],
        ModelName::Yeoh => &["c10", "c20", "c30"],
        ModelName::Ogden => &["ogden"],
        _ => &[],
    };
    if let Some(key) = given.iter().find(|k| !allowed.contains(k)) {
        return Err(format!(
            "{key} is not a constant of model {} (its constants: {})",
            name.name(),
            if allowed.is_empty() {
                "none; give young or mu".to_string()
            } else {
                allowed.join(", ")
            }
        ));
    }
    let required = |key: &str, value: Option<f64>| {
        value.ok_or_else(|| format!("model {} needs {key}", name.name()))
    };
    Ok(match name {
        ModelName::NeoHookean => MaterialModel::NeoHookean,
        ModelName::StableNeoHookean => MaterialModel::StableNeoHookean,
        ModelName::BonetWood => MaterialModel::BonetWood,
        ModelName::MooneyRivlin => MaterialModel::MooneyRivlin {
            c10: required("c10", spec.c10)?,
            c01: spec.c01.unwrap_or(0.0),
        },
        ModelName::Yeoh => MaterialModel::Yeoh {
            c10: required("c10", spec.c10)?,
            c20: spec.c20.unwrap_or(0.0),
            c30: spec.c30.unwrap_or(0.0),
        },
        ModelName::Ogden => MaterialModel::Ogden {
            terms: spec
                .ogden
                .as_ref()
                .ok_or_else(|| "model ogden needs ogden = [[mu_p, alpha_p], ...]".to_string())?
                .iter()
                .map(|&[mu, alpha]| (mu, alpha))
                .collect(),
        },
    })
}

/// The material of a region or body (its keys at `origin`): the scene's `[material]` keys
/// overlaid with its own.
fn region_material(
    body: &MaterialSpec,
    overrides: &toml::Table,
    origin: String,
) -> Result<Material, SceneError> {
    let invalid = |key: String, message: String| SceneError::Invalid {
        origin: "scene".into(),
        key,
        message,
    };
    let mut merged =
        toml::Table::try_from(body).map_err(|e| invalid(origin.clone(), e.to_string()))?;
    // A region that gives any stiffness key replaces all of the body's.
    const STIFFNESS: [&str; 7] = ["young", "mu", "c10", "c01", "c20", "c30", "ogden"];
    if STIFFNESS.iter().any(|k| overrides.contains_key(*k)) {
        for key in STIFFNESS {
            merged.remove(key);
        }
    }
    let mut overrides = overrides.clone();
    rename_aliases(&mut overrides);
    merged.extend(overrides);
    let spec: MaterialSpec = serde_path_to_error::deserialize(toml::Value::Table(merged))
        .map_err(|e| invalid(format!("{origin}.{}", e.path()), e.inner().to_string()))?;
    build_material(&spec).map_err(|e| invalid(origin, e.to_string()))
}
