"""isochor: nearly incompressible solids on tet meshes, from Python.

Scenes of the TOML format (``Scene.builtin``, ``Scene.load``, ``Scene.from_dict``) run with
``run``; results come back as numpy arrays (``Result``). Meshes are read with ``read_mesh``
or converted from meshio with ``from_meshio``. docs/python.md in the repository is the guide.
"""

from __future__ import annotations

import json as _json
from typing import Any, Callable

import numpy as _np

from ._isochor import (
    Frame,
    IsochorError,
    Mesh,
    MeshError,
    Scene,
    SceneError,
    SolverError,
    builtin_names,
    read_mesh,
    reduced,
)
from ._isochor import run as _run
from ._isochor import RunResult as _NativeResult

__all__ = [
    "Frame",
    "IsochorError",
    "Mesh",
    "MeshError",
    "Result",
    "Scene",
    "SceneError",
    "SolverError",
    "builtin_names",
    "read_mesh",
    "reduced",
    "run",
]

# VTK's (and meshio's) quadratic tet lists the last two mid-edge nodes, on the edges (1, 3)
# and (2, 3), the other way round from Gmsh's order that isochor uses.
_VTK_TET10 = [0, 1, 2, 3, 4, 5, 6, 7, 9, 8]


class Result:
    """The result of ``run``: probes, convergence, the per-step table, the kept frames and
    the mesh. ``json`` is the object ``isochor run --json`` prints."""

    def __init__(self, native: _NativeResult) -> None:
        self._native = native

    @property
    def probes(self) -> dict[str, float]:
        """Named scalar results of the final state."""
        return self._native.probes

    @property
    def converged(self) -> bool:
        """Whether every step converged."""
        return self._native.converged

    @property
    def error(self) -> str | None:
        """The solver's error if the run stopped early, else ``None``."""
        return self._native.error

    @property
    def steps(self) -> dict[str, _np.ndarray]:
        """The per-step table as a dict of ``(steps,)`` arrays (``contact_force``:
        ``(steps, 3)``)."""
        return self._native.steps

    def steps_frame(self) -> Any:
        """The per-step table as a pandas DataFrame (needs pandas)."""
        import pandas

        table = dict(self.steps)
        force = table.pop("contact_force")
        for axis, name in enumerate("xyz"):
            table[f"contact_force_{name}"] = force[:, axis]
        return pandas.DataFrame(table)

    @property
    def frames(self) -> list[Frame]:
        """The rest state, then every frame the scene's ``output.every`` keeps."""
        return self._native.frames

    @property
    def mesh(self) -> Mesh:
        """The mesh of the run: rest nodes, elements, kind, region of each element."""
        return self._native.mesh

    @property
    def out(self) -> str | None:
        """The output folder, if the run wrote one."""
        out = self._native.out
        return None if out is None else str(out)

    @property
    def json(self) -> str:
        """The ``--json`` object as JSON text."""
        return self._native.json

    def to_dict(self) -> dict[str, Any]:
        """The ``--json`` object as a dict (non-finite numbers are ``None``)."""
        return _json.loads(self._native.json)

    def to_meshio(self, frame: int = -1) -> Any:
        """Frame ``frame`` as a ``meshio.Mesh`` (rest points, point and cell data as in the
        VTU frames). Needs meshio."""
        import meshio

        mesh, f = self.mesh, self.frames[frame]
        kind, elements = _vtk_cells(mesh)
        point_data = {"displacement": f.displacement}
        if f.pressure is not None:
            point_data["pressure"] = f.pressure
        cell_data = {
            "stress": [f.stress.reshape(-1, 9)],
            "von_mises": [f.von_mises],
            "J": [f.J],
            "region": [mesh.region],
        }
        return meshio.Mesh(
            mesh.nodes,
            [(kind, elements)],
            point_data=point_data,
            cell_data=cell_data,
        )

    def to_pyvista(self, frame: int = -1, deformed: bool = True) -> Any:
        """Frame ``frame`` as a ``pyvista.UnstructuredGrid``, at the deformed positions unless
        ``deformed=False`` (the fields as in ``to_meshio``). Needs pyvista."""
        import pyvista

        mesh, f = self.mesh, self.frames[frame]
        kind, elements = _vtk_cells(mesh)
        cell_type = pyvista.CellType.TETRA if kind == "tetra" else pyvista.CellType.QUADRATIC_TETRA
        points = f.positions if deformed else mesh.nodes
        grid = pyvista.UnstructuredGrid({cell_type: elements}, points)
        grid.point_data["displacement"] = f.displacement
        if f.pressure is not None:
            grid.point_data["pressure"] = f.pressure
        grid.cell_data["von_mises"] = f.von_mises
        grid.cell_data["J"] = f.J
        grid.cell_data["region"] = mesh.region
        grid.cell_data["stress"] = f.stress.reshape(-1, 9)
        return grid

    def __repr__(self) -> str:
        return repr(self._native).replace("RunResult", "Result", 1)


def _vtk_cells(mesh: Mesh) -> tuple[str, _np.ndarray]:
    """meshio's cell type name and the elements in VTK's node order."""
    elements = mesh.elements
    if mesh.kind == "tet4":
        return "tetra", elements
    return "tetra10", elements[:, _VTK_TET10]


def run(
    scene: Scene,
    out: str | None = None,
    progress: Callable[[int, float, int], Any] | None = None,
    *,
    frames: bool = True,
    check: bool = False,
) -> Result:
    """Runs ``scene`` with the GIL released.

    ``out``: an output folder to write as ``isochor run --out`` does. ``progress``: called as
    ``progress(step, t, newton_iterations)`` after every accepted step; an exception it raises
    (and Ctrl-C) is raised once the run returns. ``frames=False`` keeps no frames.
    ``check=True`` raises ``SolverError`` (its ``result`` attribute the ``Result`` with every
    accepted step) when the solver fails, instead of returning ``converged=False``.
    """
    try:
        native = _run(scene, out, progress, frames, check)
    except SolverError as e:
        if len(e.args) > 1 and isinstance(e.args[1], _NativeResult):
            e.result = Result(e.args[1])
        raise
    return Result(native)
