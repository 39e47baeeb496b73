"""Problems from arrays: the same scene as its TOML, and bad arrays named in the error."""

import numpy as np
import pytest

import isochor

BLOCK = """
name = "block"
method = "mixed-p1"
element = "{element}"

[mesh]
generator = "box"
min = [0.0, 0.0, 0.0]
max = [0.2, 0.05, 0.05]
res = 1
cells = [4, 1, 1]

[material]
young = 266e3
nu = 0.4999
rho = 1070.0

[selections.clamped]
plane = {{ point = [0.0, 0.0, 0.0], normal = [1.0, 0.0, 0.0] }}

[selections.free_end]
plane = {{ point = [0.2, 0.0, 0.0], normal = [1.0, 0.0, 0.0] }}

[selections.near]
box = {{ min = [-1.0, -1.0, -1.0], max = [0.1, 1.0, 1.0] }}

[[regions]]
name = "stiff"
selection = "near"
material = {{ young = 500e3 }}

[[dirichlet]]
selection = "clamped"

[loads]
gravity = [0.0, -9.8, 0.0]
traction = [{{ selection = "free_end", traction = [0.0, -50.0, 20.0] }}]

[stepping]
mode = "quasi-static"
steps = 2
"""


def boundary_faces_on(elements, on):
    """The faces of the tets whose three corners all satisfy ``on`` (a bool per node)."""
    local = [(0, 1, 2), (0, 1, 3), (0, 2, 3), (1, 2, 3)]
    faces = np.concatenate([elements[:, list(f)] for f in local])
    return faces[on[faces].all(axis=1)]


@pytest.mark.parametrize("element", ["tet4", "tet10"])
def test_problem_from_arrays_equals_its_toml(element):
    toml = isochor.run(isochor.Scene.from_toml(BLOCK.format(element=element)))
    assert toml.converged
    # The same problem from the arrays of its 4-node mesh (10-node: the same mid-edge nodes).
    corners = isochor.run(isochor.Scene.from_toml(BLOCK.format(element="tet4")), frames=False).mesh
    x, tets = corners.nodes, corners.elements
    centroids = x[tets].mean(axis=1)
    problem = isochor.Problem(
        x,
        tets,
        element=element,
        steps=2,
        material={"young": 266e3, "nu": 0.4999, "rho": 1070.0},
        regions=[{"name": "stiff", "elements": np.flatnonzero(centroids[:, 0] <= 0.1), "young": 500e3}],
        dirichlet=[{"nodes": np.flatnonzero(x[:, 0] == 0.0)}],
        tractions=[{"faces": boundary_faces_on(tets, np.isclose(x[:, 0], 0.2)), "traction": [0.0, -50.0, 20.0]}],
        gravity=[0.0, -9.8, 0.0],
    )
    arrays = isochor.run(problem)
    assert arrays.converged
    np.testing.assert_array_equal(arrays.mesh.elements, toml.mesh.elements)
    np.testing.assert_array_equal(arrays.mesh.region, toml.mesh.region)
    assert toml.mesh.region.max() == 1 and toml.mesh.region.min() == 0
    for a, b in zip(arrays.frames, toml.frames, strict=True):
        scale = np.abs(b.displacement).max()
        assert scale > 0.0 or a.index == 0
        np.testing.assert_allclose(a.positions, b.positions, rtol=0.0, atol=1e-12 * max(scale, 1e-300))
        np.testing.assert_allclose(a.stress, b.stress, rtol=1e-12, atol=1e-12 * np.abs(b.stress).max())
    np.testing.assert_allclose(arrays.steps["elastic_energy"], toml.steps["elastic_energy"], rtol=1e-12)


def test_displacement_and_pressure_from_arrays():
    mesh = isochor.run(isochor.Scene.from_toml(BLOCK.format(element="tet4")), frames=False).mesh
    x, tets = mesh.nodes, mesh.elements
    end = np.flatnonzero(np.isclose(x[:, 0], 0.2))
    problem = isochor.Problem(
        x,
        tets,
        method="standard",
        material={"young": 266e3, "nu": 0.3},
        dirichlet=[{"nodes": np.flatnonzero(x[:, 0] == 0.0)}, {"nodes": end, "axes": "x", "displacement": [0.01, 0, 0]}],
        pressures=[{"faces": boundary_faces_on(tets, np.isclose(x[:, 1], 0.05)), "pressure": 100.0}],
    )
    r = isochor.run(problem)
    assert r.converged
    np.testing.assert_allclose(r.frames[-1].displacement[end, 0], 0.01, rtol=1e-12)
    # The pressure on the top face pushes it down.
    assert r.frames[-1].displacement[np.isclose(x[:, 1], 0.05), 1].mean() < 0.0


def block_arrays():
    mesh = isochor.run(isochor.Scene.from_toml(BLOCK.format(element="tet4")), frames=False).mesh
    return mesh.nodes, mesh.elements


@pytest.mark.parametrize(
    "change, error, message",
    [
        (lambda a: {"nodes": a["nodes"][:, :2]}, isochor.MeshError, "nodes: expected an (n, 3) array"),
        (lambda a: {"nodes": np.where(a["nodes"] == 0.2, np.nan, a["nodes"])}, isochor.MeshError, "nodes: row"),
        (lambda a: {"tets": a["tets"][:, :3]}, isochor.MeshError, "tets: expected an (m, 4) or (m, 10)"),
        (lambda a: {"tets": a["tets"] + 1}, isochor.MeshError, "tets: node 20 is out of range (there are 20 nodes)"),
        (lambda a: {"dirichlet": [{"nodes": [0, 99]}]}, isochor.SceneError, "dirichlet[0].nodes: node 99 is out of range"),
        (lambda a: {"dirichlet": [{"nodes": [[0, 1]]}]}, isochor.SceneError, "dirichlet[0].nodes: expected a (k,) integer"),
        (lambda a: {"tractions": [{"faces": [0, 1, 2], "traction": [1, 0, 0]}]}, isochor.SceneError, "tractions[0].faces: expected a (k, 3)"),
        (lambda a: {"regions": [{"elements": [0, 1000]}]}, isochor.SceneError, "regions[0].elements: tet 1000 is out of range"),
        (lambda a: {"material": {"young": 1e3, "nu": 0.7}}, isochor.IsochorError, "nu"),
        (lambda a: {"dirichlet": [{"nodes": [0], "axes": "q"}]}, isochor.SceneError, "axes"),
    ],
)
def test_bad_arrays_name_the_argument(change, error, message):
    x, tets = block_arrays()
    args = {"nodes": x, "tets": tets, "material": {"young": 1e3, "nu": 0.3}}
    args.update(change(args))
    with pytest.raises(error) as info:
        isochor.run(isochor.Problem(args.pop("nodes"), args.pop("tets"), **args))
    assert message in str(info.value)
