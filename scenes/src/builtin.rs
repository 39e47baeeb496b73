//! The built-in scene library: TOML files shipped inside the crate. `isochor list` prints
//! their names; a user can copy one (`isochor show NAME > my.toml`), edit it and run it by path.

/// `(name, TOML text)` of every built-in scene, in the order `isochor list` prints them.
pub const BUILTIN: &[(&str, &str)] = &[
    ("cantilever", include_str!("../builtin/cantilever.toml")),
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
];

/// The TOML text of a built-in scene.
pub fn builtin(name: &str) -> Option<&'static str> {
    BUILTIN.iter().find(|(n, _)| *n == name).map(|(_, t)| *t)
}

/// The names of the built-in scenes.
pub fn names() -> impl Iterator<Item = &'static str> {
    BUILTIN.iter().map(|(n, _)| *n)
}
