"""Errors: each kind of inkgraph::api::Error as its Python class, with the command line's message and exit code."""

from __future__ import annotations

import os
import pickle
import subprocess

import numpy as np
import pytest

import inkgraph
from conftest import SIZE


def command_line_error(executable, arguments, folder) -> tuple[str, int]:
    """The message `inkgraph render` prints for these arguments (without "inkgraph: " and the help hint) and its
    exit code."""
    run = subprocess.run([str(executable), "render", *arguments], cwd=folder, capture_output=True, text=True)
    first_line = run.stderr.splitlines()[0] if run.stderr else ""
    assert first_line.startswith("inkgraph: "), run.stderr
    return first_line.removeprefix("inkgraph: "), run.returncode


def test_the_family():
    for kind in (inkgraph.UsageError, inkgraph.InputError, inkgraph.ContextError, inkgraph.OutputError,
                 inkgraph.RenderError):
        assert issubclass(kind, inkgraph.Error) and issubclass(kind, RuntimeError)
    assert issubclass(inkgraph.UsageError, ValueError)
    assert not issubclass(inkgraph.InputError, ValueError)


def test_a_missing_model_is_an_input_error_naming_the_file(tmp_path, inkgraph_executable):
    missing = tmp_path / "no-such-model.obj"
    with pytest.raises(inkgraph.InputError) as caught:
        inkgraph.render(missing, size=SIZE)
    error = caught.value
    assert "'" + str(missing) + "'" in str(error)
    assert error.exit_code == 3 and error.kind == "input"
    message, code = command_line_error(inkgraph_executable, [str(missing), "-o", "out.png"], tmp_path)
    assert (str(error), error.exit_code) == (message, code)


def test_a_bad_flag_value_is_a_usage_error_with_the_command_lines_message(suzanne, suzanne_path, tmp_path,
                                                                         inkgraph_executable):
    with pytest.raises(inkgraph.UsageError) as caught:
        inkgraph.render(suzanne, look={"shading": "watercolour"}, size=SIZE)
    error = caught.value
    assert isinstance(error, ValueError)
    assert error.exit_code == 2 and error.kind == "usage"
    # The command line's message after the function of the library that refused it.
    message, code = command_line_error(inkgraph_executable, [suzanne_path, "--shading", "watercolour", "-o",
                                                             "out.png"], tmp_path)
    assert message.startswith("--shading: unknown value 'watercolour' (available: ")
    assert (str(error), error.exit_code) == ("Look::set(): " + message, code)


@pytest.mark.parametrize("look", [{"silhouette-width": -1}, ["--lines", "contour,sketchy"], {"no-such-flag": 1},
                                  {"output": "x.png"}])
def test_every_bad_look_is_a_usage_error(suzanne, look):
    with pytest.raises(inkgraph.UsageError):
        inkgraph.render(suzanne, look=look, size=SIZE)


def test_a_bad_camera_and_size_are_usage_errors(suzanne):
    with pytest.raises(inkgraph.UsageError) as caught:
        inkgraph.render(suzanne, size=SIZE, camera=["--orbit", "0,95"])
    assert "--orbit" in str(caught.value)
    with pytest.raises(inkgraph.UsageError):
        inkgraph.render(suzanne, size=(0, SIZE))


def test_an_unknown_buffer_name_lists_the_available_ones(suzanne):
    with pytest.raises(inkgraph.UsageError) as caught:
        inkgraph.render(suzanne, size=SIZE, buffers=["normals"])
    message = str(caught.value)
    assert "'normals'" in message
    for available in ("normal", "depth", "nDotV"):
        assert available in message, message


def test_a_buffer_not_asked_for_names_those_there_are(suzanne):
    still = inkgraph.render(suzanne, size=SIZE, buffers=["depth", "lines.contour"]).still
    with pytest.raises(inkgraph.UsageError) as caught:
        still.buffer("normal")
    message = str(caught.value)
    assert "'normal'" in message and "depth" in message and "lines.contour" in message, message


def test_an_unwritable_output_is_an_output_error_naming_the_file(suzanne, tmp_path):
    result = inkgraph.render(suzanne, size=SIZE)
    target = tmp_path / "no-such-folder" / "picture.png"
    with pytest.raises(inkgraph.OutputError) as caught:
        result.write(target)
    assert str(target) in str(caught.value) and caught.value.exit_code == 5
    with pytest.raises(inkgraph.OutputError):
        inkgraph.write_image(target, np.zeros((4, 4), np.uint8))


def test_a_bad_style_file_is_refused_as_the_command_line_refuses_it(suzanne, suzanne_path, tmp_path,
                                                                    inkgraph_executable):
    style = tmp_path / "bad.style"
    style.write_text("shading = cel\nshading cel\n")
    with pytest.raises(inkgraph.Error) as caught:
        inkgraph.render(suzanne, look=style, size=SIZE)
    assert "'" + str(style) + "' line 2" in str(caught.value)
    message, code = command_line_error(inkgraph_executable, [suzanne_path, "--style", str(style), "-o", "out.png"],
                                       tmp_path)
    assert (str(caught.value), caught.value.exit_code) == ("Look::fromStyleFile(): " + message, code)


def test_errors_survive_pickling(tmp_path):
    with pytest.raises(inkgraph.InputError) as caught:
        inkgraph.Scene.load(tmp_path / "missing.obj")
    copy = pickle.loads(pickle.dumps(caught.value))
    assert type(copy) is inkgraph.InputError
    assert (str(copy), copy.exit_code, copy.kind) == (str(caught.value), 3, "input")


def test_the_error_classes_can_be_raised_by_callers_with_the_kinds_exit_codes(suzanne_path):
    # Mocks and re-raising code construct them with a message only; the code is the one the library gives the kind.
    with pytest.raises(inkgraph.UsageError) as usage:
        inkgraph.render(suzanne_path, size=-1)
    with pytest.raises(inkgraph.InputError) as missing:
        inkgraph.render(suzanne_path + ".absent")
    assert inkgraph.UsageError("x").exit_code == usage.value.exit_code == 2
    assert inkgraph.InputError("x").exit_code == missing.value.exit_code == 3
    expected = {inkgraph.ContextError: 4, inkgraph.OutputError: 5, inkgraph.RenderError: 1, inkgraph.Error: 1}
    assert {cls: cls("x").exit_code for cls in expected} == expected
    assert inkgraph.UsageError("x", 7).exit_code == 7


def test_text_that_is_not_utf8_is_escaped_not_refused(tmp_path):
    # Names from an older tool's OBJ (Latin-1 bytes) and a file name that is not UTF-8: pybind11's conversion raised
    # UnicodeDecodeError for the whole call (the load, .objects, .meshes, .path, an error's message).
    triangle = b"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n"
    model = tmp_path / "latin1.obj"
    model.write_bytes(b"o Fl\xe4che\nusemtl ma\xfet\n" + triangle)
    with pytest.warns(inkgraph.InkgraphWarning) as caught:
        scene = inkgraph.Scene.load(str(model))
    assert "ma\\xfet" in str(caught[0].message)
    assert scene.objects[0]["name"] == "Fl\\xe4che" and scene.objects[0]["meshes"] == ["Fl\\xe4che"]
    assert scene.meshes[0]["material"] == "ma\\xfet"

    # A path as os.fsdecode() makes it names the same file, and comes back as the same str.
    odd = os.fsdecode(bytes(tmp_path) + b"/n\xffame.obj")
    with open(odd, "wb") as file:
        file.write(triangle)
    assert inkgraph.Scene.load(odd).path == odd
    assert "n\\udcffame.obj" in repr(inkgraph.Scene.load(odd))
    with pytest.raises(inkgraph.InputError) as missing:
        inkgraph.Scene.load(os.fsdecode(bytes(tmp_path) + b"/missing\xff.obj"))
    assert "missing\\xff.obj': file not found" in str(missing.value)


def test_a_camera_refusal_is_told_as_it_is_when_buffers_are_asked_for_too(suzanne):
    # With buffers asked for, any refusal of the plan was re-told as "no buffer 'depth' in this look; it has: " with
    # an empty list; the up vector along the view is refused before the graph is built.
    frame = inkgraph.Frame(64, 64, eye=(0, 0, 5), target=(0, 0, 0), up=(0, 0, 1))
    for buffers in ([], ["depth"]):
        with pytest.raises(inkgraph.UsageError, match="parallel") as refused:
            inkgraph.Renderer().render(suzanne, None, frame, buffers)
        assert "no buffer" not in str(refused.value)


def test_a_frames_pose_or_face_on_an_obj_is_refused_in_the_renderers_name(suzanne, suzanne_path):
    # The frame's pose and face load the file again; the refusal started with "loadScene():", which the caller never
    # called, and named the flag rather than the frame's field.
    renderer = inkgraph.Renderer()
    cases = [({"expressions": {"happy": 1.0}}, "Frame::expressions: '" + suzanne_path + "': --expression: obj files"),
             ({"look_at": (0, 0, 1)}, "Frame::lookAt: '" + suzanne_path + "': --look-at: obj files"),
             ({"pose": "a-pose"}, "Frame::pose: '" + suzanne_path + "': cannot take a humanoid pose: not a VRM")]
    for fields, words in cases:
        with pytest.raises(inkgraph.InputError) as refused:
            renderer.render(suzanne, None, inkgraph.Frame(16, 16, **fields))
        assert str(refused.value).startswith("Renderer::render(): " + words), str(refused.value)
        assert refused.value.exit_code == 3


WRONG_TYPES = [
    ("Frame width past int", lambda: inkgraph.Frame(2**31, 10),
     "Frame(): width: expected an int from -2147483648 to 2147483647, got 2147483648"),
    ("Look.bands a float", lambda: setattr(inkgraph.Look(), "bands", 2.5),
     "Look.bands: expected an int from -2147483648 to 2147483647, got 2.5"),
    ("Look.set flag", lambda: inkgraph.Look().set(2, "x"), "Look.set(): flag: expected str, got 2"),
    ("Vec3 x", lambda: inkgraph.Vec3("a"), "Vec3(): x: expected float, got 'a'"),
    ("Frame.fov", lambda: setattr(inkgraph.Frame(), "fov", "wide"),
     "Frame.fov: expected Optional[float], got 'wide'"),
    ("Frame.expressions", lambda: setattr(inkgraph.Frame(), "expressions", {"happy": "very"}),
     "Frame.expressions: expected Dict[str, float], got {'happy': 'very'}"),
    ("Scene.load path", lambda: inkgraph.Scene.load(5),
     "Scene.load(): path: expected a path (str or os.PathLike), got 5"),
    ("Scene.load time", lambda: inkgraph.Scene.load("model.obj", time="now"),
     "Scene.load(): time: expected float, got 'now'"),
    ("render scene", lambda: inkgraph.Renderer().render(None), "Renderer.render(): scene: expected Scene, got None"),
    ("sample_views count", lambda: inkgraph.sample_views(-1, 0, "model"),
     "sample_views(): count: expected an int from 0 to 18446744073709551615, got -1"),
    ("sample_views model_key", lambda: inkgraph.sample_views(1, 0, None),
     "sample_views(): model_key: expected a path (str, bytes or os.PathLike), got None"),
    ("buffer_names look", lambda: inkgraph.buffer_names(3), "buffer_names(): look: expected Look, got 3"),
    ("StrokeSettings", lambda: inkgraph.StrokeSettings(min_length="long"),
     "StrokeSettings(): min_length: expected float, got 'long'"),
]


@pytest.mark.parametrize("name, call, message", WRONG_TYPES, ids=[case[0] for case in WRONG_TYPES])
def test_a_value_of_the_wrong_type_is_a_type_error_naming_the_argument(name, call, message):
    # pybind11's own refusal ("incompatible function arguments", every signature and value) named no argument.
    with pytest.raises(TypeError) as refused:
        call()
    assert str(refused.value) == message


# Calls whose arguments fit no parameter list. pybind11 refused them with "incompatible function arguments", the
# signatures and every value given, naming neither the argument nor the function's class; a keyword that is a lone
# surrogate aborted the interpreter (the refusal failed to encode it outside pybind11's try).
MISFITS = [
    ("missing", lambda: inkgraph.Scene.load(), "Scene.load(): missing required argument 'path'"),
    ("missing two", lambda: inkgraph.write_image(), "write_image(): missing required arguments 'path', 'image'"),
    ("missing second", lambda: inkgraph.Clip(1), "Clip(): missing required argument 'far'"),
    ("missing method argument", lambda: inkgraph.Renderer().render(),
     "Renderer.render(): missing required argument 'scene'"),
    ("missing self", lambda: inkgraph.ViewSample.orbit(), "ViewSample.orbit(): missing required argument 'self'"),
    ("unknown keyword", lambda: inkgraph.Orbit(bogus=1),
     "Orbit(): unexpected keyword argument 'bogus' (arguments: azimuth, elevation, distance, distance_scale)"),
    ("keyword of no keywords", lambda: inkgraph.ViewSample().orbit(bogus=1),
     "ViewSample.orbit(): unexpected keyword argument 'bogus' (it takes no keyword arguments)"),
    ("surrogate keyword", lambda: inkgraph.Orbit(**{"\udcff": 1}),
     "Orbit(): unexpected keyword argument '\\udcff' (arguments: azimuth, elevation, distance, distance_scale)"),
    ("surrogate keyword of an overloaded function", lambda: inkgraph.LineType(**{"\udcff": 1}),
     "LineType(): unexpected keyword argument '\\udcff'"),
    ("keyword of every overload", lambda: inkgraph.Shading(bogus=1), "Shading(): unexpected keyword argument 'bogus'"),
    ("too many", lambda: inkgraph.Orbit(1, 2, 3, 4, 5),
     "Orbit(): takes at most 4 positional arguments ('azimuth', 'elevation', 'distance', 'distance_scale'), got 5"),
    ("too many before keywords", lambda: inkgraph.sample_views(1, 2, "m", 3),
     "sample_views(): takes at most 3 positional arguments ('count', 'seed', 'model_key'), got 4"),
    ("none taken", lambda: inkgraph.version(1), "version(): takes no arguments, got 1"),
    ("keywords only", lambda: inkgraph.Vec3().replace(1), "Vec3.replace(): takes keyword arguments only, got 1"),
    ("twice", lambda: inkgraph.Orbit(1, azimuth=2),
     "Orbit(): argument 'azimuth' given twice, by position and by keyword"),
    ("replace field", lambda: inkgraph.Vec3().replace(w=1), "Vec3.replace(): 'w' is not a field (fields: x, y, z)"),
    ("replace self", lambda: inkgraph.Vec3.replace(None, x=1), "Vec3.replace(): self: expected Vec3, got None"),
    ("nested class", lambda: inkgraph.Renderer.Platform(bogus=1),
     "Renderer.Platform(): unexpected keyword argument 'bogus'"),
    ("nested class surrogate", lambda: inkgraph.Renderer.Platform.from_name(**{"\ud800": 1}),
     "Renderer.Platform.from_name(): unexpected keyword argument '\\ud800' (arguments: name)"),
    ("self twice", lambda: inkgraph.Look.set(inkgraph.Look(), "--shading", self=inkgraph.Look()),
     "Look.set(): argument 'self' given twice, by position and by keyword"),
    ("unknown beside self by keyword", lambda: inkgraph.Look.set(self=inkgraph.Look(), flag="--shading", bogus=1),
     "Look.set(): unexpected keyword argument 'bogus' (arguments: flag, value)"),
    # A method bound as a C++ member function took None for self as a null pointer: a segmentation fault.
    ("None for self", lambda: inkgraph.ViewSample.orbit(None), "ViewSample.orbit(): self: expected ViewSample, got None"),
    ("None for a renderer", lambda: inkgraph.Renderer.close(None),
     "Renderer.close(): self: expected Renderer, got None"),
]


@pytest.mark.parametrize("name, call, message", MISFITS, ids=[case[0] for case in MISFITS])
def test_arguments_that_fit_no_parameter_list_are_refused_by_name(name, call, message):
    with pytest.raises(TypeError) as refused:
        call()
    assert str(refused.value) == message


def test_a_call_that_fits_is_not_touched():
    # What a call that fits raises is the function's own; the keyword form of every argument still works.
    assert inkgraph.Orbit(1, elevation=2, distance_scale=3) == inkgraph.Orbit(1.0, 2.0, None, 3.0)
    assert inkgraph.Clip(near=1, far=2).far == 2
    with pytest.raises(TypeError, match=r"^Clip\(\): far: expected float, got None$"):
        inkgraph.Clip(1, far=None)
    # An overloaded function whose overloads refuse for different reasons keeps pybind11's list of overloads.
    with pytest.raises(TypeError, match="incompatible constructor arguments"):
        inkgraph.LineType(1, 2)
    # self given by keyword fits a method that names its parameters: the refusal is the function's own.
    assert inkgraph.Look.line_parameter(self=inkgraph.Look(), name="crease-angle") == 45
    with pytest.raises(TypeError, match=r"^Look\.line_parameter\(\): name: expected str, got 5$"):
        inkgraph.Look.line_parameter(self=inkgraph.Look(), name=5)
    # A constructor called on an object of another class keeps pybind11's refusal, which says so.
    with pytest.raises(TypeError, match="invalid or missing `self`"):
        inkgraph.Vec3.__init__(inkgraph.Color(), 1, 2, 3, 4)


class _ReprRaises:
    def __repr__(self):
        raise ValueError("no repr")


class _FormatInterrupts(str):
    def __format__(self, spec):
        raise KeyboardInterrupt


class _EqualToX(str):
    def __hash__(self):
        return hash("x")

    def __eq__(self, other):
        return other == "x" or str.__eq__(self, other)


def test_odd_arguments_keep_the_refusal_a_type_error_and_interrupts_pass():
    # A value whose repr raises is named by its type (the refusal was that ValueError).
    with pytest.raises(TypeError, match=r"^Vec3\(\): x: expected float, got <_ReprRaises object whose repr"):
        inkgraph.Vec3(_ReprRaises())
    # An interrupt raised while pybind11 writes its refusal is raised, not turned into a TypeError.
    with pytest.raises(KeyboardInterrupt):
        inkgraph.Vec3(**{_FormatInterrupts("bogus"): 1})
    # A keyword that is a str subclass is judged by pybind11's lookup, not by its spelling: this one is x.
    with pytest.raises(TypeError, match=r"^Vec3\(\): x: expected float, got 'text'$"):
        inkgraph.Vec3(**{_EqualToX("y2"): "text"})


def _classes(scope):
    """The extension's classes defined in `scope` (the module or a class), and those nested in them."""
    for value in vars(scope).values():
        if isinstance(value, type) and value.__module__ == inkgraph._inkgraph.__name__ and value is not scope:
            yield value
            yield from _classes(value)


def _instances(scene):
    """One made object of each of the extension's classes (a still rendered small), by class."""
    renderer = inkgraph.Renderer()
    still = renderer.render(scene, None, inkgraph.Frame(16, 16))
    made = {inkgraph.Vec3: inkgraph.Vec3(), inkgraph.Color: inkgraph.Color(), inkgraph.Orbit: inkgraph.Orbit(),
            inkgraph.Clip: inkgraph.Clip(1, 2), inkgraph.LineStyle: inkgraph.LineStyle(),
            inkgraph.StrokeSettings: inkgraph.StrokeSettings(), inkgraph.ViewSample: inkgraph.ViewSample(),
            inkgraph.Look: inkgraph.Look(), inkgraph.Frame: inkgraph.Frame(8, 8), inkgraph.Renderer: renderer,
            inkgraph.Scene: scene, inkgraph.Still: still, inkgraph.StillCamera: still.camera}
    for cls in _classes(inkgraph._inkgraph):
        if "__members__" in vars(cls):  # an enum: its first member
            made[cls] = next(iter(cls.__members__.values()))
    return made


def _compiled_calls(scene):
    """(where, call) for every function, static method, method and constructor of the extension, nested classes'
    included, each called with a keyword none of them takes (a method on a made object of its class)."""
    module = inkgraph._inkgraph
    instances = _instances(scene)
    calls = []
    for name, value in vars(module).items():
        if not isinstance(value, type) and callable(value):
            calls.append((f"{name}(): ", lambda f=value: f(no_such_argument=1)))
    for value in set(_classes(module)):
        name = value.__qualname__
        assert value in instances, f"{name}: a class this test does not know how to make; add it to _instances()"
        for attribute, member in vars(value).items():
            if attribute.startswith("__") and attribute != "__init__":
                continue  # operators answer NotImplemented; __repr__ and the like take self only
            if type(member).__name__ not in ("instancemethod", "staticmethod"):
                continue  # properties and plain values
            if attribute == "__init__":
                calls.append((f"{name}(): ", lambda c=value: c(no_such_argument=1)))
            elif isinstance(member, staticmethod):
                calls.append((f"{name}.{attribute}(): ",
                              lambda c=value, a=attribute: getattr(c, a)(no_such_argument=1)))
            else:
                calls.append((f"{name}.{attribute}(): ",
                              lambda c=value, a=attribute: getattr(instances[c], a)(no_such_argument=1)))
    return calls


def test_every_compiled_function_refuses_an_unknown_keyword_by_name(suzanne):
    calls = _compiled_calls(suzanne)
    assert len(calls) >= 50  # every class's constructor and methods, and the module's functions
    for where, call in calls:
        with pytest.raises(TypeError) as refused:
            call()
        message = str(refused.value)
        assert message.startswith(where), message
        # replace() takes any keyword and names the field it lacks.
        assert ("unexpected keyword argument 'no_such_argument'" in message or
                message.startswith(where + "'no_such_argument' is not a field")), message


def test_a_method_refuses_a_self_of_another_class_and_an_argument_never_constructed():
    unmade = inkgraph.Look.__new__(inkgraph.Look)
    cases = [
        # Methods that take self as any object answered for it: Vec3.__len__('abc') was 3.
        (lambda: inkgraph.Vec3.__len__("abc"), "Vec3.__len__(): self: expected Vec3, got str"),
        (lambda: vars(inkgraph.Vec3)["x"].fget(inkgraph.Color()), "Vec3.x: self: expected Vec3, got Color"),
        (lambda: inkgraph.Look.line_style(self=None, type="crease"), "Look.line_style(): self: expected Look, got None"),
        # Any argument made by cls.__new__(cls), by position or keyword, self by keyword too: its memory was read.
        (lambda: inkgraph.buffer_names(unmade),
         "buffer_names(): look: a Look whose constructor has not run (Look.__new__() without __init__())"),
        (lambda: inkgraph.ViewSample(light=inkgraph.Vec3.__new__(inkgraph.Vec3)),
         "ViewSample(): light: a Vec3 whose constructor has not run (Vec3.__new__() without __init__())"),
        (lambda: inkgraph.Look.line_parameter(self=unmade, name="crease-angle"),
         "Look.line_parameter(): self: a Look whose constructor has not run (Look.__new__() without __init__())"),
    ]
    for call, message in cases:
        with pytest.raises(TypeError) as refused:
            call()
        assert str(refused.value) == message


class _PointAndColour(inkgraph.Vec3, inkgraph.Color):
    def __init__(self):
        inkgraph.Vec3.__init__(self, 1, 2, 3)
        inkgraph.Color.__init__(self, 0.1, 0.2, 0.3)


def test_a_python_class_of_two_of_the_extensions_classes_is_judged_by_both():
    # pybind11's lookup of the one class of such an object throws a C++ exception, which would end the interpreter.
    with pytest.raises(TypeError, match=r"^buffer_names\(\): look: a Vec3 whose constructor has not run"):
        inkgraph.buffer_names(_PointAndColour.__new__(_PointAndColour))
    made = _PointAndColour()
    assert (made.x, made.r) == (1, 0.1)
    with pytest.raises(TypeError, match=r"^buffer_names\(\): look: expected Look, got "):
        inkgraph.buffer_names(made)


@pytest.mark.parametrize("protocol", range(pickle.HIGHEST_PROTOCOL + 1))
def test_what_does_not_pickle_is_refused_by_every_protocol(suzanne, protocol):
    # Protocols 0 and 1 went through copyreg to pybind11's base class, whose allocation threw through C: the
    # interpreter aborted (pickle.dumps(Look(), 0)). Enums pickle by their value.
    for thing in (inkgraph.Look(), inkgraph.Frame(8, 8), inkgraph.Renderer(), suzanne):
        with pytest.raises(TypeError, match=f"^cannot pickle '{type(thing).__qualname__}' object$"):
            pickle.dumps(thing, protocol)
    for member in (inkgraph.Shading.FLAT, inkgraph.Renderer.Platform.DEVICE, inkgraph.LineType.CREASE):
        assert pickle.loads(pickle.dumps(member, protocol)) is member or \
            pickle.loads(pickle.dumps(member, protocol)) == member


def test_an_object_whose_constructor_has_not_run_is_refused_not_read():
    # cls.__new__(cls) without __init__ gave an object whose fields are uninitialized memory: reading them gave garbage
    # (Vec3.x 6.9e-310), a MemoryError (ViewSample.expression), and Renderer.close() waited forever on its mutex.
    # Each accessor is tried on a fresh object: pybind11 allocates the value on an object's first use.
    tried = 0
    for cls in set(_classes(inkgraph._inkgraph)):
        for name, member in vars(cls).items():
            if type(member) is property:  # not a static property (an enum's __members__), read on the class
                call = lambda c=cls, n=name: getattr(c.__new__(c), n)
            elif type(member).__name__ == "instancemethod" and name not in ("__init__", "__setstate__"):
                call = lambda c=cls, n=name: getattr(c, n)(c.__new__(c))
            else:
                continue
            with pytest.raises(TypeError) as refused:
                call()
            # (an enum's __str__ is refused by the name property it reads)
            assert str(refused.value).startswith(f"{cls.__qualname__}."), str(refused.value)
            assert str(refused.value).endswith(
                f"self: a {cls.__qualname__} whose constructor has not run ({cls.__qualname__}.__new__() without "
                "__init__())"), str(refused.value)
            tried += 1
    assert tried >= 200  # every property and method of every class


def test_pybind11s_base_class_made_directly_is_refused_not_an_abort():
    # pybind11 throws out of its C tp_new for a class with no bound C++ class among its bases, which ended the
    # interpreter (std::terminate): its base class, reached through any object's __mro__, or a class derived from it.
    base = type(inkgraph.Look()).__mro__[1]
    derived = type("Derived", (base,), {})
    for make, name in ((base, base.__name__), (lambda: base.__new__(base), base.__name__), (derived, "Derived"),
                       (lambda: derived.__new__(derived), "Derived")):
        with pytest.raises(TypeError) as refused:
            make()
        assert str(refused.value) == f"{name}(): cannot be made: it holds no value of a bound C++ class"
    # Classes with a value are made as before, by their constructor, by __new__, and derived in Python.
    derived_look = type("DerivedLook", (inkgraph.Look,), {})
    assert isinstance(derived_look(), inkgraph.Look)
    assert type(inkgraph.Look.__new__(inkgraph.Look)) is inkgraph.Look
    assert inkgraph.Vec3(1, 2, 3).y == 2
