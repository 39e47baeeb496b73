//! The built-in scene library: TOML files shipped inside the crate. `isochor list` prints
//! their names; a user can copy one (`isochor show NAME > my.toml`), edit it and run it by path.
//! A new built-in scene is its TOML file and one entry of [`BUILTIN`].

use std::sync::OnceLock;

/// `(name, TOML text)` of the named scenes of `builtin/`, in the order given.
macro_rules! builtin_scenes {
    ($($name:literal),+ $(,)?) => {
        &[$(($name, include_str!(concat!("../../builtin/", $name, ".toml")))),+]
    };
}

/// `(name, TOML text)` of every built-in scene, in the order `isochor list` prints them.
pub const BUILTIN: &[(&str, &str)] = builtin_scenes![
    "cantilever",
    "spine-arm",
    "cushion",
    "bubble",
    "finger",
    "spine-arm-dynamics",
    "compressed-block",
    "inflated-tube",
    "stretched-cylinder",
    "twisted-box",
    "two-tets",
    "pressure-cube",
    "dynamic-cube",
    "bulge-puck",
    "epidermis-puck",
    "zoning-beam",
    "ball-drop",
    "ball-drop-coarse",
    "resting-block",
    "stretch-cube",
    "twist-cube",
    "band",
    "squeezed-creature",
    "incline",
    "colliding-balls",
    "squashed-tube",
    "grasp",
    "finger-volume",
    "garment",
];

/// The TOML text of a built-in scene.
pub fn builtin(name: &str) -> Option<&'static str> {
    BUILTIN.iter().find(|(n, _)| *n == name).map(|(_, t)| *t)
}

/// The names of the built-in scenes.
pub fn names() -> impl Iterator<Item = &'static str> {
    BUILTIN.iter().map(|(n, _)| *n)
}

/// The `--set` overrides of a built-in scene's quick version, its top-level key `reduced`
/// (see [`super::Scene::reduced`]): the same physics on a coarse mesh with few steps or
/// frames, which the smoke tests and the pinned results run. `None` for a name that is not a
/// built-in scene or a scene without the key.
pub fn reduced(name: &str) -> Option<&'static [&'static str]> {
    static REDUCED: OnceLock<Vec<(&'static str, Vec<&'static str>)>> = OnceLock::new();
    let all = REDUCED.get_or_init(|| {
        BUILTIN
            .iter()
            .map(|(name, text)| (*name, reduced_key(text)))
            .collect()
    });
    all.iter()
        .find(|(n, sets)| *n == name && !sets.is_empty())
        .map(|(_, sets)| sets.as_slice())
}

/// The strings of a scene text's top-level `reduced` key (none if it has none), kept for the
/// life of the program as the built-in texts are.
fn reduced_key(text: &str) -> Vec<&'static str> {
    let Ok(table) = toml::from_str::<toml::Table>(text) else {
        return Vec::new();
    };
    table
        .get("reduced")
        .and_then(toml::Value::as_array)
        .map(|sets| {
            sets.iter()
                .filter_map(toml::Value::as_str)
                .map(|s| &*Box::leak(s.to_string().into_boxed_str()))
                .collect()
        })
        .unwrap_or_default()
}
