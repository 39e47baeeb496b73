//! The hyperelastic models a material may have, described once: each model's name, its
//! constants (key, unit, default), how its initial shear modulus `mu` follows from them, and
//! the form its density takes under each method ([`DensityForm`]). The scene format reads
//! this catalogue ([`MaterialModel::ALL`]) instead of spelling the models again; adding a
//! model is its energy in `isochor-energies` and one entry here
//! ([docs/architecture.md](../../../docs/architecture.md)).

use isochor_energies::{BonetWood, Hyperelastic, MooneyRivlin, Ogden, ParameterError, Yeoh};
use std::fmt;
use std::sync::Arc;

/// The hyperelastic model of a material. Under the mixed, condensed, dual and zonal methods
/// the model's distortional part meets the method's volume constraints or penalty; under
/// `standard` the model is completed by its own volumetric term (see each variant).
#[derive(Debug, Clone, PartialEq, Default)]
pub enum MaterialModel {
    /// Neo-Hookean in the form each method uses: standard (eq. 6 of Francu et al. 2021) for
    /// `standard`, distortional (eq. 32) for the mixed methods, constrained (eq. 12-13 of
    /// Sheen et al. 2021) for `zonal`. Parameter: `mu`.
    #[default]
    NeoHookean,
    /// Uncoupled Mooney-Rivlin `c10 (Ib1 - 3) + c01 (Ib2 - 3)` on the isochoric invariants
    /// (FEBio's Mooney-Rivlin): `mu = 2 (c10 + c01)`; `standard` adds `kappa/2 (log J)^2`.
    /// Stable in Drucker's sense for every strain: `c10 >= 0`, `c01 >= 0`, `c10 + c01 > 0`.
    MooneyRivlin {
        /// Coefficient of `Ib1 - 3` (Pa).
        c10: f64,
        /// Coefficient of `Ib2 - 3` (Pa).
        c01: f64,
    },
    /// Yeoh `c10 (Ib1 - 3) + c20 (Ib1 - 3)^2 + c30 (Ib1 - 3)^3`: `mu = 2 c10`; `standard` adds
    /// `kappa/2 (log J)^2`.
    Yeoh {
        /// Coefficient of `Ib1 - 3` (Pa).
        c10: f64,
        /// Coefficient of `(Ib1 - 3)^2` (Pa).
        c20: f64,
        /// Coefficient of `(Ib1 - 3)^3` (Pa).
        c30: f64,
    },
    /// Uncoupled Ogden `sum_p mu_p / alpha_p (lb1^alpha_p + lb2^alpha_p + lb3^alpha_p - 3)` on
    /// the isochoric principal stretches: `mu = 1/2 sum_p mu_p alpha_p`; `standard` adds
    /// `kappa/2 (log J)^2`.
    Ogden {
        /// The terms `(mu_p, alpha_p)`.
        terms: Vec<(f64, f64)>,
    },
    /// Stable neo-Hookean of Smith et al. 2018, reparametrized to match linear elasticity with
    /// `(mu, lambda)`; its distortional part (defined for inverted elements too) under the
    /// constraints. Parameter: `mu`.
    StableNeoHookean,
    /// The isochoric neo-Hookean `mu/2 (Ib1 - 3)` of Bonet and Wood (eq. 30 of Francu et al.
    /// 2021); `standard` adds `kappa/2 (log J)^2`. Parameter: `mu`.
    BonetWood,
}

/// What one constant of a model holds.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum ConstantKind {
    /// A number, with its default (`None`: it must be given).
    Number {
        /// The value taken when the constant is not given.
        default: Option<f64>,
    },
    /// A non-empty list of pairs `[[first, second], ...]`, always given.
    Pairs {
        /// The name of each pair's first entry.
        first: &'static str,
        /// The name of each pair's second entry.
        second: &'static str,
    },
}

/// One constant of a model, as scenes write it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Constant {
    /// The key (`c10`, `ogden`).
    pub key: &'static str,
    /// The unit of its value (or of each pair's first entry).
    pub unit: &'static str,
    /// What it is.
    pub doc: &'static str,
    /// Number or pairs, and its default.
    pub kind: ConstantKind,
}

/// The value of one constant.
#[derive(Debug, Clone, PartialEq)]
pub enum ConstantValue {
    /// A number.
    Number(f64),
    /// A list of pairs.
    Pairs(Vec<(f64, f64)>),
}

/// A model as the catalogue describes it: its name, its constants and how the model is made
/// from their values.
#[derive(Debug, Clone, Copy)]
pub struct ModelInfo {
    /// The name scenes use (`model = "..."`).
    pub name: &'static str,
    /// The model's constants; none for the models whose parameter is `mu` (or `young`).
    pub constants: &'static [Constant],
    /// The model from its constants' values, in the order of [`ModelInfo::constants`].
    make: fn(&[ConstantValue]) -> MaterialModel,
}

/// Constants given to a model that does not take them, or missing, or of the wrong kind.
#[derive(Debug, Clone, PartialEq)]
pub enum ConstantError {
    /// A key that is not a constant of the model.
    NotAConstant {
        /// The key given.
        key: String,
        /// The model.
        model: &'static str,
        /// The model's constants.
        constants: Vec<&'static str>,
    },
    /// A constant without default that was not given.
    Missing {
        /// The model.
        model: &'static str,
        /// The constant.
        constant: Constant,
    },
    /// A number where pairs are expected, or the other way round.
    WrongKind {
        /// The constant.
        constant: Constant,
    },
}

impl fmt::Display for ConstantError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            ConstantError::NotAConstant {
                key,
                model,
                constants,
            } => {
                let list = if constants.is_empty() {
                    "none; give young or mu".to_string()
                } else {
                    constants.join(", ")
                };
                write!(
                    f,
                    "{key} is not a constant of model {model} (its constants: {list})"
                )
            }
            ConstantError::Missing { model, constant } => match constant.kind {
                ConstantKind::Number { .. } => write!(f, "model {model} needs {}", constant.key),
                ConstantKind::Pairs { first, second } => write!(
                    f,
                    "model {model} needs {} = [[{first}, {second}], ...]",
                    constant.key
                ),
            },
            ConstantError::WrongKind { constant } => match constant.kind {
                ConstantKind::Number { .. } => write!(f, "{} must be a number", constant.key),
                ConstantKind::Pairs { first, second } => write!(
                    f,
                    "{} must be a list of pairs [[{first}, {second}], ...]",
                    constant.key
                ),
            },
        }
    }
}

impl std::error::Error for ConstantError {}

/// How a model's density is composed under each method (see `model::densities`).
pub enum DensityForm {
    /// The neo-Hookean of each method: standard, constrained (zonal) or distortional.
    NeoHookean,
    /// Stable neo-Hookean: whole under `standard`, its distortional part otherwise.
    StableNeoHookean,
    /// A purely distortional density `W(Ib1, Ib2)` (or of the isochoric stretches): plus
    /// `kappa/2 (log J)^2` under `standard`, plus `lambda U(J; beta)` under `zonal`, alone
    /// under the methods with volume constraints.
    Isochoric(Arc<dyn Hyperelastic>),
}

const C10: &str = "coefficient of Ib1 - 3";

/// A number constant in Pa.
const fn stress(key: &'static str, doc: &'static str, default: Option<f64>) -> Constant {
    Constant {
        key,
        unit: "Pa",
        doc,
        kind: ConstantKind::Number { default },
    }
}

/// The number at `i` of values checked against the model's constants.
fn number(values: &[ConstantValue], i: usize) -> f64 {
    match values[i] {
        ConstantValue::Number(x) => x,
        ConstantValue::Pairs(_) => unreachable!("the kinds are checked against the constants"),
    }
}

/// Every model, the default (`neo-hookean`) first.
const CATALOGUE: [ModelInfo; 6] = [
    ModelInfo {
        name: "neo-hookean",
        constants: &[],
        make: |_| MaterialModel::NeoHookean,
    },
    ModelInfo {
        name: "mooney-rivlin",
        constants: &[
            stress("c10", C10, None),
            stress("c01", "coefficient of Ib2 - 3", Some(0.0)),
        ],
        make: |v| MaterialModel::MooneyRivlin {
            c10: number(v, 0),
            c01: number(v, 1),
        },
    },
    ModelInfo {
        name: "yeoh",
        constants: &[
            stress("c10", C10, None),
            stress("c20", "coefficient of (Ib1 - 3)^2", Some(0.0)),
            stress("c30", "coefficient of (Ib1 - 3)^3", Some(0.0)),
        ],
        make: |v| MaterialModel::Yeoh {
            c10: number(v, 0),
            c20: number(v, 1),
            c30: number(v, 2),
        },
    },
    ModelInfo {
        name: "ogden",
        constants: &[Constant {
            key: "ogden",
            unit: "Pa (mu_p; alpha_p is dimensionless)",
            doc: "the terms (mu_p, alpha_p)",
            kind: ConstantKind::Pairs {
                first: "mu_p",
                second: "alpha_p",
            },
        }],
        make: |v| match &v[0] {
            ConstantValue::Pairs(terms) => MaterialModel::Ogden {
                terms: terms.clone(),
            },
            ConstantValue::Number(_) => unreachable!("the kinds are checked against the constants"),
        },
    },
    ModelInfo {
        name: "stable-neo-hookean",
        constants: &[],
        make: |_| MaterialModel::StableNeoHookean,
    },
    ModelInfo {
        name: "bonet-wood",
        constants: &[],
        make: |_| MaterialModel::BonetWood,
    },
];

/// The names of [`CATALOGUE`], in its order.
const NAMES: [&str; CATALOGUE.len()] = {
    let mut names = [""; CATALOGUE.len()];
    let mut i = 0;
    while i < CATALOGUE.len() {
        names[i] = CATALOGUE[i].name;
        i += 1;
    }
    names
};

impl ModelInfo {
    /// The model from the constants given as `(key, value)`: each key must be one of the
    /// model's constants, every constant without default given, each of its kind.
    ///
    /// ```
    /// use isochor_solvers::{ConstantValue, MaterialModel};
    ///
    /// let yeoh = MaterialModel::info("yeoh").unwrap();
    /// let model = yeoh.make([("c10", ConstantValue::Number(1e4))])?;
    /// assert_eq!(model, MaterialModel::Yeoh { c10: 1e4, c20: 0.0, c30: 0.0 });
    /// let wrong = yeoh.make([("c01", ConstantValue::Number(1.0))]).unwrap_err();
    /// assert_eq!(
    ///     wrong.to_string(),
    ///     "c01 is not a constant of model yeoh (its constants: c10, c20, c30)"
    /// );
    /// # Ok::<(), isochor_solvers::ConstantError>(())
    /// ```
    pub fn make<'a>(
        &self,
        given: impl IntoIterator<Item = (&'a str, ConstantValue)>,
    ) -> Result<MaterialModel, ConstantError> {
        let mut values: Vec<Option<ConstantValue>> = vec![None; self.constants.len()];
        for (key, value) in given {
            let Some(i) = self.constants.iter().position(|c| c.key == key) else {
                return Err(ConstantError::NotAConstant {
                    key: key.to_string(),
                    model: self.name,
                    constants: self.constants.iter().map(|c| c.key).collect(),
                });
            };
            values[i] = Some(value);
        }
        let values = self
            .constants
            .iter()
            .zip(values)
            .map(|(&constant, value)| match (constant.kind, value) {
                (ConstantKind::Number { .. }, Some(v @ ConstantValue::Number(_)))
                | (ConstantKind::Pairs { .. }, Some(v @ ConstantValue::Pairs(_))) => Ok(v),
                (_, Some(_)) => Err(ConstantError::WrongKind { constant }),
                (ConstantKind::Number { default: Some(x) }, None) => Ok(ConstantValue::Number(x)),
                (_, None) => Err(ConstantError::Missing {
                    model: self.name,
                    constant,
                }),
            })
            .collect::<Result<Vec<_>, _>>()?;
        Ok((self.make)(&values))
    }
}

impl MaterialModel {
    /// Every model, the default first.
    pub const ALL: &'static [ModelInfo] = &CATALOGUE;
    /// The models' names, in the order of [`MaterialModel::ALL`].
    pub const NAMES: &'static [&'static str] = &NAMES;

    /// The model named `name` (`"mooney-rivlin"`), if there is one.
    pub fn info(name: &str) -> Option<&'static ModelInfo> {
        Self::ALL.iter().find(|m| m.name == name)
    }

    /// The catalogue's entry of this model.
    pub fn described(&self) -> &'static ModelInfo {
        let name = match self {
            MaterialModel::NeoHookean => "neo-hookean",
            MaterialModel::MooneyRivlin { .. } => "mooney-rivlin",
            MaterialModel::Yeoh { .. } => "yeoh",
            MaterialModel::Ogden { .. } => "ogden",
            MaterialModel::StableNeoHookean => "stable-neo-hookean",
            MaterialModel::BonetWood => "bonet-wood",
        };
        Self::info(name).expect("every model is in the catalogue")
    }

    /// The name scenes use (`model = "..."`).
    pub fn name(&self) -> &'static str {
        self.described().name
    }

    /// The constant keys of any model (`c10`, `c01`, ..., `ogden`), each once.
    pub fn constant_keys() -> Vec<&'static str> {
        let mut keys: Vec<&str> = Vec::new();
        for constant in Self::ALL.iter().flat_map(|m| m.constants) {
            if !keys.contains(&constant.key) {
                keys.push(constant.key);
            }
        }
        keys
    }

    /// The constant of any model with key `key` (the first model's where several share it).
    pub fn constant(key: &str) -> Option<&'static Constant> {
        Self::ALL
            .iter()
            .flat_map(|m| m.constants)
            .find(|c| c.key == key)
    }

    /// Checks the model's constants (the error names the first bad one). Mooney-Rivlin also
    /// needs `c10 >= 0` and `c01 >= 0`: stable in Drucker's sense for every strain
    /// ([docs/materials.md](../../../docs/materials.md)).
    pub fn validate(&self) -> Result<(), ParameterError> {
        self.density_form().map(drop)
    }

    /// The initial shear modulus the model's constants set, or `None` for the models whose
    /// parameter is `mu` itself.
    pub fn shear_modulus(&self) -> Option<f64> {
        match self {
            MaterialModel::MooneyRivlin { c10, c01 } => Some(2.0 * (c10 + c01)),
            MaterialModel::Yeoh { c10, .. } => Some(2.0 * c10),
            MaterialModel::Ogden { terms } => {
                Some(0.5 * terms.iter().map(|(m, a)| m * a).sum::<f64>())
            }
            MaterialModel::NeoHookean
            | MaterialModel::StableNeoHookean
            | MaterialModel::BonetWood => None,
        }
    }

    /// How the model's density is composed under each method, with `mu` the material's shear
    /// modulus; errors name the first bad constant.
    pub fn density_form_with(&self, mu: f64) -> Result<DensityForm, ParameterError> {
        Ok(match self {
            MaterialModel::NeoHookean => DensityForm::NeoHookean,
            MaterialModel::StableNeoHookean => DensityForm::StableNeoHookean,
            MaterialModel::BonetWood => DensityForm::Isochoric(Arc::new(BonetWood::new(mu)?)),
            &MaterialModel::MooneyRivlin { c10, c01 } => {
                let density = MooneyRivlin::new(c10, c01)?;
                for (name, value) in [("c10", c10), ("c01", c01)] {
                    if value < 0.0 {
                        return Err(ParameterError {
                            name,
                            value,
                            reason: "Mooney-Rivlin is stable for every strain (Drucker) only with c10 >= 0 and c01 >= 0 (docs/materials.md)",
                        });
                    }
                }
                DensityForm::Isochoric(Arc::new(density))
            }
            &MaterialModel::Yeoh { c10, c20, c30 } => {
                DensityForm::Isochoric(Arc::new(Yeoh::new(c10, c20, c30)?))
            }
            MaterialModel::Ogden { terms } => DensityForm::Isochoric(Arc::new(Ogden::new(terms)?)),
        })
    }

    /// [`MaterialModel::density_form_with`] at the shear modulus the constants set (`1` for
    /// the models whose parameter is `mu`, which a form does not need to be checked).
    fn density_form(&self) -> Result<DensityForm, ParameterError> {
        self.density_form_with(self.shear_modulus().unwrap_or(1.0))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_model_is_described_once_and_names_itself() {
        for (info, name) in MaterialModel::ALL.iter().zip(MaterialModel::NAMES) {
            assert_eq!(info.name, *name);
            assert_eq!(MaterialModel::info(name).unwrap().name, *name);
        }
        let mut names = MaterialModel::NAMES.to_vec();
        names.dedup();
        assert_eq!(names.len(), MaterialModel::ALL.len());
        assert_eq!(MaterialModel::default().name(), MaterialModel::NAMES[0]);
    }

    #[test]
    fn a_key_means_one_kind_in_every_model() {
        for key in MaterialModel::constant_keys() {
            let kinds: Vec<_> = MaterialModel::ALL
                .iter()
                .flat_map(|m| m.constants)
                .filter(|c| c.key == key)
                .map(|c| std::mem::discriminant(&c.kind))
                .collect();
            assert!(kinds.windows(2).all(|w| w[0] == w[1]), "{key}");
        }
    }

    #[test]
    fn models_are_made_from_their_constants() {
        let mr = MaterialModel::info("mooney-rivlin").unwrap();
        let made = mr
            .make([
                ("c10", ConstantValue::Number(2.0)),
                ("c01", ConstantValue::Number(0.5)),
            ])
            .unwrap();
        assert_eq!(made, MaterialModel::MooneyRivlin { c10: 2.0, c01: 0.5 });
        assert_eq!(made.name(), "mooney-rivlin");
        let e = mr.make([("c20", ConstantValue::Number(1.0))]).unwrap_err();
        assert_eq!(
            e.to_string(),
            "c20 is not a constant of model mooney-rivlin (its constants: c10, c01)"
        );
        assert_eq!(
            mr.make([]).unwrap_err().to_string(),
            "model mooney-rivlin needs c10"
        );
        let ogden = MaterialModel::info("ogden").unwrap();
        assert_eq!(
            ogden.make([]).unwrap_err().to_string(),
            "model ogden needs ogden = [[mu_p, alpha_p], ...]"
        );
        let e = ogden
            .make([("ogden", ConstantValue::Number(1.0))])
            .unwrap_err();
        assert!(matches!(e, ConstantError::WrongKind { .. }), "{e}");
        let neo = MaterialModel::info("neo-hookean").unwrap();
        assert_eq!(
            neo.make([("c10", ConstantValue::Number(1.0))])
                .unwrap_err()
                .to_string(),
            "c10 is not a constant of model neo-hookean (its constants: none; give young or mu)"
        );
    }

    #[test]
    fn mooney_rivlin_is_drucker_stable() {
        let mr = |c10, c01| MaterialModel::MooneyRivlin { c10, c01 }.validate();
        mr(1.0, 0.0).unwrap();
        mr(0.0, 1.0).unwrap();
        assert_eq!(mr(-0.2, 1.0).unwrap_err().name, "c10");
        assert_eq!(mr(1.0, -0.2).unwrap_err().name, "c01");
        assert_eq!(mr(0.0, 0.0).unwrap_err().name, "c10");
    }
}
