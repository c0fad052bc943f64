"""The package: where it is imported from, its version, the scene's facts, and write_image()'s files."""

from __future__ import annotations

import pathlib
import re

import numpy as np
import pytest

import inkgraph
from pngread import read_png


def test_the_version_is_the_projects(repo):
    project = re.search(r"project\(inkgraph VERSION (\S+)", (repo / "CMakeLists.txt").read_text()).group(1)
    assert inkgraph.__version__ == inkgraph.version() == project
    assert re.fullmatch(r"[0-9a-f]{7,40}(-dirty)?|unknown", inkgraph.git_commit()), inkgraph.git_commit()


def test_the_package_is_the_built_one_not_the_source_folder(repo):
    # The source tree's python/inkgraph has no extension; the tests run against a built package (PYTHONPATH).
    package = pathlib.Path(inkgraph.__file__).resolve().parent
    assert package != (repo / "python" / "inkgraph").resolve()
    assert pathlib.Path(inkgraph._inkgraph.__file__).resolve().parent == package


def test_a_scene_knows_its_file_and_counts(suzanne, suzanne_path):
    assert suzanne.path == suzanne_path
    # suzanne_npm_4k.obj: 3936 triangles (Blender's monkey, subdivided once into quads, triangulated).
    with open(suzanne_path) as obj:
        faces = [line.split()[1:] for line in obj if line.startswith("f ")]
    assert suzanne.triangle_count == sum(len(face) - 2 for face in faces)
    assert suzanne.mesh_count >= 1 and suzanne.vertex_count > 0


@pytest.mark.parametrize("shape", [(5, 7), (5, 7, 1), (5, 7, 4)])
def test_write_image_writes_png_exactly(tmp_path, shape):
    pixels = np.random.default_rng(21).integers(0, 256, size=shape, dtype=np.uint8)
    path = tmp_path / "pixels.png"
    inkgraph.write_image(path, pixels)
    assert np.array_equal(read_png(path), pixels.reshape(shape[:2]) if len(shape) == 2 or shape[2] == 1 else pixels)


def test_write_image_takes_any_strides_and_refuses_what_it_cannot_write(tmp_path):
    pixels = np.arange(6 * 8, dtype=np.uint8).reshape(6, 8)
    inkgraph.write_image(tmp_path / "transposed.png", pixels.T)
    assert np.array_equal(read_png(tmp_path / "transposed.png"), pixels.T)
    with pytest.raises(inkgraph.UsageError, match="write_image\\(\\): expected a uint8 or float32 array, got float64"):
        inkgraph.write_image(tmp_path / "x.png", np.zeros((4, 4)))
    with pytest.raises(inkgraph.UsageError, match="expected 1 or 4 channels, got 3"):
        inkgraph.write_image(tmp_path / "x.png", np.zeros((4, 4, 3), np.uint8))
    assert not (tmp_path / "x.png").exists()


def test_the_picture_written_is_the_picture(suzanne, tmp_path):
    result = inkgraph.render(suzanne, size=64)
    result.write(tmp_path / "picture.png")
    assert np.array_equal(read_png(tmp_path / "picture.png"), result.picture)
