//! Finding a scene (a built-in name or a TOML file) and applying a variant and `--set`
//! overrides to it.

use super::builtin;
use super::limits;
use super::mesh::MeshSpec;
use super::obstacles::ObstacleSpec;
use super::overrides::{apply_all, Override};
use super::scene::Scene;
use crate::error::SceneError;
use isochor_mesh::io::excerpt as shown;
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
    /// A built-in scene by name, or else a TOML file by path. A name that looks like a path
    /// (it has a `/` or ends in `.toml`) or names an existing file is read as a file, with the
    /// I/O error if that fails; any other unknown name lists the built-in scenes.
    pub fn resolve(spec: &str) -> Result<SceneSource, SceneError> {
        if let Some(text) = builtin::builtin(spec) {
            return Ok(SceneSource {
                text: text.to_string(),
                origin: format!("built-in scene {spec}"),
                base_dir: std::env::current_dir().unwrap_or_default(),
            });
        }
        let path = Path::new(spec);
        let looks_like_path = spec.contains(std::path::is_separator) || spec.ends_with(".toml");
        if !looks_like_path && path.symlink_metadata().is_err() {
            return Err(SceneError::UnknownScene {
                name: shown(spec),
                valid: builtin::names().collect::<Vec<_>>().join(", "),
            });
        }
        if path.is_dir() {
            return Err(SceneError::io(
                path,
                std::io::Error::other("is a directory, not a scene file"),
            ));
        }
        // A device or FIFO would be read for ever, or block.
        isochor_mesh::io::check_regular_file(path).map_err(|e| SceneError::Invalid {
            origin: path.display().to_string(),
            key: String::new(),
            message: match e {
                isochor_mesh::MeshError::Format { message, .. } => message,
                other => other.to_string(),
            },
        })?;
        let bytes = std::fs::read(path).map_err(|e| {
            let e = match e.kind() {
                std::io::ErrorKind::NotFound => std::io::Error::new(
                    e.kind(),
                    format!(
                        "no such scene file (built-in scenes: {})",
                        builtin::names().collect::<Vec<_>>().join(", ")
                    ),
                ),
                _ => e,
            };
            SceneError::io(path, e)
        })?;
        let text = String::from_utf8(bytes).map_err(|e| {
            SceneError::io(
                path,
                std::io::Error::other(format!(
                    "not a TOML scene: invalid UTF-8 at byte {}",
                    e.utf8_error().valid_up_to()
                )),
            )
        })?;
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

    /// Parses the scene, applies the named variant (if any) and then the overrides, and checks
    /// that the result fits in memory ([`super::limits`]).
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
            let scene = self.resolve_paths(base)?;
            limits::check_memory(&scene, &self.origin)?;
            return Ok(scene);
        }
        let mut tree = tree;
        apply_all(&mut tree, &all)?;
        let origin = format!("{} (with --set overrides)", self.origin);
        let scene = self.resolve_paths(Scene::from_value(tree, &origin)?)?;
        limits::check_memory(&scene, &origin)?;
        Ok(scene)
    }

    /// Resolves a relative mesh path of every body and meshed obstacle against the scene's
    /// folder and refuses a
    /// path that is a device, FIFO or socket (the header scan of
    /// [`limits::check_memory`] reads it next).
    fn resolve_paths(&self, mut scene: Scene) -> Result<Scene, SceneError> {
        let meshes = scene.mesh.iter_mut();
        for mesh in meshes.chain(scene.bodies.iter_mut().map(|b| &mut b.mesh)) {
            let MeshSpec::File { path } = mesh else {
                continue;
            };
            if path.is_relative() {
                *path = self.base_dir.join(&*path);
            }
            let tetgen = matches!(
                path.extension().and_then(|e| e.to_str()),
                Some("node" | "ele")
            );
            isochor_mesh::io::check_regular_file(path)?;
            if tetgen {
                for ext in ["node", "ele"] {
                    isochor_mesh::io::check_regular_file(&path.with_extension(ext))?;
                }
            }
        }
        for obstacle in &mut scene.obstacles {
            if let ObstacleSpec::Mesh { path, .. } = obstacle {
                if path.is_relative() {
                    *path = self.base_dir.join(&*path);
                }
                isochor_mesh::io::check_regular_file(path)?;
            }
        }
        Ok(scene)
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
