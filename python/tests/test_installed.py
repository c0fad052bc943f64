"""The package as `cmake --install` lays it out (ctest python_installed): the runtime and python components in a
scratch prefix, imported from there by Debian's python3 in a folder outside the repository, finding the installed
libinkgraph.so (and through it the installed shaders) by its RPATH, and drawing what the build tree draws; its type
stubs and py.typed installed beside it."""

from __future__ import annotations

import json
import os
import pathlib
import subprocess
import sys

import numpy as np

import inkgraph

# Run in the installed package's own interpreter: where the package and libinkgraph.so came from, and a picture.
PROBE = """
import json, sys
import numpy as np
import inkgraph
result = inkgraph.render(sys.argv[1], size=96, buffers=["depth"])
np.save(sys.argv[2], result.picture)
libraries = [line.split()[-1] for line in open("/proc/self/maps") if "libinkgraph.so" in line]
print(json.dumps({"package": inkgraph.__file__, "libraries": sorted(set(libraries)), "version": inkgraph.__version__}))
"""


def test_the_installed_package_renders_with_the_installed_library(suzanne_path, tmp_path):
    build = pathlib.Path(os.environ["INKGRAPH_BUILD_DIR"])
    cmake = os.environ.get("CMAKE_COMMAND", "cmake")
    prefix = tmp_path / "prefix"
    for component in ("runtime", "python"):
        subprocess.run([cmake, "--install", str(build), "--prefix", str(prefix), "--component", component],
                       check=True, capture_output=True)
    site = prefix / "lib" / "python3" / "dist-packages"
    assert (site / "inkgraph" / "__init__.py").is_file()
    # Typed (PEP 561): the marker and the extension's stubs beside it, as the source tree has them, so a user's type
    # checker sees the installed package's types.
    source = pathlib.Path(__file__).resolve().parents[1] / "inkgraph"
    for typing_file in ("py.typed", "_inkgraph.pyi"):
        assert (site / "inkgraph" / typing_file).read_bytes() == (source / typing_file).read_bytes(), typing_file

    folder = tmp_path / "elsewhere"
    folder.mkdir()
    environment = {key: value for key, value in os.environ.items() if key not in ("PYTHONPATH", "LD_LIBRARY_PATH")}
    environment["PYTHONPATH"] = str(site)
    run = subprocess.run([sys.executable, "-c", PROBE, suzanne_path, str(tmp_path / "picture.npy")], cwd=folder,
                         env=environment, capture_output=True, text=True)
    assert run.returncode == 0, run.stderr
    report = json.loads(run.stdout)
    assert pathlib.Path(report["package"]).resolve() == (site / "inkgraph" / "__init__.py").resolve()
    assert len(report["libraries"]) == 1, report["libraries"]
    assert pathlib.Path(report["libraries"][0]).resolve().is_relative_to(prefix.resolve()), report["libraries"]
    assert report["version"] == inkgraph.__version__

    installed = np.load(tmp_path / "picture.npy")
    assert np.array_equal(installed, inkgraph.render(suzanne_path, size=96).picture)
