//! The `[paper]` section of a scene: published values of its probes over a swept parameter
//! (e.g. Table 2 of Francu et al. 2021: the spine arm's tip deflection per method over four
//! Poisson ratios), which `isochor compare` prints beside its own when it sweeps that
//! parameter.

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
