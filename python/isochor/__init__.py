"""isochor: nearly incompressible solids on tet meshes, from Python.

Scenes of the TOML format (``Scene.builtin``, ``Scene.load``, ``Scene.from_dict``) run with
``run``; results come back as numpy arrays (``Result``). Meshes are read with ``read_mesh``
or converted from meshio with ``from_meshio``. docs/python.md in the repository is the guide.
"""

from __future__ import annotations

import json as _json
from typing import Any, Callable, Sequence

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
from ._isochor import mesh_from_arrays as _mesh_from_arrays
from ._isochor import run as _run
from ._isochor import RunResult as _NativeResult

__all__ = [
    "Frame",
    "IsochorError",
    "Mesh",
    "MeshError",
    "Problem",
    "Result",
    "Scene",
    "SceneError",
    "SolverError",
    "builtin_names",
    "from_meshio",
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


def Problem(
    nodes: Any,
    tets: Any,
    *,
    material: dict[str, Any],
    method: str = "mixed-p1",
    element: str | None = None,
    steps: int = 1,
    name: str = "problem",
    regions: Sequence[dict[str, Any]] = (),
    dirichlet: Sequence[dict[str, Any]] = (),
    tractions: Sequence[dict[str, Any]] = (),
    pressures: Sequence[dict[str, Any]] = (),
    gravity: Any = None,
    obstacles: Sequence[dict[str, Any]] = (),
    **keys: Any,
) -> Scene:
    """A scene of the explicit mesh ``nodes`` ``(n, 3)`` and ``tets`` ``(m, 4 or 10)`` (corners,
    then the mid-edge nodes in Gmsh's order), resolved and validated as every scene is.

    ``material``: the ``[material]`` keys. ``regions``: ``{"elements": (k,) tet indices,
    "name": str, **material keys that differ}``. ``dirichlet``: ``{"nodes": (k,) node
    indices, "axes": "xyz", "displacement": (3,) reached at the end of the run, "curve"}``
    (on 10-node tets the mid-edge nodes between two held corners are held with them, and
    only those). ``tractions``: ``{"faces": (k, 3) corner triangles, "traction": (3,) Pa,
    "curve"}``. ``pressures``: ``{"faces": (k, 3), "pressure": Pa or "volume_ratio", ...}``
    (the keys of ``[[loads.pressure]]``). ``gravity``: ``(3,)`` m/s^2. ``obstacles``: the
    ``[[obstacles]]`` tables. ``element`` (default: the tets' own), ``steps`` (quasi-static),
    and any other top-level key of the format (``solver``, ``probes``, ``output``, ...).

    The nodes are renumbered only when the tets do not list every node with the corners
    first (``result.mesh`` holds the mesh as run). A bad array raises ``MeshError`` (nodes,
    tets) or ``SceneError`` naming the argument.
    """
    x = _np.asarray(nodes)
    t = _np.asarray(tets)
    if x.ndim != 2 or x.shape[1] != 3 or not _np.issubdtype(x.dtype, _np.number):
        raise MeshError(f"nodes: expected an (n, 3) array of numbers, got shape {x.shape}")
    if not _np.isfinite(x).all():
        raise MeshError(f"nodes: row {_np.argwhere(~_np.isfinite(x))[0][0]} is not finite")
    if t.ndim != 2 or t.shape[1] not in (4, 10) or not _np.issubdtype(t.dtype, _np.integer):
        raise MeshError(f"tets: expected an (m, 4) or (m, 10) integer array, got shape {t.shape}")
    _check_range(t, len(x), "tets", "node", MeshError)
    corner = _np.zeros(len(x), bool)
    corner[t[:, :4].ravel()] = True
    mid = _np.zeros(len(x), bool)
    mid[t[:, 4:].ravel()] = True
    if (both := corner & mid).any():
        node = _np.flatnonzero(both)[0]
        raise MeshError(f"tets: node {node} is a corner of one tet and a mid-edge node of another")
    # The mesh's numbering: the corners first, then the mid-edge nodes, each in input order.
    order = _np.concatenate([_np.flatnonzero(corner), _np.flatnonzero(mid)])
    index = _np.full(len(x), -1)
    index[order] = _np.arange(len(order))
    corners = int(corner.sum())
    groups: dict[str, dict[str, Any]] = {}
    selections: dict[str, dict[str, Any]] = {}

    def faces_group(key: str, faces: Any) -> str:
        f = _array(faces, f"{key}.faces", 2, 3)
        _check_range(f, len(x), f"{key}.faces", "node", SceneError)
        f = index[f]
        if (f < 0).any() or (f >= corners).any():
            raise SceneError(f"{key}.faces: every node of a face must be a tet's corner")
        groups[key] = {"faces": f.tolist()}
        selections[key] = {"physical": key}
        return key

    scene: dict[str, Any] = {
        "name": name,
        "method": method,
        "element": element or ("tet10" if t.shape[1] == 10 else "tet4"),
        "material": dict(material),
        "stepping": {"mode": "quasi-static", "steps": steps},
    }
    scene["regions"] = []
    for i, r in enumerate(regions):
        key = f"regions[{i}]"
        r = dict(r)
        e = _array(r.pop("elements", None), f"{key}.elements", 1)
        _check_range(e, len(t), f"{key}.elements", "tet", SceneError)
        groups[key] = {"tets": e.tolist()}
        selections[key] = {"physical": key}
        scene["regions"].append({"name": r.pop("name", f"region{i}"), "selection": key, "material": r})
    scene["dirichlet"] = []
    for i, d in enumerate(dirichlet):
        key = f"dirichlet[{i}]"
        d = dict(d)
        given = _array(d.pop("nodes", None), f"{key}.nodes", 1)
        _check_range(given, len(x), f"{key}.nodes", "node", SceneError)
        held = index[given]
        if (held < 0).any():
            raise SceneError(f"{key}.nodes: node {given[held < 0][0]} is in no tet")
        selections[key] = {"vertices": sorted(set(held[held < corners].tolist()))}
        condition = {"selection": key, "axes": d.pop("axes", "xyz")}
        if (displacement := d.pop("displacement", None)) is not None:
            condition["motion"] = {"translate": _np.asarray(displacement, float).tolist()}
        scene["dirichlet"].append({**condition, **d})
    loads: dict[str, Any] = {"traction": [], "pressure": []}
    for kind, items in (("traction", tractions), ("pressure", pressures)):
        for i, load in enumerate(items):
            load = dict(load)
            key = faces_group(f"{kind}s[{i}]", load.pop("faces", None))
            loads[kind].append({"selection": key, **load})
    if gravity is not None:
        loads["gravity"] = _np.asarray(gravity, float).tolist()
    scene["loads"] = loads
    scene["obstacles"] = [dict(o) for o in obstacles]
    scene["selections"] = selections
    scene["mesh"] = {
        "generator": "explicit",
        "positions": x[order].astype(float).tolist(),
        "tets": index[t].tolist(),
        "groups": groups,
    }
    scene.update(keys)
    return Scene.from_dict(scene)


def _array(value: Any, key: str, ndim: int, width: int | None = None) -> _np.ndarray:
    """``value`` as an integer array of ``ndim`` dimensions (``width`` columns)."""
    if value is None:
        raise SceneError(f"{key}: missing")
    a = _np.asarray(value)
    if a.size == 0:
        raise SceneError(f"{key}: empty")
    shape = "(k,)" if ndim == 1 else f"(k, {width})"
    if a.ndim != ndim or (width is not None and a.shape[1] != width) or not _np.issubdtype(
        a.dtype, _np.integer
    ):
        raise SceneError(f"{key}: expected a {shape} integer array, got shape {a.shape} of {a.dtype}")
    return a


def _check_range(a: _np.ndarray, n: int, key: str, what: str, error: type[Exception]) -> None:
    """Raises ``error`` naming ``key`` if an index of ``a`` is outside ``[0, n)``."""
    bad = (a < 0) | (a >= n)
    if bad.any():
        raise error(f"{key}: {what} {a[bad][0]} is out of range (there are {n} {what}s)")


def from_meshio(mesh: Any) -> Mesh:
    """The tets of a ``meshio.Mesh`` (``tetra`` or ``tetra10`` cells, every block in order) as
    ``read_mesh`` reads a file: nodes renumbered corners first, and the ``gmsh:physical`` tags
    of its triangles and tets as groups named by ``field_data`` (``{name: [tag, dim]}``, the
    named point and curve groups without elements)."""
    kinds = {"tetra": 4, "tetra10": 10}
    blocks = [c for c in mesh.cells if c.type in kinds]
    if not blocks or len({c.type for c in blocks}) > 1:
        raise MeshError("from_meshio: the mesh needs tetra or tetra10 cells, of one kind")
    elements = _np.concatenate([c.data for c in blocks]).astype(_np.int64)
    if blocks[0].type == "tetra10":
        elements = elements[:, _VTK_TET10]
    tags = mesh.cell_data.get("gmsh:physical")
    faces: dict[int, list[_np.ndarray]] = {}
    tets: dict[int, list[_np.ndarray]] = {}
    first = 0
    for block, cells in enumerate(mesh.cells):
        tag = None if tags is None else _np.asarray(tags[block])
        if cells.type in kinds:
            if tag is not None:
                for t in _np.unique(tag):
                    tets.setdefault(int(t), []).append(first + _np.flatnonzero(tag == t))
            first += len(cells.data)
        elif cells.type in ("triangle", "triangle6") and tag is not None:
            for t in _np.unique(tag):
                faces.setdefault(int(t), []).append(cells.data[tag == t, :3])
    names = {(int(v[1]), int(v[0])): k for k, v in (mesh.field_data or {}).items()}
    keys = {(2, t) for t in faces} | {(3, t) for t in tets} | set(names)
    no_faces = _np.zeros((0, 3), _np.int64)
    no_tets = _np.zeros(0, _np.int64)
    groups = [
        (
            dim,
            tag,
            names.get((dim, tag)),
            _np.concatenate(faces[tag]).astype(_np.int64) if dim == 2 and tag in faces else no_faces,
            _np.concatenate(tets[tag]).astype(_np.int64) if dim == 3 and tag in tets else no_tets,
        )
        for dim, tag in sorted(keys)
    ]
    return _mesh_from_arrays(_np.asarray(mesh.points, _np.float64)[:, :3], elements, groups)


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
    ``progress(step, t, newton_iterations)`` after every accepted step. An exception it
    raises, or Ctrl-C (``KeyboardInterrupt``), stops the run after that step and is raised
    with a ``result`` attribute: the ``Result`` of the accepted steps (``converged`` False,
    ``error`` "interrupted after step N: " and the exception, ``frames[-1]`` the last good
    state). ``frames=False`` keeps no frames. ``check=True`` raises ``SolverError`` (its
    ``result`` attribute the ``Result`` with every accepted step) when the solver fails,
    instead of returning ``converged=False``.
    """
    try:
        native = _run(scene, out, progress, frames, check)
    except SolverError as e:
        if len(e.args) > 1 and isinstance(e.args[1], _NativeResult):
            e.result = Result(e.args[1])
        raise
    except BaseException as e:
        if isinstance(getattr(e, "result", None), _NativeResult):
            e.result = Result(e.result)
        raise
    return Result(native)
