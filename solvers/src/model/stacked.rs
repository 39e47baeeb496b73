//! A method's volume constraints and the rows of its volume-controlled cavities as one
//! constraint set: the method's rows first, the cavities' after them (unanchored, so the
//! KKT ordering places them last).

use super::cavities::Cavities;
use isochor_constraints::{Compliance, ConstraintError, ConstraintSet};
use isochor_mesh::Vec3;
use std::sync::Arc;

/// The rows of `method` followed by those of `cavities`.
#[derive(Debug)]
pub struct StackedConstraints {
    method: Arc<dyn ConstraintSet>,
    cavities: Arc<Cavities>,
    /// Lengths of the method's Jacobian and geometric stiffness patterns.
    method_jacobian_len: usize,
    method_geometric_len: usize,
}

impl StackedConstraints {
    /// The rows of `method`, then those of `cavities`.
    pub fn new(method: Arc<dyn ConstraintSet>, cavities: Arc<Cavities>) -> Self {
        StackedConstraints {
            method_jacobian_len: method.jacobian_pattern().len(),
            method_geometric_len: method.geometric_stiffness_pattern().len(),
            method,
            cavities,
        }
    }

    fn split(&self) -> usize {
        self.method.num_constraints()
    }
}

impl ConstraintSet for StackedConstraints {
    fn name(&self) -> &'static str {
        self.method.name()
    }

    fn num_constraints(&self) -> usize {
        self.method.num_constraints() + self.cavities.num_constraints()
    }

    fn admits_inversion(&self) -> bool {
        self.method.admits_inversion() && self.cavities.admits_inversion()
    }

    fn values(&self, x: &[Vec3], out: &mut [f64]) -> Result<(), ConstraintError> {
        let (a, b) = out.split_at_mut(self.split());
        self.method.values(x, a)?;
        self.cavities.values(x, b)
    }

    fn jacobian_pattern(&self) -> Vec<(usize, usize)> {
        let m = self.split();
        let mut pattern = self.method.jacobian_pattern();
        pattern.extend(
            self.cavities
                .jacobian_pattern()
                .into_iter()
                .map(|(r, d)| (r + m, d)),
        );
        pattern
    }

    fn jacobian_values(&self, x: &[Vec3], out: &mut [f64]) -> Result<(), ConstraintError> {
        let (a, b) = out.split_at_mut(self.method_jacobian_len);
        self.method.jacobian_values(x, a)?;
        self.cavities.jacobian_values(x, b)
    }

    fn geometric_stiffness_pattern(&self) -> Vec<(usize, usize)> {
        let mut pattern = self.method.geometric_stiffness_pattern();
        pattern.extend(self.cavities.geometric_stiffness_pattern());
        pattern
    }

    fn geometric_stiffness_values(
        &self,
        x: &[Vec3],
        multipliers: &[f64],
        out: &mut [f64],
    ) -> Result<(), ConstraintError> {
        let (a, b) = out.split_at_mut(self.method_geometric_len);
        let (p, q) = multipliers.split_at(self.split().min(multipliers.len()));
        self.method.geometric_stiffness_values(x, p, a)?;
        self.cavities.geometric_stiffness_values(x, q, b)
    }

    fn compliance(&self) -> Compliance {
        let extra = self.cavities.num_constraints();
        match self.method.compliance() {
            Compliance::Diagonal(mut d) => {
                d.resize(d.len() + extra, 0.0);
                Compliance::Diagonal(d)
            }
            sparse @ Compliance::Sparse(_) => sparse,
        }
    }

    /// The method's pressures (the cavities' act on their walls, not in the material).
    fn tet_pressures(&self, x: &[Vec3], multipliers: &[f64]) -> Vec<f64> {
        if multipliers.len() != self.num_constraints() {
            return Vec::new();
        }
        self.method.tet_pressures(x, &multipliers[..self.split()])
    }

    fn anchor_vertex(&self, row: usize) -> Option<usize> {
        (row < self.split())
            .then(|| self.method.anchor_vertex(row))
            .flatten()
    }
}
