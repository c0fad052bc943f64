"""The exceptions of inkgraph: one class per kind of inkgraph::api::Error (inkgraph/inkgraph.h).

The extension (python/Bindings.cpp) raises the class of the C++ error's kind with the library's message unchanged
(the function or flag first, names quoted, as the command line prints it) and the exit code the library gives for
that kind, the one `inkgraph render` exits with (README, "Errors and exit codes").
"""

from __future__ import annotations

from typing import Any


class Error(RuntimeError):
    """Every failure of inkgraph. ``kind`` names the kind ("usage", "input", "context", "output", "render");
    ``exit_code`` is the exit code `inkgraph render` gives for it."""

    kind: str = "render"
    default_exit_code: int = 1  #: the command line's code for the kind, when a caller raises one without it

    def __init__(self, message: str, exit_code: int | None = None) -> None:
        super().__init__(message)
        self.exit_code = self.default_exit_code if exit_code is None else exit_code

    def __reduce__(self) -> tuple[Any, ...]:
        # Picklable (a multiprocessing batch sends errors back): the default would call cls(message) alone.
        return type(self), (str(self), self.exit_code)


class UsageError(Error, ValueError):
    """A bad flag, value, buffer name or camera, too little memory for the request, or a still written over a file
    its render read."""

    kind = "usage"
    default_exit_code = 2


class InputError(Error):
    """An unreadable or invalid model, shade map or texture (a bad style file is a UsageError, as its flags are)."""

    kind = "input"
    default_exit_code = 3


class ContextError(Error):
    """No OpenGL 4.5 core context through EGL, or the shaders are missing or do not compile."""

    kind = "context"
    default_exit_code = 4


class OutputError(Error):
    """A file could not be written, or its place is not a regular file or a new name (a FIFO, a device)."""

    kind = "output"
    default_exit_code = 5


class RenderError(Error):
    """The render itself failed: an internal error."""

    kind = "render"
