"""examples/line-art-dataset/make_dataset.py run small (ctest python_line_art_dataset): two models, one view; the
manifest lists every file it wrote, each mask is 0/255 with the ink count the manifest gives, and the picture is dark
wherever a mask has a line."""

from __future__ import annotations

import json
import os
import subprocess
import sys

import numpy as np

from pngread import read_png

SIZE = 96


def test_two_models_one_view(repo, tmp_path):
    output = tmp_path / "dataset"
    script = repo / "examples" / "line-art-dataset" / "make_dataset.py"
    run = subprocess.run(
        [sys.executable, str(script), "--output", str(output), "--limit", "2", "--views", "1", "--size", str(SIZE),
         "--lines", "silhouette,contour"],
        capture_output=True, text=True, env=os.environ, cwd=tmp_path)
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

    for item in manifest["items"]:
        assert item["view"] == {"index": 0, "azimuth": 0.0, "elevation": 15.0}
        picture = read_png(output / item["picture"])
        assert picture.shape == (SIZE, SIZE, 4)
        for line_type, file in item["masks"].items():
            mask = read_png(output / file)
            assert mask.shape == (SIZE, SIZE)
            assert set(np.unique(mask).tolist()) <= {0, 255}
            assert item["ink_pixels"][line_type] == np.count_nonzero(mask) > 0, (item["model"], line_type)
            assert (picture[mask == 255][:, :3] < 64).all()
