//! `[material]` and `[[regions]]`: the material parameters of the body and of its parts.

use super::common::is_false;
use super::names::{KappaName, ModelName, ZonalEnergyName};
use isochor_solvers::{ConstantKind, ConstantValue, MaterialModel};
use serde::de::{self, DeserializeSeed, Deserializer, MapAccess, Visitor};
use serde::ser::{SerializeMap, Serializer};
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;
use std::fmt;

/// Material parameters. Give exactly one of `young` and `mu`, or, for the models with
/// constants (`mooney-rivlin`, `yeoh`, `ogden`), the constants and neither.
///
/// A model's constants are keys of this table too (`c10 = 1e4`): they are the solver's
/// catalogue's ([`MaterialModel::ALL`]), read from it rather than listed here, and a key that
/// is neither one of the fields below nor a constant of some model is an unknown field.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct MaterialSpec {
    /// The hyperelastic model (default `neo-hookean`).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub model: Option<ModelName>,
    /// The model's constants by key (`c10`, `c01`, `c20`, `c30`, `ogden`, ...), as given;
    /// checked against the model when the material is built.
    #[serde(flatten, serialize_with = "in_catalogue_order")]
    pub constants: BTreeMap<String, ConstantSpec>,
    /// Young's modulus `E` (Pa).
    pub young: Option<f64>,
    /// Shear modulus `mu` (Pa), instead of `young`.
    pub mu: Option<f64>,
    /// Poisson's ratio.
    pub nu: f64,
    /// Density (kg/m^3, default 1000).
    pub rho: f64,
    /// Local penalty stiffness of the zonal method, the `lambda` of `lambda U(J; beta)` in
    /// Sheen et al. 2021, eq. 13 (Pa; default: equivalent to nu = 0.45). The old key `lambda`
    /// is accepted (`kappa = "lambda"` is Lame's lambda, another thing).
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
    #[serde(skip_serializing_if = "is_false")]
    pub epidermis: bool,
    /// Young's modulus of the epidermis (Pa).
    pub epidermis_young: Option<f64>,
    /// Poisson's ratio of the epidermis.
    pub epidermis_nu: Option<f64>,
    /// Steepness of the epidermis area penalty.
    pub epidermis_gamma: Option<f64>,
}

/// The constants in the order of [`material_keys`] (`c10` before `c01`), as scenes write
/// them.
fn in_catalogue_order<S: Serializer>(
    constants: &BTreeMap<String, ConstantSpec>,
    s: S,
) -> Result<S::Ok, S::Error> {
    let keys = material_keys();
    let mut map = s.serialize_map(Some(constants.len()))?;
    for key in &keys {
        if let Some(value) = constants.get(*key) {
            map.serialize_entry(key, value)?;
        }
    }
    // Keys of no model (set by a library caller) are kept, to be refused when read.
    for (key, value) in constants
        .iter()
        .filter(|(k, _)| !keys.contains(&k.as_str()))
    {
        map.serialize_entry(key, value)?;
    }
    map.end()
}

/// The value of one model constant as a scene gives it: a number or `[[a, b], ...]`.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[serde(untagged)]
pub enum ConstantSpec {
    /// A number.
    Number(f64),
    /// A list of pairs.
    Pairs(Vec<[f64; 2]>),
}

impl From<&ConstantSpec> for ConstantValue {
    fn from(spec: &ConstantSpec) -> ConstantValue {
        match spec {
            ConstantSpec::Number(x) => ConstantValue::Number(*x),
            ConstantSpec::Pairs(pairs) => {
                ConstantValue::Pairs(pairs.iter().map(|&[a, b]| (a, b)).collect())
            }
        }
    }
}

/// The keys of `[material]` other than the models' constants.
const FIELDS: [&str; 16] = [
    "model",
    "young",
    "mu",
    "nu",
    "rho",
    "lambda",
    "zonal_penalty",
    "beta",
    "epsilon",
    "kappa",
    "zonal_energy",
    "dual_base_nu",
    "epidermis",
    "epidermis_young",
    "epidermis_nu",
    "epidermis_gamma",
];

/// Every key `[material]` takes: its fields (with the old spellings) and every model's
/// constants.
pub fn material_keys() -> Vec<&'static str> {
    let mut keys = FIELDS.to_vec();
    keys.splice(1..1, MaterialModel::constant_keys());
    keys
}

impl<'de> Deserialize<'de> for MaterialSpec {
    /// By hand, as serde's `flatten` cannot be combined with `deny_unknown_fields`: each field
    /// and constant is read by its own type through the map (so an error names its key), and
    /// a key that is neither is refused as serde refuses an unknown field.
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        d.deserialize_map(MaterialVisitor)
    }
}

struct MaterialVisitor;

impl<'de> Visitor<'de> for MaterialVisitor {
    type Value = MaterialSpec;

    fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
        f.write_str("struct MaterialSpec")
    }

    fn visit_map<A: MapAccess<'de>>(self, mut map: A) -> Result<MaterialSpec, A::Error> {
        let mut spec = MaterialSpec {
            model: None,
            constants: BTreeMap::new(),
            young: None,
            mu: None,
            nu: f64::NAN,
            rho: default_density(),
            zonal_penalty: None,
            beta: None,
            epsilon: None,
            kappa: None,
            zonal_energy: None,
            dual_base_nu: None,
            epidermis: false,
            epidermis_young: None,
            epidermis_nu: None,
            epidermis_gamma: None,
        };
        let mut seen: Vec<String> = Vec::new();
        while let Some(key) = map.next_key_seed(KnownKey)? {
            // The old spelling of a key is its new one.
            let key = MATERIAL_ALIASES
                .iter()
                .find(|(old, _)| *old == key)
                .map_or(key, |(_, new)| new.to_string());
            if seen.contains(&key) {
                return Err(de::Error::custom(format_args!("duplicate field `{key}`")));
            }
            let number = |map: &mut A| map.next_value::<Number>().map(|n| n.0);
            match key.as_str() {
                "model" => spec.model = Some(map.next_value()?),
                "young" => spec.young = Some(number(&mut map)?),
                "mu" => spec.mu = Some(number(&mut map)?),
                "nu" => spec.nu = number(&mut map)?,
                "rho" => spec.rho = number(&mut map)?,
                "zonal_penalty" => spec.zonal_penalty = Some(number(&mut map)?),
                "beta" => spec.beta = Some(number(&mut map)?),
                "epsilon" => spec.epsilon = Some(number(&mut map)?),
                "kappa" => spec.kappa = Some(map.next_value()?),
                "zonal_energy" => spec.zonal_energy = Some(map.next_value()?),
                "dual_base_nu" => spec.dual_base_nu = Some(number(&mut map)?),
                "epidermis" => spec.epidermis = map.next_value()?,
                "epidermis_young" => spec.epidermis_young = Some(number(&mut map)?),
                "epidermis_nu" => spec.epidermis_nu = Some(number(&mut map)?),
                "epidermis_gamma" => spec.epidermis_gamma = Some(number(&mut map)?),
                constant => {
                    let value = match MaterialModel::constant(constant).map(|c| c.kind) {
                        Some(ConstantKind::Pairs { .. }) => ConstantSpec::Pairs(map.next_value()?),
                        _ => ConstantSpec::Number(number(&mut map)?),
                    };
                    spec.constants.insert(constant.to_string(), value);
                }
            }
            seen.push(key);
        }
        if !seen.iter().any(|k| k == "nu") {
            return Err(de::Error::missing_field("nu"));
        }
        Ok(spec)
    }
}

/// A key of `[material]`, refused as serde refuses an unknown field (read as a key, so the
/// error's path ends in the key).
struct KnownKey;

impl<'de> DeserializeSeed<'de> for KnownKey {
    type Value = String;

    fn deserialize<D: Deserializer<'de>>(self, d: D) -> Result<String, D::Error> {
        let key = String::deserialize(d)?;
        let keys = material_keys();
        if keys.contains(&key.as_str()) {
            return Ok(key);
        }
        let expected: Vec<String> = keys.iter().map(|k| format!("`{k}`")).collect();
        Err(de::Error::custom(format_args!(
            "unknown field `{key}`, expected one of {}",
            expected.join(", ")
        )))
    }
}

/// A number of `[material]`; a text that reads as a number too large for `f64` (`1e400`, as
/// `--set E=1e400` gives it) is named as not finite rather than as a string.
struct Number(f64);

impl<'de> Deserialize<'de> for Number {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Number, D::Error> {
        d.deserialize_any(NumberVisitor)
    }
}

struct NumberVisitor;

impl Visitor<'_> for NumberVisitor {
    type Value = Number;

    fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
        f.write_str("f64")
    }

    fn visit_f64<E: de::Error>(self, x: f64) -> Result<Number, E> {
        Ok(Number(x))
    }

    fn visit_i64<E: de::Error>(self, x: i64) -> Result<Number, E> {
        Ok(Number(x as f64))
    }

    fn visit_u64<E: de::Error>(self, x: u64) -> Result<Number, E> {
        Ok(Number(x as f64))
    }

    fn visit_str<E: de::Error>(self, text: &str) -> Result<Number, E> {
        match text.trim().parse::<f64>() {
            Ok(x) if !x.is_finite() => {
                Err(E::custom(format_args!("{text} is not a finite number")))
            }
            _ => Err(E::invalid_type(de::Unexpected::Str(text), &self)),
        }
    }
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
