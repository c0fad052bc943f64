"""NumPy in and out: Scene.from_arrays() renders as the OBJ of the same mesh, takes other dtypes and layouts by
converting them, and refuses what is not a mesh with errors naming the argument; render(out=...) draws into the
caller's array."""

from __future__ import annotations

import gc

import numpy as np
import pytest

import inkgraph

SIZE = 96


def read_obj(path: str) -> tuple[np.ndarray, np.ndarray]:
    """The vertices and triangles of an OBJ of 'v' lines and triangular or polygonal 'f' lines (fanned)."""
    vertices, faces = [], []
    with open(path) as obj:
        for line in obj:
            words = line.split()
            if words and words[0] == "v":
                vertices.append([float(value) for value in words[1:4]])
            elif words and words[0] == "f":
                corners = [int(word.split("/")[0]) - 1 for word in words[1:]]
                faces.extend([corners[0], corners[i], corners[i + 1]] for i in range(1, len(corners) - 1))
    return np.array(vertices, np.float32), np.array(faces, np.uint32)


@pytest.fixture(scope="module")
def mesh(suzanne_path):
    return read_obj(suzanne_path)


@pytest.fixture(scope="module")
def mesh_obj(mesh, tmp_path_factory):
    """Suzanne's vertices and faces alone, as an OBJ (no normals: both sides compute them the same way)."""
    vertices, faces = mesh
    path = tmp_path_factory.mktemp("arrays") / "mesh.obj"
    lines = [f"v {x!r} {y!r} {z!r}" for x, y, z in vertices.tolist()]
    lines += [f"f {a + 1} {b + 1} {c + 1}" for a, b, c in faces.tolist()]
    path.write_text("\n".join(lines) + "\n")
    return path


def picture(scene: inkgraph.Scene) -> np.ndarray:
    return inkgraph.render(scene, size=SIZE, look={"shading": "cel"}).picture


@pytest.mark.filterwarnings("ignore::inkgraph.InkgraphWarning")  # the OBJ has no normals: a warning of its load
def test_arrays_render_as_the_obj_of_the_same_mesh(mesh, mesh_obj):
    vertices, faces = mesh
    from_arrays = inkgraph.Scene.from_arrays(vertices, faces, name="suzanne")
    assert from_arrays.path == "" and from_arrays.triangle_count == len(faces)
    assert from_arrays.vertex_count > 0 and from_arrays.mesh_count == 1
    expected = picture(inkgraph.Scene.load(mesh_obj))
    assert np.array_equal(picture(from_arrays), expected)
    # Other dtypes and layouts are converted: float64 vertices, int64 faces, a Fortran-order and a strided view.
    converted = inkgraph.Scene.from_arrays(vertices.astype(np.float64), faces.astype(np.int64))
    assert np.array_equal(picture(converted), expected)
    fortran = inkgraph.Scene.from_arrays(np.asfortranarray(vertices), np.asfortranarray(faces.astype(np.int32)))
    assert np.array_equal(picture(fortran), expected)
    padded = np.zeros((len(vertices), 5), np.float32)
    padded[:, 1:4] = vertices
    strided = padded[:, 1:4]
    assert not strided.flags.c_contiguous
    assert np.array_equal(picture(inkgraph.Scene.from_arrays(strided, faces.tolist())), expected)


def test_the_scene_owns_its_copy_of_the_arrays(mesh):
    vertices, faces = mesh
    vertices, faces = vertices.copy(), faces.copy()
    scene = inkgraph.Scene.from_arrays(vertices, faces)
    before = picture(scene)
    vertices[:] = 0  # the caller's arrays change and go away; the scene keeps what it was made from
    del vertices, faces
    gc.collect()
    assert np.array_equal(picture(scene), before)


def test_normals_uvs_and_colours_are_taken(mesh):
    vertices, faces = mesh
    normals = np.tile(np.array([[0, 0, 1]], np.float32), (len(vertices), 1))  # every vertex facing +z: flat light
    uvs = vertices[:, :2]
    red = np.tile(np.array([[1, 0, 0]], np.float32), (len(vertices), 1))
    plain = picture(inkgraph.Scene.from_arrays(vertices, faces))
    with_all = inkgraph.Scene.from_arrays(vertices, faces, normals=normals, uvs=uvs, colors=red)
    assert not np.array_equal(picture(with_all), plain)
    rgba = np.concatenate([red, np.ones((len(vertices), 1), np.float32)], axis=1)
    assert inkgraph.Scene.from_arrays(vertices, faces, colors=rgba).triangle_count == len(faces)


def test_colours_outside_0_to_1_are_clamped_with_a_warning(mesh):
    # uint8 colours of 0 to 255 (made float) drew every channel above 1/255 at full strength, without a word.
    vertices, faces = mesh
    bytes_ = np.tile(np.array([[255, 128, 0]], np.uint8), (len(vertices), 1))
    with pytest.warns(inkgraph.InkgraphWarning, match="give them divided by 255"):
        scene = inkgraph.Scene.from_arrays(vertices, faces, colors=bytes_)
    assert [warning.code for warning in scene.warnings] == ["value-out-of-range"]


TRIANGLE = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0]], np.float32)
FACE = np.array([[0, 1, 2]], np.uint32)
BAD_ARRAYS = [
    ("vertices (N, 2)", dict(vertices=np.zeros((5, 2), np.float32)),
     "Scene.from_arrays(): vertices: expected an (N, 3) array of numbers, got shape (5, 2)"),
    ("vertices 1-D", dict(vertices=np.zeros(9, np.float32)), "vertices: expected an (N, 3) array of numbers, got "
                                                             "shape (9,)"),
    ("vertices complex", dict(vertices=TRIANGLE.astype(np.complex64)), "vertices: expected an (N, 3) array of "
                                                                       "numbers, got dtype complex64"),
    ("vertices strings", dict(vertices=[["a", "b", "c"]] * 3), "vertices: expected an (N, 3) array of numbers, got "
                                                               "dtype <U1"),
    ("vertices objects", dict(vertices=np.array([[None] * 3] * 3, dtype=object)), "vertices: expected an (N, 3) "
                                                                                   "array of numbers, got dtype object"),
    ("faces float", dict(faces=FACE.astype(np.float64)), "faces: expected an (M, 3) array of integer vertex indices, "
                                                         "got dtype float64"),
    ("faces (M, 4)", dict(faces=np.zeros((2, 4), np.uint32)), "faces: expected an (M, 3) array of integer vertex "
                                                              "indices, got shape (2, 4)"),
    ("vertices ragged", dict(vertices=[[0, 0, 0], [1, 0], [0, 1, 0]]), "vertices: expected an (N, 3) array of "
                                                                      "numbers, got a sequence NumPy cannot make an "
                                                                      "array of ("),
    ("faces ragged", dict(faces=[[0, 1, 2], [0, 1]]), "faces: expected an (M, 3) array of integer vertex indices, got "
                                                      "a sequence NumPy cannot make an array of ("),
    ("faces negative", dict(faces=np.array([[0, -1, 2]])), "faces: index -1 is negative"),
    ("faces beyond 32 bits", dict(faces=np.array([[0, 1, 2**32]], np.int64)), "faces: index 4294967296 does not fit"),
    ("normals rows", dict(normals=np.zeros((2, 3), np.float32)), "normals: expected 3 rows (one per vertex), got 2"),
    ("uvs (N, 3)", dict(uvs=np.zeros((3, 3), np.float32)), "uvs: expected an (N, 2) array of numbers, got shape "
                                                           "(3, 3)"),
    ("colors (N, 2)", dict(colors=np.zeros((3, 2), np.float32)), "colors: expected an (N, 3) or (N, 4) array of "
                                                                 "numbers, got shape (3, 2)"),
]


@pytest.mark.parametrize("name, arguments, message", BAD_ARRAYS, ids=[case[0] for case in BAD_ARRAYS])
def test_what_is_not_a_mesh_is_refused_naming_the_argument(name, arguments, message):
    given = {"vertices": TRIANGLE, "faces": FACE, **arguments}
    with pytest.raises(inkgraph.InputError) as caught:
        inkgraph.Scene.from_arrays(**given)
    assert message in str(caught.value), str(caught.value)
    assert str(caught.value).startswith("Scene.from_arrays(): ") or "Scene::fromArrays" in str(caught.value)


BAD_VALUES = [
    ("NaN vertex", dict(vertices=np.array([[0, 0, 0], [1, np.nan, 0], [0, 1, 0]], np.float32)),
     "Scene.from_arrays(): 'arrays': vertices: vertex 1: y is not finite (nan)"),
    ("infinite vertex", dict(vertices=np.array([[0, 0, 0], [1, 0, 0], [0, 0, -np.inf]])),
     "Scene.from_arrays(): 'arrays': vertices: vertex 2: z is not finite (-inf)"),
    ("float64 beyond float32", dict(vertices=np.array([[0, 0, 0], [1e39, 0, 0], [0, 1, 0]])),
     "Scene.from_arrays(): 'arrays': vertices: vertex 1: x is not finite (inf)"),
    ("NaN normal", dict(normals=np.full((3, 3), np.nan, np.float32)),
     "Scene.from_arrays(): 'arrays': normals: vertex 0: x is not finite (nan)"),
    ("index out of range", dict(faces=np.array([[0, 1, 2], [0, 2, 3]], np.uint32)),
     "Scene.from_arrays(): 'arrays': face 1: vertex index 3 out of range (vertices has 3 rows)"),
    ("no faces", dict(faces=np.zeros((0, 3), np.uint32)), "Scene.from_arrays(): 'arrays': no faces: faceCount is 0"),
    ("no vertices", dict(vertices=np.zeros((0, 3), np.float32)),
     "Scene.from_arrays(): 'arrays': face 0: vertex index 0 out of range (vertices has 0 rows)"),
]


@pytest.mark.filterwarnings("ignore:overflow encountered:RuntimeWarning")  # NumPy's, converting 1e39 to float32
@pytest.mark.parametrize("name, arguments, message", BAD_VALUES, ids=[case[0] for case in BAD_VALUES])
def test_values_that_are_not_a_mesh_are_refused_naming_the_argument(name, arguments, message):
    with pytest.raises(inkgraph.InputError) as caught:
        inkgraph.Scene.from_arrays(**{"vertices": TRIANGLE, "faces": FACE, **arguments})
    assert str(caught.value) == message


def test_the_librarys_own_checks_stay_behind_them():
    # A value the binding passes (a colour far outside [0, 1] is the library's to judge): not a crash, an answer.
    colors = np.full((3, 3), 2.0, np.float32)
    try:
        scene = inkgraph.Scene.from_arrays(TRIANGLE, FACE, colors=colors)
    except inkgraph.InputError as error:
        assert "colors" in str(error) or "colours" in str(error), str(error)
    else:
        assert scene.triangle_count == 1


def test_render_into_the_callers_array(suzanne):
    expected = inkgraph.render(suzanne, size=(SIZE, 64)).picture
    out = np.zeros((64, SIZE, 4), np.uint8)
    result = inkgraph.render(suzanne, size=(SIZE, 64), out=out)
    assert np.array_equal(out, expected)
    assert np.shares_memory(result.picture, out) and np.array_equal(result.picture, expected)
    assert not result.picture.flags.writeable and out.flags.writeable
    # Rows further apart than the picture is wide: a window of a larger canvas, the rest of it untouched.
    canvas = np.full((80, SIZE + 40, 4), 7, np.uint8)
    window = canvas[8:72, 20:20 + SIZE]
    still = inkgraph.default_renderer().render(suzanne, inkgraph.Look(), inkgraph.Frame(SIZE, 64), out=window)
    assert np.array_equal(window, expected) and np.shares_memory(still.picture, canvas)
    assert (canvas[:8] == 7).all() and (canvas[:, :20] == 7).all() and (canvas[:, 20 + SIZE:] == 7).all()
    # The still keeps the array it drew into alive.
    del canvas, window
    gc.collect()
    assert np.array_equal(still.picture, expected)


@pytest.mark.parametrize("name, out, problem", [
    ("wrong shape", np.zeros((SIZE, SIZE, 4), np.uint8), "got shape (96, 96, 4)"),
    ("wrong dtype", np.zeros((64, SIZE, 4), np.float32), "got dtype float32"),
    ("read-only", np.zeros((64, SIZE, 4), np.uint8)[...].view(), "got a read-only array"),
    ("channels apart", np.zeros((64, SIZE, 8), np.uint8)[:, :, ::2], "must be packed"),
])
def test_a_bad_out_array_is_refused(suzanne, name, out, problem):
    if name == "read-only":
        out.flags.writeable = False
    with pytest.raises(inkgraph.UsageError) as caught:
        inkgraph.render(suzanne, size=(SIZE, 64), out=out)
    message = str(caught.value)
    assert message.startswith("Renderer.render(): out: ") and problem in message, message
    with pytest.raises(TypeError):
        inkgraph.render(suzanne, size=(SIZE, 64), out=[[0]])  # type: ignore[arg-type]


def test_weld_distance_is_the_loads_from_arrays_and_files(tmp_path):
    # Triangles of 5e-4 units beside one of 1000: merged away at the default weld distance (1e-6 x 1414 units),
    # kept at 0; a distance out of 0 to 0.01 is a UsageError naming the argument's flag.
    vertices = np.array([[0, 0, 0], [1000, 0, 0], [0, 1000, 0], [10, 10, 0], [10.0005, 10, 0], [10, 10.0005, 0]],
                        np.float32)
    faces = np.array([[0, 1, 2], [3, 4, 5]], np.uint32)
    assert inkgraph.Scene.from_arrays(vertices, faces).triangle_count == 1
    assert inkgraph.Scene.from_arrays(vertices, faces, weld_distance=0.0).triangle_count == 2
    obj = tmp_path / "tiny.obj"
    obj.write_text("".join(f"v {x} {y} {z}\n" for x, y, z in vertices.tolist()) + "f 1 2 3\nf 4 5 6\n")
    assert inkgraph.Scene.load(obj).triangle_count == 1
    assert inkgraph.Scene.load(obj, weld_distance=0.0).triangle_count == 2
    with pytest.raises(inkgraph.UsageError, match="--weld-distance: expected 0 to 0.01, got '0.02'"):
        inkgraph.Scene.load(obj, weld_distance=0.02)


def test_arrays_changed_by_another_thread_during_the_load_never_reach_it_unchecked():
    # The load reads its arrays without the GIL, its checks first and then the mesh: an index another thread made out
    # of range between the two read past the end (a segmentation fault within about a dozen calls). The binding now
    # hands the library copies of its own, so each call either sees the index and refuses it or never sees it.
    import threading
    import time

    count = 200_000
    generator = np.random.default_rng(7)
    vertices = generator.random((count, 3), dtype=np.float32)
    normals = generator.random((count, 3), dtype=np.float32)
    faces = generator.integers(0, count, (count, 3)).astype(np.uint32)
    stop = threading.Event()

    def flip():
        while not stop.is_set():
            faces[-4:] = 4_000_000_000
            time.sleep(0.001)
            faces[-4:] = 0
            time.sleep(0.001)

    flipper = threading.Thread(target=flip, daemon=True)
    flipper.start()
    outcomes = set()
    try:
        for _ in range(60):
            try:
                inkgraph.Scene.from_arrays(vertices, faces, normals=normals)
                outcomes.add("loaded")
            except inkgraph.InputError as error:
                assert "out of range" in str(error)
                outcomes.add("refused")
    finally:
        stop.set()
        flipper.join()
    assert outcomes <= {"loaded", "refused"}


def test_an_array_too_large_to_convert_is_a_memory_error_naming_it(tmp_path):
    # 9e9 float64 values to convert to float32: NumPy has no memory for the copy. It was told as an array that cannot
    # be converted (InputError), and write_image() of a view too large to lay out crashed.
    huge = np.broadcast_to(np.zeros(3, np.float64), (3_000_000_000, 3))
    with pytest.raises(MemoryError, match=r"from_arrays\(\): vertices: .*no memory"):
        inkgraph.Scene.from_arrays(huge, np.array([[0, 1, 2]]))
    with pytest.raises(MemoryError, match=r"write_image\(\): no memory"):
        inkgraph.write_image(tmp_path / "x.png", np.broadcast_to(np.zeros(4, np.uint8), (100_000, 100_000, 4)))
    # A side beyond int was told as a negative size ("an image of -1294967296x1 pixels").
    with pytest.raises(inkgraph.UsageError, match="3000000000x1 pixels is larger than an image can be"):
        inkgraph.write_image(tmp_path / "x.png", np.broadcast_to(np.zeros(1, np.uint8), (1, 3_000_000_000)))
    assert list(tmp_path.iterdir()) == []


def uv_sphere(segments: int = 32, rings: int = 16) -> tuple[np.ndarray, np.ndarray]:
    """A unit sphere's vertices (which are its outward normals) and faces, counter-clockwise seen from outside."""
    theta = np.linspace(0.0, np.pi, rings + 1)[:, None]
    phi = np.linspace(0.0, 2.0 * np.pi, segments, endpoint=False)[None, :]
    vertices = np.stack([np.sin(theta) * np.cos(phi), np.cos(theta) + 0 * phi, np.sin(theta) * np.sin(phi)], axis=-1)
    vertices = vertices.reshape(-1, 3).astype(np.float32)
    faces = []
    for ring in range(rings):
        for segment in range(segments):
            a = ring * segments + segment
            b = ring * segments + (segment + 1) % segments
            if ring != rings - 1:  # the last ring's first triangle has two corners on the south pole
                faces.append([a, b + segments, a + segments])
            if ring != 0:  # the first ring's second one two on the north pole
                faces.append([a, b, b + segments])
    return vertices, np.array(faces, np.uint32)


@pytest.mark.filterwarnings("ignore::inkgraph.InkgraphWarning")  # the renders tell the load's warning again
def test_normals_given_inward_are_turned_round_with_a_warning():
    # The faces wound outward, the caller's normals inward (clockwise cross products): they reached the 'normal'
    # buffer as given, so the ball's lighting and n . v lines read its front as facing away.
    vertices, faces = uv_sphere()
    frame = inkgraph.Frame(48, 48)
    outward = inkgraph.Scene.from_arrays(vertices, faces, normals=vertices, name="ball")
    assert not outward.warnings
    with pytest.warns(inkgraph.InkgraphWarning, match="mesh 'ball': its given normals point against") as issued:
        inward = inkgraph.Scene.from_arrays(vertices, faces, normals=-vertices, name="ball")
    assert [warning.message.code for warning in issued] == ["normals-inward"]
    renderer = inkgraph.Renderer()
    normal = renderer.render(inward, None, frame, ["normal"]).buffer("normal")
    expected = renderer.render(outward, None, frame, ["normal"]).buffer("normal")
    np.testing.assert_allclose(normal, expected, atol=1e-6)
