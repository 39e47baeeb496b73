//! The assembled view of a model that the nonlinear solvers iterate on: every term's
//! energy, gradient and Hessian values in one flat buffer (plus the geometric stiffness of
//! the constraints), the constraint values and Jacobian, all mapped to free DOFs through
//! layouts built once per run.

mod layout;
mod node_pattern;

pub use node_pattern::{HessianBlock, NodePattern};

use crate::error::SolverError;
use crate::model::{Model, NonlinearScheme};
use crate::problem::schedule::LoadLevel;
use crate::settings::Settings;
use crate::terms::{BlockOrder, ElementBlocks, EnergyTerm, Inertia};
use isochor_mesh::Vec3;
use layout::Layout;
use std::time::{Duration, Instant};

/// What one evaluation produced.
#[derive(Debug, Clone)]
pub struct Evaluation {
    /// Total energy of the terms.
    pub energy: f64,
    /// Full-space gradient (length `3n`).
    pub gradient: Vec<f64>,
    /// Sum of the terms' absolute energies: the scale of the rounding error of `energy`.
    pub magnitude: f64,
}

/// Every energy term of `model` in block order: the model's, the folded constraints of the
/// dual/condensed solvers, the contact, and the inertia.
fn terms<'a>(
    model: &'a Model,
    inertia: Option<&'a Inertia>,
) -> impl Iterator<Item = &'a dyn EnergyTerm> {
    (model.terms.iter().map(|t| t.as_ref() as &dyn EnergyTerm))
        .chain(model.augmented.iter().map(|a| a as &dyn EnergyTerm))
        .chain(model.contact.iter().map(|c| c as &dyn EnergyTerm))
        .chain(model.surface_contact.iter().map(|c| c as &dyn EnergyTerm))
        .chain(model.surface_friction.iter().map(|f| f as &dyn EnergyTerm))
        .chain(inertia.into_iter().map(|i| i as &dyn EnergyTerm))
}

/// Where the constraints' geometric stiffness (eq. 23) sits in the Hessian's value buffer.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Geometric {
    /// Added into the block of the term with the same pattern (the elastic term's, for the
    /// per-element and nodal constraints over the same elements): the pattern and every
    /// Newton matrix hold its entries once.
    Shares(usize),
    /// A block of its own, after every term's.
    Own,
}

impl Geometric {
    /// Shares the first of `blocks` whose pattern is `pattern`, else its own.
    fn place(pattern: &HessianBlock, blocks: &[HessianBlock]) -> Self {
        blocks
            .iter()
            .position(|b| b.same_pattern(pattern))
            .map_or(Geometric::Own, Geometric::Shares)
    }
}

/// Start of every block's values in the value buffer, and the end of the last.
fn offsets(blocks: &[HessianBlock]) -> Vec<usize> {
    std::iter::once(0)
        .chain(blocks.iter().scan(0, |end, b| {
            *end += b.len();
            Some(*end)
        }))
        .collect()
}

/// A term's Hessian pattern: its element blocks when it has them, else its pairs.
fn block_of(term: &dyn EnergyTerm) -> HessianBlock {
    term.hessian_blocks().map_or_else(
        || HessianBlock::Pairs(term.hessian_pattern()),
        HessianBlock::Elements,
    )
}

/// A model with its inertia (in dynamics), layouts and buffers.
#[derive(Debug)]
pub struct System<'m> {
    pub model: &'m Model,
    pub inertia: Option<Inertia>,
    pub settings: Settings,
    /// Start of each term's block in `hessian_values`; the last block is the constraints'
    /// geometric stiffness unless it shares a term's block (`geometric`).
    offsets: Vec<usize>,
    /// Where the constraints' geometric stiffness goes (saddle-point schemes only).
    geometric: Option<Geometric>,
    /// The geometric stiffness's values before they are added into a shared block.
    geometric_scratch: Vec<f64>,
    /// The pattern of every block, in order (a changing surface-contact block is replaced
    /// in place).
    blocks: Vec<HessianBlock>,
    /// How many times the surface-contact pairs changed the pattern.
    pub pattern_rebuilds: usize,
    pub hessian: Layout,
    pub hessian_values: Vec<f64>,
    /// Constraint Jacobian layout and values (saddle-point and dual strategies).
    pub jacobian: Option<Layout>,
    pub jacobian_values: Vec<f64>,
    /// Time spent assembling since the last [`System::take_assembly_time`].
    assembly_time: Duration,
    /// Of that and of the pattern updates: the surface contact's and friction's, since the
    /// last [`System::take_contact_time`].
    contact_time: Duration,
}

impl<'m> System<'m> {
    /// Layouts for `model`, with the inertia term of implicit Euler if given.
    pub fn new(
        model: &'m Model,
        inertia: Option<Inertia>,
        settings: Settings,
    ) -> Result<Self, SolverError> {
        let mut blocks: Vec<HessianBlock> = terms(model, inertia.as_ref()).map(block_of).collect();
        let saddle = matches!(
            model.scheme,
            NonlinearScheme::SaddleDirect | NonlinearScheme::SaddleSchur
        );
        let mut geometric = None;
        let (jacobian, jacobian_len) = match &model.constraints {
            Some(c) => {
                if saddle {
                    let pattern = match c.geometric_stiffness_blocks() {
                        Some((nodes, per_element)) => HessianBlock::Elements(ElementBlocks {
                            nodes: nodes.to_vec(),
                            per_element,
                            order: BlockOrder::RowMajor,
                        }),
                        None => HessianBlock::Pairs(c.geometric_stiffness_pattern()),
                    };
                    geometric = Some(Geometric::place(&pattern, &blocks));
                    if geometric == Some(Geometric::Own) {
                        blocks.push(pattern);
                    }
                }
                let g = c.jacobian_pattern();
                (
                    Some(Layout::jacobian(&g, c.num_constraints(), &model.dofs)?),
                    g.len(),
                )
            }
            None => (None, 0),
        };
        let hessian = Layout::hessian(&blocks, &model.dofs)?;
        let offsets = offsets(&blocks);
        Ok(System {
            model,
            inertia,
            settings,
            hessian_values: vec![0.0; offsets[blocks.len()]],
            offsets,
            geometric,
            geometric_scratch: Vec::new(),
            blocks,
            pattern_rebuilds: 0,
            hessian,
            jacobian,
            jacobian_values: vec![0.0; jacobian_len],
            assembly_time: Duration::ZERO,
            contact_time: Duration::ZERO,
        })
    }

    /// Every energy term: the model's, the folded constraints of the dual/condensed solvers,
    /// the contact, and the inertia.
    fn terms(&self) -> impl Iterator<Item = &dyn EnergyTerm> {
        terms(self.model, self.inertia.as_ref())
    }

    /// Takes the surface-contact pairs at `x` as the pattern's, and the surface friction's
    /// pairs of its last lag; when either changed, rebuilds the Hessian layout with the new
    /// blocks and returns `true` (the solvers then redo their symbolic analysis). Without
    /// surface contact, `false`.
    pub fn update_contact_pattern(&mut self, x: &[Vec3]) -> Result<bool, SolverError> {
        let Some(contact) = &self.model.surface_contact else {
            return Ok(false);
        };
        let block = self.surface_blocks().start;
        let mut changed = false;
        let start = Instant::now();
        let updated = contact.update(x);
        self.contact_time += start.elapsed();
        if updated {
            self.splice(block, contact.hessian_pattern());
            changed = true;
        }
        if let Some(friction) = &self.model.surface_friction {
            if friction.take_pattern_change() {
                self.splice(block + 1, friction.hessian_pattern());
                changed = true;
            }
        }
        if !changed {
            return Ok(false);
        }
        self.hessian = Layout::hessian(&self.blocks, &self.model.dofs)?;
        self.hessian_values = vec![0.0; self.offsets[self.blocks.len()]];
        self.pattern_rebuilds += 1;
        Ok(true)
    }

    /// The blocks of the surface contact and surface friction terms (empty without surface
    /// contact): after the model's terms, the folded constraints and the obstacles.
    fn surface_blocks(&self) -> std::ops::Range<usize> {
        let start = self.model.terms.len()
            + usize::from(self.model.augmented.is_some())
            + usize::from(self.model.contact.is_some());
        let count = usize::from(self.model.surface_contact.is_some())
            + usize::from(self.model.surface_friction.is_some());
        start..start + count
    }

    /// Replaces the pattern of block `block` by `new`.
    fn splice(&mut self, block: usize, new: Vec<(usize, usize)>) {
        self.blocks[block] = HessianBlock::Pairs(new);
        self.offsets = offsets(&self.blocks);
    }

    /// The largest step along `direction` (three entries per node) from `x` that no pair of
    /// surfaces crosses ([`crate::terms::SurfaceContact::max_step`]); 1 without surface contact.
    pub fn max_step(&self, x: &[Vec3], direction: &[f64]) -> f64 {
        self.model
            .surface_contact
            .as_ref()
            .map_or(1.0, |c| c.max_step(x, direction))
    }

    /// Makes the element Hessians of the terms that PSD-project them (barrier contact,
    /// cloth: [`EnergyTerm::project_hessian`]) projected or exact in later assemblies;
    /// returns whether any term has such blocks now (without any there is nothing to choose,
    /// and a failed unshifted factorization would be one factorization lost).
    pub fn set_projected_hessians(&self, projected: bool) -> bool {
        // Every term is told (no short circuit), then whether any has such blocks.
        let mut any = false;
        for term in self.terms() {
            any |= term.project_hessian(projected);
        }
        any
    }

    /// Re-evaluates at `x` the Hessian blocks of the terms that project theirs, now
    /// projected, leaving the other terms' blocks as they are: the fallback when the matrix
    /// with the exact blocks does not factorize.
    pub fn project_hessians(&mut self, x: &[Vec3], level: &LoadLevel) -> Result<(), SolverError> {
        let start = Instant::now();
        let surface = self.surface_blocks();
        let mut contact_time = Duration::ZERO;
        let mut values = std::mem::take(&mut self.hessian_values);
        let result = self.terms().enumerate().try_for_each(|(block, term)| {
            if !term.project_hessian(true) {
                return Ok(());
            }
            let term_start = Instant::now();
            let mine = &mut values[self.offsets[block]..self.offsets[block + 1]];
            mine.fill(0.0);
            term.evaluate(x, level, None, Some(mine))?;
            if surface.contains(&block) {
                contact_time += term_start.elapsed();
            }
            Ok(())
        });
        self.hessian_values = values;
        self.assembly_time += start.elapsed();
        self.contact_time += contact_time;
        result
    }

    /// Energy (and gradient) of all terms at `x`, without touching the Hessian.
    pub fn energy(
        &mut self,
        x: &[Vec3],
        level: &LoadLevel,
        with_gradient: bool,
    ) -> Result<Evaluation, SolverError> {
        let start = Instant::now();
        let mut gradient = vec![0.0; if with_gradient { 3 * x.len() } else { 0 }];
        let (mut energy, mut magnitude) = (0.0, 0.0);
        for term in self.terms() {
            let g = with_gradient.then_some(gradient.as_mut_slice());
            let e = term.evaluate(x, level, g, None)?;
            energy += e;
            magnitude += e.abs() + term.rounding_scale();
        }
        self.assembly_time += start.elapsed();
        Ok(Evaluation {
            energy,
            gradient,
            magnitude,
        })
    }

    /// Energy, gradient and Hessian values of all terms at `x`; with `multipliers`, also
    /// the constraints' geometric stiffness (eq. 23) into the last block and their Jacobian.
    pub fn assemble(
        &mut self,
        x: &[Vec3],
        level: &LoadLevel,
        multipliers: Option<&[f64]>,
    ) -> Result<Evaluation, SolverError> {
        let start = Instant::now();
        let mut gradient = vec![0.0; 3 * x.len()];
        let mut values = std::mem::take(&mut self.hessian_values);
        let result = self.fill(x, level, multipliers, &mut gradient, &mut values);
        self.hessian_values = values;
        let (energy, magnitude) = result?;
        self.assembly_time += start.elapsed();
        Ok(Evaluation {
            energy,
            gradient,
            magnitude,
        })
    }

    fn fill(
        &mut self,
        x: &[Vec3],
        level: &LoadLevel,
        multipliers: Option<&[f64]>,
        gradient: &mut [f64],
        values: &mut [f64],
    ) -> Result<(f64, f64), SolverError> {
        let (mut energy, mut magnitude) = (0.0, 0.0);
        let surface = self.surface_blocks();
        let mut contact_time = Duration::ZERO;
        let mut terms = 0;
        for (block, term) in self.terms().enumerate() {
            let mine = &mut values[self.offsets[block]..self.offsets[block + 1]];
            let start = Instant::now();
            let e = term.evaluate(x, level, Some(&mut *gradient), Some(mine))?;
            if surface.contains(&block) {
                contact_time += start.elapsed();
            }
            energy += e;
            magnitude += e.abs() + term.rounding_scale();
            terms += 1;
        }
        self.contact_time += contact_time;
        if let (Some(c), Some(p)) = (&self.model.constraints, multipliers) {
            match self.geometric {
                Some(Geometric::Shares(block)) => {
                    let shared = &mut values[self.offsets[block]..self.offsets[block + 1]];
                    let scratch = &mut self.geometric_scratch;
                    scratch.clear();
                    scratch.resize(shared.len(), 0.0);
                    c.geometric_stiffness_values(x, p, scratch)?;
                    for (v, g) in shared.iter_mut().zip(scratch.iter()) {
                        *v += g;
                    }
                }
                _ => c.geometric_stiffness_values(x, p, &mut values[self.offsets[terms]..])?,
            }
            c.jacobian_values(x, &mut self.jacobian_values)?;
        }
        Ok((energy, magnitude))
    }

    /// Whether `x` lies in the domain of every term and constraint.
    pub fn is_valid(&self, x: &[Vec3]) -> bool {
        self.terms().all(|t| t.is_valid(x))
            && self.model.constraints.as_ref().is_none_or(|c| {
                let mut phi = vec![0.0; c.num_constraints()];
                c.values(x, &mut phi).is_ok()
            })
    }

    /// Whether every term and constraint has a meaning at inverted elements, so that a state
    /// with some may be accepted ([`EnergyTerm::admits_inversion`]).
    pub fn admits_inversion(&self) -> bool {
        self.terms().all(|t| t.admits_inversion())
            && self
                .model
                .constraints
                .as_ref()
                .is_none_or(|c| c.admits_inversion())
    }

    /// Assembly time since the last call.
    pub fn take_assembly_time(&mut self) -> Duration {
        std::mem::take(&mut self.assembly_time)
    }

    /// The surface contact's and friction's share of the assemblies and pattern updates
    /// since the last call.
    pub fn take_contact_time(&mut self) -> Duration {
        std::mem::take(&mut self.contact_time)
    }
}
