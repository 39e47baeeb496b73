//! The file that makes a folder an isochor output folder: `.isochor-output.json`, written
//! into every output folder with the identity of the run that wrote it. Only a folder holding
//! it (or an empty one) is ever replaced.

use crate::error::SceneError;
use std::path::Path;

/// The marker's file name.
pub const MARKER_FILE: &str = ".isochor-output.json";

/// Who wrote an output folder.
#[derive(Debug, Clone)]
pub struct OutputIdentity {
    /// The command (`run`, `compare`, `study`, `penalties`).
    pub command: String,
    /// The scene's name (empty for `penalties`).
    pub scene: String,
}

impl OutputIdentity {
    /// The identity of `command` on `scene`.
    pub fn new(command: &str, scene: &str) -> Self {
        OutputIdentity {
            command: command.into(),
            scene: scene.into(),
        }
    }

    /// Writes the marker into `dir`: command, scene, start time (seconds since 1970 UTC),
    /// process id and program version.
    pub(super) fn write(&self, dir: &Path) -> Result<(), SceneError> {
        let started = std::time::SystemTime::now()
            .duration_since(std::time::UNIX_EPOCH)
            .map_or(0, |d| d.as_secs());
        let json = serde_json::json!({
            "program": "isochor",
            "version": env!("CARGO_PKG_VERSION"),
            "command": self.command,
            "scene": self.scene,
            "started_unix_s": started,
            "pid": std::process::id(),
        });
        let path = dir.join(MARKER_FILE);
        std::fs::write(&path, format!("{json:#}\n")).map_err(|e| SceneError::io(&path, e))
    }
}

/// Whether `dir` holds a marker.
pub(super) fn is_marked(dir: &Path) -> bool {
    dir.join(MARKER_FILE).is_file()
}
