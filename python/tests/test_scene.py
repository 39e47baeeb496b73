"""Scenes from Python: built-in, file, dict, overrides, variants, and their errors."""

import tomllib

import pytest

import isochor
from conftest import REPO


def test_builtin_set_and_variant():
    scene = isochor.Scene.builtin("cantilever")
    assert scene.name == "cantilever"
    stiffer = scene.set("nu", 0.4999).set("res", 1).set("steps", 1)
    assert stiffer.overrides == ["nu=0.4999", "res=1", "steps=1"]
    assert scene.overrides == []  # scenes are immutable
    assert "material" in stiffer.to_toml()
    variant = scene.variants[0]
    assert scene.variant(variant).to_toml() != scene.to_toml() or scene.variants


def test_set_method_changes_the_method():
    scene = isochor.Scene.builtin("cantilever").set("method", "standard")
    assert scene.method == "standard"
    assert isochor.Scene.builtin("cantilever").apply("element=tet10").element == "tet10"


def test_load_and_from_dict_equal_the_builtin(tmp_path):
    text = (REPO / "scenes" / "builtin" / "cantilever.toml").read_text()
    path = tmp_path / "cantilever.toml"
    path.write_text(text)
    builtin = isochor.Scene.builtin("cantilever").reduced()
    from_file = isochor.Scene.load(path).apply(*isochor.reduced("cantilever"))
    from_dict = isochor.Scene.from_dict(tomllib.loads(text)).apply(*isochor.reduced("cantilever"))
    assert builtin.to_toml() == from_file.to_toml() == from_dict.to_toml()
    a, b = isochor.run(builtin), isochor.run(from_dict)
    assert a.probes == b.probes


def test_unknown_key_names_the_key():
    with pytest.raises(isochor.SceneError, match="no_such_key"):
        isochor.Scene.builtin("cantilever").set("material.no_such_key", 1.0)


def test_bad_value_names_the_key():
    with pytest.raises(isochor.SceneError, match="nu"):
        isochor.Scene.builtin("cantilever").set("nu", "soft")


def test_from_dict_error_names_the_key():
    table = tomllib.loads((REPO / "scenes" / "builtin" / "cantilever.toml").read_text())
    table["material"]["nu"] = "soft"
    with pytest.raises(isochor.SceneError, match="material.nu|nu"):
        isochor.Scene.from_dict(table)
    # A value of the right type but out of range is refused when the scene is built.
    table["material"]["nu"] = 0.7
    with pytest.raises(isochor.SceneError, match="nu = 0.7"):
        isochor.run(isochor.Scene.from_dict(table))


def test_unknown_scene_and_variant():
    with pytest.raises(isochor.SceneError, match="no-such-scene"):
        isochor.Scene.builtin("no-such-scene")
    with pytest.raises(isochor.SceneError, match="no-such-variant"):
        isochor.Scene.builtin("cantilever").variant("no-such-variant")


def test_missing_file_is_an_error(tmp_path):
    with pytest.raises(isochor.SceneError, match="missing.toml"):
        isochor.Scene.load(tmp_path / "missing.toml")


def test_mesh_errors_name_the_file_and_line(tmp_path):
    bad = tmp_path / "bad.msh"
    bad.write_text("$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n2\n1 0 0 zero\n$EndNodes\n")
    with pytest.raises(isochor.MeshError, match=r"bad\.msh:6: "):
        isochor.read_mesh(bad)
    scene = isochor.Scene.builtin("cantilever").set("mesh", str(bad))
    with pytest.raises(isochor.MeshError, match="bad.msh"):
        isochor.run(scene)


def test_exceptions_share_a_base_class():
    for e in (isochor.SceneError, isochor.MeshError, isochor.SolverError):
        assert issubclass(e, isochor.IsochorError)
