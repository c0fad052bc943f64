"""The typed API (issue 33): every typed field of Look and Frame draws the picture its command-line flags draw, byte
for byte; enums by their command-line words; the small value types; the package's namespace; the typed smoke file."""

from __future__ import annotations

import copy
import os
import pathlib
import pickle
import warnings

import numpy as np
import pytest

import inkgraph
import typed_api_smoke
from conftest import REPO

SIZE = 96
LT = inkgraph.LineType

# Each case: a name, the typed look, and the flags that say the same. Settings that take effect only with another
# (shininess with phong, the comic settings) set that one in both.
LOOK_CASES = [
    ("shading", lambda: inkgraph.Look(shading=inkgraph.Shading.COMIC), ["--shading", "comic"]),
    ("shading by name", lambda: inkgraph.Look(shading="flat"), ["--shading", "flat"]),
    ("shininess", lambda: inkgraph.Look(shading="phong", shininess=12.0), ["--shading", "phong", "--shininess", "12"]),
    ("bands", lambda: inkgraph.Look(bands=3), ["--bands", "3"]),
    ("shade_map", lambda: inkgraph.Look(shading="comic", shade_map=REPO / "shademaps" / "duotone-cool.png"),
     ["--shading", "comic", "--shademap", str(REPO / "shademaps" / "duotone-cool.png")]),
    ("view_vector", lambda: inkgraph.Look(shading="comic", view_vector=inkgraph.ViewVector.CONSTANT),
     ["--shading", "comic", "--view-vector", "constant"]),
    ("face_orientation and front_rule",
     lambda: inkgraph.Look(shading="comic", face_orientation=inkgraph.FaceOrientation.DURING_VERTICES, front_rule=2),
     ["--shading", "comic", "--face-orientation", "during-vertices", "--front-rule", "2"]),
    ("light", lambda: inkgraph.Look(light=inkgraph.Vec3(1, 1, 0)), ["--light", "1,1,0"]),
    ("light as a tuple", lambda: inkgraph.Look(light=(0, 1, 1)), ["--light", "0,1,1"]),
    ("paper", lambda: inkgraph.Look(paper=inkgraph.Color(0, 0, 1)), ["--background", "0,0,1"]),
    ("paper as a tuple", lambda: inkgraph.Look(paper=(1, 0.9, 0.8)), ["--background", "1,0.9,0.8"]),
    ("supersample", lambda: inkgraph.Look(supersample=2), ["--supersample", "2"]),
    ("msaa", lambda: inkgraph.Look(msaa=4), ["--msaa", "4"]),
    ("gbuffer_precision", lambda: inkgraph.Look(gbuffer_precision=inkgraph.Precision.FLOAT16),
     ["--gbuffer-precision", "half"]),
    ("lines", lambda: inkgraph.Look(lines=[LT.OUTLINE, LT.CONTOUR]), ["--lines", "outline,contour"]),
    ("outline_width_map",
     lambda: inkgraph.Look(lines=[LT.OUTLINE],
                           outline_width_map=f"texture:{REPO / 'shademaps' / 'duotone-cool.png'}:G"),
     ["--lines", "outline", "--outline-width-map", f"texture:{REPO / 'shademaps' / 'duotone-cool.png'}:G"]),
    ("lines none", lambda: inkgraph.Look(lines=[]), ["--lines", "none"]),
    ("line style", lambda: inkgraph.Look().set_line_style(LT.CONTOUR, inkgraph.LineStyle(3, (1, 0, 0))),
     ["--contour-width", "3", "--contour-color", "1,0,0"]),
    ("line parameter", lambda: inkgraph.Look(lines=[LT.CREASE]).set_line_parameter("crease-angle", 40),
     ["--lines", "crease", "--crease-angle", "40"]),
    ("line choice", lambda: inkgraph.Look(lines=[LT.SUGGESTIVE]).set_line_choice("suggestive-stencil", "5"),
     ["--lines", "suggestive", "--suggestive-stencil", "5"]),
    ("strokes", lambda: inkgraph.Look(strokes=inkgraph.StrokeSettings(min_length=0.05, taper_ends=True,
                                                                       weight_by_depth=True)),
     ["--min-stroke-length", "0.05", "--line-weight", "depth,taper"]),
    ("merged strokes", lambda: inkgraph.Look(lines=[LT.OUTLINE, LT.CONTOUR],
                                             strokes=inkgraph.StrokeSettings(merge_overlaps=True)),
     ["--lines", "outline,contour", "--overlapping-lines", "merge"]),
]

FRAME_CASES = [
    ("size", lambda: inkgraph.Frame(SIZE, 64), ["--size", f"{SIZE}x64"]),
    ("eye", lambda: inkgraph.Frame(SIZE, SIZE, eye=inkgraph.Vec3(0, 1, 5)), ["--eye", "0,1,5"]),
    ("eye, target and up", lambda: inkgraph.Frame(SIZE, SIZE, eye=(4, 0, 0), target=(0, 0.2, 0), up=(0, 0, 1)),
     ["--eye", "4,0,0", "--target", "0,0.2,0", "--up", "0,0,1"]),
    ("orbit", lambda: inkgraph.Frame(SIZE, SIZE, orbit=inkgraph.Orbit(30, 20)), ["--orbit", "30,20"]),
    ("orbit with distance", lambda: inkgraph.Frame(SIZE, SIZE, orbit=(120, -10, 6)), ["--orbit", "120,-10,6"]),
    ("fov", lambda: inkgraph.Frame(SIZE, SIZE, fov=50), ["--fov", "50"]),
    ("clip", lambda: inkgraph.Frame(SIZE, SIZE, eye=(0, 0, 4), clip=inkgraph.Clip(3.5, 4.2)),
     ["--eye", "0,0,4", "--clip", "3.5,4.2"]),
]

# Fields that need a model of their own: a file camera, nodes, an animation.
CHARACTER_FRAME_CASES = [
    ("placement", "duck.glb", lambda: inkgraph.Frame(SIZE, SIZE, placement=inkgraph.CameraPlacement.AUTO),
     ["--camera", "auto"]),
    ("frame_nodes", "godette.vrm", lambda: inkgraph.Frame(SIZE, SIZE, frame_nodes=["Face"]), ["--frame", "Face"]),
    ("animation and time", "fox.glb", lambda: inkgraph.Frame(SIZE, SIZE, animation="Walk", time=0.5),
     ["--animation", "Walk", "--time", "0.5"]),
    ("pose", "godette.vrm", lambda: inkgraph.Frame(SIZE, SIZE, pose="a-pose"), ["--pose", "a-pose"]),
    ("frame_nodes by bone", "godette.vrm", lambda: inkgraph.Frame(SIZE, SIZE, frame_nodes=["head"]),
     ["--frame", "head"]),
    ("expressions and look_at", "godette.vrm",
     lambda: inkgraph.Frame(SIZE, SIZE, frame_nodes=["Face"], expressions={"blink": 1, "aa": 0.5},
                            look_at=(-5, 1.3, -2)),
     ["--frame", "Face", "--expression", "blink=1,aa=0.5", "--look-at", "-5,1.3,-2"]),
]


def frame_from_arguments(arguments: list[str]) -> inkgraph.Frame:
    frame = inkgraph.Frame.from_arguments(arguments)
    if "--size" not in arguments:
        frame.width = frame.height = SIZE
    return frame


@pytest.mark.parametrize("name, typed, arguments", LOOK_CASES, ids=[case[0] for case in LOOK_CASES])
def test_a_typed_look_field_renders_as_its_flags(suzanne, name, typed, arguments):
    frame = inkgraph.Frame(SIZE, SIZE)
    renderer = inkgraph.default_renderer()
    typed_picture = renderer.render(suzanne, typed(), frame).picture
    flags_picture = renderer.render(suzanne, inkgraph.Look.from_arguments(arguments), frame).picture
    assert np.array_equal(typed_picture, flags_picture), name


def test_flag_values_from_the_file_system_name_the_same_file(suzanne, tmp_path):
    # os.listdir() gives a name whose bytes are not UTF-8 as a str with lone surrogates; as a flag's value it was a
    # TypeError (pybind11 could not encode it). It now names the file whose bytes it decodes.
    original = REPO / "shademaps" / "duotone-cool.png"
    (tmp_path / os.fsdecode(b"duot\xf4ne.png")).write_bytes(original.read_bytes())
    (latin1_name,) = os.listdir(tmp_path)
    assert "\udcf4" in latin1_name
    latin1 = str(tmp_path / latin1_name)
    frame = inkgraph.Frame(SIZE, SIZE)
    renderer = inkgraph.default_renderer()
    expected = renderer.render(suzanne, inkgraph.Look(shading="comic", shade_map=original), frame).picture
    for look in (inkgraph.Look(shading="comic").set("--shademap", latin1),
                 inkgraph.Look.from_arguments(["--shading", "comic", "--shademap", latin1])):
        assert np.array_equal(renderer.render(suzanne, look, frame).picture, expected)
    # What was set reads back as the str it was set from, so the documented round trip holds (it raised
    # UnicodeDecodeError).
    look = inkgraph.Look.from_arguments(["--shademap", latin1])
    assert look.arguments == ["--shademap", latin1]
    assert inkgraph.Look.from_arguments(look.arguments).arguments == look.arguments
    assert eval(repr(look), {"inkgraph": inkgraph}).arguments == look.arguments  # pylint: disable=eval-used
    assert look.shade_map == latin1
    look.outline_width_map = f"texture:{latin1}:G"
    assert look.outline_width_map == f"texture:{latin1}:G"
    with pytest.raises(inkgraph.UsageError, match="unknown"):
        inkgraph.Shading.from_name("\udcff")
    frame = inkgraph.Frame.from_arguments(["--frame", "\udcff"])
    assert frame.frame_nodes == ["\udcff"]
    frame.pose, frame.animation = latin1, "\udcf4"
    assert (frame.pose, frame.animation) == (latin1, "\udcf4")
    # A NUL cut the C string the library takes: "a.png\0junk" read a.png. Refused, as Python refuses it in a path.
    for call in (lambda: inkgraph.Look().set("--shademap", str(original) + "\0junk"),
                 lambda: inkgraph.Look.from_arguments(["--shading", "flat\0junk"]),
                 lambda: inkgraph.Frame.from_arguments(["--frame", "a\0"]),
                 lambda: inkgraph.Scene.load(str(original), pose="a-pose\0junk")):
        with pytest.raises(inkgraph.UsageError, match="holds a NUL character"):
            call()
    # A lone surrogate that stands for no byte is a name like any other: unknown, as the flag says.
    with pytest.raises(inkgraph.UsageError, match="--shading: unknown value"):
        inkgraph.Look.from_arguments(["--shading", "\ud800"])
    with pytest.raises(inkgraph.UsageError, match="--orbit: expected"):
        inkgraph.Frame.from_arguments(["--orbit", "\udcff"])


@pytest.mark.parametrize("name, typed, arguments", FRAME_CASES, ids=[case[0] for case in FRAME_CASES])
def test_a_typed_frame_field_renders_as_its_flags(suzanne, name, typed, arguments):
    renderer = inkgraph.default_renderer()
    look = inkgraph.Look()
    typed_still = renderer.render(suzanne, look, typed())
    flags_still = renderer.render(suzanne, look, frame_from_arguments(arguments))
    assert np.array_equal(typed_still.picture, flags_still.picture), name
    assert np.array_equal(typed_still.camera.extrinsics, flags_still.camera.extrinsics), name


@pytest.mark.filterwarnings("ignore::inkgraph.InkgraphWarning")
@pytest.mark.parametrize("name, model, typed, arguments", CHARACTER_FRAME_CASES,
                         ids=[case[0] for case in CHARACTER_FRAME_CASES])
def test_a_typed_frame_field_of_a_character_renders_as_its_flags(name, model, typed, arguments):
    scene = inkgraph.Scene.load(REPO / "models" / "characters" / model)
    renderer = inkgraph.default_renderer()
    look = inkgraph.Look()
    typed_picture = renderer.render(scene, look, typed()).picture
    assert np.array_equal(typed_picture, renderer.render(scene, look, frame_from_arguments(arguments)).picture), name
    # The field took effect (the flag is tested against the command line elsewhere; here it must not be a no-op).
    assert not np.array_equal(typed_picture, renderer.render(scene, look, inkgraph.Frame(SIZE, SIZE)).picture), name


def test_look_fields_read_back_what_was_set():
    look = inkgraph.Look(shading="comic", shininess=7.5, view_vector="constant", face_orientation="after-vertices",
                         front_rule=3, light=(0, 1, 0), paper=(0.5, 0.5, 0.5), supersample=3, msaa=2,
                         gbuffer_precision="half", lines=["outline", LT.CREASE])
    assert look.shading == inkgraph.Shading.COMIC and look.shininess == 7.5
    assert look.view_vector == inkgraph.ViewVector.CONSTANT
    assert look.face_orientation == inkgraph.FaceOrientation.AFTER_VERTICES and look.front_rule == 3
    assert look.light == inkgraph.Vec3(0, 1, 0) and look.paper == inkgraph.Color(0.5, 0.5, 0.5, 1)
    assert look.supersample == 3 and look.gbuffer_precision == inkgraph.Precision.FLOAT16
    assert look.msaa == 2 and inkgraph.Look().msaa == 1
    assert look.lines == [LT.OUTLINE, LT.CREASE]
    assert inkgraph.Look().bands is None and inkgraph.Look(bands=4).bands == 4
    assert inkgraph.Look().light is None and inkgraph.Look().shade_map == ""
    # The typed look is the same look again from its flags.
    again = inkgraph.Look.from_arguments(look.arguments)
    assert again.arguments == look.arguments and again.lines == look.lines and again.front_rule == 3
    # Line styles, parameters and choices.
    look.set_line_style("crease", inkgraph.LineStyle(width=4, color=inkgraph.Color(1, 0, 0)))
    assert look.line_style(LT.CREASE) == inkgraph.LineStyle(4, (1, 0, 0))
    assert "crease-angle" in inkgraph.Look.line_parameter_names("crease")
    look.set_line_parameter("crease-angle", 35)
    assert look.line_parameter("crease-angle") == 35
    assert inkgraph.Look().line_choice("suggestive-stencil") == "3"
    strokes = inkgraph.StrokeSettings(weight_by_strength=True)
    look.strokes = strokes
    assert look.strokes == strokes and look.strokes.min_length == inkgraph.StrokeSettings().min_length


def test_frame_fields_read_back_what_was_set():
    frame = inkgraph.Frame(64, 32, eye=(0, 1, 5), target=[0, 0, 0], up=np.array([0, 1, 0]), fov=40, clip=(0.1, 50),
                           placement="auto", frame_nodes=["Face"], animation="Walk", time=0.25)
    assert (frame.width, frame.height) == (64, 32)
    assert frame.eye == inkgraph.Vec3(0, 1, 5) and tuple(frame.eye) == (0, 1, 5)
    assert frame.target == inkgraph.Vec3() and frame.up == inkgraph.Vec3(0, 1, 0)
    assert frame.fov == 40 and frame.clip == inkgraph.Clip(0.1, 50)
    assert frame.placement == inkgraph.CameraPlacement.AUTO
    assert frame.frame_nodes == ["Face"] and frame.animation == "Walk" and frame.time == 0.25
    frame.expressions = {"blink": 0.5}
    frame.look_at = (1, 2, 3)
    assert frame.expressions == {"blink": 0.5} and frame.look_at == inkgraph.Vec3(1, 2, 3)
    frame.eye = None
    frame.orbit = inkgraph.Orbit(10, 5)
    assert frame.eye is None and frame.orbit == inkgraph.Orbit(10, 5) and frame.orbit.distance is None
    defaults = inkgraph.Frame()
    assert (defaults.width, defaults.height, defaults.eye, defaults.orbit, defaults.fov, defaults.time) == (
        1024, 1024, None, None, None, None)
    assert defaults.placement == inkgraph.CameraPlacement.FILE_OR_AUTO and defaults.frame_nodes == []
    copied = copy.copy(frame)
    copied.width = 8
    assert frame.width == 64
    assert "orbit=Orbit(azimuth=10.0" in repr(frame), repr(frame)
    parsed = inkgraph.Frame.from_arguments(["--orbit", "30,10", "--fov", "40", "--size", "640x480"])
    assert (parsed.orbit, parsed.fov, parsed.width, parsed.height) == (inkgraph.Orbit(30, 10), 40, 640, 480)


def test_bad_values_are_refused_with_the_flags_message_or_a_type_error():
    with pytest.raises(inkgraph.UsageError, match="--bands"):
        inkgraph.Look(bands=0)
    with pytest.raises(inkgraph.UsageError, match="--supersample"):
        inkgraph.Look().supersample = 9
    with pytest.raises(inkgraph.UsageError, match=r"Look::setMsaa\(\): --msaa: expected 1 \(off\), 2, 4 or 8"):
        inkgraph.Look().msaa = 3
    with pytest.raises(inkgraph.UsageError, match="watercolour"):
        inkgraph.Look(shading="watercolour")
    with pytest.raises(TypeError, match="Look.light"):
        inkgraph.Look(light=(0, 1))
    with pytest.raises(TypeError, match="Look.paper"):
        inkgraph.Look(paper="white")
    with pytest.raises(TypeError, match="unexpected keyword argument 'shadin'"):
        inkgraph.Look(shadin="cel")
    # Text Python cannot encode as UTF-8 (a lone surrogate, as os.fsdecode leaves undecodable bytes) is a name like
    # any other: unknown.
    with pytest.raises(inkgraph.UsageError, match="unknown shading"):
        inkgraph.Look(shading="\udcff")
    with pytest.raises(TypeError, match="unexpected keyword argument"):
        inkgraph.Look(**{"\udcff": 1})
    # NumPy arrays make their items on access: each is held while it is read.
    for _ in range(100):
        assert inkgraph.Look(light=np.array([0.0, 1.0, 0.0])).light == inkgraph.Vec3(0, 1, 0)
    with pytest.raises(TypeError, match="Frame.eye"):
        inkgraph.Frame(eye=(0, "1", 5))
    with pytest.raises(TypeError, match="unexpected keyword argument 'camera'"):
        inkgraph.Frame(camera=["--orbit", "0,0"])
    with pytest.raises(inkgraph.UsageError, match="--orbit"):
        inkgraph.Frame.from_arguments(["--orbit", "0,95"])
    with pytest.raises(inkgraph.UsageError, match="--shading"):
        inkgraph.Frame.from_arguments(["--shading", "cel"])  # a look flag, not the frame's
    with pytest.raises(inkgraph.UsageError):  # checked when it renders, by --fov's rules
        inkgraph.render(REPO / "models" / "suzanne_npm_4k.obj", size=SIZE, frame=inkgraph.Frame(fov=200))


ENUMS = [inkgraph.Shading, inkgraph.LineType, inkgraph.ViewVector, inkgraph.FaceOrientation, inkgraph.Precision,
         inkgraph.CameraPlacement, inkgraph.CameraSource, inkgraph.Renderer.Platform]


@pytest.mark.parametrize("enum", ENUMS, ids=[enum.__name__ for enum in ENUMS])
def test_enum_members_round_trip_through_their_names(enum):
    members = list(enum.__members__.values())
    assert members
    for member in members:
        assert member.name.isupper()  # Python's constant spelling: Shading.CEL, LineType.NORMAL_EDGE
        assert enum.from_name(member.cli_name) == member and enum(member.cli_name) == member
        assert getattr(enum, member.name) == member and int(enum.from_name(member.cli_name)) == int(member)
    assert len({member.cli_name for member in members}) == len(members)
    with pytest.raises(inkgraph.UsageError, match="available: " + members[0].cli_name):
        enum.from_name("no-such-name")


def test_enum_names_are_the_command_lines():
    assert inkgraph.LineType.NORMAL_EDGE.cli_name == "normal-edge"
    assert inkgraph.LineType.from_name("mesh-silhouette") == inkgraph.LineType.MESH_SILHOUETTE
    assert inkgraph.Shading.MTOON.cli_name == "mtoon"
    assert inkgraph.FaceOrientation.DURING_VERTICES.cli_name == "during-vertices"
    assert inkgraph.Precision.FLOAT16.cli_name == "half"
    assert inkgraph.Renderer.Platform.SURFACELESS.cli_name == "surfaceless"
    # Every line type of the library, in composite order: the hidden lines first, under every visible one.
    assert [t.cli_name for t in inkgraph.LineType.__members__.values()][:6] == [
        "hidden-mesh-silhouette", "hidden-crease", "hidden-border", "hidden-intersection", "hidden-suggestive-object",
        "outline"]


def test_value_types_are_immutable_values():
    eye = inkgraph.Vec3(1, 2, 3)
    assert eye == inkgraph.Vec3(x=1, y=2, z=3) and eye != inkgraph.Vec3() and hash(eye) == hash(inkgraph.Vec3(1, 2, 3))
    assert tuple(eye) == (1, 2, 3) and len(eye) == 3
    with pytest.raises(AttributeError):
        eye.x = 5
    assert eye.replace(y=0) == inkgraph.Vec3(1, 0, 3) and eye.y == 2
    assert repr(eye) == "Vec3(x=1.0, y=2.0, z=3.0)"
    assert inkgraph.Color(1, 0, 0).a == 1 and inkgraph.Orbit(30).elevation == 0
    assert inkgraph.LineStyle().width == 2 and inkgraph.LineStyle(color=(1, 0, 0)).color == inkgraph.Color(1, 0, 0)
    assert inkgraph.StrokeSettings(taper_ends=True).replace(taper_ends=False) == inkgraph.StrokeSettings()
    with pytest.raises(TypeError, match="not a field"):
        eye.replace(w=1)


VALUES = [inkgraph.Vec3(1, 2, 3), inkgraph.Color(0.1, 0.2, 0.3, 0.4), inkgraph.Orbit(30, 10),
          inkgraph.Orbit(30, 10, 5, 2), inkgraph.Clip(0.5, 50), inkgraph.LineStyle(3, (1, 0, 0)),
          inkgraph.StrokeSettings(min_length=0.02, taper_ends=True),
          inkgraph.ViewSample(3, 40, 12, 1.5, (0, 1, 0), "happy", "a-pose"), inkgraph.ViewSample(),
          # A pose file whose name is not UTF-8 (as os.fsdecode() gives it) and such an expression name: the view
          # could be made and not copied (its pose was refused as it read back) nor read (UnicodeDecodeError).
          inkgraph.ViewSample(pose="/tmp/p\udcff.json", expression="sm\udcffile"),
          inkgraph.sample_views(1, 1, "x.obj", poses=["/tmp/p\udcff.json"])[0]]


@pytest.mark.parametrize("value", VALUES, ids=[repr(value) for value in VALUES])
def test_value_types_copy_and_pickle_as_themselves(value):
    # They could not be copied or pickled ("cannot pickle 'inkgraph._inkgraph.Vec3' object"), so neither could a
    # list of views sent to a multiprocessing pool.
    for twin in (copy.copy(value), copy.deepcopy(value), pickle.loads(pickle.dumps(value))):
        assert twin == value and type(twin) is type(value) and repr(twin) == repr(value)


def test_the_namespace_is_the_api():
    public = {name for name in dir(inkgraph) if not name.startswith("_")}
    assert public == set(inkgraph.__all__), public ^ set(inkgraph.__all__)
    for name in inkgraph.__all__:
        assert getattr(inkgraph, name) is not None
    for private in ("np", "numpy", "os", "typing", "threading", "atexit", "annotations", "Any", "Union"):
        assert private not in public


def test_the_packaged_stubs_and_marker(repo):
    package = pathlib.Path(inkgraph.__file__).parent
    assert (package / "py.typed").is_file() and (package / "_inkgraph.pyi").is_file()
    stubs = (package / "_inkgraph.pyi").read_text()
    extension = inkgraph._inkgraph
    for name in dir(extension):
        if not name.startswith("_"):
            assert f"class {name}" in stubs or f"def {name}(" in stubs, f"{name} is missing from the stubs"


def test_the_typed_smoke_file_runs(suzanne_path):
    with warnings.catch_warnings():
        warnings.simplefilter("error", inkgraph.InkgraphWarning)
        assert typed_api_smoke.main(pathlib.Path(suzanne_path), 64) == []


def test_scene_load_takes_a_vrm_face_as_its_flags():
    godette = str(REPO / "models" / "characters" / "godette.vrm")
    frame = inkgraph.Frame(SIZE, SIZE, frame_nodes=["Face"])
    renderer = inkgraph.default_renderer()
    loaded = renderer.render(inkgraph.Scene.load(godette, expressions={"blink": 1}, look_at=(-5, 1.3, -2)),
                             inkgraph.Look(), frame).picture
    flags = renderer.render(inkgraph.Scene.load(godette), inkgraph.Look(),
                            frame_from_arguments(["--frame", "Face", "--expression", "blink=1", "--look-at",
                                                  "-5,1.3,-2"])).picture
    assert np.array_equal(loaded, flags)
    with pytest.raises(inkgraph.InputError, match="no expression 'smile' .*'blink' \\(0.x 'Blink'\\)"):
        inkgraph.Scene.load(godette, expressions={"smile": 1})



def test_a_frames_time_alone_moves_the_scenes_own_animation(repo):
    # Load once with an animation, sweep the clock per frame: the frame's time was ignored (the picture stayed the
    # load's) unless a face or pose in the same frame loaded the scene again.
    fox = str(repo / "models" / "characters" / "fox.glb")
    loaded = inkgraph.Scene.load(fox, animation="Walk", time=0.5)
    at_rest = inkgraph.Scene.load(fox)
    with inkgraph.Renderer() as renderer:
        swept = renderer.render(loaded, None, inkgraph.Frame(SIZE, SIZE, orbit=(30, 10), time=0.9)).picture
        posed = renderer.render(at_rest, None,
                                inkgraph.Frame(SIZE, SIZE, orbit=(30, 10), animation="Walk", time=0.9)).picture
        as_loaded = renderer.render(loaded, None, inkgraph.Frame(SIZE, SIZE, orbit=(30, 10))).picture
        # Unset, a frame's time is the scene's, also beside the animation named again (it was 0 there).
        named = renderer.render(loaded, None, inkgraph.Frame(SIZE, SIZE, orbit=(30, 10), animation="Walk")).picture
    assert np.array_equal(swept, posed)
    assert not np.array_equal(swept, as_loaded)
    assert np.array_equal(named, as_loaded)


def test_a_frames_time_that_moves_nothing_is_a_warning_as_on_the_command_line(repo):
    fox = inkgraph.Scene.load(str(repo / "models" / "characters" / "fox.glb"))
    with pytest.warns(inkgraph.InkgraphWarning, match="moves nothing"):
        still = inkgraph.render(fox, frame=inkgraph.Frame(64, 64, time=1))
    assert [warning.code for warning in still.warnings] == ["time-unused"]
    # Named as the library's fields, not the command line's flags the caller never typed.
    assert still.warnings[0].message.startswith(
        "Frame::time 1 moves nothing: without SceneOptions::animation or Frame::animation it is only the clock")
