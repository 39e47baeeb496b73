//! Reading and writing a scene's TOML: text or value tree to a checked [`Scene`] and back.

use super::scene::Scene;
use super::validate;
use crate::error::SceneError;

impl Scene {
    /// Parses a scene from TOML text. `origin` names the source in errors.
    pub fn from_toml_str(text: &str, origin: &str) -> Result<Scene, SceneError> {
        let value: toml::Value = toml::from_str(text).map_err(|e| SceneError::Toml {
            origin: origin.to_string(),
            message: e.to_string(),
        })?;
        Scene::from_value(value, origin)
    }

    /// Deserializes a scene from a TOML value tree, naming the key of the first error.
    pub fn from_value(value: toml::Value, origin: &str) -> Result<Scene, SceneError> {
        validate::finite_numbers(&value, origin)?;
        let scene: Scene = serde_path_to_error::deserialize(value).map_err(|e| {
            let key = e.path().to_string();
            SceneError::Invalid {
                origin: origin.to_string(),
                key: if key == "." { String::new() } else { key },
                message: first_line(&e.into_inner().to_string()),
            }
        })?;
        validate::scene(&scene, origin)?;
        Ok(scene)
    }

    /// The scene as a TOML value tree.
    pub fn to_value(&self) -> toml::Value {
        toml::Value::try_from(self).expect("a scene always serializes")
    }

    /// The scene as TOML text.
    pub fn to_toml_string(&self) -> String {
        toml::to_string(self).expect("a scene always serializes")
    }
}

/// The message without the "in `key`" line the TOML deserializer appends (the key is
/// reported separately).
fn first_line(message: &str) -> String {
    message
        .lines()
        .filter(|l| !l.trim().is_empty() && !l.starts_with("in `"))
        .collect::<Vec<_>>()
        .join(" ")
}
