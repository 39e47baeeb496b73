//! `isochor.Frame`: one kept state of a run (the rest state, then every frame the scene's
//! `output.every` keeps, as the VTU frames), its fields as numpy arrays on demand.

use crate::convert::{points, tensors};
use isochor_mesh::{ElementMesh, Vec3};
use isochor_scenes::output::FrameFields;
use isochor_solvers::Frame as SolverFrame;
use nalgebra::Matrix3;
use numpy::{PyArray1, PyArray2, PyArray3};
use pyo3::prelude::*;
use std::sync::Arc;

/// The fields of one state, as the run handed them over.
pub struct FrameData {
    /// Frame index (0: the rest state).
    pub index: usize,
    /// Load parameter or time.
    pub t: f64,
    positions: Vec<Vec3>,
    von_mises: Vec<f64>,
    stress: Vec<Matrix3<f64>>,
    /// Tension positive, as the solver gives it.
    nodal_pressures: Option<Vec<f64>>,
}

impl FrameData {
    /// The rest state of `mesh`.
    pub fn rest(mesh: &ElementMesh) -> FrameData {
        FrameData {
            index: 0,
            t: 0.0,
            positions: mesh.nodes().to_vec(),
            von_mises: vec![0.0; mesh.num_elements()],
            stress: vec![Matrix3::zeros(); mesh.num_elements()],
            nodal_pressures: None,
        }
    }

    /// A copy of the fields of the solver's frame `index`.
    pub fn of(index: usize, frame: &SolverFrame<'_>) -> FrameData {
        FrameData {
            index,
            t: frame.state.t,
            positions: frame.state.positions.clone(),
            von_mises: frame.von_mises.clone(),
            stress: frame.stress.clone(),
            nodal_pressures: frame.nodal_pressures.clone(),
        }
    }
}

/// One state of a run. Every array attribute is a new copy (shapes: `nodes` and `elements`
/// of `result.mesh`).
#[pyclass(module = "isochor", frozen)]
pub struct Frame {
    data: FrameData,
    mesh: Arc<ElementMesh>,
}

impl Frame {
    /// The frame `data` on `mesh`.
    pub fn new(data: FrameData, mesh: Arc<ElementMesh>) -> Frame {
        Frame { data, mesh }
    }

    fn fields(&self) -> FrameFields<'_> {
        FrameFields {
            positions: &self.data.positions,
            velocities: &[],
            von_mises: &self.data.von_mises,
            stress: &self.data.stress,
            nodal_pressures: &[],
            contact_forces: &[],
            obstacle_positions: &[],
        }
    }
}

#[pymethods]
impl Frame {
    /// Frame index: 0 is the rest state, `k` the `k`-th frame of the run.
    #[getter]
    fn index(&self) -> usize {
        self.data.index
    }

    /// Load parameter (quasi-static, 0 to 1) or time in seconds (dynamics).
    #[getter]
    fn t(&self) -> f64 {
        self.data.t
    }

    /// Deformed node positions, `(nodes, 3)` float64 (m).
    #[getter]
    fn positions<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray2<f64>>> {
        points(py, &self.data.positions)
    }

    /// Node displacements from the rest positions, `(nodes, 3)` float64 (m).
    #[getter]
    fn displacement<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray2<f64>>> {
        points(py, &self.fields().displacements(&self.mesh))
    }

    /// The nodal pressure unknowns of `mixed-p1`, `mixed-p1-log` and `dual`, compression
    /// positive as in the VTU frames, `(nodes,)` float64 (Pa); `None` for the other methods
    /// and the rest state.
    #[getter]
    fn pressure<'py>(&self, py: Python<'py>) -> Option<Bound<'py, PyArray1<f64>>> {
        let p = self.data.nodal_pressures.as_ref()?;
        Some(PyArray1::from_vec(py, p.iter().map(|p| -p).collect()))
    }

    /// Cauchy stress at each element's centroid, `(elements, 3, 3)` float64, tension
    /// positive (Pa).
    #[getter]
    fn stress<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray3<f64>>> {
        let flat = self
            .data
            .stress
            .iter()
            .flat_map(|s| {
                let r = s.transpose(); // nalgebra is column-major: rows of s are columns of r
                r.as_slice().to_vec()
            })
            .collect();
        tensors(py, flat)
    }

    /// Von Mises stress of each element, `(elements,)` float64 (Pa).
    #[getter]
    fn von_mises<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        PyArray1::from_vec(py, self.fields().von_mises_or_zeros(&self.mesh))
    }

    /// Deformed over rest volume of each element, `(elements,)` float64.
    #[getter(J)]
    fn volume_ratio<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        PyArray1::from_vec(py, self.fields().volume_ratios(&self.mesh))
    }

    fn __repr__(&self) -> String {
        format!("Frame({}, t={})", self.data.index, self.data.t)
    }
}
