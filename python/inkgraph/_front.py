"""The Pythonic front of inkgraph: render() and its Result, make_look() and make_frame() (what render() takes, turned
into a Look and a Frame), and the process's default renderer. The package's __init__ exports these; they live here so
that the package's namespace holds the API alone (no numpy, os or threading beside it)."""

from __future__ import annotations

import atexit
import copy
import numbers
import os
import threading
from collections.abc import Iterable, Mapping, Sequence
from dataclasses import dataclass, field
from typing import Any, Union

import numpy as np
import numpy.typing as npt

from ._inkgraph import Clip, Color, Frame, LineType, Look, Orbit, Renderer, Scene, Shading, Still, StillCamera, Vec3
from ._inkgraph import _stop_calls_for_exit
from ._errors import UsageError
from ._warnings import InkgraphWarning

PathLike = Union[str, "os.PathLike[str]"]
"""A file name: a str or a pathlib.Path."""
Flags = Union[Mapping[str, Any], Sequence[str]]
"""Flags of `inkgraph render`: a dict {"silhouette-width": 3} (flag names without the dashes) or command-line
arguments ["--silhouette-width", "3"]."""
LookLike = Union[None, Look, Flags, PathLike]
"""A look: None (the command line's default), a Look, flags (Flags), or a style file's path."""
LinesLike = Union[str, Iterable[Union[str, LineType]]]
"""Line types: "outline,contour" as --lines takes it, or a list of LineType members or their names."""
Size = Union[int, tuple[int, int]]
"""Pixels: 512 for a square, or (width, height)."""


@dataclass(frozen=True)
class Result:
    """What render() returns: the picture and the buffers asked for, as read-only NumPy arrays sharing the
    still's pixels (``array.copy()`` gives one to change), the camera and the warnings."""

    picture: npt.NDArray[np.uint8]
    """The final picture: height x width x 4 uint8, RGBA."""
    buffers: dict[str, npt.NDArray[Any]]
    """Each buffer asked for, by the name it was asked with."""
    still: Still
    """The still the arrays share."""
    warnings: list[InkgraphWarning] = field(default_factory=list)
    """What the load (when render() loaded the model) and the render warned about; issued through the warnings
    module too."""

    @property
    def camera(self) -> StillCamera:
        """The camera the picture was drawn with: K, [R|t], view and projection matrices, eye, field of view."""
        return self.still.camera

    @property
    def milliseconds(self) -> float:
        """Milliseconds the render took (without loading the model)."""
        return self.still.milliseconds

    def strokes(self) -> list[dict[str, Any]]:
        """Every kept stroke with its points' world points, mesh and triangle (Still.strokes()), when render() was
        asked for buffers=["strokes"]: the --strokes file's "strokes" list (docs/datasets.md)."""
        return self.still.strokes()

    def write(self, path: PathLike) -> None:
        """Writes the picture; the format follows the extension (.png; .exr, .tif, .jpg through OpenImageIO). Raises
        OutputError for a place that is not a regular file or a new name, UsageError for a file the render read."""
        self.still.write(path)


def render(
    model: PathLike | Scene,
    look: LookLike = None,
    size: Size | None = None,
    lines: LinesLike | None = None,
    buffers: str | Iterable[str] = (),
    camera: Flags | Frame | None = None,
    shading: str | Shading | None = None,
    *,
    frame: Frame | None = None,
    renderer: Renderer | None = None,
    out: npt.NDArray[np.uint8] | None = None,
) -> Result:
    """Renders one still of `model` and returns the picture, the buffers asked for, the camera and the warnings.

    model:    a model file (OBJ, glTF/GLB, VRM, STL, PLY), loaded for this call, or a Scene loaded once for many calls.
    look:     None (the command line's default look), a Look, a dict of `inkgraph render`'s look and line flags
              without the dashes ({"shading": "cel", "silhouette-width": 3, "background": (1, 0.9, 0.8)}; a list or
              tuple is joined with commas, True gives a flag without a value, False and None leave it out), a list of
              command-line arguments (["--shading", "cel"]), or a style file's path (--style).
    size:     pixels: 512 for a square, or (width, height); None: the frame's (1024 x 1024 by default).
    lines:    the line types to draw: [LineType.SILHOUETTE, "contour"], "outline,contour", or [] for none; None keeps
              the look's.
    buffers:  buffers to return besides the picture: "normal", "view", "wVec", "nDotV", "depth", "coverage",
              "baseColor", "radial", "materialId", "objectId", "meshId", "triangleId", "barycentric" (the G-buffer;
              Scene.objects and Scene.meshes name the ids), "gbuffer.*", "lines.<type>" (the coverage of a line
              type's lines), "lines.*", "picture" (inkgraph.buffer_names(look) lists them); and "strokes", no image,
              for Result.strokes().
    camera:   a Frame, or camera flags as `look` takes them: ["--orbit", "30,10"] or {"orbit": (30, 10), "fov": 40}.
    shading:  the shading (a Shading or its name), over the look's.
    frame:    a Frame (the same as camera=frame); `size`, when given, overrides its size.
    renderer: the Renderer to draw with; default: default_renderer(), kept with its GL context.
    out:      a writable uint8 (height, width, 4) array to draw the picture into (Result.picture then views it).

    The load's and the render's warnings are issued as InkgraphWarning through the warnings module, and listed in
    Result.warnings. Raises UsageError (also a ValueError) for a bad flag, value or buffer name, InputError for a
    model that cannot be read, ContextError without OpenGL 4.5, OutputError, RenderError; each carries the command
    line's message.
    """
    if frame is not None and camera is not None:
        raise TypeError("render(): give the camera as camera= or as frame=, not both")
    load_warnings: list[InkgraphWarning] = []
    if isinstance(model, Scene):
        scene = model
    elif isinstance(model, (str, os.PathLike)):
        scene = Scene.load(os.fspath(model))
        load_warnings = scene.warnings
    else:
        raise TypeError(f"model: expected a file name or a Scene, got {model!r}")
    buffer_list = [buffers] if isinstance(buffers, str) else _string_list(buffers, "buffers")
    the_look = make_look(look, shading=shading, lines=lines)
    the_frame = make_frame(size, frame if frame is not None else camera)
    def draw(with_renderer: Renderer) -> Still:
        if out is None:
            return with_renderer.render(scene, the_look, the_frame, buffer_list)
        return with_renderer.render(scene, the_look, the_frame, buffer_list, out=out)

    if renderer is not None:
        still = draw(renderer)
    else:
        for attempt in range(_DEFAULT_RENDERER_ATTEMPTS):
            the_renderer = default_renderer()
            try:
                still = draw(the_renderer)
                break
            except UsageError:
                # Another thread closed the default renderer between default_renderer() and the render: the next
                # default_renderer() makes a new one, as it promises after a close.
                if not the_renderer.closed or attempt + 1 == _DEFAULT_RENDERER_ATTEMPTS:
                    raise
    # Each buffer by the name it was asked with: the still's names (a wildcard's by their own names), and a second
    # name of a buffer already there (both "depth" and "gbuffer.depth") as well.
    arrays = {name: still.buffer(name) for name in still.buffer_names}
    for name in buffer_list:
        if name not in arrays and not name.endswith(".*") and name != "strokes":
            arrays[name] = still.buffer(name)
    return Result(picture=still.picture, buffers=arrays, still=still, warnings=load_warnings + still.warnings)


def make_look(look: LookLike = None, *, shading: str | Shading | None = None, lines: LinesLike | None = None) -> Look:
    """A Look from what render() takes as `look`, `shading` and `lines` (those two set after the look's flags,
    so they win). The caller's Look is not changed."""
    result: Look
    if look is None:
        result = Look()
    elif isinstance(look, Look):
        result = copy.copy(look)
    elif isinstance(look, (str, os.PathLike)):
        result = Look.from_style_file(look)
    elif isinstance(look, Mapping):
        result = Look()
        for flag, value in _flag_pairs(look):
            result.set(flag, "" if value is None else value)
    elif isinstance(look, Sequence):
        result = Look.from_arguments(_string_list(look, "look"))
    else:
        raise TypeError(f"look: expected None, a dict, a list of arguments, a Look or a style file, got {look!r}")
    if shading is not None:
        result.shading = Shading.from_name(shading) if isinstance(shading, str) else shading
    if lines is not None:
        # As --lines takes them, so that its words ("none") and messages carry over.
        if isinstance(lines, str):
            words = lines
        else:
            names = []
            for item in lines:
                if not isinstance(item, (str, LineType)):
                    raise TypeError(f"lines: expected LineType members or their names, got {item!r} in it")
                names.append(item if isinstance(item, str) else item.cli_name)
            words = ",".join(names) if names else "none"
        result.set("--lines", words)
    return result


def make_frame(size: Size | None = None, camera: Flags | Frame | None = None) -> Frame:
    """A Frame from what render() takes as `size` and `camera` (a Frame, which is copied, or camera flags)."""
    if camera is None:
        result = Frame()
    elif isinstance(camera, Frame):
        result = copy.copy(camera)
    elif isinstance(camera, Mapping):
        arguments = [word for flag, value in _flag_pairs(camera) for word in (flag, value) if word is not None]
        result = Frame.from_arguments(arguments)
    elif isinstance(camera, Sequence) and not isinstance(camera, str):
        result = Frame.from_arguments(_string_list(camera, "camera"))
    else:
        raise TypeError(f"camera: expected a Frame, a dict or a list of arguments, got {camera!r}")
    if size is None:
        return result
    sides: Any = (size, size) if isinstance(size, numbers.Integral) else size
    if (
        isinstance(size, bool)
        or not isinstance(sides, Sequence)
        or len(sides) != 2
        or not all(isinstance(side, numbers.Integral) and not isinstance(side, bool) for side in sides)
    ):
        raise TypeError(f"size: expected pixels (512) or (width, height), got {size!r}")
    result.width, result.height = int(sides[0]), int(sides[1])
    return result


_default_lock = threading.Lock()
_default: Renderer | None = None
#: render() with the default renderer tries this many times when another thread closes it meanwhile.
_DEFAULT_RENDERER_ATTEMPTS = 100


def default_renderer() -> Renderer:
    """The Renderer render() draws with when given none: one for the process, made on first use and kept, with its
    GL context and compiled programs, until closed (the next call then makes a new one) or the interpreter ends.
    A batch of render() calls thus makes one context.

    Every renderer has a GL context of its own: Renderers of your own render beside this one, each on its own thread
    if you like (a renderer's calls run one at a time, from any thread). A child forked after a render starts without
    a default renderer; its GL driver is the parent's, without the parent's threads, so it cannot render
    (ContextError says why) unless every renderer was closed before the fork: use multiprocessing's 'spawn' or
    'forkserver' start method."""
    global _default
    with _default_lock:
        if _default is None or _default.closed:
            _default = Renderer()
        return _default


def _forget_default_renderer_in_child() -> None:
    # The parent's renderer is left alone in a forked child (its GL driver threads live only in the parent): dropping
    # it frees nothing of the driver (the C++ library sees the other process), and the lock may have been held.
    global _default, _default_lock
    _default_lock = threading.Lock()
    _default = None


os.register_at_fork(after_in_child=_forget_default_renderer_in_child)


@atexit.register
def _close_default_renderer() -> None:
    # While the interpreter is whole, rather than whenever module teardown reaches the object.
    if _default is not None:
        _default.close()


# Registered after the closing, so it runs first (atexit is last in, first out): no load, render or write is in flight
# when the default renderer closes, and a daemon thread's later call waits for the process to end (one rendering
# while exit() tore the driver down crashed the process).
atexit.register(_stop_calls_for_exit)


def _flag_pairs(flags: Mapping[str, Any]) -> list[tuple[str, str | None]]:
    """(flag, value) pairs from a dict: "silhouette-width" (or silhouette_width) -> "--silhouette-width"; the value
    as on the command line, None for a flag given without a value (True); False and None leave the flag out."""
    pairs: list[tuple[str, str | None]] = []
    for key, value in flags.items():
        if not isinstance(key, str):
            raise TypeError(f"flag names are strings, got {key!r}")
        flag = key if key.startswith("-") else "--" + key.replace("_", "-")
        if value is None or value is False:
            continue
        pairs.append((flag, None if value is True else _flag_value(flag, value)))
    return pairs


def _flag_value(flag: str, value: Any) -> str:
    """A value as the command line writes it: numbers as Python prints them, an enum member by its command-line
    word, lists, tuples and the small value types (Vec3, Color, Orbit, Clip) joined by commas."""
    if isinstance(value, (str, numbers.Real, os.PathLike)) or hasattr(value, "cli_name"):
        return _scalar_value(flag, value)
    if isinstance(value, Orbit) and value.distance is not None and value.distance_scale != 1.0:
        raise ValueError(f"{flag}: the Orbit gives a distance and a distance_scale ({value.distance_scale}); the "
                         "scale is of the auto-framing distance, so give one of them")
    if isinstance(value, Orbit) and value.distance is None and value.distance_scale != 1.0:
        # The scale is the command line's xS in place of a distance (an Orbit's items leave it out).
        return f"{_scalar_value(flag, value.azimuth)},{_scalar_value(flag, value.elevation)}," \
            f"x{_scalar_value(flag, value.distance_scale)}"
    if isinstance(value, Color) and value.a == 1.0:
        # Opaque: R,G,B, which every colour flag takes (--background and --ambient take nothing else).
        return ",".join(_scalar_value(flag, item) for item in (value.r, value.g, value.b))
    if isinstance(value, (Sequence, np.ndarray, Vec3, Color, Orbit, Clip)):
        return ",".join(_scalar_value(flag, item) for item in value if item is not None)
    raise TypeError(f"{flag}: expected a string, a number or a list of them, got {value!r}")


def _scalar_value(flag: str, value: Any) -> str:
    if isinstance(value, str):
        return value
    if hasattr(value, "cli_name"):
        return str(value.cli_name)
    if isinstance(value, os.PathLike):
        return str(os.fspath(value))
    if isinstance(value, numbers.Integral) and not isinstance(value, (bool, np.bool_)):
        return str(int(value))
    if isinstance(value, numbers.Real) and not isinstance(value, (bool, np.bool_)):
        return str(value)
    raise TypeError(f"{flag}: expected a string or a number in the list, got {value!r}")


def _string_list(items: Iterable[Any], what: str) -> list[str]:
    if isinstance(items, str):
        raise TypeError(f"{what}: expected a list of strings, got the string {items!r}")
    result = list(items)
    for item in result:
        if not isinstance(item, str):
            raise TypeError(f"{what}: expected a list of strings, got {item!r} in it")
    return result
