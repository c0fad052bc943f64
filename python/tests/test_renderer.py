"""The kept GL context: the default renderer, explicit renderers, the one context a process has, close()."""

from __future__ import annotations

import sys
import threading

import numpy as np
import pytest

import inkgraph
from conftest import SIZE


@pytest.fixture
def own_renderer():
    """A Renderer of the test's own: the default one gives the process's GL context back first."""
    inkgraph.default_renderer().close()
    with inkgraph.Renderer() as renderer:
        yield renderer


def test_render_keeps_the_default_renderer_and_its_context(suzanne):
    first = inkgraph.render(suzanne, size=SIZE)
    renderer = inkgraph.default_renderer()
    description = renderer.gl_description
    assert "4.5" in description or "4.6" in description, description
    second = inkgraph.render(suzanne, size=SIZE)
    assert inkgraph.default_renderer() is renderer and renderer.gl_description == description
    assert np.array_equal(first.picture, second.picture)
    assert first.still is not second.still


def test_a_renderer_makes_its_context_on_the_first_render_and_keeps_it(suzanne, own_renderer):
    assert own_renderer.gl_description == ""  # nothing made yet
    first = inkgraph.render(suzanne, size=SIZE, renderer=own_renderer)
    description = own_renderer.gl_description
    assert description != ""
    second = inkgraph.render(suzanne, size=SIZE, renderer=own_renderer)
    assert own_renderer.gl_description == description
    assert np.array_equal(first.picture, second.picture)


def test_one_renderer_holds_the_context_at_a_time(suzanne):
    inkgraph.render(suzanne, size=64)  # the default renderer holds the context
    other = inkgraph.Renderer()
    with pytest.raises(inkgraph.UsageError) as caught:
        inkgraph.render(suzanne, size=64, renderer=other)
    assert "another Renderer" in str(caught.value), str(caught.value)
    inkgraph.default_renderer().close()
    assert inkgraph.render(suzanne, size=64, renderer=other).picture.shape == (64, 64, 4)
    other.close()


def test_the_default_renderer_renders_on_the_thread_of_its_first_render(suzanne):
    inkgraph.render(suzanne, size=64)
    caught = []

    def work():
        try:
            inkgraph.render(suzanne, size=64)
        except inkgraph.UsageError as error:
            caught.append(error)

    thread = threading.Thread(target=work)
    thread.start()
    thread.join()
    assert len(caught) == 1 and "thread" in str(caught[0]), caught
    assert inkgraph.render(suzanne, size=64).picture.shape == (64, 64, 4)  # still fine here


def test_a_closed_renderer_refuses_and_the_default_one_is_replaced(suzanne, own_renderer):
    inkgraph.render(suzanne, size=64, renderer=own_renderer)
    own_renderer.close()
    assert own_renderer.closed and own_renderer.gl_description == ""
    with pytest.raises(inkgraph.UsageError) as caught:
        inkgraph.render(suzanne, size=64, renderer=own_renderer)
    assert str(caught.value) == "Renderer.render(): the renderer is closed"

    default = inkgraph.default_renderer()
    default.close()
    assert inkgraph.default_renderer() is not default
    assert inkgraph.render(suzanne, size=64).picture.shape == (64, 64, 4)


def test_the_low_level_api_renders_as_render_does(suzanne):
    look = inkgraph.Look().set("--shading", "cel").set("--lines", "silhouette")
    frame = inkgraph.Frame(SIZE, SIZE, ["--orbit", "30,10"])
    still = inkgraph.default_renderer().render(suzanne, look, frame, ["depth"])
    assert still.buffer_names == ["depth"]
    expected = inkgraph.render(suzanne, look={"shading": "cel"}, lines=["silhouette"], size=SIZE,
                               camera=["--orbit", "30,10"], buffers=["depth"])
    assert np.array_equal(still.picture, expected.picture)
    assert np.array_equal(still.buffer("depth"), expected.buffers["depth"])


def test_render_lets_other_python_threads_run_while_it_draws(suzanne):
    inkgraph.render(suzanne, size=64)  # the context exists: the next render only draws
    state = {"inside": False, "seen": None}
    go = threading.Event()

    def observer():
        go.wait()
        state["seen"] = state["inside"]

    thread = threading.Thread(target=observer)
    thread.start()
    # With a switch interval this long the interpreter never takes the GIL from the main thread: the observer, woken
    # by go, gets it only when the main thread gives it up, which render() does while it draws (else the observer
    # would run at join(), after the render, and see inside False).
    interval = sys.getswitchinterval()
    sys.setswitchinterval(1000)
    try:
        state["inside"] = True
        go.set()
        inkgraph.render(suzanne, size=64)
        state["inside"] = False
    finally:
        sys.setswitchinterval(interval)
    thread.join()
    assert state["seen"] is True
