//! The Python exceptions: every error of the Rust crates becomes one, carrying its message
//! (which names the key, the file and line, or the step at fault).

use pyo3::create_exception;
use pyo3::exceptions::PyException;
use pyo3::PyErr;

create_exception!(
    isochor,
    IsochorError,
    PyException,
    "Base class of every isochor error."
);
create_exception!(
    isochor,
    SceneError,
    IsochorError,
    "A scene that cannot be loaded, built or run; the message names the key at fault."
);
create_exception!(
    isochor,
    MeshError,
    IsochorError,
    "A mesh that cannot be read or built; the message names the file and line."
);
create_exception!(
    isochor,
    SolverError,
    IsochorError,
    "The solver refused the problem or failed; `args[1]` (when present) is the Result \
     holding every accepted step."
);

/// The exception of a scenes-layer error: a mesh's and the solver's get their own classes.
pub fn scene_error(e: isochor_scenes::SceneError) -> PyErr {
    match e {
        isochor_scenes::SceneError::Mesh(_) => MeshError::new_err(e.to_string()),
        isochor_scenes::SceneError::Solver(_) => SolverError::new_err(e.to_string()),
        other => SceneError::new_err(other.to_string()),
    }
}

/// The exception of a mesh-layer error.
pub fn mesh_error(e: isochor_mesh::MeshError) -> PyErr {
    MeshError::new_err(e.to_string())
}
