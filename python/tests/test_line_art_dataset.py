"""examples/line-art-dataset/make_dataset.py run small (ctest python_line_art_dataset): two models, one view; the
manifest lists every file it wrote and the camera of each picture, the views are the command line's (--views 1
--seed 5), each file holds exactly what inkgraph.render() gives for that model and view, and the ink counts are the
masks'."""

from __future__ import annotations

import json
import os
import pathlib
import subprocess
import sys

import numpy as np

import inkgraph

from pngread import read_png

SIZE = 96


def test_two_models_one_view(repo, tmp_path):
    output = tmp_path / "dataset"
    script = repo / "examples" / "line-art-dataset" / "make_dataset.py"
    # The script imports the package these tests import, wherever the working folder is.
    package_parent = str(pathlib.Path(inkgraph.__file__).resolve().parents[1])
    environment = dict(os.environ, PYTHONPATH=os.pathsep.join([package_parent, os.environ.get("PYTHONPATH", "")]))
    run = subprocess.run(
        [sys.executable, str(script), "--output", str(output), "--limit", "2", "--views", "1", "--seed", "5", "--size", str(SIZE),
         "--lines", "silhouette,contour"],
        capture_output=True, text=True, env=environment, cwd=tmp_path)
    assert run.returncode == 0, run.stderr

    manifest = json.loads((output / "manifest.json").read_text())
    listed = [line for line in (repo / "examples" / "batch" / "models.txt").read_text().splitlines()
              if line.strip() and not line.startswith("#")]
    assert [item["model"] for item in manifest["items"]] == listed[:2]
    assert manifest["lines"] == ["silhouette", "contour"] and manifest["size"] == [SIZE, SIZE]
    assert manifest["failures"] == []
    written = {path.relative_to(output).as_posix() for path in output.rglob("*.png")}
    named = {item["picture"] for item in manifest["items"]}
    named |= {file for item in manifest["items"] for file in item["masks"].values()}
    assert written == named and len(written) == 2 * 3
    assert manifest["seed"] == 5

    for item in manifest["items"]:
        assert item["view"] == 0
        # The view the command line draws for this model path with --views 1 --seed 5 (and the default elevation).
        (sample,) = inkgraph.sample_views(1, 5, item["model"], elevation=(10, 10, -30, 60))
        assert item["orbit"] == [sample.azimuth, sample.elevation, sample.distance_scale]
        orbit = f"{sample.azimuth},{sample.elevation},x{sample.distance_scale}"
        expected = inkgraph.render(repo / item["model"], look={"shading": "cel"}, size=SIZE, lines=manifest["lines"],
                                   camera=["--orbit", orbit],
                                   buffers=[f"lines.{t}" for t in manifest["lines"]] + ["strokes"])
        assert json.loads((output / item["strokes"]).read_text()) == expected.strokes()
        # The camera as the render reports it: K and [R|t] as lists of rows, the picture's size.
        camera = item["camera"]
        assert camera["intrinsics"] == expected.camera.intrinsics.tolist()
        assert camera["extrinsics"] == expected.camera.extrinsics.tolist()
        assert (camera["width"], camera["height"]) == (SIZE, SIZE)
        assert np.array_equal(read_png(output / item["picture"]), expected.picture), item["picture"]
        for line_type, file in item["masks"].items():
            mask = read_png(output / file)
            assert np.array_equal(mask, expected.buffers[f"lines.{line_type}"]), file
            assert item["ink_pixels"][line_type] == np.count_nonzero(mask >= 128) > 0, (item["model"], line_type)
