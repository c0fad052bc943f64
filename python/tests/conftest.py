"""Shared fixtures of the inkgraph Python tests (run by ctest as python_module; README.md in this folder)."""

from __future__ import annotations

import os
import pathlib

import pytest

import inkgraph

REPO = pathlib.Path(__file__).resolve().parents[2]
SIZE = 128  # small enough for llvmpipe to stay fast, large enough for every line type to show


@pytest.fixture(scope="session")
def repo() -> pathlib.Path:
    return REPO


@pytest.fixture(scope="session")
def suzanne_path() -> str:
    return str(REPO / "models" / "suzanne_npm_4k.obj")


@pytest.fixture(scope="session")
def suzanne(suzanne_path: str) -> inkgraph.Scene:
    """Suzanne loaded once for the session (4k triangles: fast, and with contours inside the silhouette)."""
    return inkgraph.Scene.load(suzanne_path)


@pytest.fixture(scope="session")
def inkgraph_executable() -> pathlib.Path:
    """The command line the messages are compared with: INKGRAPH_EXECUTABLE (ctest sets it), else build/'s."""
    path = pathlib.Path(os.environ.get("INKGRAPH_EXECUTABLE", REPO / "build" / "inkgraph"))
    assert path.is_file(), f"no inkgraph executable at {path} (set INKGRAPH_EXECUTABLE)"
    return path
