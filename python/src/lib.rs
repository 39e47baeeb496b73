//! The `isochor` Python package's native module, `isochor._isochor`: scenes from Python
//! (`scene`), runs with their results as numpy arrays (`run`, `frames`), and meshes
//! read from files (`mesh`). Built by maturin as an abi3 extension (CPython >= 3.11); the
//! pure-Python parts of the package (`isochor/__init__.py`) wrap it. docs/python.md is the
//! user's page.

#![deny(missing_docs)]

mod convert;
mod errors;
mod frames;
mod mesh;
mod run;
mod scene;

use pyo3::prelude::*;

/// The native module `isochor._isochor`.
#[pymodule]
fn _isochor(m: &Bound<'_, PyModule>) -> PyResult<()> {
    let py = m.py();
    m.add("IsochorError", py.get_type::<errors::IsochorError>())?;
    m.add("SceneError", py.get_type::<errors::SceneError>())?;
    m.add("MeshError", py.get_type::<errors::MeshError>())?;
    m.add("SolverError", py.get_type::<errors::SolverError>())?;
    m.add_class::<scene::Scene>()?;
    m.add_class::<run::RunResult>()?;
    m.add_class::<frames::Frame>()?;
    m.add_class::<mesh::Mesh>()?;
    m.add_function(wrap_pyfunction!(scene::builtin_names, m)?)?;
    m.add_function(wrap_pyfunction!(scene::reduced, m)?)?;
    m.add_function(wrap_pyfunction!(run::run, m)?)?;
    m.add_function(wrap_pyfunction!(mesh::read_mesh, m)?)?;
    m.add_function(wrap_pyfunction!(mesh::mesh_from_arrays, m)?)?;
    Ok(())
}
