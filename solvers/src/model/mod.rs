//! The model built from a [`Problem`]: its [`Dofs`], the material of every element, and only
//! the terms the problem names: the elastic energy of its method, the loads it lists, the
//! constraint set of a mixed or zonal method, the lumped masses.

use crate::error::SolverError;
use crate::problem::friction::FrictionSpec;
use crate::problem::loads::{Load, ScheduledLoad};
use crate::problem::material::ZonalEnergy;
use crate::problem::mesh_obstacle::MeshObstacle;
use crate::problem::method::Method;
use crate::problem::schedule::LoadLevel;
use crate::problem::Problem;
use crate::terms::{
    AugmentedConstraints, Cloth, Contact, DeadLoad, Elastic, EnclosedVolume, EnergyTerm,
    EpidermisTerm, Faces, FollowerPressure,
};
use crate::terms::{SurfaceContact, SurfaceContactSpec, SurfaceFriction};
use isochor_constraints::{
    exact_rule, Compliance, ConstraintSet, Measure, NodalCompliance, NodalConstraints,
    PerElementConstraints, RowShape, ZonalConstraints,
};
use isochor_mesh::contact::ContactSurface;
use isochor_mesh::element::{RestGeometry, TetQuadrature};
use isochor_mesh::{ElementMesh, Vec3, Zones};
use std::sync::Arc;

pub mod cavities;
mod densities;
pub mod dofs;
pub mod pressure_gauges;
pub mod regions;
mod stacked;

use cavities::{Cavities, Cavity};
use densities::elastic_density;
use dofs::Dofs;
use pressure_gauges::{GaugedPressure, PressureGauge, PressureReading};
use regions::Regions;
use stacked::StackedConstraints;

/// How the nonlinear problem is solved.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum NonlinearScheme {
    /// Newton on the total energy (standard, condensed).
    Minimize,
    /// Saddle-point Newton with the full KKT system factorized (mixed methods).
    SaddleDirect,
    /// Saddle-point Newton with a Schur complement on the few constraint rows (zonal).
    SaddleSchur,
    /// Dual ascent around a primal Newton solve (dual).
    Dual,
}

/// The terms, constraints and DOFs of one problem.
#[derive(Debug)]
pub struct Model {
    pub mesh: ElementMesh,
    /// The rest geometry at each element's centroid (one-point rule), for element outputs.
    pub centroids: RestGeometry,
    pub method: Method,
    pub scheme: NonlinearScheme,
    pub terms: Vec<Box<dyn EnergyTerm>>,
    /// Constraints solved with multipliers (saddle point and dual): the method's, then the
    /// rows of the volume-controlled cavities.
    pub constraints: Option<Arc<dyn ConstraintSet>>,
    /// The volume-controlled cavities (their rows end [`Model::constraints`]).
    pub cavities: Option<Arc<Cavities>>,
    /// The gauge of every pressure load ([`Load::Pressure`] and [`Load::Cavity`]), in the
    /// order of the problem's loads.
    pub pressure_gauges: Vec<PressureGauge>,
    /// The constraints folded into the primal energy of the dual solver.
    pub augmented: Option<AugmentedConstraints>,
    /// Contact of the boundary vertices against the problem's obstacles.
    pub contact: Option<Contact>,
    /// Barrier contact between surfaces (between bodies, and of a surface with itself).
    pub surface_contact: Option<SurfaceContact>,
    /// Lagged friction between surfaces (with surface contact only).
    pub surface_friction: Option<SurfaceFriction>,
    /// Rest volume measured by each constraint row (scales the constraint residual).
    pub row_volumes: Vec<f64>,
    /// The material of every element (stresses and output pressures).
    pub regions: Regions,
    pub dofs: Dofs,
    /// Lumped (HRZ, positive) node masses.
    pub masses: Vec<f64>,
    /// The abscissae of every load, motion and obstacle curve: levels quasi-static stepping
    /// stops at, so that no corner of a load path is stepped over.
    pub curve_corners: Vec<f64>,
    mu: f64,
    /// The membrane stiffness `mu h` of the cloth sheet each node belongs to (0 off the
    /// sheets), in place of the solid's for its contact penalty.
    sheet_stiffness: Vec<f64>,
    /// The triangles of every cloth sheet, which join the boundary in surface contact.
    sheet_triangles: Vec<[usize; 3]>,
}

/// Contact penalty relative to the vertex stiffness (see [`Model::set_contact_stiffness`]).
const CONTACT_PENALTY: f64 = 100.0;

/// The rest volume measured by each row of `constraints`: by Euler's theorem for the
/// degree-3 homogeneous volume, `(G(X) X)_i = 3 V_i` for both the linear and the
/// logarithmic measure (1 for a row that measures none).
pub(crate) fn row_volumes(
    constraints: &dyn ConstraintSet,
    rest: &[Vec3],
) -> Result<Vec<f64>, SolverError> {
    let pattern = constraints.jacobian_pattern();
    let mut values = vec![0.0; pattern.len()];
    constraints.jacobian_values(rest, &mut values)?;
    let mut v = vec![0.0; constraints.num_constraints()];
    for (&(row, dof), g) in pattern.iter().zip(&values) {
        v[row] += g * rest[dof / 3][dof % 3] / 3.0;
    }
    // A row that measures no volume (a vertex in no element: a cloth's node) reads
    // `-C p = 0`; its residual is scaled by 1 rather than divided by zero.
    for volume in &mut v {
        if *volume == 0.0 {
            *volume = 1.0;
        }
    }
    Ok(v)
}

/// The diagonal of a compliance (lumped sets only).
fn diagonal(c: Compliance) -> Result<Vec<f64>, SolverError> {
    match c {
        Compliance::Diagonal(d) => Ok(d),
        Compliance::Sparse(_) => Err(SolverError::InvalidProblem(
            "this solver needs a lumped (diagonal) compliance".into(),
        )),
    }
}

/// `C_i^-1` for every row of a lumped compliance: the stiffness of static condensation
/// (eq. 37) or of a base Poisson ratio (sec. 8.3), `kappa / V_i` for one material and the
/// harmonic mean of the rows' elements for several.
fn inverse_diagonal(set: &dyn ConstraintSet) -> Result<Vec<f64>, SolverError> {
    Ok(diagonal(set.compliance())?
        .iter()
        .map(|c| 1.0 / c)
        .collect())
}

/// `volume` with its openings capped if `cap`, the error naming load `l`, pressure load `k`.
fn enclosed(
    volume: EnclosedVolume,
    cap: bool,
    l: usize,
    k: usize,
) -> Result<EnclosedVolume, SolverError> {
    if !cap {
        return Ok(volume);
    }
    volume.capped().map_err(|e| {
        SolverError::InvalidProblem(format!(
            "load {l} (pressure load {k}, loads.pressure.{k}.cap_openings of a scene): {}",
            message(e)
        ))
    })
}

/// The message of a problem error (without its `invalid problem:` prefix).
fn message(e: SolverError) -> String {
    match e {
        SolverError::InvalidProblem(m) => m,
        other => other.to_string(),
    }
}

impl Model {
    /// Sets the target volumes of the cavities at `level` (before evaluating the constraints
    /// of a step).
    pub fn set_load_level(&self, level: &LoadLevel) {
        if let Some(cavities) = &self.cavities {
            cavities.set_level(level);
        }
    }

    /// Every pressure load's pressure and enclosed volume ratio at positions `x`, load
    /// `level` and multipliers `multipliers`, in the order of the problem's loads.
    pub fn pressure_readings(
        &self,
        x: &[Vec3],
        level: &LoadLevel,
        multipliers: &[f64],
    ) -> Vec<PressureReading> {
        self.pressure_gauges
            .iter()
            .map(|g| g.read(x, level, multipliers))
            .collect()
    }

    /// Shear modulus of the model's material (the volume-weighted mean over the regions).
    pub fn mu(&self) -> f64 {
        self.mu
    }

    /// Builds the model of `problem` (checked by [`Problem::validate`] first: the caller
    /// runs it), with element Hessians projected to PSD if asked.
    pub fn new(problem: Problem, project_hessians: bool) -> Result<Self, SolverError> {
        let Problem {
            mesh,
            method,
            material,
            regions,
            zones,
            dirichlet,
            loads,
            obstacles,
            cloths,
        } = problem;
        let regions = Regions::new(&mesh, material.clone(), regions, |m| {
            elastic_density(method, m)
        })?;
        let curve_corners = loads
            .iter()
            .map(|l| l.curve.as_ref())
            .chain(dirichlet.iter().map(|d| d.curve.as_ref()))
            .chain(obstacles.iter().map(|o| o.curve.as_ref()))
            .flatten()
            .flat_map(|c| c.points().iter().map(|p| p.0))
            .collect();
        let dofs = Dofs::new(mesh.num_nodes(), &dirichlet)?;
        let density = regions.per_element(|m| m.density);
        let sheets = cloths
            .iter()
            .map(|c| {
                Cloth::new(mesh.nodes(), c.triangles.clone(), c.fabric, c.rest_scale).map_err(|e| {
                    SolverError::InvalidProblem(format!("cloth '{}': {}", c.name, message(e)))
                })
            })
            .collect::<Result<Vec<_>, _>>()?;
        // The sheets' lumped masses join the bodies' in the inertia and in gravity.
        let mut sheet_masses = vec![0.0; mesh.num_nodes()];
        for (sheet, spec) in sheets.iter().zip(&cloths) {
            sheet.add_lumped_masses(spec.density, &mut sheet_masses);
        }
        let with_sheets = |masses: Vec<f64>| -> Vec<f64> {
            masses
                .iter()
                .zip(&sheet_masses)
                .map(|(m, s)| m + s)
                .collect()
        };
        let masses = with_sheets(mesh.lumped_masses(&density));
        let mut sheet_stiffness = vec![0.0; mesh.num_nodes()];
        let mut sheet_nodes = Vec::new();
        let sheet_triangles = cloths
            .iter()
            .flat_map(|c| c.triangles.iter().copied())
            .collect();
        for sheet in &sheets {
            let nodes = sheet.nodes();
            nodes
                .iter()
                .for_each(|&v| sheet_stiffness[v] = sheet.membrane_stiffness());
            sheet_nodes.extend(nodes);
        }
        let mu = regions.mean_shear_modulus(&mesh);
        let most_incompressible = regions.most_incompressible();
        let unsupported = |reason| SolverError::Unsupported {
            method: method.name(),
            nu: most_incompressible.nu,
            reason,
        };

        // Every volumetric stiffness below comes from the regions' kappa, converted once.
        let kappa = regions.try_per_element(|m| m.mixed_kappa())?;
        let rule = |shape| exact_rule(mesh.kind(), shape);
        let nodal = |measure, kappa: &[f64], compliance| -> Result<NodalConstraints, SolverError> {
            Ok(NodalConstraints::on_regions(
                &mesh,
                rule(RowShape::Corners),
                measure,
                kappa,
                compliance,
            )?)
        };
        let mut constraints: Option<Arc<dyn ConstraintSet>> = None;
        let mut augmented = None;
        let scheme = match method {
            Method::Standard => NonlinearScheme::Minimize,
            Method::MixedP1 => {
                constraints = Some(Arc::new(nodal(
                    Measure::Linear,
                    &kappa,
                    material.nodal_compliance,
                )?));
                NonlinearScheme::SaddleDirect
            }
            Method::MixedP1Log => {
                constraints = Some(Arc::new(nodal(
                    Measure::Logarithmic,
                    &kappa,
                    material.nodal_compliance,
                )?));
                NonlinearScheme::SaddleDirect
            }
            Method::MixedP0 | Method::MixedP0Log if most_incompressible.nu >= 0.5 => {
                return Err(unsupported(
                    "element (P0) constraints with zero compliance over-constrain linear tets (about 5 tets, so 5 \
                     constraints, per 3 vertex DOFs): the system is singular and locks; use mixed-p1 or zonal",
                ));
            }
            Method::MixedP0 | Method::MixedP0Log => {
                let measure = if method == Method::MixedP0 {
                    Measure::Linear
                } else {
                    Measure::Logarithmic
                };
                constraints = Some(Arc::new(PerElementConstraints::on_regions(
                    &mesh,
                    rule(RowShape::One),
                    measure,
                    &kappa,
                )?));
                NonlinearScheme::SaddleDirect
            }
            Method::Condensed => {
                if most_incompressible.nu >= 0.5 {
                    return Err(unsupported(
                        "static condensation needs C^-1, which does not exist when C = 0; use mixed-p1 or dual",
                    ));
                }
                let set: Arc<dyn ConstraintSet> =
                    Arc::new(nodal(Measure::Linear, &kappa, NodalCompliance::Lumped)?);
                let stiffness = inverse_diagonal(set.as_ref())?;
                let zero = vec![0.0; stiffness.len()];
                augmented = Some(AugmentedConstraints::new(set, zero, stiffness));
                NonlinearScheme::Minimize
            }
            Method::Dual => {
                let set: Arc<dyn ConstraintSet> =
                    Arc::new(nodal(Measure::Linear, &kappa, NodalCompliance::Lumped)?);
                let c = diagonal(set.compliance())?;
                let stiffness = match material.dual_base_nu {
                    Some(nu) => {
                        let base = regions
                            .try_per_element(|m| isochor_energies::bulk_modulus(m.young(), nu))?;
                        inverse_diagonal(&nodal(Measure::Linear, &base, NodalCompliance::Lumped)?)?
                    }
                    None => vec![0.0; c.len()],
                };
                augmented = Some(AugmentedConstraints::new(set.clone(), c, stiffness));
                constraints = Some(set);
                NonlinearScheme::Dual
            }
            Method::Zonal => {
                let zones = zones.unwrap_or_else(|| Zones::global(mesh.corners()));
                if zones.is_empty() {
                    // "Ours without volume constraint" (Table 1 of Sheen et al. 2021): the
                    // F-bar energy with lambda U(J; beta) alone, which must then hold volume.
                    let volume_free = regions.materials().iter().any(|m| {
                        m.zonal_energy == ZonalEnergy::Constrained && m.zonal_lambda == 0.0
                    });
                    if volume_free {
                        return Err(unsupported(
                            "without zones and with lambda = 0 nothing resists a change of volume (the F-bar \
                             energy is distortional): the problem is singular; give lambda > 0 or a zone",
                        ));
                    }
                    NonlinearScheme::Minimize
                } else {
                    constraints = Some(Arc::new(ZonalConstraints::on_elements(
                        &mesh,
                        rule(RowShape::One),
                        &zones,
                    )?));
                    NonlinearScheme::SaddleSchur
                }
            }
        };

        let mut terms: Vec<Box<dyn EnergyTerm>> = vec![Box::new(Elastic::with_materials(
            &mesh,
            regions.energies().to_vec(),
            regions.element_regions().to_vec(),
            project_hessians,
        )?)];
        if let Some(skin) = material.epidermis {
            let skin = isochor_energies::Epidermis::from_young_poisson(
                skin.young,
                skin.poisson,
                skin.gamma,
            )?;
            terms.push(Box::new(EpidermisTerm::new(&mesh, skin)?));
        }
        for sheet in sheets {
            terms.push(Box::new(sheet));
        }
        let mut cavities = Vec::new();
        let mut pressure_gauges = Vec::new();
        for (l, ScheduledLoad { load, curve }) in loads.into_iter().enumerate() {
            terms.push(match load {
                Load::Gravity(g) => {
                    let weights = with_sheets(mesh.node_masses(&density));
                    Box::new(DeadLoad::gravity(&weights, g).following(curve))
                }
                Load::Traction { faces, traction } => Box::new(
                    DeadLoad::traction(mesh.nodes(), &Faces::new(&mesh, &faces)?, traction)
                        .following(curve),
                ),
                Load::Pressure {
                    faces,
                    pressure,
                    origin,
                    cap_openings,
                } => {
                    let faces = Faces::new(&mesh, &faces)?;
                    let k = pressure_gauges.len();
                    let volume = enclosed(EnclosedVolume::new(faces, origin), cap_openings, l, k)?;
                    let given = GaugedPressure::Given {
                        pressure,
                        curve: curve.clone(),
                    };
                    pressure_gauges.push(PressureGauge::new(volume.clone(), given, mesh.nodes()));
                    Box::new(FollowerPressure::on(volume, pressure).following(curve))
                }
                Load::Cavity {
                    faces,
                    volume_ratio,
                    origin,
                    cap_openings,
                } => {
                    let k = pressure_gauges.len();
                    let volume = EnclosedVolume::new(Faces::new(&mesh, &faces)?, origin);
                    let volume = enclosed(volume, cap_openings, l, k)?;
                    let cavity = Cavity::new(volume.clone(), volume_ratio, curve, mesh.nodes())
                        .map_err(|e| {
                            SolverError::InvalidProblem(format!(
                                "load {l} (pressure load {k}, loads.pressure.{k} of a scene): {}",
                                message(e)
                            ))
                        })?;
                    let row = GaugedPressure::Solved {
                        row: cavities.len(),
                    };
                    pressure_gauges.push(PressureGauge::new(volume, row, mesh.nodes()));
                    cavities.push(cavity);
                    continue;
                }
            });
        }
        let method_rows = constraints.as_ref().map_or(0, |c| c.num_constraints());
        let mut rows = constraints
            .as_deref()
            .or(augmented.as_ref().map(|a| a.constraints()))
            .map(|c| row_volumes(c, mesh.nodes()))
            .transpose()?
            .unwrap_or_default();
        if constraints.is_none() && !cavities.is_empty() {
            // Condensed: its folded rows have no multipliers, the cavities' rows do.
            rows.clear();
        }
        let cavities =
            (!cavities.is_empty()).then(|| Arc::new(Cavities::new(cavities, mesh.num_elements())));
        if let Some(cavities) = &cavities {
            if scheme == NonlinearScheme::Dual {
                return Err(SolverError::InvalidProblem(
                    "method dual cannot hold a cavity at a volume (loads.pressure volume_ratio): its \
                     dual ascent needs a compliance for every multiplier, and a cavity's row is hard; \
                     use mixed-p1 (or any other method) or a given pressure"
                        .into(),
                ));
            }
            for gauge in &mut pressure_gauges {
                gauge.offset_row(method_rows);
            }
            constraints = Some(match constraints.take() {
                Some(method) => Arc::new(StackedConstraints::new(method, cavities.clone())),
                None => cavities.clone(),
            });
        }
        let scheme = match (scheme, &cavities) {
            (NonlinearScheme::Minimize, Some(_)) => NonlinearScheme::SaddleDirect,
            (scheme, _) => scheme,
        };
        if let Some(cavities) = &cavities {
            rows.extend(cavities.cavities().iter().map(Cavity::rest_volume));
        }
        let contact = (!obstacles.is_empty())
            .then(|| -> Result<Contact, SolverError> {
                let mut nodes = mesh.boundary()?.nodes();
                nodes.extend(&sheet_nodes);
                Ok(Contact::new(nodes, obstacles, Vec::new()))
            })
            .transpose()?;
        let centroids = mesh.rest_geometry(TetQuadrature::Degree1)?;
        let mut model = Model {
            mesh,
            centroids,
            method,
            scheme,
            terms,
            constraints,
            cavities,
            pressure_gauges,
            augmented,
            row_volumes: rows,
            regions,
            dofs,
            masses,
            curve_corners,
            mu,
            sheet_stiffness,
            sheet_triangles,
            contact,
            surface_contact: None,
            surface_friction: None,
        };
        model.set_contact_stiffness(None);
        Ok(model)
    }

    /// Turns barrier contact between the boundary surfaces on (every 6-node face as its four
    /// 3-node triangles) and the cloth sheets' triangles (two-sided: the distance is to the
    /// triangle), its stiffness bounded for the shear stiffness `mu h` of a node's cells (Li
    /// et al. 2020, supplement).
    pub fn set_surface_contact(&mut self, spec: SurfaceContactSpec) -> Result<(), SolverError> {
        let boundary = ContactSurface::from_element_surface(&self.mesh.boundary()?);
        let mut triangles = boundary.triangles().to_vec();
        triangles.extend(&self.sheet_triangles);
        let surface = ContactSurface::from_triangles(triangles);
        let corners = self.mesh.corners();
        let h = (6.0 * corners.rest_volume() / corners.num_tets().max(1) as f64).cbrt();
        let contact = SurfaceContact::new(spec, surface, self.mesh.nodes().to_vec(), self.mu * h)?;
        self.surface_contact = Some(contact);
        Ok(())
    }

    /// Turns friction on: against the obstacles (with a non-zero coefficient), and between
    /// surfaces (needs surface contact, [`Model::set_surface_contact`], first).
    pub fn set_friction(&mut self, spec: FrictionSpec) -> Result<(), SolverError> {
        spec.validate()?;
        match &mut self.contact {
            Some(contact) => contact.set_friction(spec.obstacles, spec.epsv)?,
            None if !spec.obstacles.is_empty() => {
                return Err(SolverError::InvalidProblem(format!(
                    "friction: {} obstacle coefficients for a problem without obstacles",
                    spec.obstacles.len()
                )))
            }
            None => {}
        }
        self.surface_friction = match spec.surfaces {
            None => None,
            Some(_) if self.surface_contact.is_none() => {
                return Err(SolverError::InvalidProblem(
                    "friction between surfaces needs surface contact".into(),
                ))
            }
            Some(surfaces) => Some(SurfaceFriction::new(surfaces, spec.epsv)),
        };
        Ok(())
    }

    /// Adds meshed rigid obstacles to the barrier contact of [`Self::set_surface_contact`]
    /// (which must be on).
    pub fn set_mesh_obstacles(&mut self, obstacles: Vec<MeshObstacle>) -> Result<(), SolverError> {
        let Some(contact) = self.surface_contact.take() else {
            return Err(SolverError::InvalidProblem(
                "meshed obstacles need surface contact: turn it on first".into(),
            ));
        };
        self.surface_contact = Some(contact.with_obstacles(obstacles)?);
        Ok(())
    }

    /// Sets the contact penalty of every candidate vertex to
    /// `rho_i = CONTACT_PENALTY (mu h + m_i / dt^2)`: a multiple of the stiffness a unit
    /// normal displacement of the vertex meets (shear stiffness of its cells of size `h`,
    /// plus its inertia in implicit Euler). Large enough that each multiplier update cuts
    /// the penetration by orders of magnitude, small enough to keep the Newton matrices well
    /// conditioned next to the volumetric stiffness (`lambda h` up to `1e4 mu h`).
    pub fn set_contact_stiffness(&mut self, dt: Option<f64>) {
        let corners = self.mesh.corners();
        let h = (6.0 * corners.rest_volume() / corners.num_tets().max(1) as f64).cbrt();
        let elastic = self.mu * h;
        if let Some(contact) = &mut self.contact {
            let stiffness = contact
                .vertices()
                .iter()
                .map(|&v| {
                    let inertia = dt.map_or(0.0, |dt| self.masses[v] / (dt * dt));
                    let sheet = self.sheet_stiffness[v];
                    let elastic = if sheet > 0.0 { sheet } else { elastic };
                    CONTACT_PENALTY * (elastic + inertia)
                })
                .collect();
            contact.set_stiffness(stiffness);
        }
    }
}
