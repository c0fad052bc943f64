#!/usr/bin/env python3
"""Renders a character from evenly spaced orbits with the inkgraph Python module and writes each picture with the
camera it was drawn with (OpenCV's intrinsics K and extrinsics [R|t], OpenGL's view and projection matrices, the size
and where the view came from) as JSON beside it: posed pictures for multi-view work (reconstruction, novel views, training a
line-drawing model with known cameras). README.md in this folder says more.

    PYTHONPATH=build/python /usr/bin/python3 examples/orbit-cameras/orbit_cameras.py --output out/orbit-cameras
"""

from __future__ import annotations

import argparse
import json
import pathlib
import sys
from typing import Any

import inkgraph

REPOSITORY = pathlib.Path(__file__).resolve().parents[2]


def parse_arguments(argv: list[str]) -> argparse.Namespace:
    parser = argparse.ArgumentParser(description=(__doc__ or "").split("\n\n")[0])
    parser.add_argument("--model", type=pathlib.Path, default=REPOSITORY / "models" / "characters" / "godette.vrm",
                        help="the model to render (default: Godette, a VRM character)")
    parser.add_argument("--output", type=pathlib.Path, default=pathlib.Path("out/examples/orbit-cameras"),
                        help="folder to write into (made if missing; default: %(default)s)")
    parser.add_argument("--views", type=int, default=8, help="orbits, evenly around the model (default: %(default)s)")
    parser.add_argument("--elevation", type=float, default=10.0,
                        help="degrees above the horizontal every view looks from (default: %(default)s)")
    parser.add_argument("--width", type=int, default=512, help="picture width in pixels (default: %(default)s)")
    parser.add_argument("--height", type=int, default=640, help="picture height in pixels (default: %(default)s)")
    arguments = parser.parse_args(argv)
    if arguments.views < 1:
        parser.error("--views must be at least 1")
    return arguments


def main(argv: list[str]) -> int:
    arguments = parse_arguments(argv)
    output: pathlib.Path = arguments.output
    output.mkdir(parents=True, exist_ok=True)
    # The file's own MToon materials and outlines, with the silhouette and contours drawn over them.
    look = inkgraph.Look(shading=inkgraph.Shading.MTOON,
                         lines=[inkgraph.LineType.SILHOUETTE, inkgraph.LineType.CONTOUR])
    scene = inkgraph.Scene.load(arguments.model)  # once, for every view; its warnings go to the warnings module
    views: list[dict[str, Any]] = []
    # One renderer for every view: one GL context, each shader program compiled once.
    with inkgraph.Renderer() as renderer:
        for index in range(arguments.views):
            azimuth = round(360.0 * index / arguments.views, 6)
            frame = inkgraph.Frame(arguments.width, arguments.height,
                                   orbit=inkgraph.Orbit(azimuth, arguments.elevation))
            still = renderer.render(scene, look, frame)
            picture = f"view-{index}.png"
            still.write(output / picture)
            view = {"index": index, "picture": picture, "model": str(arguments.model),
                    "orbit": {"azimuth": azimuth, "elevation": arguments.elevation}, "camera": still.camera.as_dict()}
            (output / f"view-{index}.json").write_text(json.dumps(view, indent=2) + "\n")
            views.append(view)
            print(f"orbit_cameras: {picture} (azimuth {azimuth}, {still.milliseconds:.0f} ms)", file=sys.stderr)
    # Every view in one file as well, for loaders that want the whole set at once.
    cameras = {"inkgraph": inkgraph.__version__, "model": str(arguments.model), "views": views}
    (output / "cameras.json").write_text(json.dumps(cameras, indent=2) + "\n")
    print(f"orbit_cameras: {len(views)} pictures in {output}, each with its camera", file=sys.stderr)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
