//! Constraints folded into the energy: `p^T phi(x) + (phi - C p)^T R (phi - C p) / 2`.
//!
//! - Static condensation (eq. 36-37 of Francu et al. 2021): `p = 0`, `C = 0`, `R = C_lumped^-1`,
//!   so the term is `phi^T C^-1 phi / 2` and its Hessian `G^T C^-1 G + sum_i (C^-1 phi)_i Hess phi_i`
//!   is the matrix `A_1` of eq. 37 (without mass and distortional stiffness).
//! - The primal step of dual ascent (eq. 39) with the augmented-Lagrangian base material of
//!   sec. 8.3: `p` the current multipliers, `C` the constraints' compliance, `R` the lumped
//!   inverse compliance of the base Poisson ratio (`R = 0` for plain dual ascent). At a
//!   fixed point `phi = C p`, the gradient is `G^T p`, so the solution is the mixed one.

use super::EnergyTerm;
use crate::error::SolverError;
use crate::problem::schedule::LoadLevel;
use isochor_constraints::ConstraintSet;
use isochor_mesh::Vec3;
use std::sync::{Arc, RwLock};

/// A constraint set folded into the energy with multipliers `p` and stiffness `R` (diagonal).
#[derive(Debug)]
pub struct AugmentedConstraints {
    constraints: Arc<dyn ConstraintSet>,
    multipliers: RwLock<Vec<f64>>,
    compliance: Vec<f64>,
    stiffness: Vec<f64>,
    /// For each Jacobian pattern entry, its slot among the unique DOFs of its row.
    slots: Vec<usize>,
    /// Unique DOFs of each row.
    row_dofs: Vec<Vec<usize>>,
    /// Offset of each row's slots in a flat buffer.
    row_offsets: Vec<usize>,
    geometric_len: usize,
}

impl AugmentedConstraints {
    /// `constraints` with diagonal `compliance` `C` and stiffness `R`; multipliers start at 0.
    pub fn new(
        constraints: Arc<dyn ConstraintSet>,
        compliance: Vec<f64>,
        stiffness: Vec<f64>,
    ) -> Self {
        let m = constraints.num_constraints();
        let pattern = constraints.jacobian_pattern();
        let mut row_dofs: Vec<Vec<usize>> = vec![Vec::new(); m];
        for &(row, dof) in &pattern {
            row_dofs[row].push(dof);
        }
        for dofs in &mut row_dofs {
            dofs.sort_unstable();
            dofs.dedup();
        }
        let mut row_offsets = Vec::with_capacity(m + 1);
        row_offsets.push(0);
        for dofs in &row_dofs {
            row_offsets.push(row_offsets.last().copied().unwrap_or(0) + dofs.len());
        }
        let slots = pattern
            .iter()
            .map(|&(row, dof)| row_offsets[row] + row_dofs[row].binary_search(&dof).unwrap_or(0))
            .collect();
        let geometric_len = constraints.geometric_stiffness_pattern().len();
        AugmentedConstraints {
            constraints,
            multipliers: RwLock::new(vec![0.0; m]),
            compliance,
            stiffness,
            slots,
            row_dofs,
            row_offsets,
            geometric_len,
        }
    }

    /// The folded constraint set.
    pub fn constraints(&self) -> &dyn ConstraintSet {
        self.constraints.as_ref()
    }

    /// Sets the multipliers `p`.
    pub fn set_multipliers(&self, p: &[f64]) {
        self.multipliers().copy_from_slice(p);
    }

    fn multipliers(&self) -> std::sync::RwLockWriteGuard<'_, Vec<f64>> {
        // A poisoned lock only means another thread panicked mid-write of plain floats.
        self.multipliers.write().unwrap_or_else(|e| e.into_inner())
    }

    /// The effective multipliers `q = p + R (phi - C p)` at constraint values `phi`: the
    /// pressures the primal problem sees (eq. 37 recovers `p = C^-1 phi`).
    pub fn effective_multipliers(&self, phi: &[f64]) -> Vec<f64> {
        let multipliers = self.multipliers();
        (0..phi.len())
            .map(|i| {
                let p = multipliers[i];
                p + self.stiffness[i] * (phi[i] - self.compliance[i] * p)
            })
            .collect()
    }

    /// Row-wise summed Jacobian values, laid out by `row_offsets`.
    fn row_values(&self, x: &[Vec3]) -> Result<Vec<f64>, SolverError> {
        let mut entries = vec![0.0; self.slots.len()];
        self.constraints.jacobian_values(x, &mut entries)?;
        let mut rows = vec![0.0; *self.row_offsets.last().unwrap_or(&0)];
        for (slot, v) in self.slots.iter().zip(&entries) {
            rows[*slot] += v;
        }
        Ok(rows)
    }
}

impl EnergyTerm for AugmentedConstraints {
    fn name(&self) -> &'static str {
        "augmented constraints"
    }

    fn hessian_pattern(&self) -> Vec<(usize, usize)> {
        let mut pattern: Vec<(usize, usize)> = self
            .row_dofs
            .iter()
            .flat_map(|dofs| {
                dofs.iter()
                    .flat_map(move |&a| dofs.iter().map(move |&b| (a, b)))
            })
            .collect();
        pattern.extend(self.constraints.geometric_stiffness_pattern());
        pattern
    }

    fn evaluate(
        &self,
        x: &[Vec3],
        _level: &LoadLevel,
        gradient: Option<&mut [f64]>,
        hessian: Option<&mut [f64]>,
    ) -> Result<f64, SolverError> {
        let multipliers = self.multipliers().clone();
        let m = multipliers.len();
        let mut phi = vec![0.0; m];
        self.constraints.values(x, &mut phi)?;
        let energy = (0..m)
            .map(|i| {
                let r = phi[i] - self.compliance[i] * multipliers[i];
                multipliers[i] * phi[i] + 0.5 * self.stiffness[i] * r * r
            })
            .sum();
        if gradient.is_none() && hessian.is_none() {
            return Ok(energy);
        }
        let q = self.effective_multipliers(&phi);
        let rows = self.row_values(x)?;
        if let Some(g) = gradient {
            for (i, dofs) in self.row_dofs.iter().enumerate() {
                let values = &rows[self.row_offsets[i]..self.row_offsets[i + 1]];
                for (d, v) in dofs.iter().zip(values) {
                    g[*d] += q[i] * v;
                }
            }
        }
        if let Some(h) = hessian {
            let (outer, geometric) = h.split_at_mut(h.len() - self.geometric_len);
            let mut k = 0;
            for (i, dofs) in self.row_dofs.iter().enumerate() {
                let values = &rows[self.row_offsets[i]..self.row_offsets[i + 1]];
                let r = self.stiffness[i];
                for va in values {
                    for vb in values {
                        outer[k] = r * va * vb;
                        k += 1;
                    }
                }
                debug_assert_eq!(values.len(), dofs.len());
            }
            self.constraints
                .geometric_stiffness_values(x, &q, geometric)?;
        }
        Ok(energy)
    }

    fn is_valid(&self, x: &[Vec3]) -> bool {
        let mut phi = vec![0.0; self.stiffness.len()];
        self.constraints.values(x, &mut phi).is_ok()
    }

    fn admits_inversion(&self) -> bool {
        self.constraints.admits_inversion()
    }
}
