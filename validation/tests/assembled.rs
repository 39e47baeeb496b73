//! The assembled Newton system of every method against central differences of its assembled
//! residual: what the solvers factorize after Dirichlet elimination (`K_ff`, `G_f`, the
//! compliance block `-C`), what they move to the right-hand side (`K_fc`, `G_c` applied to
//! the prescribed increments), quasi-static (eq. 24 of Francu et al. 2021) and in implicit
//! Euler (eq. 21: `M / dt^2` added to `K`). The term harness (`terms.rs`) checks each term
//! alone; this checks their assembly, the constraints' Jacobian and geometric stiffness as
//! the saddle-point solver couples them, and the elimination of the prescribed DOFs. A wrong
//! but convergent Jacobian slows Newton down without changing its answer, so only this test
//! sees it.

use isochor_mesh::Vec3;
use isochor_solvers::{
    Dirichlet, Load, Material, Method, Motion, NewtonSystem, Problem, Settings, Simulation, State,
    Stepping,
};
use isochor_validation::fd;
use isochor_validation::strategies::{deformed_box, Deformed};
use nalgebra::{DMatrix, DVector};
use proptest::prelude::*;
use std::cell::RefCell;

/// Required agreement of each block, relative to its max norm: the bound of the term
/// harness (`terms.rs`). With steps of `fd::STEP` (1e-6 of the unit box, of the pressure
/// scale), truncation is O(1e-12) and rounding O(1e-16 / 1e-6) = O(1e-10) times the
/// cancellation between the residual's terms (`lambda / mu` = 50 at `nu = 0.49`), both far
/// below; a term off by 0.1% is 1e-3 of its block or more.
const TOLERANCE: f64 = 1e-6;

/// Young's modulus (Pa) of the unit box; `mu` = E / (2 (1 + nu)) sets the pressure scale.
const YOUNG: f64 = 1e5;
const NU: f64 = 0.49;

/// Time step of the dynamic check: `M / dt^2` (vertex masses from 5 kg, a quarter of a
/// 1/48 m^3 tet of 1000 kg/m^3: 5e4 N/m and up) is of the order of the elastic stiffness
/// (`mu h` = 1.7e4 N/m to `lambda h` = 8e5 N/m for cells of 0.5 m), so neither hides the other.
const DT: f64 = 0.01;

/// The unit box of `deformed` clamped at `x = 0`, under gravity and a dead traction on `x = 1`;
/// with `cavity`, its boundary faces turned inside out (enclosing the box's volume) held at
/// 1.5 times their volume about a point off the box (a row of the volume control of a
/// cavity, its multiplier the cavity's pressure).
fn problem(deformed: &Deformed, method: Method, cavity: bool) -> Problem {
    let mesh = deformed.mesh.clone();
    let rest = mesh.positions();
    let on = |v: usize, x: f64| (rest[v].x - x).abs() < 1e-12;
    let clamped = (0..mesh.num_vertices()).filter(|&v| on(v, 0.0)).collect();
    let end = mesh
        .boundary()
        .expect("box boundary")
        .triangles()
        .iter()
        .filter(|f| f.iter().all(|&v| on(v, 1.0)))
        .copied()
        .collect();
    let mut loads = vec![
        Load::Gravity(Vec3::new(0.0, 0.0, -9.8)).into(),
        Load::Traction {
            faces: end,
            traction: Vec3::new(2e3, 1e3, 0.0),
        }
        .into(),
    ];
    if cavity {
        let boundary = mesh.boundary().expect("box boundary");
        loads.push(
            Load::Cavity {
                faces: boundary
                    .triangles()
                    .iter()
                    .map(|&[a, b, c]| [a, c, b])
                    .collect(),
                volume_ratio: 1.5,
                origin: Vec3::new(0.3, -0.2, 1.4),
                cap_openings: false,
            }
            .into(),
        );
    }
    Problem {
        method,
        material: Material::from_young_poisson(YOUNG, NU, 1000.0).expect("material"),
        regions: Vec::new(),
        zones: None,
        dirichlet: vec![Dirichlet {
            nodes: clamped,
            axes: [true; 3],
            motion: Motion::Fixed,
            curve: None,
        }],
        loads,
        obstacles: Vec::new(),
        mesh: mesh.into(),
        cloths: Vec::new(),
    }
}

/// Relative errors of the blocks of one system against central differences.
#[derive(Debug, Default, Clone, Copy)]
struct Errors {
    /// `d sigma_f / d x_f` against `K_ff` (with `M / dt^2` and the geometric stiffness).
    k: f64,
    /// `d sigma_f / d p` against `G_f^T`.
    gt: f64,
    /// `d theta / d x_f` against `G_f`.
    g: f64,
    /// `d theta / d p` against `-C`.
    c: f64,
    /// `d sigma_f / d x_c` along the prescribed increments against `K_fc gap`, moved to
    /// the right-hand side.
    k_coupling: f64,
    /// `d theta / d x_c` along the prescribed increments against `G_c gap`.
    g_coupling: f64,
}

impl std::fmt::Display for Errors {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "K {:.1e}, G^T {:.1e}, G {:.1e}, -C {:.1e}, K_fc {:.1e}, G_c {:.1e}",
            self.k, self.gt, self.g, self.c, self.k_coupling, self.g_coupling
        )
    }
}

impl Errors {
    fn max(self) -> f64 {
        [
            self.k,
            self.gt,
            self.g,
            self.c,
            self.k_coupling,
            self.g_coupling,
        ]
        .into_iter()
        .fold(0.0, f64::max)
    }
}

/// Block relative error, the scale floored at the smallest normal number so that two zero
/// blocks (`C` of `zonal`) agree exactly. Each block has its own units (`K` in N/m, `G` in
/// m^2, `C` in m^3/Pa), so each is measured against its own size.
fn block(a: &DMatrix<f64>, b: &DMatrix<f64>, rows: (usize, usize), cols: (usize, usize)) -> f64 {
    let view = |m: &DMatrix<f64>| m.view((rows.0, cols.0), (rows.1, cols.1)).into_owned();
    fd::relative_error(&view(a), &view(b), f64::MIN_POSITIVE)
}

/// Checks the Newton system of `method` at the state `(deformed.x, pressures)` in the first
/// step of `stepping`.
fn check(
    deformed: &Deformed,
    pressures: &[f64],
    method: Method,
    stepping: Stepping,
    cavity: bool,
) -> Errors {
    let problem = problem(deformed, method, cavity);
    let mut sim = Simulation::new(problem, Settings::default()).expect("model");
    let mu = YOUNG / (2.0 * (1.0 + NU));
    let trial = State {
        positions: deformed.x.clone(),
        multipliers: (sim.state().multipliers.iter().zip(pressures))
            .map(|(_, p)| p * mu)
            .collect(),
        ..sim.state().clone()
    };
    let linearizer = RefCell::new(sim.linearizer(stepping, 1).expect("linearizer"));
    let system = |state: &State| -> NewtonSystem {
        linearizer
            .borrow_mut()
            .newton_system(state)
            .expect("newton system")
    };
    let at = system(&trial);
    let free = at.free.clone();
    let nf = free.len();
    // Multipliers are unknowns of the saddle-point systems only (not of dual's primal one).
    let m = at.residual.len() - nf;
    // Unknowns scaled to order one: positions in units of the box, pressures of `mu`.
    let unscale = |z: &DVector<f64>| {
        let mut s = trial.clone();
        for (k, &dof) in free.iter().enumerate() {
            s.positions[dof / 3][dof % 3] = z[k];
        }
        for (i, p) in s.multipliers.iter_mut().take(m).enumerate() {
            *p = z[nf + i] * mu;
        }
        s
    };
    let z0 = DVector::from_iterator(
        nf + m,
        free.iter()
            .map(|&d| trial.positions[d / 3][d % 3])
            .chain(trial.multipliers.iter().take(m).map(|p| p / mu)),
    );
    let residual = |z: &DVector<f64>| DVector::from_vec(system(&unscale(z)).residual);
    let mut numeric = fd::jacobian(residual, &z0, fd::STEP);
    let mut pressure_columns = numeric.columns_mut(nf, m);
    pressure_columns /= mu;
    // The coupling: the residual's derivative along the prescribed increments against
    // `-(rhs + residual) = K_fc gap` (and `G_c gap`).
    let along = |s: f64| {
        let mut state = trial.clone();
        for (dof, g) in at.gap.iter().enumerate() {
            state.positions[dof / 3][dof % 3] += s * g;
        }
        DVector::from_vec(system(&state).residual)
    };
    let coupling_fd = (along(fd::STEP) - along(-fd::STEP)) / (2.0 * fd::STEP);
    let coupling = -(DVector::from_vec(at.rhs.clone()) + DVector::from_vec(at.residual.clone()));
    let rows = |v: &DVector<f64>, start: usize, len: usize| v.rows(start, len).into_owned();
    // Measured against the size of the block times the increments', not of their product
    // alone: moving the prescribed nodes may barely change a zone's volume (the product
    // cancels), and the central differences' absolute error is of the factors' size.
    let gap_size = at.gap.iter().fold(0.0f64, |a, g| a.max(g.abs()));
    let coupling_error = |start, len| {
        let (a, b) = (rows(&coupling, start, len), rows(&coupling_fd, start, len));
        let block_size = at.matrix.view((start, 0), (len, nf)).amax();
        fd::relative_error_vec(&a, &b, (block_size * gap_size).max(f64::MIN_POSITIVE))
    };
    Errors {
        k: block(&at.matrix, &numeric, (0, nf), (0, nf)),
        gt: block(&at.matrix, &numeric, (0, nf), (nf, m)),
        g: block(&at.matrix, &numeric, (nf, m), (0, nf)),
        c: block(&at.matrix, &numeric, (nf, m), (nf, m)),
        k_coupling: coupling_error(0, nf),
        g_coupling: coupling_error(nf, m),
    }
}

/// Random states per method: each checks the quasi-static and the dynamic system.
const CASES: u32 = 4;

/// Checks `method` at one random state, quasi-static (load 1/2) and implicit Euler.
fn property(
    method: Method,
    deformed: &Deformed,
    pressures: &[f64],
    cavity: bool,
) -> Result<(), TestCaseError> {
    for stepping in [
        Stepping::quasi_static(2),
        Stepping::ImplicitEuler { dt: DT, frames: 1 },
    ] {
        let errors = check(deformed, pressures, method, stepping, cavity);
        eprintln!("{method} {stepping:?}: {errors}");
        prop_assert!(errors.max() < TOLERANCE, "{method} {stepping:?}: {errors}");
    }
    Ok(())
}

/// A deformed unit box of 2 x 2 x 2 cells (48 tets, every tet's volume ratio at least 0.6)
/// and pressures in units of `mu`, one per tet at most (P0).
fn state() -> impl Strategy<Value = (Deformed, Vec<f64>)> {
    (
        deformed_box([2, 2, 2], 0.08, 0.6),
        proptest::collection::vec(-1.0..1.0f64, 48),
    )
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(CASES))]

    /// Displacement-only Newton: `K_ff` and `K_fc` of the neo-Hookean energy.
    #[test]
    fn standard_system_matches_finite_differences((deformed, p) in state()) {
        property(Method::Standard, &deformed, &p, false)?;
    }

    /// Nodal pressures, linear measure: `K + K_g`, `G`, consistent `-C`.
    #[test]
    fn mixed_p1_system_matches_finite_differences((deformed, p) in state()) {
        property(Method::MixedP1, &deformed, &p, false)?;
    }

    /// Element pressures, linear measure.
    #[test]
    fn mixed_p0_system_matches_finite_differences((deformed, p) in state()) {
        property(Method::MixedP0, &deformed, &p, false)?;
    }

    /// Nodal pressures, logarithmic measure (sec. 6).
    #[test]
    fn mixed_p1_log_system_matches_finite_differences((deformed, p) in state()) {
        property(Method::MixedP1Log, &deformed, &p, false)?;
    }

    /// Element pressures, logarithmic measure.
    #[test]
    fn mixed_p0_log_system_matches_finite_differences((deformed, p) in state()) {
        property(Method::MixedP0Log, &deformed, &p, false)?;
    }

    /// Static condensation (eq. 37): the folded constraints with zero multipliers.
    #[test]
    fn condensed_system_matches_finite_differences((deformed, p) in state()) {
        property(Method::Condensed, &deformed, &p, false)?;
    }

    /// The primal problem of dual ascent (eq. 39) at random multipliers, augmented (sec. 8.3).
    #[test]
    fn dual_inner_system_matches_finite_differences((deformed, p) in state()) {
        property(Method::Dual, &deformed, &p, false)?;
    }

    /// F-bar energy under one global zone constraint (`C = 0`).
    #[test]
    fn zonal_system_matches_finite_differences((deformed, p) in state()) {
        property(Method::Zonal, &deformed, &p, false)?;
    }

    /// A volume-controlled cavity's row (the cone volume about an origin off the body) with
    /// the methods it joins: alone (standard, condensed: saddle-point Newton on that row),
    /// after the nodal rows (mixed-p1), after the zone's (zonal).
    #[test]
    fn systems_with_a_cavity_match_finite_differences((deformed, p) in state()) {
        for method in [Method::Standard, Method::Condensed, Method::MixedP1, Method::Zonal] {
            property(method, &deformed, &p, true)?;
        }
    }
}
