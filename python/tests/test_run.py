"""Runs from Python: arrays and their shapes and dtypes, progress, the GIL, outputs."""

import gc
import os
import signal
import threading
import time

import numpy as np
import pytest

import isochor


@pytest.fixture(scope="module")
def tet10_result():
    scene = isochor.Scene.builtin("cantilever").set("res", 1).set("element", "tet10").set("steps", 2)
    return isochor.run(scene)


def test_shapes_and_dtypes(tet10_result):
    r = tet10_result
    mesh = r.mesh
    n, m = mesh.num_nodes, mesh.num_elements
    assert mesh.kind == "tet10"
    assert mesh.nodes.shape == (n, 3) and mesh.nodes.dtype == np.float64
    assert mesh.elements.shape == (m, 10) and mesh.elements.dtype == np.int64
    assert mesh.region.shape == (m,) and mesh.region.dtype == np.int32
    assert mesh.elements.max() == n - 1
    assert [f.index for f in r.frames] == [0, 1, 2]
    for f in r.frames:
        assert f.positions.shape == (n, 3) and f.positions.dtype == np.float64
        assert f.displacement.shape == (n, 3)
        assert f.stress.shape == (m, 3, 3) and f.stress.dtype == np.float64
        assert f.von_mises.shape == (m,) and f.J.shape == (m,)
    last = r.frames[-1]
    assert last.pressure.shape == (n,) and last.pressure.dtype == np.float64
    assert r.frames[0].pressure is None
    np.testing.assert_array_equal(last.positions - mesh.nodes, last.displacement)
    np.testing.assert_allclose(last.stress, np.transpose(last.stress, (0, 2, 1)), rtol=1e-9, atol=1e-6)
    assert np.all(r.frames[0].J == 1.0) and not np.all(last.J == 1.0)
    steps = r.steps
    assert steps["step"].tolist() == [1, 2]
    assert steps["t"].dtype == np.float64 and steps["converged"].dtype == np.bool_
    assert steps["contact_force"].shape == (2, 3)
    assert r.converged and r.error is None
    assert r.probes["tip_deflection"] == r.to_dict()["probes"]["tip_deflection"]


def test_tip_deflection_is_the_frame_displacement():
    # The cantilever bends in -y: the last frame holds the final state the probe measures.
    r = isochor.run(isochor.Scene.builtin("cantilever").reduced())
    deflection = -r.frames[-1].displacement[:, 1]
    assert deflection.max() >= abs(r.probes["tip_deflection"]) > 0.0
    assert deflection.min() >= -1e-12


def test_arrays_outlive_their_result():
    r = isochor.run(isochor.Scene.builtin("cantilever").reduced())
    positions, nodes = r.frames[-1].positions, r.mesh.nodes
    copy = positions.copy()
    del r
    gc.collect()
    np.testing.assert_array_equal(positions, copy)
    assert positions.flags.owndata or positions.base is not None
    assert nodes.shape == positions.shape


def test_progress_gets_every_accepted_step():
    seen = []
    scene = isochor.Scene.builtin("cantilever").set("res", 1).set("steps", 3)
    r = isochor.run(scene, progress=lambda step, t, iterations: seen.append((step, t, iterations)))
    assert [s for s, _, _ in seen] == [1, 2, 3]
    assert [t for _, t, _ in seen] == pytest.approx(list(r.steps["t"]))
    assert [i for _, _, i in seen] == list(r.steps["newton_iterations"])


def test_progress_exception_stops_the_run_after_its_step():
    seen = []

    def fail(step, t, iterations):
        seen.append(step)
        raise RuntimeError(f"stop at {step}")

    scene = isochor.Scene.builtin("cantilever").set("res", 1).set("steps", 3).set("every", 2)
    with pytest.raises(RuntimeError, match="stop at 1") as info:
        isochor.run(scene, progress=fail)
    assert seen == [1], "no step after the one whose callback raised"
    r = info.value.result
    assert isinstance(r, isochor.Result)
    assert r.converged is False
    assert r.error == "interrupted after step 1: RuntimeError: stop at 1"
    assert r.to_dict()["error"] == r.error and r.to_dict()["failed_step"] is None
    assert r.steps["step"].tolist() == [1]
    # Frame 1 is not one `every = 2` keeps, but it is the last good state.
    assert [f.index for f in r.frames] == [0, 1]
    assert np.abs(r.frames[-1].displacement).max() > 0.0
    assert r.probes["tip_deflection"] != 0.0


def test_ctrl_c_stops_the_run_between_steps():
    # 2,000 steps of about 1.3 ms each (dev build): the signal 50 ms after step 1 lands in
    # the run with a wide margin.
    scene = isochor.Scene.builtin("cantilever").set("res", 1).set("steps", 2000)
    seen = []
    # Python raises KeyboardInterrupt on SIGINT only if SIGINT was not ignored when it
    # started; a test process started in the background by a shell without job control
    # inherits it ignored. Install Python's own handler for this test.
    previous = signal.signal(signal.SIGINT, signal.default_int_handler)

    def interrupt_soon(step, t, iterations):
        seen.append(step)
        if step == 1:
            # Ctrl-C from another thread while the solver runs: SIGINT to the process.
            threading.Timer(0.05, os.kill, (os.getpid(), signal.SIGINT)).start()

    try:
        with pytest.raises(KeyboardInterrupt) as info:
            isochor.run(scene, progress=interrupt_soon)
    finally:
        signal.signal(signal.SIGINT, previous)
    r = info.value.result
    stopped = int(r.steps["step"][-1])
    assert 1 <= stopped < 2000
    # The signal is checked before the callback: the last step's call is made only if the
    # signal arrived while it ran.
    assert seen in (list(range(1, stopped)), list(range(1, stopped + 1)))
    assert not r.converged and r.error == f"interrupted after step {stopped}: KeyboardInterrupt"
    assert r.frames[-1].index == stopped


def test_the_solve_releases_the_gil():
    scene = isochor.Scene.builtin("cantilever").set("res", 2).set("element", "tet10").set("steps", 4)
    ticks = []
    running = threading.Event()
    done = threading.Event()

    def count():
        running.set()
        while not done.is_set():
            ticks.append(time.perf_counter())
            time.sleep(0.001)

    thread = threading.Thread(target=count)
    thread.start()
    running.wait()
    start = time.perf_counter()
    isochor.run(scene, frames=False)
    end = time.perf_counter()
    done.set()
    thread.join()
    during = [t for t in ticks if start < t < end]
    # With the GIL held for the solve the thread would not tick at all in between.
    assert end - start > 0.05, "the run is too short to tell"
    assert len(during) >= 5, (len(during), end - start)


def test_out_writes_the_command_line_outputs(tmp_path):
    out = tmp_path / "run"
    r = isochor.run(isochor.Scene.builtin("cantilever").reduced(), out=str(out))
    assert r.out is not None
    assert (out / "summary.json").is_file() and (out / "frame.pvd").is_file()


def test_solver_failure_returns_or_raises():
    # One Newton iteration cannot converge the cantilever's first step.
    scene = isochor.Scene.builtin("cantilever").reduced().set("max_iterations", 1)
    r = isochor.run(scene)
    assert not r.converged
    with pytest.raises(isochor.SolverError) as info:
        isochor.run(scene, check=True)
    assert info.value.result.converged is False


def test_read_mesh_groups():
    from conftest import REPO

    mesh = isochor.read_mesh(REPO / "mesh" / "tests" / "data" / "bilayer-v41.msh")
    assert mesh.kind == "tet4" and mesh.elements.shape == (mesh.num_elements, 4)
    assert mesh.nodes.dtype == np.float64 and mesh.elements.dtype == np.int64
    assert mesh.groups, "the bilayer has named physical groups"
    for key, g in mesh.groups.items():
        assert g["dimension"] in (2, 3)
        assert g["faces"].shape[1:] == (3,) and g["tets"].ndim == 1
        assert g["faces"].dtype == np.int64 and g["tets"].dtype == np.int64
        if g["dimension"] == 3:
            assert len(g["tets"]) and g["tets"].max() < mesh.num_elements
        else:
            assert len(g["faces"]) and g["faces"].max() < mesh.num_vertices
    quadratic = isochor.read_mesh(REPO / "mesh" / "tests" / "data" / "tube-tet10-v41.msh")
    assert quadratic.kind == "tet10" and quadratic.elements.shape[1] == 10
