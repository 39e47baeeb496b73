"""The optional packages: meshio, pyvista, pandas (each test skips without its package)."""

import numpy as np
import pytest

import isochor


@pytest.fixture(scope="module")
def tet10():
    scene = isochor.Scene.builtin("cantilever").reduced().set("element", "tet10")
    return isochor.run(scene)


def test_meshio_round_trip(tet10, tmp_path):
    meshio = pytest.importorskip("meshio")
    m = tet10.to_meshio()
    assert m.cells[0].type == "tetra10"
    path = tmp_path / "last.vtu"
    m.write(path)
    back = isochor.read_mesh(path)
    np.testing.assert_array_equal(back.nodes, tet10.mesh.nodes)
    np.testing.assert_array_equal(back.elements, tet10.mesh.elements)
    read = meshio.read(path)
    np.testing.assert_array_equal(read.point_data["displacement"], tet10.frames[-1].displacement)
    np.testing.assert_array_equal(read.cell_data["J"][0], tet10.frames[-1].J)


def test_pyvista_grid(tet10):
    pytest.importorskip("pyvista")
    grid = tet10.to_pyvista()
    assert grid.n_points == tet10.mesh.num_nodes
    assert grid.n_cells == tet10.mesh.num_elements
    np.testing.assert_array_equal(grid.points, tet10.frames[-1].positions)
    np.testing.assert_array_equal(grid.cell_data["von_mises"], tet10.frames[-1].von_mises)


def test_pandas_steps(tet10):
    pytest.importorskip("pandas")
    table = tet10.steps_frame()
    assert list(table["step"]) == [1, 2]
    assert "contact_force_y" in table.columns


@pytest.mark.parametrize("name", ["bilayer-v41.msh", "tube-tet10-v41.msh"])
def test_from_meshio_equals_read_mesh(name):
    meshio = pytest.importorskip("meshio")
    from conftest import REPO

    path = REPO / "mesh" / "tests" / "data" / name
    read = isochor.read_mesh(path)
    converted = isochor.from_meshio(meshio.read(path))
    assert converted.kind == read.kind
    np.testing.assert_array_equal(converted.nodes, read.nodes)
    np.testing.assert_array_equal(converted.elements, read.elements)
    assert converted.groups.keys() == read.groups.keys()
    for key, group in read.groups.items():
        other = converted.groups[key]
        assert (other["dimension"], other["tag"]) == (group["dimension"], group["tag"]), key
        np.testing.assert_array_equal(other["faces"], group["faces"])
        np.testing.assert_array_equal(other["tets"], group["tets"])
