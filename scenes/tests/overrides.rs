//! Every flat `--set` key ([`flat_keys`]: `FLAT_KEYS` and the models' constants) reaches what the solver is given: set on a built-in
//! scene, its value is read back from the built problem, stepping and settings (or, for the
//! output keys, from the loaded scene), and was not there before. A bad value for each key is
//! an error that names the key.

use isochor_mesh::{Vec3, Zones};
use isochor_scenes::format::overrides::flat_keys;
use isochor_scenes::format::{PreviewField, VtuEncodingName};
use isochor_scenes::resolve::{build, ResolvedScene};
use isochor_scenes::{load_scene, Override, Scene, SceneError};
use isochor_solvers::{
    Epidermis, Kappa, LinearSolver, Load, MaterialModel, Method, Simulation, StepControl, Stepping,
    VolumeProjection, ZonalEnergy,
};

/// One flat key: the scene and overrides it needs first, a value that differs from the
/// scene's own, how to read it back, and a value that must be refused.
struct Case {
    key: &'static str,
    scene: &'static str,
    setup: &'static [&'static str],
    value: &'static str,
    reached: fn(&Scene, &ResolvedScene) -> bool,
    bad: &'static str,
}

/// A coarse cantilever (24 tets, `mixed-p1`, quasi-static).
const STATIC: &str = "cantilever";
/// A coarse falling cube (48 tets, `zonal`, implicit Euler).
const DYNAMIC: &str = "dynamic-cube";

fn iterative(s: &ResolvedScene) -> Option<(f64, usize)> {
    match s.settings.linear {
        LinearSolver::Iterative(i) => Some((i.tolerance, i.max_iterations)),
        LinearSolver::Direct | LinearSolver::Auto(_) => None,
    }
}

fn k_ring(b: &ResolvedScene, k: usize) -> bool {
    b.problem.zones == Some(Zones::k_ring_cover(b.problem.mesh.corners(), k).unwrap())
}

fn epidermis(b: &ResolvedScene) -> Option<Epidermis> {
    b.problem.material.epidermis
}

const CASES: &[Case] = &[
    Case {
        key: "method",
        scene: STATIC,
        setup: &[],
        value: "standard",
        reached: |_, b| b.problem.method == Method::Standard,
        bad: "newton",
    },
    Case {
        key: "element",
        scene: STATIC,
        setup: &[],
        value: "tet10",
        reached: |_, b| b.problem.mesh.kind() == isochor_mesh::element::TetElement::Tet10,
        bad: "hex8",
    },
    Case {
        key: "nu",
        scene: STATIC,
        setup: &[],
        value: "0.45",
        reached: |_, b| b.problem.material.nu == 0.45,
        bad: "0.7",
    },
    Case {
        key: "E",
        scene: STATIC,
        setup: &[],
        value: "1.5e5",
        reached: |_, b| (b.problem.material.young() - 1.5e5).abs() <= 1e-15 * 1.5e5,
        bad: "-1.0",
    },
    Case {
        key: "young",
        scene: STATIC,
        setup: &[],
        value: "2.5e5",
        reached: |_, b| (b.problem.material.young() - 2.5e5).abs() <= 1e-15 * 2.5e5,
        bad: "soft",
    },
    Case {
        key: "mu",
        scene: STATIC,
        setup: &[],
        value: "7e4",
        reached: |_, b| b.problem.material.mu == 7e4,
        bad: "-5.0",
    },
    Case {
        key: "model",
        scene: STATIC,
        setup: &[],
        value: "stable-neo-hookean",
        reached: |_, b| b.problem.material.model == MaterialModel::StableNeoHookean,
        bad: "rubber",
    },
    Case {
        key: "c10",
        scene: STATIC,
        setup: &["model=mooney-rivlin", "c10=2e4"],
        value: "4e4",
        reached: |_, b| b.problem.material.mu == 8e4,
        bad: "-1e5",
    },
    Case {
        key: "c01",
        scene: STATIC,
        setup: &["model=mooney-rivlin", "c10=4e4"],
        value: "1e4",
        reached: |_, b| {
            b.problem.material.model == MaterialModel::MooneyRivlin { c10: 4e4, c01: 1e4 }
        },
        bad: "\"stiff\"",
    },
    Case {
        key: "c20",
        scene: STATIC,
        setup: &["model=yeoh", "c10=4e4"],
        value: "-1e3",
        reached: |_, b| matches!(b.problem.material.model, MaterialModel::Yeoh { c20, .. } if c20 == -1e3),
        bad: "\"x\"",
    },
    Case {
        key: "c30",
        scene: STATIC,
        setup: &["model=yeoh", "c10=4e4"],
        value: "1e2",
        reached: |_, b| matches!(b.problem.material.model, MaterialModel::Yeoh { c30, .. } if c30 == 1e2),
        bad: "\"x\"",
    },
    Case {
        key: "ogden",
        scene: STATIC,
        setup: &["model=ogden", "ogden=[[2e4, 2.0]]"],
        value: "[[8e4, 1.3], [-1e3, -2.0]]",
        reached: |_, b| b.problem.material.mu == 0.5 * (8e4 * 1.3 + 2e3),
        bad: "[[1e4, 0.0]]",
    },
    Case {
        key: "rho",
        scene: STATIC,
        setup: &[],
        value: "1200.0",
        reached: |_, b| b.problem.material.density == 1200.0,
        bad: "-1.0",
    },
    Case {
        key: "density",
        scene: STATIC,
        setup: &[],
        value: "900.0",
        reached: |_, b| b.problem.material.density == 900.0,
        bad: "heavy",
    },
    Case {
        key: "zonal_penalty",
        scene: STATIC,
        setup: &[],
        value: "3e5",
        reached: |_, b| b.problem.material.zonal_lambda == 3e5,
        bad: "-1.0",
    },
    // The old spelling of `zonal_penalty`.
    Case {
        key: "lambda",
        scene: STATIC,
        setup: &[],
        value: "3e5",
        reached: |_, b| b.problem.material.zonal_lambda == 3e5,
        bad: "-1.0",
    },
    Case {
        key: "beta",
        scene: STATIC,
        setup: &[],
        value: "4.0",
        reached: |_, b| b.problem.material.beta == 4.0,
        bad: "-1.0",
    },
    Case {
        key: "epsilon",
        scene: STATIC,
        setup: &[],
        value: "0.2",
        reached: |_, b| b.problem.material.epsilon == 0.2,
        bad: "1.5",
    },
    Case {
        key: "kappa",
        scene: STATIC,
        setup: &[],
        value: "lambda",
        reached: |_, b| b.problem.material.kappa == Kappa::Lambda,
        bad: "shear",
    },
    Case {
        key: "zonal_energy",
        scene: STATIC,
        setup: &[],
        value: "standard",
        reached: |_, b| b.problem.material.zonal_energy == ZonalEnergy::Standard,
        bad: "elastic",
    },
    Case {
        key: "dual_base_nu",
        scene: STATIC,
        setup: &[],
        value: "0.3",
        reached: |_, b| b.problem.material.dual_base_nu == Some(0.3),
        bad: "0.6",
    },
    Case {
        key: "epidermis",
        scene: STATIC,
        setup: &[],
        value: "true",
        reached: |_, b| {
            epidermis(b)
                == Some(Epidermis {
                    young: 266e3,
                    poisson: 0.45,
                    gamma: 1.0,
                })
        },
        bad: "yes",
    },
    Case {
        key: "epidermis_young",
        scene: STATIC,
        setup: &["epidermis=true"],
        value: "5e4",
        reached: |_, b| epidermis(b).is_some_and(|e| e.young == 5e4),
        bad: "-1.0",
    },
    Case {
        key: "epidermis_nu",
        scene: STATIC,
        setup: &["epidermis=true"],
        value: "0.3",
        reached: |_, b| epidermis(b).is_some_and(|e| e.poisson == 0.3),
        bad: "0.7",
    },
    Case {
        key: "epidermis_gamma",
        scene: STATIC,
        setup: &["epidermis=true"],
        value: "2.0",
        reached: |_, b| epidermis(b).is_some_and(|e| e.gamma == 2.0),
        bad: "-1.0",
    },
    Case {
        key: "gravity",
        scene: STATIC,
        setup: &[],
        value: "[0.0, 0.0, -3.7]",
        reached: |_, b| b.problem.loads == [Load::Gravity(Vec3::new(0.0, 0.0, -3.7)).into()],
        bad: "[0.0, -9.8]",
    },
    Case {
        key: "steps",
        scene: STATIC,
        setup: &[],
        value: "7",
        reached: |_, b| b.stepping == Stepping::adaptive(7),
        bad: "0",
    },
    Case {
        key: "increments",
        scene: STATIC,
        setup: &["steps=3"],
        value: "\"fixed\"",
        reached: |_, b| b.stepping == Stepping::quasi_static(3),
        bad: "\"sometimes\"",
    },
    Case {
        key: "first_increment",
        scene: STATIC,
        setup: &[],
        value: "0.25",
        reached: |_, b| matches!(b.stepping, Stepping::QuasiStatic { control: StepControl::Adaptive(a), .. } if a.first == 0.25),
        bad: "1.5",
    },
    Case {
        key: "min_increment",
        scene: STATIC,
        setup: &[],
        value: "0.01",
        reached: |_, b| matches!(b.stepping, Stepping::QuasiStatic { control: StepControl::Adaptive(a), .. } if a.min == 0.01),
        bad: "0",
    },
    Case {
        key: "frames",
        scene: DYNAMIC,
        setup: &[],
        value: "5",
        reached: |_, b| matches!(b.stepping, Stepping::ImplicitEuler { frames: 5, .. }),
        bad: "0",
    },
    Case {
        key: "dt",
        scene: DYNAMIC,
        setup: &[],
        value: "0.004",
        reached: |_, b| matches!(b.stepping, Stepping::ImplicitEuler { dt, .. } if dt == 0.004),
        bad: "-0.01",
    },
    Case {
        key: "volume_projection",
        scene: DYNAMIC,
        setup: &[],
        value: "global-rescale",
        reached: |_, b| b.settings.volume_projection == VolumeProjection::GlobalRescale,
        bad: "sideways",
    },
    Case {
        key: "volume_recovery",
        scene: DYNAMIC,
        setup: &["volume_projection=one-ring"],
        value: "0.05",
        reached: |_, b| {
            b.settings.volume_projection == VolumeProjection::OneRing { recovery: 0.05 }
        },
        bad: "0",
    },
    Case {
        key: "max_iterations",
        scene: STATIC,
        setup: &[],
        value: "17",
        reached: |_, b| b.settings.max_iterations == 17,
        bad: "0",
    },
    Case {
        key: "force_tolerance",
        scene: STATIC,
        setup: &[],
        value: "1e-7",
        reached: |_, b| b.settings.force_tolerance == 1e-7,
        bad: "0.0",
    },
    Case {
        key: "constraint_tolerance",
        scene: STATIC,
        setup: &[],
        value: "1e-9",
        reached: |_, b| b.settings.constraint_tolerance == 1e-9,
        bad: "-1.0",
    },
    Case {
        key: "max_backtracks",
        scene: STATIC,
        setup: &[],
        value: "9",
        reached: |_, b| b.settings.max_backtracks == 9,
        bad: "-1",
    },
    Case {
        key: "max_dual_iterations",
        scene: STATIC,
        setup: &[],
        value: "44",
        reached: |_, b| b.settings.max_dual_iterations == 44,
        bad: "-3",
    },
    Case {
        key: "project_hessians",
        scene: STATIC,
        setup: &[],
        value: "true",
        reached: |_, b| b.settings.project_hessians,
        bad: "maybe",
    },
    Case {
        key: "linear",
        scene: STATIC,
        setup: &[],
        value: "iterative",
        reached: |_, b| iterative(b) == Some((1e-8, 1000)),
        bad: "cholesky",
    },
    Case {
        key: "linear_tolerance",
        scene: STATIC,
        setup: &[],
        value: "1e-6",
        reached: |_, b| iterative(b).is_some_and(|(t, _)| t == 1e-6),
        bad: "tight",
    },
    Case {
        key: "linear_max_iterations",
        scene: STATIC,
        setup: &[],
        value: "77",
        reached: |_, b| iterative(b).is_some_and(|(_, n)| n == 77),
        bad: "-1",
    },
    Case {
        key: "ordering",
        scene: STATIC,
        setup: &[],
        value: "nested-dissection",
        reached: |_, b| b.settings.ordering == isochor_solvers::linear::Ordering::NestedDissection,
        bad: "metis",
    },
    Case {
        key: "jacobian",
        scene: STATIC,
        setup: &[],
        value: "modified",
        reached: |_, b| b.settings.jacobian == isochor_solvers::Jacobian::Modified,
        bad: "bfgs",
    },
    Case {
        key: "linear_preconditioner",
        scene: STATIC,
        setup: &[],
        value: "jacobi",
        reached: |_, b| {
            matches!(b.settings.linear, LinearSolver::Iterative(i)
                if i.preconditioner == isochor_solvers::PreconditionerKind::Jacobi)
        },
        bad: "ilu",
    },
    Case {
        key: "zones",
        scene: STATIC,
        setup: &["method=zonal", "zones.kind=global", "zones.k=1"],
        value: "k-ring",
        reached: |_, b| k_ring(b, 1),
        bad: "rings",
    },
    Case {
        key: "k",
        scene: STATIC,
        setup: &["method=zonal", "zones=k-ring", "zones.k=1"],
        value: "2",
        reached: |_, b| k_ring(b, 2),
        bad: "0",
    },
    Case {
        key: "every",
        scene: STATIC,
        setup: &[],
        value: "3",
        reached: |s, _| s.output.every == 3,
        bad: "0",
    },
    Case {
        key: "vtu",
        scene: STATIC,
        setup: &[],
        value: "false",
        reached: |s, _| !s.output.vtu,
        bad: "no",
    },
    Case {
        key: "plots",
        scene: STATIC,
        setup: &[],
        value: "false",
        reached: |s, _| !s.output.plots,
        bad: "2",
    },
    Case {
        key: "vtu_encoding",
        scene: STATIC,
        setup: &[],
        value: "binary",
        reached: |s, _| s.output.vtu_encoding == VtuEncodingName::Binary,
        bad: "gzip",
    },
    Case {
        key: "preview",
        scene: STATIC,
        setup: &[],
        value: "false",
        reached: |s, _| !s.output.writes_preview(),
        bad: "no",
    },
    Case {
        key: "preview_field",
        scene: STATIC,
        setup: &[],
        value: "von_mises",
        reached: |s, _| s.output.preview_field == PreviewField::VonMises,
        bad: "stress",
    },
    Case {
        key: "preview_rest",
        scene: STATIC,
        setup: &[],
        value: "false",
        reached: |s, _| !s.output.preview_rest,
        bad: "1",
    },
];

/// Loads `scene` at `res = 1` with `setup` and then `extra`, builds it and creates the
/// simulation (which checks the solver settings); the scene and what was built, or the
/// first error.
fn load(
    scene: &str,
    setup: &[&str],
    extra: Option<String>,
) -> Result<(Scene, ResolvedScene), String> {
    let overrides = ["res=1"]
        .iter()
        .chain(setup)
        .map(|s| s.to_string())
        .chain(extra)
        .map(|s| Override::parse(&s))
        .collect::<Result<Vec<_>, SceneError>>()
        .map_err(|e| e.to_string())?;
    let scene = load_scene(scene, None, &overrides).map_err(|e| e.to_string())?;
    let built = build(&scene).map_err(|e| e.to_string())?;
    Simulation::new(built.problem.clone(), built.settings).map_err(|e| e.to_string())?;
    Ok((scene, built))
}

/// The table covers every flat key once.
#[test]
fn every_flat_key_has_a_case() {
    let mut keys: Vec<&str> = CASES.iter().map(|c| c.key).collect();
    keys.sort_unstable();
    let mut flat: Vec<&str> = flat_keys().iter().map(|(k, _)| *k).collect();
    flat.sort_unstable();
    assert_eq!(keys, flat);
}

/// Each flat key's value is read back from the built problem, stepping and settings (or the
/// loaded scene), and the scene without the override does not already have it.
#[test]
fn every_flat_key_reaches_the_problem() {
    for case in CASES {
        let (scene, built) = load(case.scene, case.setup, None)
            .unwrap_or_else(|e| panic!("{} without the override: {e}", case.key));
        assert!(
            !(case.reached)(&scene, &built),
            "{}: the scene already has {}",
            case.key,
            case.value
        );
        let set = format!("{}={}", case.key, case.value);
        let (scene, built) = load(case.scene, case.setup, Some(set.clone()))
            .unwrap_or_else(|e| panic!("--set {set}: {e}"));
        assert!(
            (case.reached)(&scene, &built),
            "--set {set} did not arrive: {:?} {:?} {:?} {:?} {:?}",
            built.problem.material,
            built.stepping,
            built.settings,
            built.problem.loads,
            scene.output
        );
    }
}

/// A bad value of each flat key is refused with an error naming the key: the dotted key it
/// stands for (scene errors), or the flat name (material parameters, solver settings).
#[test]
fn a_bad_value_of_every_flat_key_is_a_named_error() {
    for case in CASES {
        let set = format!("{}={}", case.key, case.bad);
        let error = match load(case.scene, case.setup, Some(set.clone())) {
            Ok(_) => panic!("--set {set} was accepted"),
            Err(e) => e,
        };
        let keys = flat_keys();
        let dotted = keys
            .iter()
            .find(|(k, _)| *k == case.key)
            .map(|(_, d)| d.as_str())
            .unwrap_or(case.key);
        // The scene's key, a material parameter, or a solver setting, by name.
        // An old spelling is named by its new one.
        let new_name = dotted.rsplit('.').next().unwrap_or(dotted);
        let named = error.contains(&format!("key '{dotted}'"))
            || error.contains(&format!("parameter {} = ", case.key))
            || error.contains(&format!("parameter {new_name} = "))
            || error.contains(&format!("setting: {} ", case.key));
        eprintln!("--set {set}: {error}");
        assert!(
            named,
            "--set {set}: the error does not name the key: {error}"
        );
    }
}

/// A model's constants are checked as the solver's catalogue says, and a number too large
/// for `f64` is named as such: `--set E=1e400` said "invalid type: string" before, and
/// Mooney-Rivlin with `c01 < 0` (not Drucker-stable for every strain) was accepted.
#[test]
fn constants_and_overflowing_numbers_are_named_errors() {
    let error = |sets: &[&str]| {
        let overrides: Vec<Override> = sets.iter().map(|s| Override::parse(s).unwrap()).collect();
        let scene = load_scene(STATIC, None, &overrides);
        scene
            .and_then(|s| build(&s).map(|_| ()))
            .unwrap_err()
            .to_string()
    };
    let e = error(&["E=1e400"]);
    assert!(
        e.contains("material.young") && e.contains("1e400 is not a finite number"),
        "{e}"
    );
    let e = error(&["model=mooney-rivlin", "c10=4e4", "c01=-1e3"]);
    assert!(e.contains("c01") && e.contains("Drucker"), "{e}");
    let e = error(&["model=mooney-rivlin", "c10=4e4", "c20=1e3"]);
    assert!(
        e.contains("c20 is not a constant of model mooney-rivlin (its constants: c10, c01)"),
        "{e}"
    );
    let e = error(&["material.c40=1"]);
    assert!(
        e.contains("material.c40") && e.contains("unknown field `c40`"),
        "{e}"
    );
}
