"""The kept GL context: the default renderer, explicit renderers (each with a context of its own), close()."""

from __future__ import annotations

import os
import subprocess
import sys
import threading
import time

import numpy as np
import pytest

import inkgraph
from conftest import SIZE


@pytest.fixture
def own_renderer():
    """A Renderer of the test's own, beside the default one."""
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


def test_several_renderers_render_at_once_each_with_its_own_context(suzanne):
    # Before, a second renderer raised UsageError while the default one held the process's one context. Each now
    # makes its own, and render() releases the GIL: the default renderer and two others draw on three threads at once.
    look = {"shading": "comic", "lines": "silhouette,contour,suggestive"}
    expected = [inkgraph.render(suzanne, look, size=64, camera={"orbit": (yaw, 10)}).picture for yaw in (0, 40)]
    assert not np.array_equal(expected[0], expected[1])
    pictures: dict[int, list] = {}
    failures: list[BaseException] = []
    with inkgraph.Renderer() as first, inkgraph.Renderer() as second:
        start = threading.Barrier(3)

        def draw(slot: int, renderer: inkgraph.Renderer | None) -> None:
            try:
                start.wait()
                pictures[slot] = [inkgraph.render(suzanne, look, size=64, camera={"orbit": (yaw, 10)},
                                                  renderer=renderer).picture for yaw in (0, 40, 0)]
            except BaseException as error:  # re-raised below, on the test's thread
                failures.append(error)

        threads = [threading.Thread(target=draw, args=(slot, renderer))
                   for slot, renderer in enumerate((None, first, second))]
        for thread in threads:
            thread.start()
        for thread in threads:
            thread.join()
        if failures:
            raise failures[0]
        for slot in range(3):
            for picture, wanted in zip(pictures[slot], (expected[0], expected[1], expected[0])):
                assert np.array_equal(picture, wanted), slot
        first.close()  # its context ends; the others' stay
        assert np.array_equal(inkgraph.render(suzanne, look, size=64, camera={"orbit": (40, 10)},
                                              renderer=second).picture, expected[1])
    assert np.array_equal(inkgraph.render(suzanne, look, size=64, camera={"orbit": (0, 10)}).picture, expected[0])


def test_the_default_renderer_renders_on_any_thread(suzanne):
    here = inkgraph.render(suzanne, size=64).picture
    results = []
    thread = threading.Thread(target=lambda: results.append(inkgraph.render(suzanne, size=64).picture))
    thread.start()
    thread.join()
    assert len(results) == 1 and np.array_equal(results[0], here)
    assert np.array_equal(inkgraph.render(suzanne, size=64).picture, here)


def _run_python(code: str, *arguments: str) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, "-c", code, *arguments], capture_output=True, text=True, timeout=120,
                          env={**os.environ, "PYTHONPATH": os.pathsep.join(sys.path)})


def test_a_renderer_used_on_a_worker_thread_closes_on_another_and_at_exit(suzanne_path):
    # Closing or ending the interpreter away from the render thread used to abort the process (SIGABRT in libepoxy).
    code = """
import sys, concurrent.futures as futures, inkgraph
with futures.ThreadPoolExecutor(1) as pool:
    print(pool.submit(lambda: inkgraph.render(sys.argv[1], size=32).picture.shape).result())
mine = inkgraph.Renderer()
inkgraph.default_renderer().close()
with futures.ThreadPoolExecutor(1) as pool:
    pool.submit(lambda: inkgraph.render(sys.argv[1], size=32, renderer=mine)).result()
mine.close()
print(inkgraph.render(sys.argv[1], size=32).picture.shape)  # the default renderer again, left open at exit
"""
    run = _run_python(code, suzanne_path)
    assert run.returncode == 0, run.stderr
    assert run.stdout.split("\n")[:2] == ["(32, 32, 4)", "(32, 32, 4)"], run.stdout


def test_a_child_forked_after_a_render_gets_a_clear_error_not_a_hang(suzanne_path):
    code = """
import os, sys, inkgraph
inkgraph.render(sys.argv[1], size=32)
child = os.fork()
if child == 0:
    try:
        inkgraph.render(sys.argv[1], size=32)
        os._exit(10)
    except inkgraph.ContextError as error:
        os._exit(0 if "forked from process" in str(error) else 11)
    except BaseException:
        os._exit(12)
_, status = os.waitpid(child, 0)
print(os.waitstatus_to_exitcode(status))
print(inkgraph.render(sys.argv[1], size=32).picture.shape)  # the parent renders on
"""
    run = _run_python(code, suzanne_path)
    assert run.returncode == 0, run.stderr
    assert run.stdout.split("\n")[:2] == ["0", "(32, 32, 4)"], run.stdout


def test_a_child_forked_after_every_renderer_closed_renders(suzanne_path):
    code = """
import os, sys, inkgraph
first = inkgraph.render(sys.argv[1], size=32).picture
inkgraph.default_renderer().close()
child = os.fork()
if child == 0:
    ok = (inkgraph.render(sys.argv[1], size=32).picture == first).all()
    os._exit(0 if ok else 10)
_, status = os.waitpid(child, 0)
print(os.waitstatus_to_exitcode(status))
"""
    run = _run_python(code, suzanne_path)
    assert run.returncode == 0, run.stderr
    assert run.stdout.split("\n")[0] == "0", run.stdout


def test_a_child_forked_after_a_render_writes_an_exr_and_exits_cleanly(suzanne_path, tmp_path):
    # oneTBB's workers (OpenCV's parallel loops) are joined before each fork: a child that inherited the parent's
    # worker records detached threads it does not have in oneTBB's exit handler, SIGSEGV at sys.exit() (5-8 of 10).
    code = """
import os, sys, inkgraph
with inkgraph.Renderer() as renderer:
    depth = renderer.render(inkgraph.Scene.load(sys.argv[1]), None, inkgraph.Frame(32, 32), ["depth"]).buffer("depth")
statuses = []
for attempt in range(4):
    child = os.fork()
    if child == 0:
        inkgraph.write_image(os.path.join(sys.argv[2], f"child-{attempt}.exr"), depth)
        sys.exit(0)  # exit handlers and static destructors run, as in a plain forked child
    statuses.append(os.waitstatus_to_exitcode(os.waitpid(child, 0)[1]))
print(statuses)
"""
    run = _run_python(code, suzanne_path, str(tmp_path))
    assert run.returncode == 0, run.stderr
    assert run.stdout.split("\n")[0] == "[0, 0, 0, 0]", run.stdout + run.stderr
    assert sorted(path.name for path in tmp_path.iterdir()) == [f"child-{i}.exr" for i in range(4)]


def test_a_pool_forked_after_an_exr_write_writes_exrs(suzanne_path, tmp_path):
    # OpenEXR's worker pool is off: a child forked after the parent wrote an EXR inherited the pool without its
    # threads, and its own EXR write waited for them forever (multiprocessing's default 'fork' start method).
    code = """
import multiprocessing, os, sys, inkgraph
def save(index):
    inkgraph.write_image(os.path.join(sys.argv[2], f"pool-{index}.exr"), depth)
    return index
if __name__ == "__main__":
    depth = inkgraph.render(sys.argv[1], size=32, buffers=["depth"]).buffers["depth"]
    inkgraph.write_image(os.path.join(sys.argv[2], "parent.exr"), depth)
    inkgraph.default_renderer().close()
    with multiprocessing.get_context("fork").Pool(2) as pool:
        print(sorted(pool.map(save, range(4))))
"""
    run = _run_python(code, suzanne_path, str(tmp_path))
    assert run.returncode == 0, run.stderr
    assert run.stdout.split("\n")[0] == "[0, 1, 2, 3]", run.stdout + run.stderr
    assert len(list(tmp_path.glob("pool-*.exr"))) == 4


def test_render_takes_a_new_default_renderer_when_another_thread_closes_it(suzanne):
    # default_renderer() promises a new renderer after a close: a close between render()'s default_renderer() and
    # its draw raised "the renderer is closed" (43 of 2,182 calls with three threads rendering, one closing).
    errors: list[str] = []
    done = threading.Event()

    def draw() -> None:
        for _ in range(15):
            try:
                inkgraph.render(suzanne, size=32)
            except Exception as error:  # noqa: BLE001 - every failure is what the test counts
                errors.append(repr(error))

    def close() -> None:
        while not done.is_set():
            inkgraph.default_renderer().close()

    drawers = [threading.Thread(target=draw) for _ in range(3)]
    closer = threading.Thread(target=close)
    for thread in [*drawers, closer]:
        thread.start()
    for thread in drawers:
        thread.join()
    done.set()
    closer.join()
    assert errors == []


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
    frame = inkgraph.Frame(SIZE, SIZE, orbit=(30, 10))
    still = inkgraph.default_renderer().render(suzanne, look, frame, ["depth"])
    assert still.buffer_names == ["depth"]
    expected = inkgraph.render(suzanne, look={"shading": "cel"}, lines=["silhouette"], size=SIZE,
                               camera=["--orbit", "30,10"], buffers=["depth"])
    assert np.array_equal(still.picture, expected.picture)
    assert np.array_equal(still.buffer("depth"), expected.buffers["depth"])


def _an_observer_runs_inside(call, attempts: int, before=lambda: None) -> bool:
    """Whether another Python thread ran while call() ran, in one of `attempts` tries. With a switch interval this long
    the interpreter never takes the GIL from the main thread: the observer, woken just before call(), gets it only when
    the main thread gives it up, which call() must do (else the observer runs at join(), after it, and sees inside
    False). The OS may not schedule the woken observer during one short call on a loaded machine (this failed under a
    parallel ctest), so each try has an observer of its own; `before` runs ahead of each."""
    for _ in range(attempts):
        before()
        state = {"inside": False, "seen": None}
        go = threading.Event()

        def observer():
            go.wait()
            state["seen"] = state["inside"]

        thread = threading.Thread(target=observer)
        thread.start()
        interval = sys.getswitchinterval()
        sys.setswitchinterval(1000)
        try:
            state["inside"] = True
            go.set()
            call()
        finally:
            state["inside"] = False
            sys.setswitchinterval(interval)
        thread.join()
        if state["seen"]:
            return True
    return False


def test_render_lets_other_python_threads_run_while_it_draws(suzanne):
    inkgraph.render(suzanne, size=64)  # the context exists: the next render only draws
    assert _an_observer_runs_inside(lambda: inkgraph.render(suzanne, size=64), 50)


def test_gl_description_lets_other_threads_run_while_a_render_holds_the_renderer(suzanne):
    # Both wait for a render another thread is in; they waited holding the GIL, so every Python thread stood still for
    # the rest of that render (render() reads the default renderer's closed on every call). As in the test above, the
    # observer can only run when the main thread gives up the GIL: now inside closed, while the drawer's render holds
    # the renderer. Before each try the main thread sleeps, so the drawer (which needs the GIL between its renders)
    # gets into its next render.
    with inkgraph.Renderer() as renderer:
        inkgraph.render(suzanne, size=64, renderer=renderer)
        stop = threading.Event()

        def draw():
            while not stop.is_set():
                inkgraph.render(suzanne, size=512, renderer=renderer)

        drawer = threading.Thread(target=draw)
        drawer.start()
        try:
            # closed answers at once, without the lock; gl_description waits, without the GIL. Before each try the
            # main thread sleeps, so the drawer (which needs the GIL between its renders) gets into its next render.
            assert renderer.closed is False
            assert _an_observer_runs_inside(lambda: renderer.gl_description, 100, lambda: time.sleep(0.02))
        finally:
            stop.set()
            drawer.join()


def _fork_while_a_thread_renders(model_path: str, draw: str, child: str) -> None:
    """Runs a process whose thread renders (`draw`, a statement on `scene` and `renderer`) while the main thread forks;
    the child runs `child` (indented Python) and must end with status 0."""
    code = f"""
import os, sys, threading, time, inkgraph
scene = inkgraph.Scene.load(sys.argv[1])
renderer = inkgraph.Renderer()
renderer.render(scene, None, inkgraph.Frame(32, 32))
stop = threading.Event()
started = threading.Event()
def draw():
    while not stop.is_set():
        started.set()
        {draw}
thread = threading.Thread(target=draw)
thread.start()
started.wait()
time.sleep(0.2)
child = os.fork()
if child == 0:
{child}
_, status = os.waitpid(child, 0)
stop.set()
thread.join()
print(os.waitstatus_to_exitcode(status))
"""
    run = _run_python(code, model_path)
    assert run.returncode == 0, run.stderr
    assert run.stdout.split("\n")[0] == "0", run.stdout


def test_a_child_forked_while_another_thread_renders_gets_a_clear_error_not_a_hang(suzanne_path):
    # The child inherits the renderer's lock held by a thread it does not have: closed, render() and close() hung.
    _fork_while_a_thread_renders(suzanne_path, "renderer.render(scene, None, inkgraph.Frame(256, 256))", """
    try:
        assert renderer.closed is False
        try:
            renderer.render(scene, None, inkgraph.Frame(32, 32))
            os._exit(10)
        except inkgraph.UsageError as error:
            if "which forked this one" not in str(error):
                os._exit(11)
        renderer.close()
        os._exit(0 if renderer.closed else 12)
    except BaseException:
        os._exit(13)""")


def test_the_interpreter_exits_cleanly_while_a_daemon_thread_is_inside_a_call(suzanne_path):
    # At exit Python 3.11 ends a daemon thread that takes the GIL back with pthread_exit, whose unwind through
    # pybind11's noexcept GIL guard aborted the process (exit 134) when the thread was inside a load or a render.
    code = """
import sys, threading, time, inkgraph
scene = inkgraph.Scene.load(sys.argv[1])
def work():
    while True:
        inkgraph.Scene.load(sys.argv[1])
        inkgraph.render(scene, size=128)
threading.Thread(target=work, daemon=True).start()
time.sleep(0.3)
print("leaving")
"""
    for _ in range(3):
        run = _run_python(code, suzanne_path)
        assert run.returncode == 0, (run.returncode, run.stderr)
        assert run.stdout.strip() == "leaving"


def test_a_child_forked_during_a_render_exits_through_its_atexit_handlers(suzanne_path):
    # The exit waits for the calls in flight; a child forked while a parent's thread rendered counted that render as
    # its own and waited for it for ever at sys.exit().
    _fork_while_a_thread_renders(suzanne_path, "inkgraph.render(scene, size=256)", "    sys.exit(0)")
