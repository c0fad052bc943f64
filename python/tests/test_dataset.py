"""A data set made with `inkgraph render --dataset` (docs/datasets.md), read from Python as a consumer reads it: every
index line validates against docs/schemas/index.schema.json, check-dataset passes, and each still's recorded camera
(OpenCV's K and [R|t]) projects its model's vertices onto the picture's drawn pixels. The checker lives in the command
line (app/DatasetCheck.h), not in the library the module wraps, so it is run as a program here."""

from __future__ import annotations

import json
import pathlib
import subprocess

import jsonschema
import numpy as np

from pngread import read_png

SIDE = 96
MODELS = ["spot_c3d.obj", "suzanne_npm_4k.obj"]


def obj_vertices(path: pathlib.Path) -> np.ndarray:
    rows = [line.split()[1:4] for line in path.read_text().splitlines() if line.startswith("v ")]
    return np.array(rows, dtype=np.float64)


def make_dataset(inkgraph_executable: pathlib.Path, repo: pathlib.Path, folder: pathlib.Path) -> None:
    folder.mkdir()
    models = [str(repo / "models" / name) for name in MODELS]
    run = subprocess.run([str(inkgraph_executable), "render", *models, "--size", f"{SIDE}x{SIDE}", "--lines",
                          "silhouette", "--shading", "none", "--dataset", ".", "-o", "{name}.png", "--svg",
                          "{name}.svg", "-q"], cwd=folder, capture_output=True, text=True)
    assert run.returncode == 0, run.stderr


def test_the_index_validates_and_check_dataset_passes(inkgraph_executable, repo, tmp_path):
    folder = tmp_path / "set"
    make_dataset(inkgraph_executable, repo, folder)
    schema = json.loads((repo / "docs" / "schemas" / "index.schema.json").read_text())
    jsonschema.Draft202012Validator.check_schema(schema)
    validator = jsonschema.Draft202012Validator(schema)
    lines = (folder / "index.jsonl").read_text().splitlines()
    assert len(lines) == len(MODELS)
    records = [json.loads(line) for line in lines]
    for record in records:
        validator.validate(record)
    assert [record["position"] for record in records] == [0, 1]
    assert all(record["status"] == "ok" for record in records)
    assert records[0]["files"] == {"-o": "spot_c3d.png", "--svg": "spot_c3d.svg"}
    # The schema refuses what the index must never hold: a path out of the folder, a still without its files.
    bad = dict(records[0], files={"-o": "../elsewhere.png"})
    assert not validator.is_valid(bad)
    assert not validator.is_valid({key: value for key, value in records[0].items() if key != "checksums"})

    card = (folder / "README.md").read_text()
    assert "| stills in the set | 2 |" in card and "| failed | 0 |" in card
    assert "inkgraph check-dataset" in card
    check = subprocess.run([str(inkgraph_executable), "check-dataset", str(folder)], capture_output=True, text=True)
    assert check.returncode == 0, check.stdout + check.stderr
    assert "2 stills, 0 failed, 4 files verified; 0 errors, 0 warnings: whole" in check.stdout

    # A file cut short: not whole (exit 1), named.
    picture = folder / "suzanne_npm_4k.png"
    picture.write_bytes(picture.read_bytes()[:-12])
    check = subprocess.run([str(inkgraph_executable), "check-dataset", str(folder)], capture_output=True, text=True)
    assert check.returncode == 1
    assert "'suzanne_npm_4k.png' is a PNG cut short" in check.stdout


def test_the_recorded_cameras_project_the_models_onto_their_pictures(inkgraph_executable, repo, tmp_path):
    folder = tmp_path / "set"
    make_dataset(inkgraph_executable, repo, folder)
    for line in (folder / "index.jsonl").read_text().splitlines():
        record = json.loads(line)
        camera = record["camera"]
        assert (camera["width"], camera["height"]) == (SIDE, SIDE)
        K = np.array(camera["intrinsics"])
        Rt = np.array(camera["extrinsics"])
        # The eye is the camera centre: [R|t] maps it to the origin; the target lies on the optical axis.
        eye = np.append(camera["eye"], 1.0)
        assert np.allclose(Rt @ eye, 0.0, atol=1e-9)
        target = K @ (Rt @ np.append(camera["target"], 1.0))
        assert np.allclose(target[:2] / target[2], [SIDE / 2 - 0.5, SIDE / 2 - 0.5], atol=1e-9)

        vertices = obj_vertices(pathlib.Path(record["model"]))
        homogeneous = np.hstack([vertices, np.ones((len(vertices), 1))])
        projected = (K @ (Rt @ homogeneous.T)).T
        assert np.all(projected[:, 2] > 0), "every vertex in front of the camera"
        pixels = projected[:, :2] / projected[:, 2:3]
        # The silhouette (2 px wide, anti-aliased, --shading none) traces the model's outline from outside: the box
        # of the drawn pixels holds the box of the projected vertices, with a margin of at most the line's width
        # plus a pixel of anti-aliasing on each side (a wrong K, R or t shifts or scales it by far more).
        image = read_png(folder / record["files"]["-o"])
        ink = np.argwhere(image[..., :3].min(axis=2) < 250)
        assert len(ink) > 50
        drawn = np.array([ink[:, 1].min(), ink[:, 0].min(), ink[:, 1].max(), ink[:, 0].max()], dtype=np.float64)
        model = np.array([pixels[:, 0].min(), pixels[:, 1].min(), pixels[:, 0].max(), pixels[:, 1].max()])
        margins = np.concatenate([model[:2] - drawn[:2], drawn[2:] - model[2:]])
        assert np.all((margins >= -0.5) & (margins <= 3.0)), f"{record['model']}: drawn {drawn}, projected {model}"
