"""The warnings of inkgraph: each warning record of the C++ library (inkgraph::api::Warning: a texture it could not
read, a camera that sees none of the model) is an InkgraphWarning, a category of Python's warnings module of its own.

The extension (python/Bindings.cpp) makes one per record and issues them through warnings.warn() when Scene.load(),
Scene.from_arrays() or Renderer.render() returns (inkgraph.render() through those), attributed to the first caller
outside this package; the same objects stay available as lists (Scene.warnings, Still.warnings, Result.warnings).
So the warnings module's filters apply: ``warnings.simplefilter("error", inkgraph.InkgraphWarning)`` makes the call
that warns raise instead, ``"ignore"`` silences them, ``warnings.catch_warnings(record=True)`` collects them.
docs/robustness.md ("Warning codes") lists every code.
"""

from __future__ import annotations

import os as _os
import sys as _sys
import warnings as _warnings_module
from collections.abc import Iterable
from typing import Any

_PACKAGE_FOLDER = _os.path.dirname(_os.path.abspath(__file__))


class InkgraphWarning(UserWarning):
    """A warning of a load or a render. ``str(w)`` is the message as the command line prints it after
    "inkgraph: warning: "; ``code`` is stable and kebab-case ("texture-missing"), ``file`` the file it concerns (a
    texture, a shade map, the model) or "", ``item`` the thing in the model it concerns (a material, mesh, texture or
    node) or ""."""

    def __init__(self, message: str, code: str = "", file: str = "", item: str = "") -> None:
        super().__init__(message)
        self.message = message
        self.code = code
        self.file = file
        self.item = item

    def __repr__(self) -> str:
        return (f"InkgraphWarning({self.message!r}, code={self.code!r}, file={self.file!r}, "
                f"item={self.item!r})")

    def __eq__(self, other: object) -> bool:
        if not isinstance(other, InkgraphWarning):
            return NotImplemented
        return self._fields() == other._fields()

    def __hash__(self) -> int:
        return hash(self._fields())

    def __reduce__(self) -> tuple[Any, ...]:
        # Picklable with its fields (a multiprocessing batch sends results back): the default passes args alone.
        return type(self), self._fields()

    def _fields(self) -> tuple[str, str, str, str]:
        return (self.message, self.code, self.file, self.item)


def issue(records: Iterable[InkgraphWarning]) -> None:
    """Issues each record through warnings.warn(), attributed to the first frame outside this package: the user's
    line that loaded or rendered, whether directly or through inkgraph.render()."""
    level = 1
    frame = _sys._getframe(0)
    while frame is not None and _os.path.dirname(_os.path.abspath(frame.f_code.co_filename)) == _PACKAGE_FOLDER:
        frame = frame.f_back  # type: ignore[assignment]
        level += 1
    for record in records:
        _warnings_module.warn(record, stacklevel=level)
