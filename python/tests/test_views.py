"""inkgraph.sample_views() draws the command line's --views: the same numbers as each still's --stats "view" record,
and a Frame with a view's orbit (and its light) renders the command line's picture, pixel for pixel."""

from __future__ import annotations

import json
import shutil
import subprocess

import numpy as np
import pytest

import inkgraph
from pngread import read_png

LOOK = ["--shading", "comic", "--lines", "outline,contour,crease"]


def test_sample_views_are_the_command_lines_views_and_render_its_pictures(tmp_path, suzanne_path,
                                                                          inkgraph_executable):
    shutil.copy(suzanne_path, tmp_path / "m.obj")
    run = subprocess.run([str(inkgraph_executable), "render", "m.obj", "--views", "3", "--seed", "7",
                          "--view-elevation", "5,20,-40,70", "--view-distance-jitter", "0.2", "--light", "0.2,1,0.5",
                          "--light-jitter", "30", "--size", "64x64", "-q", "-o", "v-{view}.png", "--stats",
                          "v-{view}.json", *LOOK], cwd=tmp_path, capture_output=True, text=True)
    assert run.returncode == 0, run.stderr
    views = inkgraph.sample_views(3, 7, "m.obj", elevation=(5, 20, -40, 70), distance_jitter=0.2, light_jitter=30,
                                  light=(0.2, 1, 0.5))
    assert [view.index for view in views] == [0, 1, 2]
    scene = inkgraph.Scene.load(tmp_path / "m.obj")
    for view in views:
        record = json.loads((tmp_path / f"v-{view.index}.json").read_text())["view"]
        # Exactly: the same doubles, not close ones.
        assert (view.azimuth, view.elevation, view.distance_scale) == (
            record["azimuth"], record["elevation"], record["distance_scale"])
        assert view.light is not None and tuple(view.light) == tuple(record["light"])
        assert view.expression is None and view.pose is None and record["expression"] is None
        orbit = view.orbit()
        assert (orbit.azimuth, orbit.elevation, orbit.distance, orbit.distance_scale) == (
            view.azimuth, view.elevation, None, view.distance_scale)
        look = inkgraph.Look.from_arguments([*LOOK, "--light", ",".join(repr(x) for x in view.light)])
        still = inkgraph.default_renderer().render(scene, look, inkgraph.Frame(64, 64, orbit=orbit))
        assert still.camera.source == inkgraph.CameraSource.ORBIT
        assert np.array_equal(still.picture, read_png(tmp_path / f"v-{view.index}.png")), view
    assert len({view.azimuth for view in views}) == 3


def test_sample_views_takes_choices_and_refuses_as_the_flags_do():
    views = inkgraph.sample_views(40, 1, "a.vrm", expressions=["happy=1", "angry=1,blink=0.5", "none"],
                                  poses=["rest", "a-pose"])
    assert {view.expression for view in views} == {"happy=1", "angry=1,blink=0.5", "none"}
    assert {view.pose for view in views} == {"rest", "a-pose"}
    assert all(view.light is None for view in views)
    again = inkgraph.sample_views(40, 1, "a.vrm")
    assert [view.azimuth for view in again] == [view.azimuth for view in views], "choices take draws of their own"
    assert views[3] == views[3].replace() and views[3] != views[4]
    with pytest.raises(inkgraph.UsageError, match="--view-distance-jitter: expected a number from 0 to 0.9"):
        inkgraph.sample_views(2, 0, "a.vrm", distance_jitter=1.5)
    with pytest.raises(inkgraph.UsageError, match="--light-jitter turns --light's direction"):
        inkgraph.sample_views(2, 0, "a.vrm", light_jitter=10)
    with pytest.raises(inkgraph.UsageError, match="--views: expected a whole number from 1 to 100000"):
        inkgraph.sample_views(0, 0, "a.vrm")
    with pytest.raises(inkgraph.UsageError, match="--expressions: an empty alternative"):
        inkgraph.sample_views(2, 0, "a.vrm", expressions=["happy=1", ""])
