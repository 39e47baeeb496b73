"""Type stubs of the native module isochor._isochor (see isochor/__init__.py)."""

from os import PathLike
from typing import Any, Callable

import numpy as np
import numpy.typing as npt

class IsochorError(Exception):
    """Base class of every isochor error."""

class SceneError(IsochorError):
    """A scene that cannot be loaded, built or run; the message names the key at fault."""

class MeshError(IsochorError):
    """A mesh that cannot be read or built; the message names the file and line."""

class SolverError(IsochorError):
    """The solver refused the problem or failed (``result``: the Result of a failed run)."""

class Scene:
    """A scene of the TOML format with its variant and overrides; immutable."""

    @staticmethod
    def builtin(name: str) -> Scene: ...
    @staticmethod
    def load(path: str | PathLike[str]) -> Scene: ...
    @staticmethod
    def from_dict(scene: dict[str, Any], base_dir: str | PathLike[str] | None = None) -> Scene: ...
    @staticmethod
    def from_toml(text: str, base_dir: str | PathLike[str] | None = None) -> Scene: ...
    def set(self, key: str, value: Any) -> Scene: ...
    def apply(self, *assignments: str) -> Scene: ...
    def variant(self, name: str) -> Scene: ...
    def reduced(self) -> Scene: ...
    @property
    def name(self) -> str: ...
    @property
    def method(self) -> str: ...
    @property
    def element(self) -> str: ...
    @property
    def num_steps(self) -> int: ...
    @property
    def variants(self) -> list[str]: ...
    @property
    def overrides(self) -> list[str]: ...
    def to_toml(self) -> str: ...

class Mesh:
    """A tet mesh; every array attribute is a new copy."""

    @property
    def nodes(self) -> npt.NDArray[np.float64]:
        """``(num_nodes, 3)`` rest positions (m)."""
    @property
    def elements(self) -> npt.NDArray[np.int64]:
        """``(num_elements, 4 or 10)`` node indices, Gmsh's node order."""
    @property
    def region(self) -> npt.NDArray[np.int32]:
        """``(num_elements,)`` region of each element (0: the body's material)."""
    @property
    def groups(self) -> dict[str, dict[str, Any]]:
        """``{key: {"dimension", "tag", "faces": (k, 3) int64, "tets": (k,) int64}}``."""
    @property
    def kind(self) -> str: ...
    @property
    def num_vertices(self) -> int: ...
    @property
    def num_nodes(self) -> int: ...
    @property
    def num_elements(self) -> int: ...

class Frame:
    """One kept state of a run; every array attribute is a new copy."""

    @property
    def index(self) -> int: ...
    @property
    def t(self) -> float: ...
    @property
    def positions(self) -> npt.NDArray[np.float64]:
        """``(num_nodes, 3)`` deformed positions (m)."""
    @property
    def displacement(self) -> npt.NDArray[np.float64]:
        """``(num_nodes, 3)`` displacements (m)."""
    @property
    def pressure(self) -> npt.NDArray[np.float64] | None:
        """``(num_nodes,)`` nodal pressure, compression positive (Pa), P1 methods only."""
    @property
    def stress(self) -> npt.NDArray[np.float64]:
        """``(num_elements, 3, 3)`` Cauchy stress at the centroids, tension positive (Pa)."""
    @property
    def von_mises(self) -> npt.NDArray[np.float64]:
        """``(num_elements,)`` von Mises stress (Pa)."""
    @property
    def J(self) -> npt.NDArray[np.float64]:
        """``(num_elements,)`` deformed over rest volume."""

class RunResult:
    """The native result ``isochor.Result`` wraps."""

    @property
    def probes(self) -> dict[str, float]: ...
    @property
    def converged(self) -> bool: ...
    @property
    def error(self) -> str | None: ...
    @property
    def steps(self) -> dict[str, npt.NDArray[Any]]: ...
    @property
    def frames(self) -> list[Frame]: ...
    @property
    def mesh(self) -> Mesh: ...
    @property
    def out(self) -> PathLike[str] | None: ...
    @property
    def json(self) -> str: ...

def builtin_names() -> list[str]: ...
def reduced(name: str) -> list[str] | None: ...
def read_mesh(path: str | PathLike[str]) -> Mesh: ...
def mesh_from_arrays(
    nodes: npt.NDArray[np.float64],
    elements: npt.NDArray[np.int64],
    groups: list[tuple[int, int, str | None, npt.NDArray[np.int64], npt.NDArray[np.int64]]],
) -> Mesh: ...
def run(
    scene: Scene,
    out: str | PathLike[str] | None = None,
    progress: Callable[[int, float, int], Any] | None = None,
    frames: bool = True,
    check: bool = False,
) -> RunResult: ...
