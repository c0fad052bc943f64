"""The typed API as a user's type checker sees it: every class, enum and function of the package used once with the
types its stubs (inkgraph/_inkgraph.pyi) give, checked by `mypy --strict` (ctest python_typing) and run by
test_typed_api.py, so that the stubs and the extension cannot drift apart unnoticed on either side."""

from __future__ import annotations

import pathlib
import warnings

import numpy as np
import numpy.typing as npt

import inkgraph


def typed_look() -> inkgraph.Look:
    look = inkgraph.Look(shading=inkgraph.Shading.CEL, lines=[inkgraph.LineType.SILHOUETTE, "contour"])
    look.bands = 3
    look.paper = inkgraph.Color(1.0, 0.95, 0.9)
    look.light = inkgraph.Vec3(0.0, 1.0, 1.0)
    look.supersample = 2
    look.msaa = 4
    look.gbuffer_precision = inkgraph.Precision.from_name("half")
    look.strokes = look.strokes.replace(taper_ends=True)
    look.set_line_style(inkgraph.LineType.CONTOUR, inkgraph.LineStyle(width=3.0, color=(0.2, 0.1, 0.0)))
    shading: inkgraph.Shading = look.shading
    lines: list[inkgraph.LineType] = look.lines
    assert shading.cli_name == "cel" and [t.cli_name for t in lines] == ["silhouette", "contour"]
    style: inkgraph.LineStyle = look.line_style("contour")
    assert style.width == 3.0 and style.color == inkgraph.Color(0.2, 0.1, 0.0)
    names: list[str] = inkgraph.Look.line_parameter_names(inkgraph.LineType.CREASE)
    assert "crease-angle" in names
    return look


def typed_frame(size: int) -> inkgraph.Frame:
    frame = inkgraph.Frame(size, size, orbit=inkgraph.Orbit(30.0, 10.0))
    frame.fov = 40.0
    frame.clip = inkgraph.Clip(0.1, 100.0)
    orbit: inkgraph.Orbit | None = frame.orbit
    assert orbit is not None and (orbit.azimuth, orbit.elevation, orbit.distance) == (30.0, 10.0, None)
    return frame


def camera_record(camera: inkgraph.StillCamera) -> dict[str, object]:
    intrinsics: npt.NDArray[np.float64] = camera.intrinsics
    extrinsics: npt.NDArray[np.float64] = camera.extrinsics
    source: inkgraph.CameraSource = camera.source
    return {"K": intrinsics.tolist(), "Rt": extrinsics.tolist(), "source": source.cli_name}


def main(model: pathlib.Path, size: int) -> list[inkgraph.InkgraphWarning]:
    """Renders `model` through the typed API, once into an array of the caller's, and returns the warnings."""
    scene = inkgraph.Scene.load(model)
    look = typed_look()
    frame = typed_frame(size)
    out: npt.NDArray[np.uint8] = np.zeros((size, size, 4), np.uint8)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", inkgraph.InkgraphWarning)
        still: inkgraph.Still = inkgraph.default_renderer().render(scene, look, frame, ["depth"], out=out)
    depth = still.buffer("depth")
    assert depth.shape == (2 * size, 2 * size) and np.shares_memory(still.picture, out)
    assert camera_record(still.camera)["source"] == "orbit"
    result: inkgraph.Result = inkgraph.render(scene, look=look, frame=frame)
    assert np.array_equal(result.picture, out)
    return result.warnings + still.warnings
