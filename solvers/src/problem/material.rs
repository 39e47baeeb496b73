//! Material parameters: the hyperelastic model, its moduli and the settings of each method's
//! volumetric part.

use super::material_model::MaterialModel;
use isochor_constraints::NodalCompliance;
use isochor_energies::{bulk_modulus, Lame, ParameterError};

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

    /// A material of a model with its own constants ([`MaterialModel::MooneyRivlin`],
    /// [`MaterialModel::Yeoh`], [`MaterialModel::Ogden`]): `mu` is the initial shear modulus
    /// they set, Poisson's ratio `nu` gives the volumetric stiffness, and the other
    /// parameters are the defaults of [`Material::from_young_poisson`] at `E = 2 mu (1 + nu)`.
    ///
    /// Errors: a model whose parameter is `mu` itself (state it with
    /// [`Material::from_young_poisson`] and [`Material::with_model`]), or constants that give
    /// no positive shear modulus.
    ///
    /// ```
    /// use isochor_solvers::{Material, MaterialModel};
    ///
    /// let terms = vec![(2e4, 2.0), (-1e3, -2.0)];
    /// let rubber = Material::from_model(MaterialModel::Ogden { terms }, 0.49, 1100.0)?;
    /// assert!((rubber.mu - 0.5 * (2e4 * 2.0 + 1e3 * 2.0)).abs() < 1e-9);
    /// assert!(Material::from_model(MaterialModel::NeoHookean, 0.49, 1100.0).is_err());
    /// # Ok::<(), isochor_energies::ParameterError>(())
    /// ```
    pub fn from_model(model: MaterialModel, nu: f64, density: f64) -> Result<Self, ParameterError> {
        model.validate()?;
        let mu = model.shear_modulus().ok_or(ParameterError {
            name: "model",
            value: f64::NAN,
            reason: "this model's parameter is mu: use Material::from_young_poisson",
        })?;
        if !(mu.is_finite() && mu > 0.0) {
            return Err(ParameterError {
                name: "mu",
                value: mu,
                reason: "the model's constants must give a finite, positive initial shear modulus",
            });
        }
        Material::from_young_poisson(2.0 * mu * (1.0 + nu), nu, density)?.with_model(model)
    }

    /// A Mooney-Rivlin material `c10 (Ib1 - 3) + c01 (Ib2 - 3)` (Pa) with Poisson's ratio `nu`
    /// and density `density` (see [`Material::from_model`]).
    ///
    /// ```
    /// use isochor_solvers::Material;
    ///
    /// let silicone = Material::mooney_rivlin(1.2e4, 3e3, 0.499, 1070.0)?;
    /// assert!((silicone.mu - 3e4).abs() < 1e-9); // mu = 2 (c10 + c01)
    /// # Ok::<(), isochor_energies::ParameterError>(())
    /// ```
    pub fn mooney_rivlin(
        c10: f64,
        c01: f64,
        nu: f64,
        density: f64,
    ) -> Result<Self, ParameterError> {
        Material::from_model(MaterialModel::MooneyRivlin { c10, c01 }, nu, density)
    }

    /// A Yeoh material `c10 (Ib1 - 3) + c20 (Ib1 - 3)^2 + c30 (Ib1 - 3)^3` (Pa) with Poisson's
    /// ratio `nu` and density `density` (see [`Material::from_model`]).
    ///
    /// ```
    /// use isochor_solvers::Material;
    ///
    /// // Ecoflex-like constants; no Young's modulus is needed.
    /// let ecoflex = Material::yeoh(1.1e4, 2.0e2, 0.0, 0.499, 1070.0)?;
    /// assert!((ecoflex.mu - 2.2e4).abs() < 1e-9); // mu = 2 c10
    /// assert!(Material::yeoh(-1.0, 0.0, 0.0, 0.499, 1070.0).is_err());
    /// # Ok::<(), isochor_energies::ParameterError>(())
    /// ```
    pub fn yeoh(
        c10: f64,
        c20: f64,
        c30: f64,
        nu: f64,
        density: f64,
    ) -> Result<Self, ParameterError> {
        Material::from_model(MaterialModel::Yeoh { c10, c20, c30 }, nu, density)
    }

    /// An Ogden material with the terms `(mu_p, alpha_p)` (Pa, dimensionless), Poisson's ratio
    /// `nu` and density `density` (see [`Material::from_model`]).
    pub fn ogden(terms: Vec<(f64, f64)>, nu: f64, density: f64) -> Result<Self, ParameterError> {
        Material::from_model(MaterialModel::Ogden { terms }, nu, density)
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
