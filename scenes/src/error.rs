//! Errors of the scenes layer: each names the key, file or selection at fault and, where there
//! is a closed set of choices, lists them.

use std::path::PathBuf;

/// Why a scene could not be loaded, built, run or written.
#[derive(Debug, thiserror::Error)]
pub enum SceneError {
    #[error("unknown scene '{name}': not a built-in scene (valid: {valid}), nor a file")]
    UnknownScene { name: String, valid: String },
    #[error("{origin}: TOML syntax error: {message}")]
    Toml { origin: String, message: String },
    #[error("{origin}: {}{message}", key_prefix(.key))]
    Invalid {
        origin: String,
        key: String,
        message: String,
    },
    #[error("--set {key}: {message}")]
    Override { key: String, message: String },
    #[error("unknown variant '{name}' of scene {scene} (valid: {valid})")]
    UnknownVariant {
        scene: String,
        name: String,
        valid: String,
    },
    #[error("mesh: {0}")]
    Mesh(#[from] isochor_mesh::MeshError),
    #[error("selection '{name}': {message}")]
    Selection { name: String, message: String },
    #[error("probe '{name}': {message}")]
    Probe { name: String, message: String },
    #[error("material: {0}")]
    Material(#[from] isochor_energies::ParameterError),
    #[error("solver: {0}")]
    Solver(#[from] isochor_solvers::SolverError),
    #[error("{path}: {source}")]
    Io {
        path: PathBuf,
        #[source]
        source: std::io::Error,
    },
    #[error("output: {0}")]
    Output(String),
    #[error("stdout: {0}")]
    Stdout(#[source] std::io::Error),
    #[error("{0}")]
    Usage(String),
}

fn key_prefix(key: &str) -> String {
    if key.is_empty() {
        String::new()
    } else {
        format!("key '{key}': ")
    }
}

impl SceneError {
    /// An I/O error on `path`.
    pub fn io(path: impl Into<PathBuf>, source: std::io::Error) -> Self {
        SceneError::Io {
            path: path.into(),
            source,
        }
    }
}
