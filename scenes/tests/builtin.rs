//! Every built-in scene (and every variant of it) parses, builds a problem whose selections
//! are non-empty, round-trips through `isochor show`, and runs in its reduced version
//! ([`builtin::reduced`]); there, the physics of each paper figure holds, asserted from
//! analysis or from the paper (the absolute values are pinned in
//! `validation/tests/reference.rs`).

use isochor_scenes::format::{Scene, SteppingSpec};
use isochor_scenes::resolve::build;
use isochor_scenes::{
    builtin, load_scene, run_scene, Override, RunOptions, RunResult, SceneSource, StepRecord,
};
use isochor_solvers::Settings;

/// The overrides of a built-in scene's reduced version ([`builtin::reduced`]), then `extra`.
fn reduced(name: &str, extra: &[&str]) -> Vec<Override> {
    builtin::reduced(name)
        .unwrap_or_else(|| {
            panic!("no reduced version of scene {name}: add one to builtin::reduced")
        })
        .iter()
        .chain(extra)
        .map(|s| Override::parse(s).unwrap_or_else(|e| panic!("{s}: {e}")))
        .collect()
}

/// Runs `scene` and checks that every step converged (`what` names the run).
fn run_converged(scene: &Scene, what: &str) -> RunResult {
    let (r, _) = run_scene(scene, &RunOptions::default()).unwrap_or_else(|e| panic!("{what}: {e}"));
    assert!(
        r.converged,
        "{what}: failed at step {:?}: {:?}",
        r.failed_step, r.error
    );
    r
}

/// Runs a variant of a built-in scene in its reduced version, with `extra` overrides.
fn run(name: &str, variant: &str, extra: &[&str]) -> RunResult {
    let what = format!("{name} [{variant}]");
    let scene = load_scene(name, Some(variant), &reduced(name, extra))
        .unwrap_or_else(|e| panic!("{what}: {e}"));
    run_converged(&scene, &what)
}

/// The solver's constraint tolerance: a converged step has `max_i |theta_i| / V_i` below it,
/// with `V_i` the rest volume constraint row `i` measures. The rows of one global zone, and
/// the nodal rows of `mixed-p1` (whose `V_i` sum to the body's rest volume `V`), add up to
/// the whole-body volume law, which therefore holds to `sum_i |theta_i| <= tol V`.
fn constraint_tolerance() -> f64 {
    Settings::default().constraint_tolerance
}

/// The elastic energy of a run's last accepted state.
fn final_elastic_energy(r: &RunResult) -> f64 {
    r.history
        .last()
        .expect("a converged run has steps")
        .elastic_energy
}

#[test]
fn every_builtin_scene_parses_and_builds_a_problem() {
    for (name, _) in builtin::BUILTIN {
        let scene = load_scene(name, None, &[]).unwrap_or_else(|e| panic!("{name}: {e}"));
        assert_eq!(&scene.name, name);
        assert!(!scene.description.is_empty(), "{name} has no description");
        assert!(!scene.probes.is_empty(), "{name} has no probes");
        let built = build(&scene).unwrap_or_else(|e| panic!("{name}: {e}"));
        assert!(built.problem.mesh.num_elements() > 0);
        // Something drives every scene: a support, an obstacle, or (in free flight) a body's
        // initial velocity.
        let launched = scene.bodies.iter().any(|b| b.velocity.is_some());
        assert!(
            !built.problem.dirichlet.is_empty() || !built.problem.obstacles.is_empty() || launched,
            "{name} has no Dirichlet condition, obstacle or initial velocity"
        );
        for d in &built.problem.dirichlet {
            assert!(!d.nodes.is_empty());
        }
        assert_eq!(built.problem.method, scene.method());
        assert_eq!(
            built.problem.zones.is_some(),
            scene.method() == isochor_solvers::Method::Zonal
        );
    }
}

#[test]
fn default_sizes_match_the_papers() {
    let tets = |name: &str| {
        build(&load_scene(name, None, &[]).unwrap())
            .unwrap()
            .problem
            .mesh
            .num_elements()
    };
    assert_eq!(tets("cantilever"), 6 * 8 * 2 * 2);
    assert_eq!(tets("compressed-block"), 6 * 8 * 8 * 8);
    assert_eq!(tets("inflated-tube"), 3600);
    assert_eq!(tets("stretched-cylinder"), 7680);
    assert_eq!(tets("twisted-box"), 20250);
    assert_eq!(tets("two-tets"), 2);
    let verts = |name: &str| {
        build(&load_scene(name, None, &[]).unwrap())
            .unwrap()
            .problem
            .mesh
            .num_vertices()
    };
    assert_eq!(verts("pressure-cube"), 12 * 12 * 12);
    assert_eq!(verts("zoning-beam"), 16 * 4 * 4);
    assert_eq!(tets("dynamic-cube"), 6 * 16 * 16 * 16);
    // 48 res^3 tets: res 11 is the "64K tets" ball of Fig. 10 of Sheen et al., res 5 the
    // closest to the 4.7K tets of Fig. 11.
    assert_eq!(tets("ball-drop"), 63_888);
    assert_eq!(tets("ball-drop-coarse"), 6_000);
}

#[test]
fn every_variant_and_reduced_version_loads_and_builds() {
    for (name, _) in builtin::BUILTIN {
        let source = SceneSource::resolve(name).unwrap();
        let base = source.load(None, &[]).unwrap();
        for variant in base.variants.keys() {
            let scene = source
                .load(Some(variant), &[])
                .unwrap_or_else(|e| panic!("{name} [{variant}]: {e}"));
            build(&scene).unwrap_or_else(|e| panic!("{name} [{variant}]: {e}"));
        }
        let scene = source
            .load(None, &reduced(name, &[]))
            .unwrap_or_else(|e| panic!("{name} reduced: {e}"));
        build(&scene).unwrap_or_else(|e| panic!("{name} reduced: {e}"));
    }
}

#[test]
fn shown_scenes_parse_back_to_the_same_scene() {
    for (name, _) in builtin::BUILTIN {
        let scene = load_scene(name, None, &[]).unwrap();
        let text = scene.to_toml_string();
        let again =
            Scene::from_toml_str(&text, "shown").unwrap_or_else(|e| panic!("{name}: {e}\n{text}"));
        assert_eq!(scene, again, "{name}");
    }
}

/// Runs every scene in its reduced version: each completes with finite probes, every step
/// converged but in the scenes that accept unconverged steps on purpose
/// (`solver.accept_unconverged`). Needs the solver's `Simulation`.
#[test]
fn every_builtin_scene_runs_reduced() {
    let mut failures = Vec::new();
    for (name, _) in builtin::BUILTIN {
        let scene = load_scene(name, None, &reduced(name, &[])).unwrap();
        let (result, _) =
            run_scene(&scene, &RunOptions::default()).unwrap_or_else(|e| panic!("{name}: {e}"));
        assert_eq!(result.steps_requested, scene.num_steps());
        assert_eq!(result.probes.len(), scene.probes.len(), "{name}");
        let completed = result.converged
            || (result.error.is_none() && scene.solver.accept_unconverged == Some(true));
        if !completed || !result.probes.values().all(|v| v.is_finite()) {
            failures.push(format!("{name}: {:?} {:?}", result.error, result.probes));
        }
    }
    assert!(failures.is_empty(), "{failures:#?}");
}

/// Fig. 2 of Sheen et al. 2021, exactly. The pressed tet is scaled to 5% of its width (its
/// shared face lies in the plane the scaling keeps), so it keeps 5% of its volume. Without a
/// constraint the free tet is unloaded and keeps its own: the total is (0.05 + 1) / 2 = 0.525.
/// With one global constraint the free tet takes the lost 95%: 1.95, and the total stays 1.
#[test]
fn two_tets_reproduce_fig_2_of_sheen_et_al() {
    let settings = Settings::default();
    // The free apex is the only unknown. Stopping at a force residual |r| <= tau F (F =
    // mu h^2 sqrt(5) for this unloaded scene, h^2 = (V / 2)^(2/3) = 0.30) moves it by at most
    // |r| / k, with k ~ mu V / H^2 = mu / 6 its stiffness (apex height H = 1), i.e. by
    // 4.1 tau; the total ratio moves by half of that (its derivative is A / (3 V) = 1/2 along
    // the normal): 10 tau bounds both ratios.
    let free_tol = 10.0 * settings.force_tolerance;
    let free = run("two-tets", "unconstrained", &[]);
    let total = free.probes["total_volume_ratio"];
    assert!(
        (total - 0.525).abs() <= free_tol,
        "unconstrained total volume ratio {total:.15} != 0.525"
    );
    let own = free.probes["free_tet_volume_ratio"];
    assert!(
        (own - 1.0).abs() <= 2.0 * free_tol,
        "unconstrained free tet volume ratio {own:.15} != 1"
    );
    // The global constraint holds to its tolerance: |V / V0 - 1| <= tol, and the free tet's
    // ratio is 2 V / V0 - 0.05, to 2 tol.
    let tol = settings.constraint_tolerance;
    let constrained = run("two-tets", "constrained", &[]);
    let total = constrained.probes["total_volume_ratio"];
    assert!(
        (total - 1.0).abs() <= tol,
        "constrained total volume ratio {total:.15} != 1"
    );
    let own = constrained.probes["free_tet_volume_ratio"];
    assert!(
        (own - 1.95).abs() <= 2.0 * tol,
        "constrained free tet volume ratio {own:.15} != 1.95"
    );
}

/// The mid-section's outer radial displacement of an infinitely long incompressible
/// neo-Hookean tube (inner radius `a`, outer `b`) under internal pressure `p`, in plane
/// strain: with `lambda = r / R` the hoop stretch, `p = mu [ln(l_a / l_b) + 1/(2 l_b^2) -
/// 1/(2 l_a^2)]` and `l_a^2 = 1 + (l_b^2 - 1) b^2 / a^2` (radial equilibrium integrated over
/// the wall), solved for `l_b` by bisection; `(l_b - 1) b`.
fn long_tube_outer_displacement(mu: f64, p: f64, a: f64, b: f64) -> f64 {
    let pressure = |lb: f64| {
        let la = (1.0 + (lb * lb - 1.0) * b * b / (a * a)).sqrt();
        mu * ((la / lb).ln() + 0.5 / (lb * lb) - 0.5 / (la * la))
    };
    let (mut lo, mut hi) = (1.0, 1.0 + b / a);
    assert!(pressure(hi) > p, "p above the tube's limit pressure");
    for _ in 0..100 {
        let mid = 0.5 * (lo + hi);
        if pressure(mid) < p {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    (lo - 1.0) * b
}

/// Figs. 1 and 11 of Francu et al. 2021: the tube inflates under its internal pressure;
/// standard neo-Hookean locks and inflates less than `mixed-p1`. The ends are held, so the
/// mid-section inflates less than an infinitely long tube's. `mixed-p1`'s volume follows its
/// pressures (the volume law of its constraints) to the constraint tolerance, and grows: the
/// wall is in mean tension (sigma_rr + sigma_tt = 2 p a^2 / (b^2 - a^2) > 0 in the Lame
/// solution), so a compressible wall (nu = 0.499) expands.
#[test]
fn inflated_tube_inflates_and_standard_locks() {
    let mismatch = ["probes.volume_law.kind=pressure-volume-mismatch"];
    let mixed = run("inflated-tube", "mixed-p1", &mismatch);
    let standard = run("inflated-tube", "standard", &[]);
    let scene = load_scene("inflated-tube", None, &[]).unwrap();
    let (young, nu) = (scene.material.young.unwrap(), scene.material.nu);
    let long = long_tube_outer_displacement(young / (2.0 * (1.0 + nu)), 10e3, 0.03, 0.05);
    let (m, s) = (
        mixed.probes["mean_radius_increase"],
        standard.probes["mean_radius_increase"],
    );
    eprintln!(
        "outer radius increase: mixed-p1 {:.3} mm, standard {:.3} mm, long tube {:.3} mm",
        1e3 * m,
        1e3 * s,
        1e3 * long
    );
    assert!(
        m > 0.0 && m < long,
        "mixed-p1 radius increase {m} outside (0, {long})"
    );
    assert!(s > 0.0 && s < m, "standard {s} vs mixed-p1 {m}");
    let law = mixed.probes["volume_law"];
    assert!(
        law.abs() <= constraint_tolerance(),
        "mixed-p1 volume departs from its pressures' by {law:e}"
    );
    assert!(mixed.volume_change > 0.0, "{}", mixed.volume_change);
}

/// Fig. 12(c, d) of Francu et al. 2021: the block under 50 kPa, above the 15 kPa at which the
/// paper's standard neo-Hookean stopped converging at nu = 0.4999 (FEBio's uncoupled
/// Mooney-Rivlin stood in for it there). Here every run converges, standard neo-Hookean too
/// (its line search rejects inverted elements). On each material `standard` locks: the top
/// centre deflects less than under `mixed-p1` with the same material, whose volume follows
/// its pressures to the constraint tolerance.
#[test]
fn compressed_block_at_50_kpa_converges_and_standard_locks_on_either_material() {
    let law = "probes.volume_law.kind=pressure-volume-mismatch";
    let (mooney, neo) = ("fig-12c-mooney-rivlin", "fig-12d-mixed-p1");
    for (material, standard, mixed) in [
        (
            "Mooney-Rivlin",
            run("compressed-block", mooney, &[]),
            run("compressed-block", mooney, &["method=mixed-p1", law]),
        ),
        (
            "neo-Hookean",
            run("compressed-block", neo, &["method=standard"]),
            run("compressed-block", neo, &[law]),
        ),
    ] {
        let (s, m) = (
            standard.probes["top_center_deflection"],
            mixed.probes["top_center_deflection"],
        );
        eprintln!(
            "{material} at 50 kPa: top centre deflects {:.2} mm (standard, {} iterations), {:.2} mm (mixed-p1, {} iterations)",
            1e3 * s,
            standard.newton_iterations,
            1e3 * m,
            mixed.newton_iterations
        );
        assert!(0.0 < s && s < m, "{material}: standard {s}, mixed-p1 {m}");
        let law = mixed.probes["volume_law"];
        assert!(
            law.abs() <= constraint_tolerance(),
            "{material}: mixed-p1 volume departs from its pressures' by {law:e}"
        );
    }
}

/// Fig. 14 of Francu et al. 2021: the top face is twisted by the full angle (its corner
/// (0.2, 0.2, 0.2) turns by 180 degrees, or 90 for `twist-90`, about the vertical axis through
/// (0.1, 0.1)); at nu = 0.45 the volume of `mixed-p1` may change, but exactly as its pressures
/// say: the paper's check, the residual of the constraint equation, is within the constraint
/// tolerance, and so is the mismatch between the volume change and the one the pressures
/// imply through the constitutive law (`sum_e V_e p_e / kappa / V`), which is a real change,
/// far above that tolerance (the paper: 1.5%). It shrinks: held at its height, the twisted
/// cube would lengthen (the Poynting effect), so its mean stress is compressive, more so at
/// 180 than at 90 degrees.
#[test]
fn twisted_box_reaches_the_twist_and_its_volume_follows_the_pressures() {
    let corner = [
        "probes.corner_x.kind=displacement",
        "probes.corner_x.point=[0.2, 0.2, 0.2]",
        "probes.corner_x.component=x",
        "probes.corner_y.kind=displacement",
        "probes.corner_y.point=[0.2, 0.2, 0.2]",
        "probes.corner_y.component=y",
    ];
    let mut volume_changes = Vec::new();
    for (variant, degrees) in [("mixed-p1", 180.0f64), ("twist-90", 90.0)] {
        let r = run("twisted-box", variant, &corner);
        let (sin, cos) = degrees.to_radians().sin_cos();
        // The corner relative to the axis is (0.1, 0.1); prescribed motions are exact to
        // rounding.
        let expected = [0.1 * (cos - sin) - 0.1, 0.1 * (sin + cos) - 0.1];
        let got = [r.probes["corner_x"], r.probes["corner_y"]];
        for (g, e) in got.iter().zip(expected) {
            assert!(
                (g - e).abs() < 1e-12,
                "{variant}: corner moved {got:?}, not {expected:?}"
            );
        }
        let tol = constraint_tolerance();
        assert!(
            r.probes["constraint_residual"] <= tol,
            "{variant}: {:?}",
            r.probes
        );
        assert!(
            r.probes["pressure_volume_mismatch"].abs() <= tol,
            "{variant}: {:?}",
            r.probes
        );
        let implied = r.volume_change - r.probes["pressure_volume_mismatch"];
        eprintln!(
            "{variant}: constraint residual {:.2e}, volume change {:+.4}%, implied by the pressures {:+.4}%",
            r.probes["constraint_residual"],
            100.0 * r.volume_change,
            100.0 * implied
        );
        assert!(r.volume_change.abs() > tol, "{variant}: {:?}", r.probes);
        volume_changes.push(r.volume_change);
    }
    eprintln!("volume change at 180 and 90 degrees: {volume_changes:?}");
    assert!(
        volume_changes[0] < volume_changes[1] && volume_changes[1] < 0.0,
        "{volume_changes:?}"
    );
}

/// The one-ring cube at 10 cells a side (6,000 tets, the size from which it failed): at
/// `C = 0` the anchored AMD order of the KKT met a singular leading block, and the refined
/// solution of the regularized `LDL^T` kept a relative residual of 5.9, so the first Newton
/// iteration failed; the solver now analyses the KKT again under nested dissection and
/// converges in the same 3 iterations as a run given that ordering.
#[test]
fn pressure_cube_one_ring_converges_at_ten_cells() {
    let r = run("pressure-cube", "one-ring", &["res=10"]);
    assert_eq!(r.newton_iterations, 3, "{:?}", r.probes);
    assert!(r.volume_change.abs() <= constraint_tolerance());
}

/// Fig. 7 of Sheen et al. 2021 (the cube standing under gravity): one global zone (`zonal`)
/// and one-ring constraints (`mixed-p1` at nu = 0.5) keep the volume to the constraint
/// tolerance; every method sags; standard neo-Hookean at nu = 0.495 locks: it sags less than
/// the incompressible one-ring solution, although in the continuum nu = 0.495 is the softer.
/// (The roughness of the pressure fields is compared in `validation/tests/volume.rs`.)
#[test]
fn pressure_cube_keeps_volume_and_standard_locks() {
    let standard = run("pressure-cube", "standard", &[]);
    let one_ring = run("pressure-cube", "one-ring", &[]);
    let zonal = run("pressure-cube", "zonal", &[]);
    let deflection = |r: &RunResult| r.probes["top_center_deflection"];
    for (variant, r) in [
        ("standard", &standard),
        ("one-ring", &one_ring),
        ("zonal", &zonal),
    ] {
        eprintln!("{variant}: {:?}", r.probes);
        assert!(deflection(r) > 0.0, "{variant}: {:?}", r.probes);
    }
    for (variant, r) in [("one-ring", &one_ring), ("zonal", &zonal)] {
        assert!(
            r.volume_change.abs() <= constraint_tolerance(),
            "{variant}: volume change {:e}",
            r.volume_change
        );
    }
    assert!(
        deflection(&standard) < deflection(&one_ring),
        "standard {} vs one-ring {}",
        deflection(&standard),
        deflection(&one_ring)
    );
}

/// Fig. 6 of Sheen et al. 2021: the epidermis adds a surface energy (non-negative, zero at
/// rest), so it stiffens the indented puck. Both runs reach the same prescribed indentation;
/// the one without skin minimizes the bulk energy alone, so its bulk energy is at most the
/// skinned run's bulk energy, which is at most the skinned run's total elastic energy: the
/// elastic energy (the work of the indenter) grows with the skin, for standard neo-Hookean and
/// for the zonal method. `zonal` keeps the volume to the constraint tolerance with and
/// without skin.
#[test]
fn epidermis_puck_skin_stiffens_the_surface() {
    for (bare, skinned) in [("unh", "unh-epidermis"), ("cnh", "cnh-epidermis")] {
        let (a, b) = (
            run("epidermis-puck", bare, &[]),
            run("epidermis-puck", skinned, &[]),
        );
        let (ea, eb) = (final_elastic_energy(&a), final_elastic_energy(&b));
        for (variant, r) in [(bare, &a), (skinned, &b)] {
            eprintln!(
                "{variant}: elastic energy {:.6e} J, bulge {:.3} mm, volume change {:+.2e}",
                final_elastic_energy(r),
                1e3 * r.probes["bulge_height"],
                r.volume_change
            );
        }
        assert!(eb > ea, "{skinned} energy {eb} <= {bare} energy {ea}");
        for (variant, r) in [(bare, &a), (skinned, &b)] {
            assert_eq!(r.max_inverted_tets, 0, "{variant}");
            if r.method == "zonal" {
                assert!(
                    r.volume_change.abs() <= constraint_tolerance(),
                    "{variant}: volume change {:e}",
                    r.volume_change
                );
            }
        }
    }
}

/// Fig. 8 of Sheen et al. 2021 (the cube falling into its rest shape with 8 ms steps): every
/// method is stable. Implicit Euler dissipates: from `M (v' - v) / dt = -grad W(x')` and the
/// convexity of `W` near rest, `E' <= E - |v' - v|_M^2 / 2` for the total energy `E =
/// kinetic + W`, so `E` falls every frame (the constraint forces add only second-order terms
/// in the step). `E` never goes below the static equilibrium's `W`, the smallest `W` over the
/// same constraints. `zonal` and the implicit one-ring constraints keep the volume every
/// frame. (The baselines with volume projections are `dynamic_cube_baselines_...`.)
#[test]
fn dynamic_cube_dissipates_energy_towards_its_equilibrium() {
    for variant in ["standard", "one-ring-implicit", "zonal"] {
        let r = run("dynamic-cube", variant, &["frames=20"]);
        let mut scene =
            load_scene("dynamic-cube", Some(variant), &reduced("dynamic-cube", &[])).unwrap();
        scene.stepping = SteppingSpec::QuasiStatic {
            steps: 1,
            increments: None,
            first_increment: None,
            min_increment: None,
        };
        let statics = run_converged(&scene, &format!("dynamic-cube [{variant}] at rest"));
        let last = statics.history.last().unwrap();
        let w_min = last.potential_energy();
        let energies: Vec<f64> = r.history.iter().map(StepRecord::total_energy).collect();
        eprintln!("{variant}: static energy {w_min:.6}, total energy per frame {energies:.4?}");
        // At rest before the first frame the total energy is 0.
        assert!(energies[0] < 0.0, "{variant}: {energies:?}");
        assert!(
            energies.windows(2).all(|w| w[1] < w[0]),
            "{variant}: the total energy rises: {energies:?}"
        );
        assert!(
            energies.iter().all(|&e| e > w_min),
            "{variant}: below the static equilibrium's {w_min}: {energies:?}"
        );
        if variant != "standard" {
            for s in &r.history {
                assert!(
                    s.volume_change.abs() <= constraint_tolerance(),
                    "{variant} frame {}: volume change {:e}",
                    s.step,
                    s.volume_change
                );
            }
        }
    }
}

/// Fig. 9 of Francu et al. 2021, reduced to its first 5 frames of 16 ms: the arm falls from
/// rest, so until it first passes its equilibrium (the stiffer `standard` arm near frame 6,
/// measured with the full run) the tip's deflection grows and the total potential energy
/// falls below its rest value 0 every frame; each frame is 3 Newton iterations (or fewer if they meet the tolerances),
/// reported as not converged when short. The per-frame probe is the final probe's value at
/// the last frame, and `potential.csv` and `potential.png` are written.
#[test]
fn spine_arm_dynamics_samples_the_potential_against_the_deflection() {
    let out = std::env::temp_dir().join(format!("isochor-fig9-{}", std::process::id()));
    for variant in ["standard", "mixed-p1"] {
        let scene = load_scene(
            "spine-arm-dynamics",
            Some(variant),
            &reduced("spine-arm-dynamics", &["frames=5", "vtu=false"]),
        )
        .unwrap();
        let dir = out.join(variant);
        let options = RunOptions {
            out: Some(dir.clone()),
            ..RunOptions::default()
        };
        let (r, _) = run_scene(&scene, &options).unwrap();
        assert!(r.error.is_none(), "{variant}: {:?}", r.error);
        let series: Vec<(f64, f64)> = isochor_scenes::output::potential_series(&r.history);
        eprintln!("{variant}: (deflection, potential) per frame {series:?}");
        assert_eq!(series.len(), 5, "{variant}");
        for (s, (x, e)) in r.history.iter().zip(&series) {
            assert!(s.newton_iterations <= 3, "{variant}: {s:?}");
            assert!(s.converged || s.newton_iterations == 3, "{variant}: {s:?}");
            assert!(x.is_finite() && *e < 0.0, "{variant}: {series:?}");
        }
        assert!(series[0].0 > 0.0, "{variant}: {series:?}");
        assert!(
            series
                .windows(2)
                .all(|w| w[1].0 > w[0].0 && w[1].1 < w[0].1),
            "{variant}: {series:?}"
        );
        assert_eq!(series.last().unwrap().0, r.probes["tip_deflection"]);
        assert_eq!(isochor_scenes::output::minimum(&series), Some(4));
        let csv = std::fs::read_to_string(dir.join("potential.csv")).unwrap();
        assert_eq!(csv.lines().count(), 1 + 5, "{variant}: {csv}");
        assert!(dir.join("potential.png").is_file(), "{variant}");
    }
    std::fs::remove_dir_all(&out).unwrap();
}

/// The Fig. 9 keys are refused where they make no sense, naming the key: accepting
/// unconverged steps in quasi-static stepping (whose steps must be equilibria), and a
/// potential plot against a probe the scene does not have.
#[test]
fn fig_9_keys_are_refused_where_they_make_no_sense() {
    let error = |name: &str, set: &str| {
        load_scene(name, None, &[Override::parse(set).unwrap()])
            .unwrap_err()
            .to_string()
    };
    let e = error("spine-arm", "solver.accept_unconverged=true");
    assert!(e.contains("solver.accept_unconverged"), "{e}");
    let e = error("spine-arm-dynamics", "output.potential_against=tip");
    assert!(
        e.contains("output.potential_against") && e.contains("tip"),
        "{e}"
    );
    // Off is fine anywhere.
    load_scene(
        "spine-arm",
        None,
        &[Override::parse("solver.accept_unconverged=false").unwrap()],
    )
    .unwrap();
}

/// Sec. 8.7 and Table 1 of Sheen et al. 2021, the stretched and twisted cubes (reduced: 48
/// tets, 2 frames): ours with a global zone keeps the volume within the constraint tolerance
/// (with and without the epidermis); Stable neo-Hookean without volume constraint changes the
/// volume, more at lambda = 40 kPa than at 400 kPa; ours without volume constraint runs (the
/// zones are `none`) and its volume is held by `lambda U(J; beta)` alone, so it changes.
#[test]
fn stretch_and_twist_cubes_of_table_1() {
    let tol = constraint_tolerance();
    let mut changes = std::collections::BTreeMap::new();
    for (scene, variants) in [
        (
            "stretch-cube",
            &[
                "snh-40",
                "snh-400",
                "ours-beta-0",
                "ours-beta-1",
                "ours-beta-1-epidermis",
                "ours-no-volume-constraint",
            ][..],
        ),
        (
            "twist-cube",
            &[
                "snh-100",
                "ours-no-volume-constraint",
                "ours",
                "ours-epidermis",
            ][..],
        ),
    ] {
        for variant in variants {
            let r = run(scene, variant, &[]);
            eprintln!(
                "{scene} [{variant}]: volume change {:+.4e}, {} Newton iterations, {} inverted tets",
                r.volume_change, r.newton_iterations, r.max_inverted_tets
            );
            changes.insert(format!("{scene} {variant}"), r.volume_change);
        }
    }
    let change = |key: &str| changes[key].abs();
    for key in [
        "stretch-cube ours-beta-0",
        "stretch-cube ours-beta-1",
        "stretch-cube ours-beta-1-epidermis",
        "twist-cube ours",
        "twist-cube ours-epidermis",
    ] {
        assert!(change(key) <= tol, "{key}: {changes:?}");
    }
    assert!(
        change("stretch-cube snh-40") > change("stretch-cube snh-400")
            && change("stretch-cube snh-400") > tol,
        "{changes:?}"
    );
    for key in [
        "twist-cube snh-100",
        "stretch-cube ours-no-volume-constraint",
        "twist-cube ours-no-volume-constraint",
    ] {
        assert!(change(key) > tol, "{key}: {changes:?}");
    }
}

/// `zones.kind = "none"` with `zonal_penalty = 0` (or its old spelling `lambda = 0`) leaves
/// the volume free (the F-bar energy is distortional): refused, naming the key.
#[test]
fn no_zones_with_zonal_penalty_zero_is_refused() {
    let e = load_scene(
        "stretch-cube",
        Some("ours-no-volume-constraint"),
        &[Override::parse("lambda=0").unwrap()],
    )
    .unwrap_err()
    .to_string();
    assert!(
        e.contains("material.zonal_penalty") && e.contains("none"),
        "{e}"
    );
}

/// Local extrema of a per-frame series: the frames where its increments change sign.
fn turns(series: &[f64]) -> usize {
    series
        .windows(3)
        .filter(|w| (w[1] - w[0]) * (w[2] - w[1]) < 0.0)
        .count()
}

/// Fig. 8 of Sheen et al. 2021, the baselines against ours on the reduced cube (res 4, 40
/// frames of 8 ms): ours (`zonal`) loses total energy every frame (implicit Euler dissipates,
/// see `dynamic_cube_dissipates_energy_towards_its_equilibrium`); the global rescaling holds
/// the total volume to its secant tolerance (1e-12) every frame; both baselines, which move
/// the positions after the step without a force doing the work, gain total energy in some
/// frames. (Measured 2026-11-30: the rescaling gains in 7 of 40 frames, the one-ring
/// projection in 17; all three potential energies turn 6 times in these 40 frames, so the
/// count of oscillations is not asserted.)
#[test]
fn dynamic_cube_baselines_gain_energy_where_ours_dissipates() {
    let sets = ["res=4", "frames=40"];
    let curves: Vec<(&str, RunResult)> = ["zonal", "global-rescale", "one-ring"]
        .into_iter()
        .map(|v| (v, run("dynamic-cube", v, &sets)))
        .collect();
    let total =
        |r: &RunResult| -> Vec<f64> { r.history.iter().map(StepRecord::total_energy).collect() };
    let potential = |r: &RunResult| -> Vec<f64> {
        r.history.iter().map(StepRecord::potential_energy).collect()
    };
    let rises = |e: &[f64]| e.windows(2).filter(|w| w[1] > w[0]).count();
    for (variant, r) in &curves {
        let volume = r
            .history
            .iter()
            .map(|s| s.volume_change.abs())
            .fold(0.0, f64::max);
        eprintln!(
            "{variant}: total energy rises in {} frames, potential energy turns {} times, max |volume change| {volume:.2e}\n  total {:.4?}\n  potential {:.4?}",
            rises(&total(r)),
            turns(&potential(r)),
            total(r),
            potential(r)
        );
    }
    let [(_, ours), (_, rescale), (_, one_ring)] = &curves[..] else {
        unreachable!()
    };
    assert_eq!(rises(&total(ours)), 0, "ours: {:?}", total(ours));
    for s in &rescale.history {
        assert!(s.volume_change.abs() <= 1e-12, "rescaling: {s:?}");
    }
    assert!(
        rises(&total(rescale)) > 0,
        "rescaling: {:?}",
        total(rescale)
    );
    assert!(
        rises(&total(one_ring)) > 0,
        "one-ring: {:?}",
        total(one_ring)
    );
}

/// The band of Figs. 1 and 4 of Sheen et al. 2021 (reduced: 2,016 tets, 2 steps, the ring's
/// hole shrinking from 125 to 115 mm): ours keeps every painted zone and the whole body at
/// their volume to the solver's constraint tolerance (each zone is one constraint row:
/// `|V_z / V_z0 - 1| <= tol`) and squeezes the waist in; next to the band (4 cm above and
/// below its centre) its surface stays further out than the unconstrained neo-Hookean's at
/// nu = 0.4545, which loses volume instead, more than at nu = 0.499; no variant enters the
/// ring beyond the contact tolerance.
#[test]
fn band_zones_keep_their_volume_under_the_band() {
    let tol = constraint_tolerance();
    let ours = run("band", "ours", &[]);
    let unconstrained = run("band", "neo-hookean-0.4545", &[]);
    let locked = run("band", "neo-hookean-0.499", &[]);
    for r in [&ours, &unconstrained, &locked] {
        eprintln!(
            "band [{}]: {:?}, {} Newton iterations",
            r.variant.as_deref().unwrap_or(""),
            r.probes,
            r.newton_iterations
        );
        let scene = load_scene("band", r.variant.as_deref(), &reduced("band", &[])).unwrap();
        let (lo, hi) = build(&scene).unwrap().problem.mesh.corners().bounding_box();
        let contact = Settings::default().contact_tolerance * (hi - lo).norm();
        assert!(r.probes["max_penetration"] <= contact, "{:?}", r.probes);
    }
    let zones: Vec<(&String, &f64)> = ours
        .probes
        .iter()
        .filter(|(k, _)| k.starts_with("zone_"))
        .collect();
    assert_eq!(zones.len(), 7);
    for (zone, change) in zones {
        assert!(change.abs() <= tol, "ours, {zone}: {change:e}");
    }
    assert!(ours.probes["radius_under"] < 0.0, "{:?}", ours.probes);
    let beside = |r: &RunResult| r.probes["radius_above"] + r.probes["radius_below"];
    assert!(
        beside(&ours) > beside(&unconstrained),
        "{} {}",
        beside(&ours),
        beside(&unconstrained)
    );
    let body = |r: &RunResult| r.probes["zone_6_body"];
    assert!(
        body(&unconstrained) < body(&locked) && body(&locked) < -tol,
        "{} {}",
        body(&unconstrained),
        body(&locked)
    );
}

/// Sec. 8.7 and Table 1 of Sheen et al. 2021, the creature squeezed between two cylinders
/// (reduced: 942 tets, 2 frames): both cylinders press on the body and no vertex enters them
/// beyond the contact tolerance (1e-6 of the bounding-box diagonal, the solver's default);
/// ours keeps the volume within the constraint tolerance; Stable neo-Hookean at lambda =
/// 400 kPa without volume constraint changes it by more than that.
#[test]
fn squeezed_creature_of_table_1() {
    let tol = constraint_tolerance();
    let [length, width, height] = isochor_mesh::generate::CREATURE_SIZE;
    let diagonal = (length * length + width * width + height * height).sqrt();
    let mut changes = Vec::new();
    for variant in ["ours", "snh-400"] {
        let r = run("squeezed-creature", variant, &[]);
        eprintln!(
            "squeezed-creature [{variant}]: volume change {:+.4e}, {} Newton iterations, probes {:?}",
            r.volume_change, r.newton_iterations, r.probes
        );
        for probe in ["top_cylinder_force", "bottom_cylinder_force"] {
            assert!(r.probes[probe] > 0.0, "{variant}: {probe}");
        }
        assert!(r.probes["max_penetration"] <= 1e-6 * diagonal, "{variant}");
        changes.push(r.volume_change.abs());
    }
    assert!(changes[0] <= tol, "ours: {changes:?}");
    assert!(changes[1] > tol, "snh-400: {changes:?}");
}

/// A contact-force probe of an obstacle the scene does not have is refused, naming the key.
#[test]
fn contact_force_of_a_missing_obstacle_is_refused() {
    let e = load_scene(
        "squeezed-creature",
        None,
        &[Override::parse("probes.top_cylinder_force.obstacle=2").unwrap()],
    )
    .unwrap_err()
    .to_string();
    assert!(
        e.contains("probes.top_cylinder_force.obstacle") && e.contains("has 2"),
        "{e}"
    );
}
