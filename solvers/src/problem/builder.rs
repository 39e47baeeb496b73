//! [`ProblemBuilder`]: a [`Problem`] stated call by call, with defaults for what most
//! problems share, checked when built.

use super::cloth::ClothSheet;
use super::loads::{Dirichlet, Load, Motion, ScheduledLoad};
use super::material::Material;
use super::method::Method;
use super::obstacle::Obstacle;
use super::{Problem, Region};
use crate::error::SolverError;
use isochor_mesh::{ElementMesh, Vec3, Zones};

/// Young's modulus of the default material, in Pa.
const DEFAULT_YOUNG: f64 = 1e5;
/// Poisson's ratio of the default material.
const DEFAULT_POISSON: f64 = 0.49;
/// Density of the default material, in kg/m^3.
const DEFAULT_DENSITY: f64 = 1070.0;

/// Builds a [`Problem`] from a mesh, with defaults:
///
/// - method [`Method::MixedP1`]: nodal pressures, free of volumetric locking on linear tets
///   up to `nu = 0.5` (Francu et al. 2021, sec. 4);
/// - material [`ProblemBuilder::default_material`]: a soft silicone rubber in SI units
///   (`E = 100 kPa`, `nu = 0.49`, `rho = 1070 kg/m^3`, close to cast platinum-cure silicones
///   of soft robots); a default rather than a required argument so that a first run needs
///   only a mesh and its supports, but any quantitative study should set
///   [`ProblemBuilder::material`];
/// - no supports, loads, obstacles or zones (the `zonal` method then uses one global zone).
///
/// [`ProblemBuilder::build`] checks the result (see [`Problem::validate`]).
///
/// ```
/// use isochor_mesh::generate::box_grid;
/// use isochor_solvers::{Material, Method, Problem, Vec3};
///
/// let mesh = box_grid(Vec3::zeros(), Vec3::new(0.1, 0.02, 0.02), [5, 1, 1])?;
/// let clamped: Vec<usize> = (0..mesh.num_vertices())
///     .filter(|&v| mesh.positions()[v].x == 0.0)
///     .collect();
/// let problem = Problem::builder(mesh)
///     .method(Method::MixedP1)
///     .material(Material::from_young_poisson(1e5, 0.5, 1000.0)?)
///     .clamp(clamped)
///     .gravity(Vec3::new(0.0, 0.0, -9.81))
///     .build()?;
/// assert_eq!(problem.loads.len(), 1);
///
/// // A bad index is an error that names it.
/// let bad = Problem::builder(problem.mesh.clone()).clamp([10_000]).build();
/// assert!(bad.unwrap_err().to_string().contains("node 10000"));
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[derive(Debug, Clone)]
pub struct ProblemBuilder {
    mesh: ElementMesh,
    method: Method,
    material: Material,
    regions: Vec<Region>,
    zones: Option<Zones>,
    dirichlet: Vec<Dirichlet>,
    loads: Vec<ScheduledLoad>,
    obstacles: Vec<Obstacle>,
    cloths: Vec<ClothSheet>,
}

impl Problem {
    /// A [`ProblemBuilder`] on `mesh` (a [`isochor_mesh::TetMesh`] or an [`ElementMesh`]).
    pub fn builder(mesh: impl Into<ElementMesh>) -> ProblemBuilder {
        ProblemBuilder::new(mesh)
    }
}

impl ProblemBuilder {
    /// A builder on `mesh` with the defaults listed on [`ProblemBuilder`].
    pub fn new(mesh: impl Into<ElementMesh>) -> Self {
        ProblemBuilder {
            mesh: mesh.into(),
            method: Method::MixedP1,
            material: Self::default_material(),
            regions: Vec::new(),
            zones: None,
            dirichlet: Vec::new(),
            loads: Vec::new(),
            obstacles: Vec::new(),
            cloths: Vec::new(),
        }
    }

    /// The default material: `E = 1e5 Pa`, `nu = 0.49`, `rho = 1070 kg/m^3`, with the
    /// papers' defaults of [`Material::from_young_poisson`] elsewhere.
    pub fn default_material() -> Material {
        Material::from_young_poisson(DEFAULT_YOUNG, DEFAULT_POISSON, DEFAULT_DENSITY)
            .expect("the default parameters are valid")
    }

    /// The method (default [`Method::MixedP1`]).
    pub fn method(mut self, method: Method) -> Self {
        self.method = method;
        self
    }

    /// The material (default [`ProblemBuilder::default_material`]).
    pub fn material(mut self, material: Material) -> Self {
        self.material = material;
        self
    }

    /// Gives the `elements` of `name` their own `material` (see [`Region`]).
    pub fn region(mut self, name: &str, elements: Vec<usize>, material: Material) -> Self {
        self.regions.push(Region {
            name: name.to_string(),
            elements,
            material,
        });
        self
    }

    /// Zones of the `zonal` method (default: one zone holding every tet).
    pub fn zones(mut self, zones: Zones) -> Self {
        self.zones = Some(zones);
        self
    }

    /// Holds `nodes` at their rest positions (every component). On a 10-node mesh, list the
    /// mid-edge nodes of the held region too.
    pub fn clamp(self, nodes: impl IntoIterator<Item = usize>) -> Self {
        self.dirichlet(Dirichlet {
            nodes: nodes.into_iter().collect(),
            axes: [true; 3],
            motion: Motion::Fixed,
            curve: None,
        })
    }

    /// Adds a Dirichlet condition (a later condition wins on a component two of them name).
    pub fn dirichlet(mut self, condition: Dirichlet) -> Self {
        self.dirichlet.push(condition);
        self
    }

    /// Adds gravity: the body force `rho g` per unit rest volume.
    pub fn gravity(self, g: Vec3) -> Self {
        self.load(Load::Gravity(g))
    }

    /// Adds a dead traction (force per unit rest area) on boundary `faces`, given by their
    /// corner vertices.
    pub fn traction(self, faces: impl IntoIterator<Item = [usize; 3]>, traction: Vec3) -> Self {
        self.load(Load::Traction {
            faces: faces.into_iter().collect(),
            traction,
        })
    }

    /// Adds a follower pressure on boundary `faces` (positive pushes into the body, so the
    /// faces lining a chamber inflate it). The faces must close a surface, or their rim be
    /// held by Dirichlet conditions (a chamber whose ends are clamped): the load is the
    /// gradient of `p` times the volume the faces enclose with the origin, which on a free
    /// rim adds forces no pressure exerts.
    pub fn pressure(self, faces: impl IntoIterator<Item = [usize; 3]>, pressure: f64) -> Self {
        self.load(Load::Pressure {
            origin: Vec3::zeros(),
            cap_openings: false,
            faces: faces.into_iter().collect(),
            pressure,
        })
    }

    /// Holds the cavity lined by boundary `faces` (body-outward, closed or closed by symmetry
    /// planes through `origin`) at `volume_ratio` times its rest volume at full load; its
    /// pressure is solved for ([`Load::Cavity`]).
    pub fn cavity(
        self,
        faces: impl IntoIterator<Item = [usize; 3]>,
        volume_ratio: f64,
        origin: Vec3,
    ) -> Self {
        self.load(Load::Cavity {
            faces: faces.into_iter().collect(),
            volume_ratio,
            origin,
            cap_openings: false,
        })
    }

    /// Adds a load: a bare [`Load`] (ramped in quasi-static stepping, constant in dynamics)
    /// or a [`ScheduledLoad`] following a curve.
    pub fn load(mut self, load: impl Into<ScheduledLoad>) -> Self {
        self.loads.push(load.into());
        self
    }

    /// Adds a rigid obstacle.
    pub fn obstacle(mut self, obstacle: Obstacle) -> Self {
        self.obstacles.push(obstacle);
        self
    }

    /// Adds a sheet of cloth over mesh vertices that no tet uses.
    pub fn cloth(mut self, sheet: ClothSheet) -> Self {
        self.cloths.push(sheet);
        self
    }

    /// The problem, checked by [`Problem::validate`].
    pub fn build(self) -> Result<Problem, SolverError> {
        let problem = self.into_problem();
        problem.validate()?;
        Ok(problem)
    }

    /// The one place a builder's fields become a [`Problem`].
    fn into_problem(self) -> Problem {
        let ProblemBuilder {
            mesh,
            method,
            material,
            regions,
            zones,
            dirichlet,
            loads,
            obstacles,
            cloths,
        } = self;
        Problem {
            mesh,
            method,
            material,
            regions,
            zones,
            dirichlet,
            loads,
            obstacles,
            cloths,
        }
    }
}
