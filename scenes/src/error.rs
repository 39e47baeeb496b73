//! Errors of the scenes layer: each names the key, file or selection at fault and, where there
//! is a closed set of choices, lists them.

use std::path::PathBuf;

/// Why a scene could not be loaded, built, run or written.
#[derive(Debug, thiserror::Error)]
pub enum SceneError {
    /// `name` is neither a built-in scene nor a file.
    #[error("unknown scene '{name}': not a built-in scene (valid: {valid}), nor a file")]
    UnknownScene {
        /// The name given.
        name: String,
        /// The valid names, comma-separated.
        valid: String,
    },
    /// The scene is not valid TOML.
    #[error("{origin}: TOML syntax error: {message}")]
    Toml {
        /// The scene's file or built-in name.
        origin: String,
        /// What is wrong.
        message: String,
    },
    /// A key of the scene is invalid: `origin`: `key`: `message`.
    #[error("{origin}: {}{message}", key_prefix(.key))]
    Invalid {
        /// The scene's file or built-in name.
        origin: String,
        /// The key.
        key: String,
        /// What is wrong.
        message: String,
    },
    /// A command-line override `--set key=value` is invalid.
    #[error("--set {key}: {message}")]
    Override {
        /// The key.
        key: String,
        /// What is wrong.
        message: String,
    },
    /// The scene has no variant of that name.
    #[error("unknown variant '{name}' of scene {scene} (valid: {valid})")]
    UnknownVariant {
        /// The scene's name.
        scene: String,
        /// The variant asked for.
        name: String,
        /// The valid names, comma-separated.
        valid: String,
    },
    /// The mesh could not be built or read.
    #[error("mesh: {0}")]
    Mesh(#[from] isochor_mesh::MeshError),
    /// A selection is invalid or selects nothing.
    #[error("selection '{name}': {message}")]
    Selection {
        /// The selection's name.
        name: String,
        /// What is wrong.
        message: String,
    },
    /// A probe could not be evaluated.
    #[error("probe '{name}': {message}")]
    Probe {
        /// The probe's name.
        name: String,
        /// What is wrong.
        message: String,
    },
    /// The material parameters are invalid.
    #[error("material: {0}")]
    Material(#[from] isochor_energies::ParameterError),
    /// The solver refused the problem or failed.
    #[error("solver: {0}")]
    Solver(#[from] isochor_solvers::SolverError),
    /// A file could not be read or written.
    #[error("{path}: {source}")]
    Io {
        /// The file.
        path: PathBuf,
        /// The underlying I/O error.
        #[source]
        source: std::io::Error,
    },
    /// The output folder could not be written (the message says why).
    #[error("output: {0}")]
    Output(String),
    /// Standard output could not be written.
    #[error("stdout: {0}")]
    Stdout(#[source] std::io::Error),
    /// The command line is invalid (the message says how).
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
