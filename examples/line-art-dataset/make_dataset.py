#!/usr/bin/env python3
"""Builds a small line-art data set from the bundled models with the inkgraph Python module: for each model and view,
the picture and one mask per line type (the coverage of that type's drawn lines: 255 on a line, 0 off it, partial
along antialiased edges), and manifest.json listing every file with its model, its camera (OpenCV's intrinsics K and
extrinsics [R|t]) and the ink pixels of each type (those at least half covered). README.md in this folder says
more.

    PYTHONPATH=build/python /usr/bin/python3 examples/line-art-dataset/make_dataset.py --output out/line-art
"""

from __future__ import annotations

import argparse
import json
import pathlib
import sys
from typing import Any

import numpy as np

import inkgraph

REPOSITORY = pathlib.Path(__file__).resolve().parents[2]
INK = 128  # a mask's pixel counts as ink from half coverage up (masks are antialiased: 255 inside a line)


def parse_arguments(argv: list[str]) -> argparse.Namespace:
    parser = argparse.ArgumentParser(description=(__doc__ or "").split("\n\n")[0])
    parser.add_argument("--output", type=pathlib.Path, default=pathlib.Path("out/examples/line-art-dataset"),
                        help="folder to write into (made if missing; default: %(default)s)")
    parser.add_argument("--models", type=pathlib.Path, default=REPOSITORY / "examples" / "batch" / "models.txt",
                        help="a list of model files, one a line, # comments (default: every bundled model)")
    parser.add_argument("--root", type=pathlib.Path, default=REPOSITORY,
                        help="the folder the list's relative paths start from (default: the repository)")
    parser.add_argument("--limit", type=int, default=0, help="only the first N models of the list (0: all)")
    parser.add_argument("--views", type=int, default=2,
                        help="views per model, drawn as `inkgraph render --views N --seed S` draws them: the same "
                        "views as the command line for the same model path (default: %(default)s)")
    parser.add_argument("--seed", type=int, default=0, help="the views' seed (default: %(default)s)")
    parser.add_argument("--elevation", default="10,10,-30,60",
                        help="MEAN,SD,LOW,HIGH of the views' elevation in degrees, as --view-elevation "
                        "(default: %(default)s)")
    parser.add_argument("--size", type=int, default=256, help="square picture size in pixels (default: %(default)s)")
    parser.add_argument("--lines", default="silhouette,contour,crease,suggestive",
                        help="the line types drawn, each with its mask (default: %(default)s)")
    parser.add_argument("--shading", default="cel", help="the pictures' shading mode (default: %(default)s)")
    arguments = parser.parse_args(argv)
    if arguments.views < 1 or arguments.limit < 0:
        parser.error("--views must be at least 1 and --limit at least 0")
    try:
        arguments.elevation = [float(value) for value in arguments.elevation.split(",")]
    except ValueError:
        parser.error(f"--elevation '{arguments.elevation}': four numbers MEAN,SD,LOW,HIGH")
    return arguments


def model_list(path: pathlib.Path, limit: int) -> list[str]:
    entries = [line.strip() for line in path.read_text().splitlines()]
    models = [entry for entry in entries if entry and not entry.startswith("#")]
    return models[:limit] if limit else models


def main(argv: list[str]) -> int:
    arguments = parse_arguments(argv)
    line_types = [inkgraph.LineType.from_name(name) for name in arguments.lines.split(",") if name]
    look = inkgraph.Look(shading=inkgraph.Shading.from_name(arguments.shading), lines=line_types)
    masks = [f"lines.{line_type.cli_name}" for line_type in line_types]
    output: pathlib.Path = arguments.output
    output.mkdir(parents=True, exist_ok=True)
    items: list[dict[str, Any]] = []
    failures: list[dict[str, str]] = []
    # One renderer for the whole set: one GL context, each shader program compiled once; each model loaded once.
    with inkgraph.Renderer() as renderer:
        for model in model_list(arguments.models, arguments.limit):
            try:
                scene = inkgraph.Scene.load(arguments.root / model)
            except inkgraph.InputError as error:  # an unreadable model is reported, the others still rendered
                print(f"make_dataset: {error}", file=sys.stderr)
                failures.append({"model": model, "error": str(error)})
                continue
            name = pathlib.PurePath(model).stem
            (output / name).mkdir(exist_ok=True)
            # The command line's views for this model path (the list's entry, the key the views are drawn by).
            for sample in inkgraph.sample_views(arguments.views, arguments.seed, model,
                                                elevation=arguments.elevation):
                view = sample.index
                frame = inkgraph.Frame(arguments.size, arguments.size, orbit=sample.orbit())
                still = renderer.render(scene, look, frame, masks + ["strokes"])
                picture = f"{name}/view-{view}.png"
                still.write(output / picture)
                # Every stroke with its type, visibility, and per point its pixel and the world point it came from.
                strokes = f"{name}/view-{view}-strokes.json"
                (output / strokes).write_text(json.dumps(still.strokes()) + "\n")
                camera = still.camera
                mask_files: dict[str, str] = {}
                ink_pixels: dict[str, int] = {}
                for line_type, mask_name in zip(line_types, masks):
                    mask = still.buffer(mask_name)
                    file = f"{name}/view-{view}-{line_type.cli_name}.png"
                    inkgraph.write_image(output / file, mask)
                    mask_files[line_type.cli_name] = file
                    ink_pixels[line_type.cli_name] = int(np.count_nonzero(mask >= INK))
                # The camera as numbers, not as the orbit that placed it: K and [R|t] take a pixel to its ray and a
                # world point to its pixel without knowing how inkgraph frames an orbit.
                item: dict[str, Any] = {
                    "model": model, "view": view, "picture": picture, "strokes": strokes,
                    "orbit": [sample.azimuth, sample.elevation, sample.distance_scale],
                    "camera": {"intrinsics": camera.intrinsics.tolist(), "extrinsics": camera.extrinsics.tolist(),
                               "width": camera.width, "height": camera.height},
                    "masks": mask_files, "ink_pixels": ink_pixels}
                items.append(item)
                counts = ", ".join(f"{line_type} {count}" for line_type, count in ink_pixels.items())
                print(f"make_dataset: {picture} (ink pixels: {counts})", file=sys.stderr)
    manifest = {"inkgraph": inkgraph.__version__, "size": [arguments.size, arguments.size], "seed": arguments.seed,
                "shading": arguments.shading, "lines": [line_type.cli_name for line_type in line_types], "items": items,
                "failures": failures}
    (output / "manifest.json").write_text(json.dumps(manifest, indent=2) + "\n")
    print(f"make_dataset: {len(items)} pictures in {output}, manifest.json lists them", file=sys.stderr)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
