"""Shared helpers of the isochor Python tests."""

import os
import pathlib
import shutil

import pytest

REPO = pathlib.Path(__file__).resolve().parents[2]


@pytest.fixture(scope="session")
def cli() -> str:
    """The `isochor` program: $ISOCHOR_CLI, else the workspace's debug build, else PATH."""
    for candidate in (
        os.environ.get("ISOCHOR_CLI"),
        str(REPO / "target" / "debug" / "isochor"),
        shutil.which("isochor"),
    ):
        if candidate and os.access(candidate, os.X_OK):
            return candidate
    pytest.skip("no isochor program (cargo build -p isochor-scenes, or set ISOCHOR_CLI)")
