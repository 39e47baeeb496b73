//! `isochor.run`: a scene run by the scenes crate's `run_scene` with the GIL released, every
//! accepted step handed to the Python progress callback and the kept frames copied out.

use crate::errors::{scene_error, SolverError};
use crate::frames::{Frame, FrameData};
use crate::mesh::Mesh;
use crate::scene::Scene;
use isochor_mesh::{ElementMesh, PhysicalGroups};
use isochor_scenes::commands::run::StepHook;
use isochor_scenes::record::StepRecord;
use isochor_scenes::{resolve, run_scene, RunOptions};
use numpy::{PyArray1, PyArrayMethods};
use pyo3::prelude::*;
use pyo3::types::PyDict;
use std::ops::ControlFlow;
use std::path::PathBuf;
use std::sync::{Arc, Mutex};

/// What the run's step hook collects.
#[derive(Default)]
struct Collected {
    frames: Vec<FrameData>,
    /// The exception of the progress callback (or a pending Ctrl-C) that stopped the run.
    error: Option<PyErr>,
}

/// The result of a run: the command line's `--json` object, the per-step table, the kept
/// frames and the mesh.
#[pyclass(module = "isochor", frozen)]
pub struct RunResult {
    result: isochor_scenes::RunResult,
    /// The `--json` object as JSON text (`isochor run --json` prints the same).
    #[pyo3(get)]
    json: String,
    frames: Vec<Py<Frame>>,
    /// The mesh the run was on (rest nodes, elements, region of each element).
    #[pyo3(get)]
    mesh: Py<Mesh>,
    /// The output folder, if the run wrote one.
    #[pyo3(get)]
    out: Option<PathBuf>,
}

/// The per-step columns of the history: `(name, value of a step)`.
type Column = (&'static str, fn(&StepRecord) -> f64);

const COLUMNS: &[Column] = &[
    ("t", |s| s.t),
    ("increment", |s| s.increment),
    ("volume_change", |s| s.volume_change),
    ("kinetic_energy", |s| s.kinetic_energy),
    ("elastic_energy", |s| s.elastic_energy),
    ("constraint_energy", |s| s.constraint_energy),
    ("external_energy", |s| s.external_energy),
    ("wall_time_s", |s| s.wall_time_s),
    ("max_penetration", |s| s.contact.max_penetration),
];

/// The per-step counts of the history: `(name, count of a step)`.
type Count = (&'static str, fn(&StepRecord) -> usize);

const COUNTS: &[Count] = &[
    ("step", |s| s.step),
    ("newton_iterations", |s| s.newton_iterations),
    ("cuts", |s| s.cuts.len()),
    ("inverted_tets", |s| s.inverted_tets),
    ("active_vertices", |s| s.contact.active_vertices),
];

#[pymethods]
impl RunResult {
    /// Named scalar results of the final state.
    #[getter]
    fn probes(&self) -> std::collections::BTreeMap<String, f64> {
        self.result.probes.clone()
    }

    /// Whether every step converged.
    #[getter]
    fn converged(&self) -> bool {
        self.result.converged
    }

    /// The solver's error if the run stopped early, else `None`.
    #[getter]
    fn error(&self) -> Option<String> {
        self.result.error.clone()
    }

    /// The per-step table: a dict of `(steps,)` arrays, float64 (`t`, `increment`,
    /// `volume_change`, the energies, `wall_time_s`, `max_penetration`), int64 (`step`,
    /// `newton_iterations`, `cuts`, `inverted_tets`, `active_vertices`), bool (`converged`),
    /// and `contact_force` `(steps, 3)` float64.
    #[getter]
    fn steps<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let h = &self.result.history;
        let d = PyDict::new(py);
        for (name, f) in COUNTS {
            let v: Vec<i64> = h.iter().map(|s| f(s) as i64).collect();
            d.set_item(*name, PyArray1::from_vec(py, v))?;
        }
        for (name, f) in COLUMNS {
            d.set_item(*name, PyArray1::from_vec(py, h.iter().map(f).collect()))?;
        }
        let converged: Vec<bool> = h.iter().map(|s| s.converged).collect();
        d.set_item("converged", PyArray1::from_vec(py, converged))?;
        let force: Vec<f64> = h.iter().flat_map(|s| s.contact.force).collect();
        d.set_item(
            "contact_force",
            PyArray1::from_vec(py, force).reshape([h.len(), 3])?,
        )?;
        Ok(d)
    }

    /// The kept states: the rest state first, then every frame the scene's `output.every`
    /// keeps (and always the last accepted one).
    #[getter]
    fn frames(&self, py: Python<'_>) -> Vec<Py<Frame>> {
        self.frames.iter().map(|f| f.clone_ref(py)).collect()
    }

    fn __repr__(&self) -> String {
        format!(
            "RunResult(scene='{}', method='{}', converged={}, steps={}, probes={:?})",
            self.result.scene,
            self.result.method,
            self.result.converged,
            self.result.steps,
            self.result.probes
        )
    }
}

/// The region of every element of a resolved problem (0: the body's material).
fn element_regions(problem: &isochor_solvers::Problem) -> Vec<i32> {
    let mut ids = vec![0; problem.mesh.num_elements()];
    for (i, region) in problem.regions.iter().enumerate() {
        for &e in &region.elements {
            ids[e] = i as i32 + 1;
        }
    }
    ids
}

/// Whether frame `index` of `total` is kept, as the VTU writer keeps it (every `every`-th
/// and the last).
fn kept(index: usize, every: usize, total: usize) -> bool {
    index % every.max(1) == 0 || index == total
}

/// The step hook: copies the kept frames, then calls `progress(step, t, newton_iterations)`
/// with the GIL held and checks for Ctrl-C; an exception of either stops the run there (its
/// frame kept).
fn hook(
    collected: Arc<Mutex<Collected>>,
    progress: Option<Py<PyAny>>,
    keep_frames: bool,
    every: usize,
    total: usize,
) -> StepHook {
    StepHook(Arc::new(move |frame| {
        let mut c = collected.lock().unwrap_or_else(|e| e.into_inner());
        let k = frame.frame;
        if keep_frames && k.is_some_and(|k| kept(k, every, total)) {
            c.frames.extend(k.map(|k| FrameData::of(k, frame)));
        }
        let outcome = Python::attach(|py| {
            py.check_signals()?;
            if let Some(f) = &progress {
                f.call1(
                    py,
                    (frame.index, frame.state.t, frame.report.newton_iterations()),
                )?;
            }
            Ok::<(), PyErr>(())
        });
        let Err(e) = outcome else {
            return ControlFlow::Continue(());
        };
        // The last good state is the run's last frame.
        if keep_frames && c.frames.last().map(|f| f.index) != k {
            c.frames.extend(k.map(|k| FrameData::of(k, frame)));
        }
        c.error = Some(e);
        ControlFlow::Break(())
    }))
}

/// Runs `scene` (see docs/python.md).
#[pyfunction]
#[pyo3(signature = (scene, out=None, progress=None, frames=true, check=false))]
pub fn run(
    py: Python<'_>,
    scene: &Scene,
    out: Option<PathBuf>,
    progress: Option<Py<PyAny>>,
    frames: bool,
    check: bool,
) -> PyResult<RunResult> {
    let loaded = scene.loaded.clone();
    let (mesh, regions) = py
        .detach(|| {
            resolve::build(&loaded).map(|r| {
                let regions = element_regions(&r.problem);
                (r.problem.mesh, regions)
            })
        })
        .map_err(scene_error)?;
    let mesh: Arc<ElementMesh> = Arc::new(mesh);
    let collected = Arc::new(Mutex::new(Collected::default()));
    if frames {
        collected
            .lock()
            .unwrap()
            .frames
            .push(FrameData::rest(&mesh));
    }
    let mut options = RunOptions::in_memory(scene.variant_name(), scene.override_list(), false);
    options.out = out;
    options.on_step = Some(hook(
        collected.clone(),
        progress,
        frames,
        loaded.output.every,
        loaded.num_steps(),
    ));
    let outcome = py.detach(|| run_scene(&loaded, &options));
    let collected = std::mem::take(&mut *collected.lock().unwrap_or_else(|e| e.into_inner()));
    let (result, out) = match (outcome, collected.error) {
        (Ok(run), None) => run,
        (Err(e), None) => return Err(scene_error(e)),
        (Err(_), Some(stop)) => return Err(stop),
        (Ok((mut result, out)), Some(stop)) => {
            // The exception that stopped the run, raised with the run up to there.
            let error = result.error.take().unwrap_or_default();
            result.error = Some(format!("{error}: {}", exception_text(py, &stop)));
            let run = result_of(py, result, out, &mesh, regions, collected.frames)?;
            stop.value(py).setattr("result", Py::new(py, run)?)?;
            return Err(stop);
        }
    };
    let error = result.error.clone();
    let run = result_of(py, result, out, &mesh, regions, collected.frames)?;
    match error {
        Some(message) if check => {
            let run = Py::new(py, run)?;
            Err(SolverError::new_err((message, run)))
        }
        _ => Ok(run),
    }
}

/// `Type: message` of an exception, `Type` alone when its message is empty (Ctrl-C's
/// `KeyboardInterrupt`).
fn exception_text(py: Python<'_>, e: &PyErr) -> String {
    let name = e
        .get_type(py)
        .name()
        .map(|n| n.to_string())
        .unwrap_or_default();
    match e.value(py).str().map(|s| s.to_string()) {
        Ok(message) if !message.is_empty() => format!("{name}: {message}"),
        _ => name,
    }
}

/// The Python result of the run `result` on `mesh`, with its kept `frames`.
fn result_of(
    py: Python<'_>,
    result: isochor_scenes::RunResult,
    out: Option<PathBuf>,
    mesh: &Arc<ElementMesh>,
    regions: Vec<i32>,
    frames: Vec<FrameData>,
) -> PyResult<RunResult> {
    let json = serde_json::to_string(&result.to_json())
        .map_err(|e| SolverError::new_err(e.to_string()))?;
    let frames = frames
        .into_iter()
        .map(|f| Py::new(py, Frame::new(f, mesh.clone())))
        .collect::<PyResult<_>>()?;
    Ok(RunResult {
        result,
        json,
        frames,
        mesh: Py::new(py, Mesh::new(mesh, regions, &PhysicalGroups::default()))?,
        out,
    })
}
