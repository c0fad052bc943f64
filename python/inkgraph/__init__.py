"""inkgraph for Python: render 3D models as anime/comic-style stills, the picture and any buffer as NumPy arrays.

    import inkgraph

    result = inkgraph.render("models/bunny_c3d_70k.obj", look={"shading": "cel", "silhouette-width": 3},
                             size=512, lines=["silhouette", "contour"], buffers=["normal", "depth", "lines.contour"])
    result.picture                   # 512 x 512 x 4 uint8, RGBA
    result.buffers["normal"]         # 512 x 512 x 4 float32, alpha = coverage
    result.buffers["lines.contour"]  # 512 x 512 uint8, 255 on the contour lines

Looks and cameras are `inkgraph render`'s flags (`inkgraph help render`), checked by the same code as on the command
line, so errors read the same (inkgraph.UsageError and the rest of the inkgraph.Error family). render() draws with
a renderer kept for the process, so a batch makes its GL context once; inkgraph.Renderer gives explicit control, and
inkgraph.Scene loads a model once for many renders. The classes Renderer, Scene, Look, Frame and Still are the C++
API's (inkgraph/inkgraph.h, docs/api.md) as the extension `inkgraph._inkgraph` binds them. docs/python.md has it all.
"""

from __future__ import annotations

import atexit
import numbers
import os
import threading
from collections.abc import Iterable, Mapping, Sequence
from dataclasses import dataclass
from typing import Any, Union

import numpy as np

from ._errors import ContextError, Error, InputError, OutputError, RenderError, UsageError
from ._inkgraph import Frame, Look, Renderer, Scene, Still, buffer_resource_name, git_commit, version, write_image

__version__: str = version()

__all__ = [
    "ContextError",
    "Error",
    "Frame",
    "InputError",
    "Look",
    "OutputError",
    "RenderError",
    "Renderer",
    "Result",
    "Scene",
    "Still",
    "UsageError",
    "buffer_resource_name",
    "default_renderer",
    "git_commit",
    "make_frame",
    "make_look",
    "render",
    "version",
    "write_image",
]

PathLike = Union[str, "os.PathLike[str]"]
"""A file name: a str or a pathlib.Path."""
Flags = Union[Mapping[str, Any], Sequence[str]]
"""Flags of `inkgraph render`: a dict {"silhouette-width": 3} (flag names without the dashes) or command-line
arguments ["--silhouette-width", "3"]."""
LookLike = Union[None, Look, Flags, PathLike]
"""A look: None (the command line's default), a Look, flags (Flags), or a style file's path."""


@dataclass(frozen=True)
class Result:
    """What render() returns: the picture and the buffers asked for, as read-only NumPy arrays sharing the
    still's pixels (``array.copy()`` gives one to change)."""

    picture: np.ndarray
    """The final picture: height x width x 4 uint8, RGBA."""
    buffers: dict[str, np.ndarray]
    """Each buffer asked for, by the name it was asked with."""
    still: Still
    """The C++ still the arrays share."""

    @property
    def milliseconds(self) -> float:
        """Milliseconds the render took (without loading the model)."""
        return self.still.milliseconds

    def write(self, path: PathLike) -> None:
        """Writes the picture; the format follows the extension (.png; .exr, .tif, .jpg through OpenImageIO). Raises
        OutputError for a place that is not a regular file or a new name, UsageError for a file the render read."""
        self.still.write(path)


def render(
    model: PathLike | Scene,
    look: LookLike = None,
    size: int | tuple[int, int] = 1024,
    lines: str | Iterable[str] | None = None,
    buffers: str | Iterable[str] = (),
    camera: Flags | None = None,
    shading: str | None = None,
    *,
    renderer: Renderer | None = None,
) -> Result:
    """Renders one still of `model` and returns the picture and the buffers asked for.

    model:    a model file (OBJ, glTF/GLB, VRM, STL, PLY), loaded for this call, or a Scene loaded once for many calls.
    look:     None (the command line's default look), a dict of `inkgraph render`'s look and line flags without the
              dashes ({"shading": "cel", "silhouette-width": 3, "background": (1, 0.9, 0.8)}; a list or tuple is
              joined with commas, True gives a flag without a value, False and None leave it out), a list of
              command-line arguments (["--shading", "cel"]), a Look, or a style file's path (--style).
    size:     pixels: 512 for a square, or (width, height).
    lines:    the line types to draw (--lines): ["silhouette", "contour"], "outline,contour", or [] for none;
              None keeps the look's.
    buffers:  buffers to return besides the picture: "normal", "view", "wVec", "nDotV", "depth", "coverage",
              "baseColor", "radial", "materialId" (the G-buffer), "lines.<type>" (the coverage of a line type's lines),
              "picture", or a full graph resource name ("shade.color", "gbuffer.*").
    camera:   camera flags as `look` takes them: ["--orbit", "30,10"] or {"orbit": (30, 10), "fov": 40}.
    shading:  the shading mode (--shading), over the look's.
    renderer: the Renderer to draw with; default: default_renderer(), kept with its GL context.

    Raises UsageError (also a ValueError) for a bad flag, value or buffer name, InputError for a model that cannot
    be read, ContextError without OpenGL 4.5, OutputError, RenderError; each carries the command line's message.
    """
    scene = model if isinstance(model, Scene) else Scene.load(os.fspath(model))
    buffers = [buffers] if isinstance(buffers, str) else _string_list(buffers, "buffers")
    still = (renderer or default_renderer()).render(
        scene, make_look(look, shading=shading, lines=lines), make_frame(size, camera), buffers
    )
    # Each buffer by the name it was asked with: the still's names (a wildcard's fields by their full names), and a
    # second name of a buffer already there (both "depth" and "gbuffer.depth") as well.
    arrays = {name: still.buffer(name) for name in still.buffer_names}
    for name in buffers:
        if name not in arrays and not name.endswith(".*"):
            arrays[name] = still.buffer(name)
    return Result(picture=still.picture, buffers=arrays, still=still)


def make_look(look: LookLike = None, *, shading: str | None = None, lines: str | Iterable[str] | None = None) -> Look:
    """A Look from what render() takes as `look`, `shading` and `lines` (those two set after the look's flags,
    so they win). The caller's Look is not changed."""
    if look is None:
        result = Look()
    elif isinstance(look, Look):
        result = Look.from_arguments(look.arguments)
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
        result.set("--shading", shading)
    if lines is not None:
        result.set("--lines", _lines_value(lines))
    return result


def make_frame(size: int | tuple[int, int] = 1024, camera: Flags | None = None) -> Frame:
    """A Frame from what render() takes as `size` and `camera`."""
    if isinstance(size, numbers.Integral) and not isinstance(size, bool):
        width = height = int(size)
    elif isinstance(size, Sequence) and len(size) == 2 and all(isinstance(side, numbers.Integral) for side in size):
        width, height = (int(side) for side in size)
    else:
        raise TypeError(f"size: expected pixels (512) or (width, height), got {size!r}")
    if camera is None:
        arguments: list[str] = []
    elif isinstance(camera, Mapping):
        arguments = [word for flag, value in _flag_pairs(camera) for word in (flag, value) if word is not None]
    elif isinstance(camera, Sequence) and not isinstance(camera, str):
        arguments = _string_list(camera, "camera")
    else:
        raise TypeError(f"camera: expected a dict or a list of arguments, got {camera!r}")
    return Frame(width, height, arguments)


_default_lock = threading.Lock()
_default: Renderer | None = None


def default_renderer() -> Renderer:
    """The Renderer render() draws with when given none: one for the process, made on first use and kept, with its
    GL context and compiled programs, until closed (the next call then makes a new one) or the interpreter ends.
    A batch of render() calls thus makes one context.

    The C++ library lets one renderer at a time hold the process's GL context (it renders on any thread, one render
    at a time): to render with a Renderer of your own, close this one first (``inkgraph.default_renderer().close()``);
    the library's UsageError says so otherwise. A child forked after a render starts without a default renderer;
    its GL driver is the parent's, without the parent's threads, so it cannot render (ContextError says why) unless
    every renderer was closed before the fork: use multiprocessing's 'spawn' or 'forkserver' start method."""
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
    """A value as the command line writes it: numbers as Python prints them, lists and tuples joined by commas."""
    if isinstance(value, (str, numbers.Real, os.PathLike)):
        return _scalar_value(flag, value)
    if isinstance(value, (Sequence, np.ndarray)):
        return ",".join(_scalar_value(flag, item) for item in value)
    raise TypeError(f"{flag}: expected a string, a number or a list of them, got {value!r}")


def _scalar_value(flag: str, value: Any) -> str:
    if isinstance(value, str):
        return value
    if isinstance(value, os.PathLike):
        return os.fspath(value)
    if isinstance(value, numbers.Integral) and not isinstance(value, (bool, np.bool_)):
        return str(int(value))
    if isinstance(value, numbers.Real) and not isinstance(value, (bool, np.bool_)):
        return str(value)
    raise TypeError(f"{flag}: expected a string or a number in the list, got {value!r}")


def _lines_value(lines: str | Iterable[str]) -> str:
    if isinstance(lines, str):
        return lines
    names = _string_list(lines, "lines")
    return ",".join(names) if names else "none"


def _string_list(items: Iterable[Any], what: str) -> list[str]:
    if isinstance(items, str):
        raise TypeError(f"{what}: expected a list of strings, got the string {items!r}")
    result = list(items)
    for item in result:
        if not isinstance(item, str):
            raise TypeError(f"{what}: expected a list of strings, got {item!r} in it")
    return result
