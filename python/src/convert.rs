//! Python values to TOML values (a scene from a dict, `scene.set`), and flat Rust buffers to
//! numpy arrays (always copies: an array never points into memory Rust frees).

use crate::errors::SceneError;
use isochor_mesh::Vec3;
use numpy::{PyArray1, PyArray2, PyArray3, PyArrayMethods};
use pyo3::prelude::*;
use pyo3::types::{PyBool, PyDict, PyFloat, PyInt, PyList, PyString, PyTuple};

/// The TOML value of a Python value: bool, int, float, str, list or tuple, dict with str
/// keys, or anything with `tolist()` (numpy arrays and scalars). `key` names the value in
/// the error.
pub fn to_toml(value: &Bound<'_, PyAny>, key: &str) -> PyResult<toml::Value> {
    if value.is_instance_of::<PyBool>() {
        return Ok(toml::Value::Boolean(value.extract()?));
    }
    if value.is_instance_of::<PyInt>() {
        return Ok(toml::Value::Integer(value.extract()?));
    }
    if value.is_instance_of::<PyFloat>() {
        return Ok(toml::Value::Float(value.extract()?));
    }
    if value.is_instance_of::<PyString>() {
        return Ok(toml::Value::String(value.extract()?));
    }
    if let Ok(dict) = value.cast::<PyDict>() {
        let mut table = toml::Table::new();
        for (k, v) in dict.iter() {
            let name: String = k.extract().map_err(|_| {
                SceneError::new_err(format!("key '{key}': a table's keys must be strings"))
            })?;
            let path = if key.is_empty() {
                name.clone()
            } else {
                format!("{key}.{name}")
            };
            table.insert(name, to_toml(&v, &path)?);
        }
        return Ok(toml::Value::Table(table));
    }
    if value.is_instance_of::<PyList>() || value.is_instance_of::<PyTuple>() {
        let items = value
            .try_iter()?
            .enumerate()
            .map(|(i, v)| to_toml(&v?, &format!("{key}.{i}")))
            .collect::<PyResult<_>>()?;
        return Ok(toml::Value::Array(items));
    }
    if value.hasattr("tolist")? {
        return to_toml(&value.call_method0("tolist")?, key);
    }
    Err(SceneError::new_err(format!(
        "key '{key}': {} is not a scene value (bool, int, float, str, list or dict)",
        value.get_type().name()?
    )))
}

/// An `(n, 3)` float64 array of points.
pub fn points<'py>(py: Python<'py>, v: &[Vec3]) -> PyResult<Bound<'py, PyArray2<f64>>> {
    let flat: Vec<f64> = v.iter().flat_map(|p| [p.x, p.y, p.z]).collect();
    PyArray1::from_vec(py, flat).reshape([v.len(), 3])
}

/// An `(n, width)` array of the flat row-major `values`.
pub fn rows<'py, T: numpy::Element>(
    py: Python<'py>,
    values: Vec<T>,
    width: usize,
) -> PyResult<Bound<'py, PyArray2<T>>> {
    let n = values.len().checked_div(width).unwrap_or(0);
    PyArray1::from_vec(py, values).reshape([n, width])
}

/// An `(n, 3, 3)` array of the flat row-major 3x3 `values`.
pub fn tensors<'py>(py: Python<'py>, values: Vec<f64>) -> PyResult<Bound<'py, PyArray3<f64>>> {
    let n = values.len() / 9;
    PyArray1::from_vec(py, values).reshape([n, 3, 3])
}

/// Indices as int64 (numpy's and VTK's index type).
pub fn indices(v: &[usize]) -> Vec<i64> {
    v.iter().map(|&i| i as i64).collect()
}
