"""Every built-in scene's reduced run from Python gives the command line's --json object."""

import json
import math
import subprocess

import pytest

import isochor

# Measured, not compared: the time of the solve and where it went.
TIMINGS = {"wall_time_s", "timings"}


def close(a, b, path=""):
    """Asserts that two JSON values agree, numbers to 1e-12 relative."""
    if isinstance(a, dict):
        assert isinstance(b, dict) and a.keys() == b.keys(), path
        for k in a:
            if k not in TIMINGS:
                close(a[k], b[k], f"{path}.{k}")
    elif isinstance(a, list):
        assert isinstance(b, list) and len(a) == len(b), path
        for i, (x, y) in enumerate(zip(a, b)):
            close(x, y, f"{path}.{i}")
    elif isinstance(a, float) or isinstance(b, float):
        assert isinstance(a, (int, float)) and isinstance(b, (int, float)), (path, a, b)
        assert math.isclose(a, b, rel_tol=1e-12, abs_tol=0.0) or a == b, (path, a, b)
    else:
        assert a == b, (path, a, b)


@pytest.mark.parametrize("name", [n for n in isochor.builtin_names() if isochor.reduced(n)])
def test_reduced_run_equals_cli_json(cli, name):
    sets = isochor.reduced(name)
    args = [cli, "run", name, "--json"]
    for s in sets:
        args += ["--set", s]
    done = subprocess.run(args, capture_output=True, text=True, check=False)
    # Exit status 3: the run finished but did not converge (the JSON is still printed).
    assert done.returncode in (0, 3), done.stderr
    expected = json.loads(done.stdout)
    result = isochor.run(isochor.Scene.builtin(name).reduced(), frames=False)
    close(result.to_dict(), expected)
    assert result.converged == expected["converged"]
    assert result.probes.keys() == expected["probes"].keys()


def test_every_builtin_scene_has_a_reduced_version():
    assert all(isochor.reduced(n) for n in isochor.builtin_names())
