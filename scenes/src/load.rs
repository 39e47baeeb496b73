//! Finding a scene (a built-in name or a TOML file) and applying a variant and `--set`
//! overrides to it.

use crate::overrides::{apply_all, Override};
use crate::scene::{MeshSpec, Scene};
use crate::{builtin, SceneError};
use std::path::{Path, PathBuf};

/// A scene's TOML text and where it came from.
#[derive(Debug, Clone)]
pub struct SceneSource {
    /// The text.
    pub text: String,
    /// For error messages: `built-in scene NAME` or the file path.
    pub origin: String,
    /// Folder against which a relative mesh path is resolved.
    pub base_dir: PathBuf,
}

impl SceneSource {
    /// A built-in scene by name, or else a TOML file by path.
    pub fn resolve(spec: &str) -> Result<SceneSource, SceneError> {
        if let Some(text) = builtin::builtin(spec) {
            return Ok(SceneSource {
                text: text.to_string(),
                origin: format!("built-in scene {spec}"),
                base_dir: std::env::current_dir().unwrap_or_default(),
            });
        }
        let path = Path::new(spec);
        if !path.is_file() {
            return Err(SceneError::UnknownScene {
                name: spec.to_string(),
                valid: builtin::names().collect::<Vec<_>>().join(", "),
            });
        }
        let text = std::fs::read_to_string(path).map_err(|e| SceneError::io(path, e))?;
        let base_dir = path
            .parent()
            .filter(|p| !p.as_os_str().is_empty())
            .map(Path::to_path_buf)
            .unwrap_or_else(|| PathBuf::from("."));
        Ok(SceneSource {
            text,
            origin: path.display().to_string(),
            base_dir,
        })
    }

    /// Parses the scene, applies the named variant (if any) and then the overrides.
    pub fn load(&self, variant: Option<&str>, overrides: &[Override]) -> Result<Scene, SceneError> {
        let tree: toml::Value = toml::from_str(&self.text).map_err(|e| SceneError::Toml {
            origin: self.origin.clone(),
            message: e.to_string(),
        })?;
        // The scene as written must be valid on its own, so that its variants can be listed.
        let base = Scene::from_value(tree.clone(), &self.origin)?;
        let mut all = Vec::new();
        if let Some(name) = variant {
            let sets = base
                .variants
                .get(name)
                .ok_or_else(|| SceneError::UnknownVariant {
                    scene: base.name.clone(),
                    name: name.to_string(),
                    valid: base.variants.keys().cloned().collect::<Vec<_>>().join(", "),
                })?;
            all.extend(
                sets.iter()
                    .map(|(k, v)| Override::new(k.clone(), v.clone())),
            );
        }
        all.extend_from_slice(overrides);
        if all.is_empty() {
            return Ok(self.resolve_paths(base));
        }
        let mut tree = tree;
        apply_all(&mut tree, &all)?;
        let origin = format!("{} (with --set overrides)", self.origin);
        Ok(self.resolve_paths(Scene::from_value(tree, &origin)?))
    }

    fn resolve_paths(&self, mut scene: Scene) -> Scene {
        if let MeshSpec::File { path } = &mut scene.mesh {
            if path.is_relative() {
                *path = self.base_dir.join(&*path);
            }
        }
        scene
    }
}

/// Loads a scene by name or path with a variant and overrides.
pub fn load_scene(
    spec: &str,
    variant: Option<&str>,
    overrides: &[Override],
) -> Result<Scene, SceneError> {
    SceneSource::resolve(spec)?.load(variant, overrides)
}
