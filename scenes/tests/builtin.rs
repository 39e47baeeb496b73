//! Every built-in scene (and every variant of it) parses, builds a problem whose selections
//! are non-empty, round-trips through `isochor show`, and runs in a reduced version.

use isochor_scenes::problem::build;
use isochor_scenes::scene::Scene;
use isochor_scenes::{builtin, load_scene, run_scene, Override, RunOptions, SceneSource};

/// Overrides that make a scene run in well under a few seconds in the dev profile.
fn reduced(name: &str) -> Vec<Override> {
    let sets: &[&str] = match name {
        "cantilever" => &["res=1", "steps=2"],
        "compressed-block" => &["res=4", "steps=2"],
        "inflated-tube" => &["res=1", "steps=2"],
        // A 10% stretch: the coarsest cylinder does not converge stretched much further in
        // two steps with mixed-p1 at nu = 0.4999.
        "stretched-cylinder" => &[
            "res=1",
            "steps=2",
            "dirichlet.1.motion.translate=[0.0, 0.0, 0.01]",
        ],
        "twisted-box" => &["res=2", "steps=2"],
        "two-tets" => &["steps=2"],
        "pressure-cube" => &["res=3", "steps=1"],
        "dynamic-cube" => &["res=2", "frames=3"],
        "bulge-puck" | "epidermis-puck" => &["res=2", "steps=3"],
        "zoning-beam" => &["res=1", "steps=2"],
        // Dropped from 0.2 mm so that the 48-tet ball lands within the frames.
        "ball-drop" | "ball-drop-coarse" => {
            &["res=1", "frames=12", "mesh.center=[0.0, 0.0, 0.1002]"]
        }
        "resting-block" => &["res=2", "steps=1"],
        other => panic!("no reduced version of scene {other}: add one here"),
    };
    sets.iter().map(|s| Override::parse(s).unwrap()).collect()
}

#[test]
fn every_builtin_scene_parses_and_builds_a_problem() {
    for (name, _) in builtin::BUILTIN {
        let scene = load_scene(name, None, &[]).unwrap_or_else(|e| panic!("{name}: {e}"));
        assert_eq!(&scene.name, name);
        assert!(!scene.description.is_empty(), "{name} has no description");
        assert!(!scene.probes.is_empty(), "{name} has no probes");
        let built = build(&scene).unwrap_or_else(|e| panic!("{name}: {e}"));
        assert!(built.problem.mesh.num_tets() > 0);
        assert!(
            !built.problem.dirichlet.is_empty() || !built.problem.obstacles.is_empty(),
            "{name} has no Dirichlet condition or obstacle"
        );
        for d in &built.problem.dirichlet {
            assert!(!d.vertices.is_empty());
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
            .num_tets()
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
            .load(None, &reduced(name))
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

/// Runs every scene in its reduced version. Needs the solver's `Simulation`.
#[test]
fn every_builtin_scene_runs_reduced() {
    let mut failures = Vec::new();
    for (name, _) in builtin::BUILTIN {
        let scene = load_scene(name, None, &reduced(name)).unwrap();
        let (result, _) =
            run_scene(&scene, &RunOptions::default()).unwrap_or_else(|e| panic!("{name}: {e}"));
        assert_eq!(result.steps_requested, scene.num_steps());
        assert_eq!(result.probes.len(), scene.probes.len(), "{name}");
        if !result.converged || !result.probes.values().all(|v| v.is_finite()) {
            failures.push(format!("{name}: {:?} {:?}", result.error, result.probes));
        }
    }
    assert!(failures.is_empty(), "{failures:#?}");
}

#[test]
fn two_tets_reproduce_fig_2_of_sheen_et_al() {
    let run = |variant: &str| {
        let scene = load_scene(
            "two-tets",
            Some(variant),
            &[Override::parse("steps=4").unwrap()],
        )
        .unwrap();
        run_scene(&scene, &RunOptions::default()).unwrap().0
    };
    // Without a volume constraint the pressed tet's volume is simply lost...
    let free = run("unconstrained");
    assert!(free.converged, "{:?}", free.error);
    assert!(
        (free.probes["total_volume_ratio"] - 0.525).abs() < 0.02,
        "{:?}",
        free.probes
    );
    // ...with a global one the free tet inflates to keep the total.
    let constrained = run("constrained");
    assert!(constrained.converged, "{:?}", constrained.error);
    assert!(
        (constrained.probes["total_volume_ratio"] - 1.0).abs() < 1e-8,
        "{:?}",
        constrained.probes
    );
    assert!(
        (constrained.probes["free_tet_volume_ratio"] - 1.95).abs() < 1e-6,
        "{:?}",
        constrained.probes
    );
}
