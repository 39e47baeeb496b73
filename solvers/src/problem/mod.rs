//! What a user states: a mesh, a method, materials, boundary conditions, loads and obstacles.
//! [`crate::Simulation::new`] turns a [`Problem`] into a model holding only the terms it
//! names.

pub mod builder;
pub mod cloth;
pub mod friction;
pub mod loads;
pub mod material;
pub mod material_model;
pub mod mesh_obstacle;
pub mod method;
pub mod obstacle;
pub mod schedule;
mod supports;
mod validate;

use cloth::ClothSheet;
use isochor_mesh::{ElementMesh, Zones};
use loads::{Dirichlet, ScheduledLoad};
use material::Material;
use method::Method;
use obstacle::Obstacle;

/// A part of the body with its own material.
///
/// Everything that enters an element's energy or mass is the region's: the model and its
/// moduli, `nu` (so `lambda` and `kappa`), the zonal `lambda`, `beta`, `epsilon` and energy,
/// and the density. The settings of the whole body (`nodal_compliance`, `dual_base_nu`,
/// `epidermis`) are read from [`Problem::material`] and ignored here.
#[derive(Debug, Clone, PartialEq)]
pub struct Region {
    /// Name for reports and outputs.
    pub name: String,
    /// The elements of the region.
    pub elements: Vec<usize>,
    /// Their material.
    pub material: Material,
}

/// Everything a simulation needs.
#[derive(Debug, Clone)]
pub struct Problem {
    /// The mesh in its rest configuration: 4- or 10-node tets (a [`isochor_mesh::TetMesh`]
    /// converts into the 4-node one with `.into()`).
    pub mesh: ElementMesh,
    /// The method.
    pub method: Method,
    /// The material of every element that no region claims; also the source of the settings
    /// that hold for the whole body (`nodal_compliance`, `dual_base_nu`, `epidermis`).
    pub material: Material,
    /// Parts of the body with their own material (a stiff strain-limiting layer under a soft
    /// body): each element belongs to at most one region.
    pub regions: Vec<Region>,
    /// Zones for the `zonal` method (defaults to one global zone; none: no volume constraint,
    /// the energy's `lambda U(J; beta)` alone).
    pub zones: Option<Zones>,
    /// Dirichlet conditions.
    pub dirichlet: Vec<Dirichlet>,
    /// External loads.
    pub loads: Vec<ScheduledLoad>,
    /// Rigid obstacles the surface nodes may not enter (frictionless contact).
    pub obstacles: Vec<Obstacle>,
    /// Sheets of cloth over mesh vertices that no tet uses.
    pub cloths: Vec<ClothSheet>,
}
