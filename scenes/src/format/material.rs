//! `[material]` and `[[regions]]`: the material parameters of the body and of its parts.

use super::common::is_false;
use super::names::{KappaName, ModelName, ZonalEnergyName};
use serde::{Deserialize, Serialize};

/// Material parameters. Give exactly one of `young` and `mu`, or, for the models with
/// constants (`mooney-rivlin`, `yeoh`, `ogden`), the constants and neither.
#[derive(Debug, Clone, PartialEq, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct MaterialSpec {
    /// The hyperelastic model (default `neo-hookean`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub model: Option<ModelName>,
    /// Mooney-Rivlin and Yeoh: coefficient of `Ib1 - 3` (Pa).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub c10: Option<f64>,
    /// Mooney-Rivlin: coefficient of `Ib2 - 3` (Pa, default 0).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub c01: Option<f64>,
    /// Yeoh: coefficient of `(Ib1 - 3)^2` (Pa, default 0).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub c20: Option<f64>,
    /// Yeoh: coefficient of `(Ib1 - 3)^3` (Pa, default 0).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub c30: Option<f64>,
    /// Ogden: the terms `[[mu_p, alpha_p], ...]` (`mu_p` in Pa).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub ogden: Option<Vec<[f64; 2]>>,
    /// Young's modulus `E` (Pa).
    pub young: Option<f64>,
    /// Shear modulus `mu` (Pa), instead of `young`.
    pub mu: Option<f64>,
    /// Poisson's ratio.
    pub nu: f64,
    /// Density (kg/m^3).
    #[serde(default = "default_density")]
    pub rho: f64,
    /// Local penalty stiffness of the zonal method, the `lambda` of `lambda U(J; beta)` in
    /// Sheen et al. 2021, eq. 13 (Pa; default: equivalent to nu = 0.45). The old key `lambda`
    /// is accepted (`kappa = "lambda"` is Lame's lambda, another thing).
    #[serde(alias = "lambda")]
    pub zonal_penalty: Option<f64>,
    /// Steepness `beta` of `U(J; beta)` (eq. 13 of Sheen et al.).
    pub beta: Option<f64>,
    /// Threshold `epsilon` of the F-bar C2 extension (eq. 11 of Sheen et al.).
    pub epsilon: Option<f64>,
    /// Volumetric stiffness of the mixed methods: `bulk` or `lambda`.
    pub kappa: Option<KappaName>,
    /// The energy under the zonal constraints: `constrained` or `standard`.
    pub zonal_energy: Option<ZonalEnergyName>,
    /// Base Poisson ratio of the augmented dual solver, or `0` for plain dual ascent.
    pub dual_base_nu: Option<f64>,
    /// Whether the epidermis surface energy (eq. 16 of Sheen et al.) is on.
    #[serde(default, skip_serializing_if = "is_false")]
    pub epidermis: bool,
    /// Young's modulus of the epidermis (Pa).
    pub epidermis_young: Option<f64>,
    /// Poisson's ratio of the epidermis.
    pub epidermis_nu: Option<f64>,
    /// Steepness of the epidermis area penalty.
    pub epidermis_gamma: Option<f64>,
}

fn default_density() -> f64 {
    1000.0
}

/// A part of the body with its own material: the tets of a named selection (centroid inside
/// its region, or the elements of a physical volume group).
#[derive(Debug, Clone, PartialEq, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct RegionSpec {
    /// Name, for outputs and errors.
    pub name: String,
    /// The named selection (`[selections.NAME]`) whose tets form the region.
    pub selection: String,
    /// The keys of `[material]` that differ in this region (`young` replaces the body's `mu`
    /// and the other way round); every other key is the body's.
    pub material: toml::Table,
}

/// Keys of `[material]` that an older spelling may still give, as `(old, new)`.
pub const MATERIAL_ALIASES: [(&str, &str); 1] = [("lambda", "zonal_penalty")];

/// Renames the old spellings of a `[material]` table's keys ([`MATERIAL_ALIASES`]) in place,
/// so that tables merged or overridden key by key never hold one parameter twice.
pub fn rename_aliases(table: &mut toml::Table) {
    for (old, new) in MATERIAL_ALIASES {
        if let Some(value) = table.remove(old) {
            table.insert(new.to_string(), value);
        }
    }
}
