//! The `[paper]` section of a scene: published values of its probes over a swept parameter
//! (e.g. Table 2 of Francu et al. 2021: the spine arm's tip deflection per method over four
//! Poisson ratios), which `isochor compare` prints beside its own when it sweeps that
//! parameter.

use crate::scene::Scene;
use isochor_solvers::Method;
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;

/// Published values of a scene's probes, in SI units.
#[derive(Debug, Clone, PartialEq, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct PaperSpec {
    /// Where the values are published, e.g. `"Francu et al. 2021, Table 2"`.
    pub source: String,
    /// The parameter the publication varies, as `--sweep` names it (`"nu"`, `"material.nu"`).
    pub sweep: String,
    /// The values of `sweep` the publication gives numbers at.
    pub values: Vec<f64>,
    /// Per probe of the scene, per method or variant name: one published value per entry of
    /// `values`.
    pub probes: BTreeMap<String, BTreeMap<String, Vec<f64>>>,
}

impl PaperSpec {
    /// Checks the section against its scene: the sweep key's syntax, distinct values, probes
    /// the scene defines, method or variant names, and one value per swept value. The error
    /// is the key at fault and what is wrong.
    pub fn validate(&self, scene: &Scene) -> Result<(), (String, String)> {
        crate::overrides::check_key_syntax(&self.sweep).map_err(|m| ("paper.sweep".into(), m))?;
        if self.values.is_empty() {
            return Err(("paper.values".into(), "give at least one value".into()));
        }
        for (i, v) in self.values.iter().enumerate() {
            if self.values[..i].contains(v) {
                return Err((format!("paper.values.{i}"), format!("{v} is given twice")));
            }
        }
        if self.probes.is_empty() {
            return Err((
                "paper.probes".into(),
                "give the values of at least one probe".into(),
            ));
        }
        for (probe, configs) in &self.probes {
            let key = format!("paper.probes.{probe}");
            if !scene.probes.contains_key(probe) {
                let defined: Vec<&str> = scene.probes.keys().map(String::as_str).collect();
                return Err((
                    key,
                    format!("unknown probe '{probe}' (defined: {})", defined.join(", ")),
                ));
            }
            for (label, values) in configs {
                let key = format!("{key}.{label}");
                if label.parse::<Method>().is_err() && !scene.variants.contains_key(label) {
                    let variants: Vec<&str> = scene.variants.keys().map(String::as_str).collect();
                    return Err((
                        key,
                        format!(
                            "'{label}' is neither a method ({}) nor a variant of the scene ({})",
                            Method::ALL.map(Method::name).join(", "),
                            variants.join(", ")
                        ),
                    ));
                }
                if values.len() != self.values.len() {
                    return Err((
                        key,
                        format!(
                            "{} values, but paper.values has {}",
                            values.len(),
                            self.values.len()
                        ),
                    ));
                }
            }
        }
        Ok(())
    }

    /// The published value of `probe` for the method or variant `label` at the swept value
    /// `at`, if `at` is one of `values`.
    pub fn value(&self, probe: &str, label: &str, at: f64) -> Option<f64> {
        let i = self.position(at)?;
        Some(self.probes.get(probe)?.get(label)?[i])
    }

    /// The index of `at` in `values` (the same decimal text parses to the same number).
    pub fn position(&self, at: f64) -> Option<usize> {
        self.values.iter().position(|v| *v == at)
    }
}
