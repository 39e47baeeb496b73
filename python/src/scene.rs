//! `isochor.Scene`: a scene of the TOML format (a built-in one, a file, or a dict of the same
//! keys) with a variant and overrides, validated by the scenes crate at every change so that
//! a bad key raises where it is set, with the command line's message.

use crate::convert::to_toml;
use crate::errors::scene_error;
use isochor_scenes::format::builtin;
use isochor_scenes::format::overrides::check_key_syntax;
use isochor_scenes::{Override, SceneSource};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::PyDict;
use std::path::PathBuf;

/// A scene with its variant and overrides. Immutable: `set`, `apply`, `variant` and
/// `reduced` return a new scene.
#[pyclass(module = "isochor", frozen)]
#[derive(Clone)]
pub struct Scene {
    source: SceneSource,
    variant: Option<String>,
    overrides: Vec<Override>,
    /// The scene as the scenes crate loaded it.
    pub loaded: isochor_scenes::Scene,
}

impl Scene {
    /// Loads `source` with `variant` and `overrides`.
    fn new(
        source: SceneSource,
        variant: Option<String>,
        overrides: Vec<Override>,
    ) -> PyResult<Scene> {
        let loaded = source
            .load(variant.as_deref(), &overrides)
            .map_err(scene_error)?;
        Ok(Scene {
            source,
            variant,
            overrides,
            loaded,
        })
    }

    /// The same scene with `more` overrides after its own.
    fn with(&self, more: Vec<Override>) -> PyResult<Scene> {
        let mut overrides = self.overrides.clone();
        overrides.extend(more);
        Scene::new(self.source.clone(), self.variant.clone(), overrides)
    }

    /// The variant's name, if any.
    pub fn variant_name(&self) -> Option<String> {
        self.variant.clone()
    }

    /// The overrides applied.
    pub fn override_list(&self) -> &[Override] {
        &self.overrides
    }
}

/// A scene source from TOML text (for error messages: `origin`).
fn text_source(text: String, origin: &str, base_dir: Option<PathBuf>) -> SceneSource {
    SceneSource {
        text,
        origin: origin.to_string(),
        base_dir: base_dir.unwrap_or_else(|| std::env::current_dir().unwrap_or_default()),
    }
}

#[pymethods]
impl Scene {
    /// The built-in scene `name` (`isochor.builtin_names()` lists them).
    #[staticmethod]
    fn builtin(name: &str) -> PyResult<Scene> {
        if builtin::builtin(name).is_none() {
            return Err(crate::errors::SceneError::new_err(format!(
                "unknown built-in scene '{name}' (valid: {})",
                builtin::names().collect::<Vec<_>>().join(", ")
            )));
        }
        Scene::new(
            SceneSource::resolve(name).map_err(scene_error)?,
            None,
            Vec::new(),
        )
    }

    /// The TOML scene file at `path` (a relative mesh path in it is read from the file's folder).
    #[staticmethod]
    fn load(path: PathBuf) -> PyResult<Scene> {
        let mut spec = path.to_string_lossy().into_owned();
        if !spec.contains(std::path::is_separator) {
            // A bare file name is a file here, never a built-in scene of the same name.
            spec = format!(".{}{spec}", std::path::MAIN_SEPARATOR);
        }
        Scene::new(
            SceneSource::resolve(&spec).map_err(scene_error)?,
            None,
            Vec::new(),
        )
    }

    /// A scene from a dict of the TOML format's keys (validated with the same messages);
    /// relative mesh paths are read from `base_dir` (default: the working folder).
    #[staticmethod]
    #[pyo3(signature = (scene, base_dir=None))]
    fn from_dict(scene: &Bound<'_, PyDict>, base_dir: Option<PathBuf>) -> PyResult<Scene> {
        let value = to_toml(scene.as_any(), "")?;
        let text = toml::to_string(&value)
            .map_err(|e| crate::errors::SceneError::new_err(format!("scene from a dict: {e}")))?;
        Scene::new(
            text_source(text, "scene from a dict", base_dir),
            None,
            Vec::new(),
        )
    }

    /// A scene from TOML text; relative mesh paths are read from `base_dir`.
    #[staticmethod]
    #[pyo3(signature = (text, base_dir=None))]
    fn from_toml(text: String, base_dir: Option<PathBuf>) -> PyResult<Scene> {
        Scene::new(
            text_source(text, "scene from TOML text", base_dir),
            None,
            Vec::new(),
        )
    }

    /// The scene with `key` (a flat name such as `nu`, `res`, `method`, or a dotted path such
    /// as `material.nu`) set to `value` (bool, int, float, str, list, dict, numpy values).
    fn set(&self, key: &str, value: &Bound<'_, PyAny>) -> PyResult<Scene> {
        check_key_syntax(key)
            .map_err(|m| crate::errors::SceneError::new_err(format!("key '{key}': {m}")))?;
        self.with(vec![Override::new(key, to_toml(value, key)?)])
    }

    /// The scene with command-line overrides `KEY=VALUE` (`VALUE` read as TOML, else as a
    /// bare string), as `isochor run --set` takes them.
    #[pyo3(signature = (*assignments))]
    fn apply(&self, assignments: Vec<String>) -> PyResult<Scene> {
        let parsed = assignments
            .iter()
            .map(|a| Override::parse(a).map_err(scene_error))
            .collect::<PyResult<_>>()?;
        self.with(parsed)
    }

    /// The scene with its variant `name` applied (before the overrides).
    fn variant(&self, name: &str) -> PyResult<Scene> {
        Scene::new(
            self.source.clone(),
            Some(name.to_string()),
            self.overrides.clone(),
        )
    }

    /// The quick version of a built-in scene (its `reduced` overrides, as the tests run it).
    fn reduced(&self) -> PyResult<Scene> {
        let sets = builtin::reduced(&self.loaded.name)
            .filter(|_| self.source.origin.starts_with("built-in scene"))
            .ok_or_else(|| {
                PyValueError::new_err(format!(
                    "scene {} is not a built-in scene with a reduced version",
                    self.loaded.name
                ))
            })?;
        self.apply(sets.iter().map(|s| s.to_string()).collect())
    }

    /// The scene's name.
    #[getter]
    fn name(&self) -> String {
        self.loaded.name.clone()
    }

    /// Its method (`"mixed-p1"`, ...).
    #[getter]
    fn method(&self) -> &'static str {
        self.loaded.method().name()
    }

    /// Its element (`"tet4"` or `"tet10"`).
    #[getter]
    fn element(&self) -> &'static str {
        self.loaded.element().name()
    }

    /// The steps (quasi-static) or frames (dynamic) the run takes.
    #[getter]
    fn num_steps(&self) -> usize {
        self.loaded.num_steps()
    }

    /// The names of its variants.
    #[getter]
    fn variants(&self) -> Vec<String> {
        self.loaded.variants.keys().cloned().collect()
    }

    /// The overrides applied, as `KEY=VALUE`.
    #[getter]
    fn overrides(&self) -> Vec<String> {
        self.overrides
            .iter()
            .map(|o| format!("{}={}", o.key, o.display_value()))
            .collect()
    }

    /// The scene as TOML text (variant and overrides applied).
    fn to_toml(&self) -> String {
        self.loaded.to_toml_string()
    }

    fn __repr__(&self) -> String {
        let mut s = format!("Scene('{}'", self.loaded.name);
        if let Some(v) = &self.variant {
            s += &format!(", variant='{v}'");
        }
        for o in self.overrides() {
            s += &format!(", {o}");
        }
        s + ")"
    }
}

/// The names of the built-in scenes.
#[pyfunction]
pub fn builtin_names() -> Vec<&'static str> {
    builtin::names().collect()
}

/// The overrides (`KEY=VALUE`) of a built-in scene's quick version, or `None`.
#[pyfunction]
pub fn reduced(name: &str) -> Option<Vec<&'static str>> {
    builtin::reduced(name).map(<[_]>::to_vec)
}
