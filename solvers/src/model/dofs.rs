//! Degrees of freedom: which position components are unknowns and which are prescribed by
//! Dirichlet conditions (removed from the linear systems, sec. 8.2 of Francu et al. 2021).

use crate::error::SolverError;
use crate::problem::loads::Dirichlet;
use crate::problem::schedule::LoadLevel;
use isochor_mesh::Vec3;

/// Sentinel for a prescribed DOF in [`Dofs::free_index`].
const FIXED: usize = usize::MAX;

/// The split of the `3n` position DOFs into free unknowns and prescribed values.
#[derive(Debug, Clone)]
pub struct Dofs {
    free_index: Vec<usize>,
    free: Vec<usize>,
    /// Prescribed DOFs with the condition that drives them (the last condition naming a
    /// component wins).
    prescribed: Vec<(usize, usize)>,
    conditions: Vec<Dirichlet>,
}

impl Dofs {
    /// DOFs of `num_nodes` nodes under `conditions`.
    pub fn new(num_nodes: usize, conditions: &[Dirichlet]) -> Result<Self, SolverError> {
        let mut driver = vec![FIXED; 3 * num_nodes];
        for (c, condition) in conditions.iter().enumerate() {
            for &v in &condition.nodes {
                if v >= num_nodes {
                    return Err(SolverError::InvalidProblem(format!(
                        "Dirichlet condition {c} names node {v}, but the mesh has {num_nodes} nodes"
                    )));
                }
                for (k, &on) in condition.axes.iter().enumerate() {
                    if on {
                        driver[3 * v + k] = c;
                    }
                }
            }
        }
        let mut free_index = vec![FIXED; 3 * num_nodes];
        let mut free = Vec::new();
        let mut prescribed = Vec::new();
        for (dof, &c) in driver.iter().enumerate() {
            if c == FIXED {
                free_index[dof] = free.len();
                free.push(dof);
            } else {
                prescribed.push((dof, c));
            }
        }
        Ok(Dofs {
            free_index,
            free,
            prescribed,
            conditions: conditions.to_vec(),
        })
    }

    /// Number of DOFs, free and prescribed (`3n`).
    pub fn num_dofs(&self) -> usize {
        self.free_index.len()
    }

    /// Number of free DOFs.
    pub fn num_free(&self) -> usize {
        self.free.len()
    }

    /// The free index of `dof`, or `None` if it is prescribed.
    pub fn free_index(&self, dof: usize) -> Option<usize> {
        let i = self.free_index[dof];
        (i != FIXED).then_some(i)
    }

    /// Free DOFs in order.
    pub fn free(&self) -> &[usize] {
        &self.free
    }

    /// Whether any DOF is prescribed.
    pub fn has_prescribed(&self) -> bool {
        !self.prescribed.is_empty()
    }

    /// The prescribed DOFs with their target values at `level`.
    pub fn targets<'a>(
        &'a self,
        rest: &'a [Vec3],
        level: LoadLevel,
    ) -> impl Iterator<Item = (usize, f64)> + 'a {
        self.prescribed.iter().map(move |&(dof, c)| {
            let (v, k) = (dof / 3, dof % 3);
            let condition = &self.conditions[c];
            let t = level.motion_parameter(condition.curve.as_ref());
            (dof, condition.motion.position(&rest[v], t)[k])
        })
    }

    /// Gathers the free entries of a full `3n` vector.
    pub fn gather(&self, full: &[f64]) -> Vec<f64> {
        self.free.iter().map(|&d| full[d]).collect()
    }

    /// Writes `free` (one value per free DOF) into the free entries of the full vector
    /// `full`, leaving the prescribed entries as they are.
    pub fn scatter(&self, free: &[f64], full: &mut [f64]) {
        for (&d, &v) in self.free.iter().zip(free) {
            full[d] = v;
        }
    }
}
