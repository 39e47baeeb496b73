//! `--set KEY=VALUE`: overrides applied to the parsed TOML tree before the scene is
//! deserialized again, so a wrong type is reported against its key.
//!
//! `KEY` is a dotted path (`material.nu`, `stepping.steps`, `dirichlet.1.motion.rotate.degrees`,
//! array entries by index) or a flat parameter name from [`FLAT_KEYS`] (`nu`, `E`, `res`,
//! `steps`, `method`, `element`, ...). Any key of the scene's `[mesh]` table (`res`, `radius`, ...) is a
//! flat name too. Two names are special: `mesh=PATH` replaces the generated mesh by a mesh
//! file, and `zones=K-ring` is shorthand for `zones.kind = "k-ring"`, `zones.k = K`.
//! `VALUE` is read as a TOML value (`0.4999`, `4`, `true`, `[0, -9.8, 0]`, `"text"`) and
//! otherwise taken as a bare string (`mixed-p1`, `meshes/tube.msh`).

use super::material::{rename_aliases, MATERIAL_ALIASES};
use crate::error::SceneError;
use isochor_solvers::MaterialModel;
use toml::Value;

/// Flat parameter names and the dotted keys they set; every material model's constants
/// (`c10`, ..., `ogden`, from the solver's catalogue) are flat names of `material.KEY` too
/// ([`flat_keys`]).
pub const FLAT_KEYS: &[(&str, &str)] = &[
    ("method", "method"),
    ("element", "element"),
    ("nu", "material.nu"),
    ("E", "material.young"),
    ("young", "material.young"),
    ("mu", "material.mu"),
    ("model", "material.model"),
    ("rho", "material.rho"),
    ("density", "material.rho"),
    ("zonal_penalty", "material.zonal_penalty"),
    ("lambda", "material.zonal_penalty"),
    ("beta", "material.beta"),
    ("epsilon", "material.epsilon"),
    ("kappa", "material.kappa"),
    ("zonal_energy", "material.zonal_energy"),
    ("dual_base_nu", "material.dual_base_nu"),
    ("epidermis", "material.epidermis"),
    ("epidermis_young", "material.epidermis_young"),
    ("epidermis_nu", "material.epidermis_nu"),
    ("epidermis_gamma", "material.epidermis_gamma"),
    ("gravity", "loads.gravity"),
    ("steps", "stepping.steps"),
    ("frames", "stepping.frames"),
    ("dt", "stepping.dt"),
    ("increments", "stepping.increments"),
    ("first_increment", "stepping.first_increment"),
    ("min_increment", "stepping.min_increment"),
    ("volume_projection", "stepping.volume_projection"),
    ("volume_recovery", "stepping.volume_recovery"),
    ("max_iterations", "solver.max_iterations"),
    ("force_tolerance", "solver.force_tolerance"),
    ("constraint_tolerance", "solver.constraint_tolerance"),
    ("max_backtracks", "solver.max_backtracks"),
    ("max_dual_iterations", "solver.max_dual_iterations"),
    ("project_hessians", "solver.project_hessians"),
    ("linear", "solver.linear"),
    ("linear_tolerance", "solver.linear_tolerance"),
    ("linear_max_iterations", "solver.linear_max_iterations"),
    ("ordering", "solver.ordering"),
    ("jacobian", "solver.jacobian"),
    ("linear_preconditioner", "solver.linear_preconditioner"),
    ("zones", "zones.kind"),
    ("k", "zones.k"),
    ("every", "output.every"),
    ("vtu", "output.vtu"),
    ("plots", "output.plots"),
    ("vtu_encoding", "output.vtu_encoding"),
    ("preview", "output.preview"),
    ("preview_field", "output.preview_field"),
    ("preview_rest", "output.preview_rest"),
];

/// One `KEY=VALUE` override.
#[derive(Debug, Clone, PartialEq)]
pub struct Override {
    /// The key as given.
    pub key: String,
    /// The value, parsed as TOML or taken as a string.
    pub value: Value,
}

impl Override {
    /// Parses `KEY=VALUE`.
    pub fn parse(assignment: &str) -> Result<Override, SceneError> {
        let (key, raw) = assignment
            .split_once('=')
            .ok_or_else(|| SceneError::Override {
                key: assignment.to_string(),
                message: "expected KEY=VALUE (e.g. nu=0.4999, res=4, method=mixed-p1)".into(),
            })?;
        let key = key.trim();
        check_key_syntax(key).map_err(|message| SceneError::Override {
            key: isochor_mesh::io::excerpt(key),
            message,
        })?;
        Ok(Override {
            key: key.to_string(),
            value: parse_value(raw.trim()),
        })
    }

    /// An override from a key and an already parsed value.
    pub fn new(key: impl Into<String>, value: Value) -> Override {
        Override {
            key: key.into(),
            value,
        }
    }

    /// `KEY=VALUE` with the value in TOML syntax (strings unquoted).
    pub fn display_value(&self) -> String {
        match &self.value {
            Value::String(s) => s.clone(),
            v => v.to_string(),
        }
    }
}

/// A value as TOML (number, bool, array, quoted string), or else the raw text as a string.
pub fn parse_value(raw: &str) -> Value {
    toml::from_str::<toml::Table>(&format!("v = {raw}"))
        .ok()
        .and_then(|mut t| t.remove("v"))
        .unwrap_or_else(|| Value::String(raw.to_string()))
}

/// The most segments a dotted key may have: the deepest key of a scene has 6
/// (`dirichlet.0.motion.rotate.axis.0`); a deeper one would build tables nested deep enough
/// to overflow the stack of the code that reads them.
pub const MAX_KEY_DEPTH: usize = 32;

/// Checks that a key is a non-empty dotted path of at most [`MAX_KEY_DEPTH`] non-empty
/// segments.
pub fn check_key_syntax(key: &str) -> Result<(), String> {
    if key.is_empty() || key.split('.').any(str::is_empty) {
        return Err(format!(
            "'{key}' is not a key: use a parameter name ({}) or a dotted key like material.nu",
            flat_names().join(", ")
        ));
    }
    let depth = key.split('.').count();
    if depth > MAX_KEY_DEPTH {
        return Err(format!(
            "a key of {depth} dotted segments: at most {MAX_KEY_DEPTH} (no scene key is that deep)"
        ));
    }
    Ok(())
}

/// Every flat parameter name and the dotted key it sets: [`FLAT_KEYS`] and the constants of
/// every material model.
pub fn flat_keys() -> Vec<(&'static str, String)> {
    let constants = MaterialModel::constant_keys()
        .into_iter()
        .map(|k| (k, format!("material.{k}")));
    FLAT_KEYS
        .iter()
        .map(|&(k, path)| (k, path.to_string()))
        .chain(constants)
        .collect()
}

/// The flat parameter names, for error messages.
pub fn flat_names() -> Vec<&'static str> {
    let mut names: Vec<&str> = flat_keys().iter().map(|(n, _)| *n).collect();
    names.push("mesh");
    names.push("res");
    names.sort_unstable();
    names.dedup();
    names
}

/// Applies overrides in order to a scene's TOML tree (a later one wins). A relative
/// `mesh=PATH` is resolved against the working directory.
pub fn apply_all(tree: &mut Value, overrides: &[Override]) -> Result<(), SceneError> {
    rename_material_aliases(tree);
    overrides.iter().try_for_each(|o| apply(tree, o))
}

/// Renames the old spellings of the keys of the tree's `[material]` and regions' material
/// tables, so that an override in the new spelling replaces the old key instead of joining it.
fn rename_material_aliases(tree: &mut Value) {
    let Some(root) = tree.as_table_mut() else {
        return;
    };
    if let Some(Value::Table(m)) = root.get_mut("material") {
        rename_aliases(m);
    }
    if let Some(Value::Array(regions)) = root.get_mut("regions") {
        for region in regions {
            if let Some(Value::Table(m)) = region.get_mut("material") {
                rename_aliases(m);
            }
        }
    }
}

/// A dotted key with the old spelling of a material key replaced by the new one
/// (`material.lambda` is `material.zonal_penalty`).
fn canonical(path: String) -> String {
    let Some((table, key)) = path.rsplit_once('.') else {
        return path;
    };
    let is_material = table == "material" || table.ends_with(".material");
    match MATERIAL_ALIASES.iter().find(|(old, _)| *old == key) {
        Some((_, new)) if is_material => format!("{table}.{new}"),
        _ => path,
    }
}

/// Refuses a command line's overrides that set one parameter twice, under one name or two
/// (`E` and `young`), alternatives (`E` and `mu`), or a table and a key inside it
/// (`mesh=PATH` and `res`): in order, the later one would silently win.
pub fn check_conflicts(overrides: &[Override]) -> Result<(), SceneError> {
    let mut targets: Vec<(String, &str)> = Vec::new();
    for o in overrides {
        let target = target(o);
        if let Some((_, earlier)) = targets.iter().find(|(t, _)| conflict(t, &target)) {
            let what = if stiffness(&target) {
                "the stiffness: young (E), mu and a model's constants are alternatives".to_string()
            } else {
                target.clone()
            };
            return Err(SceneError::Override {
                key: o.key.clone(),
                message: format!(
                    "conflicts with --set {earlier} (both set {what}): give each parameter once"
                ),
            });
        }
        targets.push((target, &o.key));
    }
    Ok(())
}

/// The dotted key an override sets, as far as it is known without the scene (a flat mesh
/// key other than `res` stays as given).
fn target(o: &Override) -> String {
    match (o.key.as_str(), &o.value) {
        ("zones", Value::String(s)) if k_ring(s).is_some() => "zones".into(),
        (key, _) => canonical(dotted(key)),
    }
}

/// The dotted key a flat or dotted key names, as far as it is known without the scene
/// (`nu` is `material.nu`, `res` is `mesh.res`; a flat mesh key other than `res` stays as
/// given).
pub fn dotted(key: &str) -> String {
    match key {
        "res" => "mesh.res".into(),
        key => flat_keys()
            .into_iter()
            .find(|(name, _)| *name == key)
            .map_or(key.to_string(), |(_, path)| path),
    }
}

/// The alternative ways of giving a material's stiffness: Young's modulus, the shear
/// modulus, or the constants of a model (which go together).
fn stiffness_groups() -> [Vec<&'static str>; 3] {
    [vec!["young"], vec!["mu"], MaterialModel::constant_keys()]
}

/// The stiffness group of a dotted key, if it is one of the material's stiffness keys.
fn stiffness_group(key: &str) -> Option<usize> {
    let key = key.strip_prefix("material.")?;
    stiffness_groups().iter().position(|g| g.contains(&key))
}

fn stiffness(key: &str) -> bool {
    stiffness_group(key).is_some()
}

/// Whether two dotted keys set the same thing: equal, one inside the other, or alternative
/// stiffness keys (`young`, `mu`, a model's constants).
fn conflict(a: &str, b: &str) -> bool {
    let inside = |outer: &str, inner: &str| {
        inner
            .strip_prefix(outer)
            .is_some_and(|rest| rest.is_empty() || rest.starts_with('.'))
    };
    let alternatives = matches!(
        (stiffness_group(a), stiffness_group(b)),
        (Some(x), Some(y)) if x != y
    );
    inside(a, b) || inside(b, a) || alternatives
}

/// Applies one override.
pub fn apply(tree: &mut Value, o: &Override) -> Result<(), SceneError> {
    let err = |message: String| SceneError::Override {
        key: isochor_mesh::io::excerpt(&o.key),
        message,
    };
    // A variant's keys come from the scene file, not through `Override::parse`.
    check_key_syntax(&o.key).map_err(err)?;
    if o.key == "mesh" {
        let Value::String(path) = &o.value else {
            return Err(err(
                "expected a mesh file path (.msh, .node, .ele or .vtu)".into()
            ));
        };
        let mut table = toml::Table::new();
        table.insert("generator".into(), Value::String("file".into()));
        // A path given on the command line is relative to the working directory.
        let path = std::path::Path::new(path);
        let path = match std::env::current_dir() {
            Ok(cwd) if path.is_relative() => cwd.join(path),
            _ => path.to_path_buf(),
        };
        table.insert("path".into(), Value::String(path.display().to_string()));
        root(tree)?.insert("mesh".into(), Value::Table(table));
        return Ok(());
    }
    if o.key == "zones" {
        if let Value::String(s) = &o.value {
            if let Some(k) = k_ring(s) {
                set_path(tree, "zones.kind", Value::String("k-ring".into())).map_err(err)?;
                return set_path(tree, "zones.k", Value::Integer(k)).map_err(err);
            }
        }
    }
    let path = canonical(resolve(tree, &o.key).map_err(err)?);
    // Young's modulus, the shear modulus and a model's constants are alternatives: setting
    // one drops the others.
    if let Some(group) = stiffness_group(&path) {
        if let Some(Value::Table(m)) = root(tree)?.get_mut("material") {
            for (g, keys) in stiffness_groups().iter().enumerate() {
                if g != group {
                    keys.iter().for_each(|k| {
                        m.remove(*k);
                    });
                }
            }
        }
    }
    set_path(tree, &path, o.value.clone()).map_err(err)
}

/// `K` of the shorthand `zones=K-ring`.
fn k_ring(value: &str) -> Option<i64> {
    value.strip_suffix("-ring")?.parse().ok()
}

fn root(tree: &mut Value) -> Result<&mut toml::Table, SceneError> {
    tree.as_table_mut().ok_or_else(|| SceneError::Override {
        key: String::new(),
        message: "the scene is not a TOML table".into(),
    })
}

/// The dotted key a (possibly flat) key stands for.
fn resolve(tree: &Value, key: &str) -> Result<String, String> {
    if key.contains('.') {
        return Ok(key.to_string());
    }
    if let Some((_, path)) = flat_keys().into_iter().find(|(n, _)| *n == key) {
        return Ok(path);
    }
    if let Some(mesh) = tree.get("mesh").and_then(Value::as_table) {
        if mesh.contains_key(key) && key != "generator" {
            return Ok(format!("mesh.{key}"));
        }
        if key == "res" {
            return Err(format!(
                "this scene's mesh ({}) has no resolution: res applies to generated meshes",
                mesh.get("generator").and_then(Value::as_str).unwrap_or("?")
            ));
        }
    }
    if tree.get(key).is_some() {
        return Ok(key.to_string());
    }
    let mesh_keys = tree
        .get("mesh")
        .and_then(Value::as_table)
        .map(|m| {
            m.keys()
                .filter(|k| *k != "generator")
                .cloned()
                .collect::<Vec<_>>()
        })
        .unwrap_or_default();
    let mut valid: Vec<String> = flat_names().iter().map(|s| s.to_string()).collect();
    valid.extend(mesh_keys);
    valid.sort();
    valid.dedup();
    Err(format!(
        "unknown parameter '{key}' (valid: {}; or a dotted key such as material.nu or mesh.radius)",
        valid.join(", ")
    ))
}

/// Sets `value` at a dotted path, creating missing tables; array entries are addressed by
/// index and must exist.
fn set_path(tree: &mut Value, path: &str, value: Value) -> Result<(), String> {
    let segments: Vec<&str> = path.split('.').collect();
    let mut node = tree;
    for (i, seg) in segments.iter().enumerate() {
        let last = i + 1 == segments.len();
        let here = segments[..i].join(".");
        node = match node {
            Value::Table(t) => {
                if last {
                    t.insert(seg.to_string(), value);
                    return Ok(());
                }
                t.entry(seg.to_string())
                    .or_insert_with(|| Value::Table(toml::Table::new()))
            }
            Value::Array(a) => {
                let index: usize = seg.parse().map_err(|_| {
                    format!(
                        "'{here}' is a list: address its entries by index (0..{})",
                        a.len()
                    )
                })?;
                let len = a.len();
                let slot = a
                    .get_mut(index)
                    .ok_or_else(|| format!("'{here}' has {len} entries, no index {index}"))?;
                if last {
                    *slot = value;
                    return Ok(());
                }
                slot
            }
            other => {
                return Err(format!(
                    "'{here}' is a {} value, not a table, so it has no key '{seg}'",
                    other.type_str()
                ))
            }
        };
    }
    unreachable!("a path has at least one segment")
}

/// Splits `KEY=V1,V2,...` (commas inside brackets do not split).
pub fn parse_sweep(spec: &str) -> Result<(String, Vec<Value>), SceneError> {
    let (key, list) = spec.split_once('=').ok_or_else(|| SceneError::Override {
        key: spec.to_string(),
        message: "expected KEY=V1,V2,... (e.g. nu=0.49,0.499,0.4999)".into(),
    })?;
    let mut values = Vec::new();
    let (mut depth, mut start) = (0i32, 0);
    for (i, c) in list.char_indices() {
        match c {
            '[' | '{' => depth += 1,
            ']' | '}' => depth -= 1,
            ',' if depth == 0 => {
                values.push(parse_value(list[start..i].trim()));
                start = i + 1;
            }
            _ => {}
        }
    }
    values.push(parse_value(list[start..].trim()));
    if values.iter().any(|v| v.as_str() == Some("")) {
        return Err(SceneError::Override {
            key: key.to_string(),
            message: "empty value in the sweep list".into(),
        });
    }
    Ok((key.trim().to_string(), values))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn tree() -> Value {
        toml::from_str(
            r#"
            method = "standard"
            [mesh]
            generator = "box"
            res = 2
            [material]
            young = 1.0
            nu = 0.3
            [[dirichlet]]
            selection = "a"
            "#,
        )
        .unwrap()
    }

    #[test]
    fn values_parse_as_toml_or_strings() {
        assert_eq!(parse_value("4"), Value::Integer(4));
        assert_eq!(parse_value("0.4999"), Value::Float(0.4999));
        assert_eq!(parse_value("true"), Value::Boolean(true));
        assert_eq!(parse_value("mixed-p1"), Value::String("mixed-p1".into()));
        assert_eq!(parse_value("a/b.msh"), Value::String("a/b.msh".into()));
        assert!(matches!(parse_value("[0, -9.8, 0]"), Value::Array(a) if a.len() == 3));
    }

    #[test]
    fn flat_and_dotted_keys() {
        let mut t = tree();
        apply(&mut t, &Override::parse("nu=0.49").unwrap()).unwrap();
        apply(&mut t, &Override::parse("res=4").unwrap()).unwrap();
        apply(&mut t, &Override::parse("stepping.steps=3").unwrap()).unwrap();
        apply(&mut t, &Override::parse("dirichlet.0.axes=z").unwrap()).unwrap();
        apply(&mut t, &Override::parse("mu=5").unwrap()).unwrap();
        assert_eq!(t["material"]["nu"].as_float(), Some(0.49));
        assert_eq!(t["mesh"]["res"].as_integer(), Some(4));
        assert_eq!(t["stepping"]["steps"].as_integer(), Some(3));
        assert_eq!(t["dirichlet"][0]["axes"].as_str(), Some("z"));
        assert!(t["material"].get("young").is_none());
        apply(&mut t, &Override::parse("zones=2-ring").unwrap()).unwrap();
        assert_eq!(t["zones"]["kind"].as_str(), Some("k-ring"));
        assert_eq!(t["zones"]["k"].as_integer(), Some(2));
    }

    #[test]
    fn bad_keys_are_named() {
        let mut t = tree();
        let e = apply(&mut t, &Override::parse("nuu=0.3").unwrap()).unwrap_err();
        let msg = e.to_string();
        assert!(
            msg.contains("nuu") && msg.contains("valid:") && msg.contains("nu,"),
            "{msg}"
        );
        let e = apply(&mut t, &Override::parse("dirichlet.3.axes=z").unwrap()).unwrap_err();
        assert!(e.to_string().contains("no index 3"), "{e}");
        assert!(Override::parse("nu").is_err());
        assert!(Override::parse("a..b=1").is_err());
        apply(&mut t, &Override::parse("mesh=foo.msh").unwrap()).unwrap();
        let e = apply(&mut t, &Override::parse("res=2").unwrap()).unwrap_err();
        assert!(e.to_string().contains("file"), "{e}");
    }

    #[test]
    fn overrides_that_set_one_parameter_twice_conflict() {
        let parse = |sets: &[&str]| -> Vec<Override> {
            sets.iter().map(|s| Override::parse(s).unwrap()).collect()
        };
        for sets in [
            &["E=1", "mu=2"][..],
            &["E=1", "young=2"],
            &["rho=1", "density=2"],
            &["nu=0.3", "material.nu=0.4"],
            &["res=2", "mesh=a.msh"],
            &["zones=2-ring", "k=3"],
            &["steps=2", "steps=3"],
        ] {
            let e = check_conflicts(&parse(sets)).unwrap_err();
            assert!(
                e.to_string().contains("conflicts with --set"),
                "{sets:?}: {e}"
            );
        }
        let e = check_conflicts(&parse(&["E=1", "mu=2"])).unwrap_err();
        assert!(e.to_string().contains("alternatives"), "{e}");
        check_conflicts(&parse(&["zones=k-ring", "k=2", "mu=3", "nu=0.4"])).unwrap();
        // Applied in order (the library's reduced scenes extend a list), the later one wins.
        let mut t = tree();
        apply_all(&mut t, &parse(&["nu=0.3", "nu=0.4"])).unwrap();
        assert_eq!(t["material"]["nu"].as_float(), Some(0.4));
    }

    #[test]
    fn sweeps_split_on_top_level_commas() {
        let (k, v) = parse_sweep("nu=0.49,0.499").unwrap();
        assert_eq!(k, "nu");
        assert_eq!(v, vec![Value::Float(0.49), Value::Float(0.499)]);
        let (_, v) = parse_sweep("gravity=[0,0,-1],[0,0,-2]").unwrap();
        assert_eq!(v.len(), 2);
        assert!(parse_sweep("nu").is_err());
        assert!(parse_sweep("nu=0.4,").is_err());
    }
}
