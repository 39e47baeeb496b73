//! What a user asks for: a mesh, a method, material parameters, boundary conditions and
//! loads. [`crate::Simulation::new`] turns a [`Problem`] into a model holding only the terms
//! it names.

use super::schedule::Curve;
use crate::SolverError;
use isochor_constraints::NodalCompliance;
use isochor_energies::{bulk_modulus, Lame, ParameterError};
use isochor_mesh::{ElementMesh, Vec3, Zones};
use std::fmt;
use std::str::FromStr;

/// The discretization and solver of the volumetric response, as named on the command line.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Method {
    /// Displacement-only coupled neo-Hookean (eq. 6 of Francu et al. 2021), Newton with line search.
    Standard,
    /// Mixed FEM, nodal (P1) pressures, linear measure `J - 1` (eq. 24/27), saddle-point Newton.
    MixedP1,
    /// Mixed FEM, element (P0) pressures, linear measure (sec. 4.6), saddle-point Newton.
    MixedP0,
    /// Mixed FEM, nodal pressures, logarithmic measure `log J` (sec. 6).
    MixedP1Log,
    /// Mixed FEM, element pressures, logarithmic measure. With `kappa = lambda` its static
    /// condensation is exactly the standard neo-Hookean energy.
    MixedP0Log,
    /// Static condensation of the nodal mixed system (eq. 37) with a lumped `C^-1`.
    Condensed,
    /// Dual ascent / nonlinear Uzawa on the nodal constraints (eq. 39-41), optionally
    /// augmented with a base Poisson ratio (sec. 8.3).
    Dual,
    /// Constrained neo-Hookean of Sheen et al. 2021: F-bar deviatoric energy plus
    /// `lambda U(J; beta)`, subject to zonal volume constraints (eq. 6-15).
    Zonal,
}

impl Method {
    /// Every method, in the order tables list them.
    pub const ALL: [Method; 8] = [
        Method::Standard,
        Method::MixedP1,
        Method::MixedP0,
        Method::MixedP1Log,
        Method::MixedP0Log,
        Method::Condensed,
        Method::Dual,
        Method::Zonal,
    ];

    /// The name used by scenes and the command line.
    pub fn name(self) -> &'static str {
        match self {
            Method::Standard => "standard",
            Method::MixedP1 => "mixed-p1",
            Method::MixedP0 => "mixed-p0",
            Method::MixedP1Log => "mixed-p1-log",
            Method::MixedP0Log => "mixed-p0-log",
            Method::Condensed => "condensed",
            Method::Dual => "dual",
            Method::Zonal => "zonal",
        }
    }

    /// Whether the method carries pressure unknowns or multipliers.
    pub fn has_constraints(self) -> bool {
        self != Method::Standard
    }
}

impl fmt::Display for Method {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

impl FromStr for Method {
    type Err = SolverError;
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        Method::ALL
            .into_iter()
            .find(|m| m.name() == s)
            .ok_or_else(|| SolverError::UnknownMethod {
                name: s.to_string(),
                valid: Method::ALL
                    .iter()
                    .map(|m| m.name())
                    .collect::<Vec<_>>()
                    .join(", "),
            })
    }
}

/// Which volumetric stiffness `kappa` the mixed methods use in their compliance `C = V / kappa`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Kappa {
    /// The bulk modulus `E / (3 (1 - 2 nu))`, the paper's default (sec. 5).
    #[default]
    Bulk,
    /// The first Lame parameter, as Patterson et al. 2012 (makes `mixed-p0-log` condense
    /// to the standard neo-Hookean energy exactly).
    Lambda,
}

/// The energy the `zonal` method puts under its zone constraints.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub enum ZonalEnergy {
    /// F-bar deviatoric neo-Hookean plus `lambda U(J; beta)` (eq. 12-13 of Sheen et al.).
    #[default]
    Constrained,
    /// The standard coupled neo-Hookean with Lame parameters from `(mu, nu)` (Fig. 2 of Sheen et al.).
    Standard,
}

/// The epidermis surface energy of eq. 16 (Sheen et al. 2021).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Epidermis {
    /// Young's modulus of the skin layer, `E_e`.
    pub young: f64,
    /// Poisson's ratio of the skin layer, `nu_e` (`lambda_e` from eq. 3).
    pub poisson: f64,
    /// Steepness `gamma` of the area penalty.
    pub gamma: f64,
}

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

impl MaterialModel {
    /// The name scenes use (`model = "..."`).
    pub fn name(&self) -> &'static str {
        match self {
            MaterialModel::NeoHookean => "neo-hookean",
            MaterialModel::MooneyRivlin { .. } => "mooney-rivlin",
            MaterialModel::Yeoh { .. } => "yeoh",
            MaterialModel::Ogden { .. } => "ogden",
            MaterialModel::StableNeoHookean => "stable-neo-hookean",
            MaterialModel::BonetWood => "bonet-wood",
        }
    }

    /// Checks the model's constants (the error names the first bad one).
    pub fn validate(&self) -> Result<(), ParameterError> {
        match self {
            &MaterialModel::MooneyRivlin { c10, c01 } => {
                isochor_energies::MooneyRivlin::new(c10, c01).map(drop)
            }
            &MaterialModel::Yeoh { c10, c20, c30 } => {
                isochor_energies::Yeoh::new(c10, c20, c30).map(drop)
            }
            MaterialModel::Ogden { terms } => isochor_energies::Ogden::new(terms).map(drop),
            _ => Ok(()),
        }
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
            _ => None,
        }
    }
}

/// Material parameters shared by every method; each method reads what it needs.
#[derive(Debug, Clone, PartialEq)]
pub struct Material {
    /// The hyperelastic model.
    pub model: MaterialModel,
    /// Shear modulus `mu` (for models with constants, the initial shear modulus they set).
    pub mu: f64,
    /// Poisson's ratio `nu` in `(-1, 0.5]`: gives `lambda` (standard) and `kappa` (mixed).
    pub nu: f64,
    /// Mass density `rho` (gravity and inertia).
    pub density: f64,
    /// Volumetric stiffness of the mixed methods.
    pub kappa: Kappa,
    /// Integration of the nodal compliance (eq. 18) for `mixed-p1`, `mixed-p1-log` and
    /// `dual` (`condensed` always lumps, and `dual` needs a diagonal one).
    pub nodal_compliance: NodalCompliance,
    /// Local penalty stiffness `lambda` of the zonal method.
    pub zonal_lambda: f64,
    /// Steepness `beta` of `U(J; beta)` (eq. 13).
    pub beta: f64,
    /// Threshold `epsilon` of the F-bar C2 extension (eq. 11).
    pub epsilon: f64,
    /// The energy under the zonal constraints.
    pub zonal_energy: ZonalEnergy,
    /// Base Poisson ratio of the augmented-Lagrangian dual solver (sec. 8.3); `None` for
    /// plain dual ascent.
    pub dual_base_nu: Option<f64>,
    /// Optional epidermis energy on the boundary surface.
    pub epidermis: Option<Epidermis>,
}

impl Material {
    /// Parameters from Young's modulus and Poisson's ratio, with the papers' defaults
    /// elsewhere: `kappa` = bulk modulus, zonal `lambda` equivalent to `nu = 0.45`,
    /// `beta = 1`, `epsilon = 0.1`, dual base `nu = 0.4`, no epidermis.
    ///
    /// ```
    /// use isochor_solvers::Material;
    ///
    /// // A silicone rubber in SI units: E = 100 kPa, incompressible, 1070 kg/m^3.
    /// let silicone = Material::from_young_poisson(1e5, 0.5, 1070.0)?;
    /// assert!((silicone.mu - 1e5 / 3.0).abs() < 1e-9);
    /// assert_eq!(silicone.mixed_kappa()?, f64::INFINITY); // C = 0 in the mixed methods
    /// assert!(Material::from_young_poisson(1e5, 0.6, 1070.0).is_err());
    /// # Ok::<(), isochor_energies::ParameterError>(())
    /// ```
    pub fn from_young_poisson(young: f64, nu: f64, density: f64) -> Result<Self, ParameterError> {
        let mu = Lame::shear_modulus(young, nu)?;
        let zonal_lambda = Lame::from_young_poisson(young, 0.45)?.lambda;
        let material = Material {
            model: MaterialModel::NeoHookean,
            mu,
            nu,
            density,
            kappa: Kappa::Bulk,
            nodal_compliance: NodalCompliance::Consistent,
            zonal_lambda,
            beta: 1.0,
            epsilon: 0.1,
            zonal_energy: ZonalEnergy::Constrained,
            dual_base_nu: Some(0.4),
            epidermis: None,
        };
        material.validate()?;
        Ok(material)
    }

    /// The same material with `model`: a model with constants sets `mu` (and the default
    /// zonal `lambda`, equivalent to `nu = 0.45`) from them; set other parameters after.
    ///
    /// Errors: constants that give no positive shear modulus.
    pub fn with_model(mut self, model: MaterialModel) -> Result<Self, ParameterError> {
        model.validate()?;
        if let Some(mu) = model.shear_modulus() {
            if !(mu.is_finite() && mu > 0.0) {
                return Err(ParameterError {
                    name: "mu",
                    value: mu,
                    reason:
                        "the model's constants must give a finite, positive initial shear modulus",
                });
            }
            self.mu = mu;
            self.zonal_lambda = Lame::from_young_poisson(self.young(), 0.45)?.lambda;
        }
        self.model = model;
        self.validate()?;
        Ok(self)
    }

    /// Young's modulus `E = 2 mu (1 + nu)`.
    pub fn young(&self) -> f64 {
        2.0 * self.mu * (1.0 + self.nu)
    }

    /// Lame parameters of the standard neo-Hookean; an error at `nu = 0.5`.
    pub fn lame(&self) -> Result<Lame, ParameterError> {
        Lame::from_young_poisson(self.young(), self.nu)
    }

    /// The volumetric stiffness `kappa` of the mixed methods (`+inf` at `nu = 0.5`).
    pub fn mixed_kappa(&self) -> Result<f64, ParameterError> {
        match self.kappa {
            Kappa::Bulk => bulk_modulus(self.young(), self.nu),
            Kappa::Lambda if self.nu == 0.5 => Ok(f64::INFINITY),
            Kappa::Lambda => Ok(self.lame()?.lambda),
        }
    }

    /// Checks every parameter, naming the first bad one.
    pub fn validate(&self) -> Result<(), ParameterError> {
        let bad = |name, value, reason| {
            Err(ParameterError {
                name,
                value,
                reason,
            })
        };
        self.model.validate()?;
        Lame::shear_modulus(self.young(), self.nu)?;
        if let Some(mu) = self.model.shear_modulus() {
            if (mu - self.mu).abs() > 1e-12 * mu.abs() {
                return bad(
                    "mu",
                    self.mu,
                    "mu must be the initial shear modulus of the model's constants (see Material::with_model)",
                );
            }
        }
        if !(self.density.is_finite() && self.density >= 0.0) {
            return bad(
                "rho",
                self.density,
                "density must be finite and non-negative",
            );
        }
        if !(self.zonal_lambda.is_finite() && self.zonal_lambda >= 0.0) {
            return bad(
                "lambda",
                self.zonal_lambda,
                "must be finite and non-negative",
            );
        }
        if !(self.beta.is_finite() && self.beta >= 0.0) {
            return bad(
                "beta",
                self.beta,
                "beta must be finite and non-negative (eq. 13)",
            );
        }
        if !(self.epsilon.is_finite() && self.epsilon > 0.0 && self.epsilon < 1.0) {
            return bad(
                "epsilon",
                self.epsilon,
                "epsilon must lie in (0, 1) (eq. 11)",
            );
        }
        if let Some(nu) = self.dual_base_nu {
            if !(nu > -1.0 && nu < 0.5) {
                return bad(
                    "dual_base_nu",
                    nu,
                    "the base Poisson ratio must lie in (-1, 0.5)",
                );
            }
        }
        if let Some(skin) = self.epidermis {
            // Named as the epidermis' own parameters, not the body's E and nu.
            Lame::from_young_poisson(skin.young, skin.poisson).map_err(|e| ParameterError {
                name: match e.name {
                    "E" => "epidermis_young",
                    "nu" => "epidermis_nu",
                    other => other,
                },
                ..e
            })?;
            if !(skin.gamma.is_finite() && skin.gamma >= 0.0) {
                return bad(
                    "epidermis_gamma",
                    skin.gamma,
                    "gamma must be finite and non-negative",
                );
            }
        }
        Ok(())
    }
}

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

/// How a Dirichlet-constrained vertex moves with its parameter `t`: the load parameter in
/// `[0, 1]` (quasi-static) or `time / duration` (dynamics), or the value of the condition's
/// [`Curve`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Motion {
    /// Held at the rest position.
    Fixed,
    /// Translated by `t * offset`.
    Translate(Vec3),
    /// Rotated by `t * angle` (radians) about `axis` through `center` (twisting).
    Rotate {
        /// A point on the axis.
        center: Vec3,
        /// The axis' direction (any length but zero).
        axis: Vec3,
        /// The angle at `t = 1`, in radians.
        angle: f64,
    },
    /// Scaled about `center` by `1 + t (factors - 1)` per axis (stretching).
    Scale {
        /// The fixed point of the scaling.
        center: Vec3,
        /// The scale factors along x, y and z at `t = 1`.
        factors: Vec3,
    },
}

impl Motion {
    /// Prescribed position at load parameter `t` of the vertex with rest position `rest`.
    pub fn position(&self, rest: &Vec3, t: f64) -> Vec3 {
        match *self {
            Motion::Fixed => *rest,
            Motion::Translate(offset) => rest + t * offset,
            Motion::Rotate {
                center,
                axis,
                angle,
            } => {
                let rotation = nalgebra::Rotation3::from_axis_angle(
                    &nalgebra::Unit::new_normalize(axis),
                    t * angle,
                );
                center + rotation * (rest - center)
            }
            Motion::Scale { center, factors } => {
                let s = Vec3::repeat(1.0) + t * (factors - Vec3::repeat(1.0));
                center + (rest - center).component_mul(&s)
            }
        }
    }
}

/// A Dirichlet condition: the listed components of the listed nodes follow `motion`.
#[derive(Debug, Clone, PartialEq)]
pub struct Dirichlet {
    /// Node indices (on a 10-node mesh, include the mid-edge nodes of the held region).
    pub nodes: Vec<usize>,
    /// Which components (x, y, z) are prescribed.
    pub axes: [bool; 3],
    /// How they move.
    pub motion: Motion,
    /// The motion's parameter as a function of the load parameter or time (`None`: the
    /// fraction of the run).
    pub curve: Option<Curve>,
}

/// An external load at full scale; a [`ScheduledLoad`] says how it is scaled over the run.
#[derive(Debug, Clone, PartialEq)]
pub enum Load {
    /// Body force `rho g` per unit rest volume, as consistent nodal forces.
    Gravity(Vec3),
    /// Dead traction (force per unit rest area) on boundary faces, given by their corner
    /// triangles (on a 10-node mesh, the 6-node faces over them are loaded).
    Traction {
        /// The loaded boundary faces, by their corner vertices.
        faces: Vec<[usize; 3]>,
        /// Force per unit rest area.
        traction: Vec3,
    },
    /// Follower pressure on boundary faces, oriented with the body's outward normal: a
    /// positive pressure pushes the faces into the body, so listing the faces that line a
    /// chamber inflates it.
    Pressure {
        /// The loaded boundary faces, by their corner vertices; they must close a surface or
        /// have their rim held by Dirichlet conditions.
        faces: Vec<[usize; 3]>,
        /// Pressure, force per unit deformed area.
        pressure: f64,
    },
}

/// A load and its scale over the run.
#[derive(Debug, Clone, PartialEq)]
pub struct ScheduledLoad {
    /// The load at scale 1.
    pub load: Load,
    /// Its scale as a function of the load parameter or time (`None`: ramped with the load
    /// parameter in quasi-static stepping, constant in dynamics).
    pub curve: Option<Curve>,
}

impl From<Load> for ScheduledLoad {
    fn from(load: Load) -> Self {
        ScheduledLoad { load, curve: None }
    }
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
}

/// The shape of a rigid obstacle in its reference position. Each has a signed distance
/// `d(x)`, positive outside, that the contact constraints `d(x_i) >= 0` act on (sec. 8.2-8.3
/// of Francu et al. 2021).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Shape {
    /// The half-space below the plane through `point` with (outward) `normal`:
    /// `d = n . (x - p)`.
    HalfSpace {
        /// A point of the boundary plane.
        point: Vec3,
        /// The outward normal (any length but zero).
        normal: Vec3,
    },
    /// A solid sphere: `d = |x - c| - R`.
    Sphere {
        /// The centre.
        center: Vec3,
        /// The radius.
        radius: f64,
    },
    /// An infinite solid cylinder around the line through `point` along `axis`:
    /// `d = dist(x, axis) - R`.
    Cylinder {
        /// A point of the axis.
        point: Vec3,
        /// The axis' direction (any length but zero).
        axis: Vec3,
        /// The radius.
        radius: f64,
    },
    /// A solid torus, a ring whose hole a body passes through (a tight band around a waist):
    /// the tube of radius `r` around the circle of radius `R` about `center` in the plane
    /// normal to `axis`. With `q = x - c - R rho_hat` (`rho_hat` the unit direction from the
    /// axis to `x` in that plane), `d = |q| - r`, gradient `n = q / |q|` and Hessian
    /// `(I - n n^T - (R / rho) P) / |q|`, `rho` the distance from the axis and
    /// `P = I - a a^T - rho_hat rho_hat^T` the projection onto the circle's tangent. The
    /// hole's radius is `R - r`.
    Ring {
        /// The centre of the ring (a point of the axis).
        center: Vec3,
        /// The axis' direction (any length but zero).
        axis: Vec3,
        /// The major radius `R`, from the axis to the tube's centre circle.
        radius: f64,
        /// The tube's radius `r` (less than `R`).
        tube: f64,
    },
}

/// A rigid obstacle: a shape translated by `t * translate` and with its radius changed by
/// `t * radius_change`, with `t` the load parameter (quasi-static), `time / duration`
/// (dynamics) or the value of its curve, like a [`Motion::Translate`] condition.
#[derive(Debug, Clone, PartialEq)]
pub struct Obstacle {
    /// The shape at `t = 0`.
    pub shape: Shape,
    /// Displacement at `t = 1`.
    pub translate: Vec3,
    /// Change of the radius at `t = 1`: a sphere's or cylinder's radius, a ring's major
    /// radius `R` (a negative change tightens the ring's hole); a half-space has none (it
    /// must be 0).
    pub radius_change: f64,
    /// The motion's parameter as a function of the load parameter or time (`None`: the
    /// fraction of the run).
    pub curve: Option<Curve>,
}

impl Obstacle {
    /// A fixed obstacle.
    pub fn fixed(shape: Shape) -> Self {
        Obstacle {
            shape,
            translate: Vec3::zeros(),
            radius_change: 0.0,
            curve: None,
        }
    }

    /// Checks the shape: finite data, a non-zero normal or axis, a positive radius at `t = 0`
    /// and at `t = 1` (after the radius change), a ring's tube thinner than its major radius
    /// at both (so that its hole stays open), no radius change for a half-space.
    pub fn validate(&self) -> Result<(), SolverError> {
        let bad = |what: &str| Err(SolverError::InvalidProblem(format!("obstacle: {what}")));
        let finite = |v: &Vec3| v.iter().all(|c| c.is_finite());
        let positive = |r: f64| r.is_finite() && r > 0.0;
        if !finite(&self.translate) {
            return bad("the translation must be finite");
        }
        let change = self.radius_change;
        if !change.is_finite() {
            return bad("the radius change must be finite");
        }
        // The radius at t = 0 and at t = 1.
        let both = |radius: f64, above: f64| radius > above && radius + change > above;
        match self.shape {
            Shape::HalfSpace { point, normal } => {
                if !finite(&point) || !finite(&normal) || normal.norm() == 0.0 {
                    return bad("a half-space needs a finite point and a non-zero normal");
                }
                if change != 0.0 {
                    return bad("a half-space has no radius to change");
                }
            }
            Shape::Sphere { center, radius } => {
                if !(finite(&center) && positive(radius) && both(radius, 0.0)) {
                    return bad("a sphere needs a finite center and a positive radius, also after its radius change");
                }
            }
            Shape::Cylinder {
                point,
                axis,
                radius,
            } => {
                if !(finite(&point)
                    && finite(&axis)
                    && axis.norm() > 0.0
                    && positive(radius)
                    && both(radius, 0.0))
                {
                    return bad(
                        "a cylinder needs a finite point, a non-zero axis and a positive radius, also after its radius change",
                    );
                }
            }
            Shape::Ring {
                center,
                axis,
                radius,
                tube,
            } => {
                if !(finite(&center)
                    && finite(&axis)
                    && axis.norm() > 0.0
                    && positive(tube)
                    && positive(radius)
                    && both(radius, tube))
                {
                    return bad(
                        "a ring needs a finite center, a non-zero axis, a positive tube radius and a major radius above it, also after its radius change",
                    );
                }
            }
        }
        Ok(())
    }

    /// Signed distance `d`, its gradient `n` and Hessian at `x`, with the obstacle moved to
    /// parameter `t`.
    pub fn distance(&self, x: &Vec3, t: f64) -> (f64, Vec3, nalgebra::Matrix3<f64>) {
        let shift = t * self.translate;
        let grown = |radius: f64| radius + t * self.radius_change;
        let zero = nalgebra::Matrix3::zeros();
        match self.shape {
            Shape::HalfSpace { point, normal } => {
                let n = normal.normalize();
                (n.dot(&(x - point - shift)), n, zero)
            }
            Shape::Sphere { center, radius } => radial(x - center - shift, grown(radius), None),
            Shape::Cylinder {
                point,
                axis,
                radius,
            } => {
                let a = axis.normalize();
                let r = x - point - shift;
                radial(r - a * a.dot(&r), grown(radius), Some(a))
            }
            Shape::Ring {
                center,
                axis,
                radius,
                tube,
            } => ring(x - center - shift, axis.normalize(), grown(radius), tube),
        }
    }
}

/// The signed distance to the ring of [`Shape::Ring`] at `r = x - c`, with unit `axis`,
/// major radius `big` and tube radius `tube`. On the axis (`rho = 0`, where `d` has a
/// ridge and no gradient) any radial direction is taken, with no curvature along the
/// circle; on the tube's centre circle (`q = 0`, deep inside) `n` points towards the axis,
/// with no curvature: neither is met by a body inside the hole and clear of the tube's core.
fn ring(r: Vec3, axis: Vec3, big: f64, tube: f64) -> (f64, Vec3, nalgebra::Matrix3<f64>) {
    let tiny = f64::MIN_POSITIVE.sqrt();
    let height = axis.dot(&r);
    let w = r - axis * height;
    let rho = w.norm();
    let (rho_hat, bend) = if rho <= tiny * big {
        (
            axis.cross(&Vec3::x())
                .try_normalize(tiny)
                .unwrap_or_else(|| axis.cross(&Vec3::y()).normalize()),
            0.0,
        )
    } else {
        (w / rho, big / rho)
    };
    // `q = r - big rho_hat` from its two coordinates: near the axis `rho_hat` carries the
    // rounding of `w` divided by `rho`, which would otherwise reach `d` itself.
    let radial = rho - big;
    let len = radial.hypot(height);
    if len <= tiny * tube {
        return (-tube, -rho_hat, nalgebra::Matrix3::zeros());
    }
    let n = (radial * rho_hat + height * axis) / len;
    let identity = nalgebra::Matrix3::identity();
    let tangent = identity - axis * axis.transpose() - rho_hat * rho_hat.transpose();
    let h = (identity - n * n.transpose() - bend * tangent) / len;
    (len - tube, n, h)
}

/// `d = |r| - R` with gradient `u = r / |r|` and Hessian `(I - u u^T - a a^T) / |r|` (`a` the
/// cylinder axis). At `r = 0` (a vertex on the centre, far inside) the direction is
/// undefined: `+z` is taken, with no curvature.
fn radial(r: Vec3, radius: f64, axis: Option<Vec3>) -> (f64, Vec3, nalgebra::Matrix3<f64>) {
    let len = r.norm();
    if len <= f64::MIN_POSITIVE.sqrt() {
        return (-radius, Vec3::z(), nalgebra::Matrix3::zeros());
    }
    let u = r / len;
    let mut h = nalgebra::Matrix3::identity() - u * u.transpose();
    if let Some(a) = axis {
        h -= a * a.transpose();
    }
    (len - radius, u, h / len)
}
