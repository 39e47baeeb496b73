//! The built-in scene library: TOML files shipped inside the crate. `isochor list` prints
//! their names; a user can copy one (`isochor show NAME > my.toml`), edit it and run it by path.

/// `(name, TOML text)` of every built-in scene, in the order `isochor list` prints them.
pub const BUILTIN: &[(&str, &str)] = &[
    ("cantilever", include_str!("../builtin/cantilever.toml")),
    ("spine-arm", include_str!("../builtin/spine-arm.toml")),
    ("cushion", include_str!("../builtin/cushion.toml")),
    ("bubble", include_str!("../builtin/bubble.toml")),
    ("finger", include_str!("../builtin/finger.toml")),
    (
        "spine-arm-dynamics",
        include_str!("../builtin/spine-arm-dynamics.toml"),
    ),
    (
        "compressed-block",
        include_str!("../builtin/compressed-block.toml"),
    ),
    (
        "inflated-tube",
        include_str!("../builtin/inflated-tube.toml"),
    ),
    (
        "stretched-cylinder",
        include_str!("../builtin/stretched-cylinder.toml"),
    ),
    ("twisted-box", include_str!("../builtin/twisted-box.toml")),
    ("two-tets", include_str!("../builtin/two-tets.toml")),
    (
        "pressure-cube",
        include_str!("../builtin/pressure-cube.toml"),
    ),
    ("dynamic-cube", include_str!("../builtin/dynamic-cube.toml")),
    ("bulge-puck", include_str!("../builtin/bulge-puck.toml")),
    (
        "epidermis-puck",
        include_str!("../builtin/epidermis-puck.toml"),
    ),
    ("zoning-beam", include_str!("../builtin/zoning-beam.toml")),
    ("ball-drop", include_str!("../builtin/ball-drop.toml")),
    (
        "ball-drop-coarse",
        include_str!("../builtin/ball-drop-coarse.toml"),
    ),
    (
        "resting-block",
        include_str!("../builtin/resting-block.toml"),
    ),
    ("stretch-cube", include_str!("../builtin/stretch-cube.toml")),
    ("twist-cube", include_str!("../builtin/twist-cube.toml")),
    ("band", include_str!("../builtin/band.toml")),
    (
        "squeezed-creature",
        include_str!("../builtin/squeezed-creature.toml"),
    ),
];

/// The TOML text of a built-in scene.
pub fn builtin(name: &str) -> Option<&'static str> {
    BUILTIN.iter().find(|(n, _)| *n == name).map(|(_, t)| *t)
}

/// The names of the built-in scenes.
pub fn names() -> impl Iterator<Item = &'static str> {
    BUILTIN.iter().map(|(n, _)| *n)
}

/// The `--set` overrides of a built-in scene's reduced version: the same physics on a coarse
/// mesh with few steps or frames, so that every scene and variant runs in well under a second
/// in the dev profile (the smoke tests and the pinned results run these; the overrides are
/// part of each pinned value's key, so changing one means pinning anew). `None` for a name
/// that is not a built-in scene.
pub fn reduced(name: &str) -> Option<&'static [&'static str]> {
    let sets: &'static [&'static str] = match name {
        "cantilever" | "spine-arm" => &["res=1", "steps=2"],
        "cushion" | "bubble" | "finger" => &["res=1", "steps=2"],
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
        "stretch-cube" | "twist-cube" => &["res=2", "steps=2"],
        // A 6 mm squeeze (3 mm per cylinder): the 942-tet creature needs about 70 Newton
        // iterations for two frames of it.
        "squeezed-creature" => &[
            "res=1",
            "steps=2",
            "obstacles.0.translate=[0.0, 0.0, -0.004]",
            "obstacles.1.translate=[0.0, 0.0, 0.004]",
        ],
        "spine-arm-dynamics" => &["res=1", "frames=3"],
        // A milder squeeze (the ring's hole from 125 to 115 mm, not 96 mm): the full one
        // needs many cut steps on the coarsest torso.
        "band" => &["res=1", "steps=2", "obstacles.0.radius_change=-0.01"],
        _ => return None,
    };
    Some(sets)
}
