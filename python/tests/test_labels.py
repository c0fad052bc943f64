"""The labels a data set reads (issue 37): the G-buffer's meshId, triangleId and barycentric buffers as NumPy arrays,
Scene.meshes naming their values, and the hidden lines' masks beside the visible ones."""

from __future__ import annotations

import numpy as np
import pytest

import inkgraph
from conftest import SIZE

# Two quads (two triangles each) in the plane z = 0, side by side, each an OBJ object with its own material: the
# left is mesh 1 (triangles 1 and 2), the right mesh 2 (triangles 3 and 4).
TWO_QUADS_OBJ = """mtllib two.mtl
v -2.2 -1 0
v -0.2 -1 0
v -0.2 1 0
v -2.2 1 0
v 0.2 -1 0
v 2.2 -1 0
v 2.2 1 0
v 0.2 1 0
o left
usemtl paint
f 1 2 3
f 1 3 4
o right
usemtl metal
f 5 6 7
f 5 7 8
"""
TWO_QUADS_MTL = "newmtl paint\nKd 0.8 0.2 0.2\nnewmtl metal\nKd 0.2 0.2 0.8\n"
CAMERA = ["--eye", "0.3,0.4,6", "--target", "0,0,0"]


@pytest.fixture(scope="module")
def quads(tmp_path_factory):
    folder = tmp_path_factory.mktemp("labels")
    (folder / "two.obj").write_text(TWO_QUADS_OBJ)
    (folder / "two.mtl").write_text(TWO_QUADS_MTL)
    return inkgraph.Scene.load(folder / "two.obj")


@pytest.fixture(scope="module")
def still(quads):
    frame = inkgraph.Frame(SIZE, SIZE, eye=(0.3, 0.4, 6), target=(0, 0, 0))
    return inkgraph.default_renderer().render(
        quads, inkgraph.Look(), frame, buffers=["triangleId", "meshId", "barycentric", "coverage"]
    )


def test_scene_meshes_name_the_mesh_and_triangle_ids(quads):
    assert quads.meshes == [
        {"id": 1, "drawn": True, "name": "left", "node_path": ["left"], "object_id": 1, "material_id": 1,
         "material": "paint", "first_triangle": 0, "triangle_count": 2},
        {"id": 2, "drawn": True, "name": "right", "node_path": ["right"], "object_id": 2, "material_id": 2,
         "material": "metal", "first_triangle": 2, "triangle_count": 2},
    ]


def test_the_label_buffers_are_float32_arrays_listed_in_buffer_names(still):
    for name in ("triangleId", "meshId", "barycentric"):
        assert name in still.buffer_names, still.buffer_names
    assert still.buffer("triangleId").shape == (SIZE, SIZE) and still.buffer("triangleId").dtype == np.float32
    assert still.buffer("gbuffer.triangleId").shape == (SIZE, SIZE)  # the graph's own name answers too
    assert still.buffer("meshId").dtype == np.float32
    assert still.buffer("barycentric").shape == (SIZE, SIZE, 4) and still.buffer("barycentric").dtype == np.float32


def test_mesh_and_triangle_ids_hold_the_scenes_numbering(still):
    covered = still.buffer("coverage") > 0
    triangles = still.buffer("triangleId")
    meshes = still.buffer("meshId")
    assert 0.1 < covered.mean() < 0.9
    assert set(np.unique(triangles[covered]).tolist()) == {1.0, 2.0, 3.0, 4.0}
    assert set(np.unique(meshes[covered]).tolist()) == {1.0, 2.0}
    assert (triangles[~covered] == 0).all() and (meshes[~covered] == 0).all()
    # Every triangle lies in its mesh: 1 and 2 in the left quad, 3 and 4 in the right.
    assert (meshes[covered] == np.where(triangles[covered] <= 2, 1.0, 2.0)).all()
    # The left quad is left of the image centre, the right one right of it.
    columns = np.nonzero(covered)[1]
    assert (columns[meshes[covered] == 1] < SIZE / 2).all() and (columns[meshes[covered] == 2] > SIZE / 2).all()


def test_barycentric_weights_sum_to_one_on_the_model_and_are_zero_off_it(still):
    weights = still.buffer("barycentric")
    covered = still.buffer("coverage") > 0
    # Alpha: the weights' own triangle id, here as the triangleId buffer has it (no surfaces fight for a pixel).
    assert (weights[covered][:, 3] == still.buffer("triangleId")[covered]).all()
    assert np.abs(weights[covered][:, :3].sum(axis=1) - 1).max() < 1e-5
    assert weights[covered][:, :3].min() >= 0 and weights[covered][:, :3].max() <= 1
    assert (weights[~covered] == 0).all()
    # Along a row through the left quad's lower triangle (1, 2, 3: corners (-2.2,-1), (-0.2,-1), (-0.2,1)), the
    # weight of its 2nd corner grows left to right: the weights vary across the triangle, not just per triangle.
    triangles = still.buffer("triangleId")
    row = int(np.argmax((triangles == 1).sum(axis=1)))
    second = weights[row, triangles[row] == 1, 1]
    assert second.size > 5 and (np.diff(second) > 0).all(), second


def test_the_hidden_lines_come_as_masks_of_their_own(tmp_path):
    # Issue 36's hidden lines are types of their own ("hidden-<type>"): lines.* gives each visible type's mask and
    # its hidden twin's, which is all a data set needs to tell visible from hidden per type. A quad in front of
    # another hides part of its border; --hidden-dash none makes the hidden mask solid.
    (tmp_path / "overlap.obj").write_text(
        "v -2.2 -1 0.5\nv -0.2 -1 0.5\nv -0.2 1 0.5\nv -2.2 1 0.5\n"
        "v -1 -0.6 -0.5\nv 1 -0.6 -0.5\nv 1 0.6 -0.5\nv -1 0.6 -0.5\n"
        "o front\nf 1 2 3\nf 1 3 4\no back\nf 5 6 7\nf 5 7 8\n"
    )
    look = inkgraph.Look.from_arguments(["--lines", "border", "--hidden-lines", "border", "--hidden-dash", "none"])
    frame = inkgraph.Frame(SIZE, SIZE, eye=(0, 0, 7), target=(-0.4, 0, 0))
    result = inkgraph.render(str(tmp_path / "overlap.obj"), look, frame=frame, buffers=["lines.*"])
    visible, hidden = result.buffers["lines.border"], result.buffers["lines.hidden-border"]
    assert visible.dtype == np.uint8 and hidden.shape == visible.shape
    assert (visible == 255).sum() > 50 and (hidden == 255).sum() > 20
    # Where one is a full line pixel the other is not: the two masks split the border.
    assert ((visible == 255) & (hidden == 255)).sum() < 0.1 * (hidden == 255).sum()


def three_quads_gltf(path):
    """Three quads side by side, meshes and nodes "A", "Prop" and "C" (materials "a", "p", "c"), and animation 0
    scaling Prop from 1 at t = 0 to 0 at t = 1: posed at t = 1, the whole mesh Prop collapses."""
    import base64
    import json
    import struct

    corners = [(-0.8, -0.8, 0), (0.8, -0.8, 0), (0.8, 0.8, 0), (-0.8, 0.8, 0)]
    data = b"".join(struct.pack("<3f", *p) for p in corners)
    data += struct.pack("<6H", 0, 1, 2, 0, 2, 3)
    times = struct.pack("<2f", 0.0, 1.0)
    scales = struct.pack("<6f", 1, 1, 1, 0, 0, 0)
    data += times + scales
    gltf = {
        "asset": {"version": "2.0"},
        "buffers": [{"byteLength": len(data),
                     "uri": "data:application/octet-stream;base64," + base64.b64encode(data).decode()}],
        "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 48},
                        {"buffer": 0, "byteOffset": 48, "byteLength": 12},
                        {"buffer": 0, "byteOffset": 60, "byteLength": 8},
                        {"buffer": 0, "byteOffset": 68, "byteLength": 24}],
        "accessors": [{"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3",
                       "min": [-0.8, -0.8, 0], "max": [0.8, 0.8, 0]},
                      {"bufferView": 1, "componentType": 5123, "count": 6, "type": "SCALAR"},
                      {"bufferView": 2, "componentType": 5126, "count": 2, "type": "SCALAR", "min": [0], "max": [1]},
                      {"bufferView": 3, "componentType": 5126, "count": 2, "type": "VEC3"}],
        "materials": [{"name": name} for name in ("a", "p", "c")],
        "meshes": [{"name": name, "primitives": [{"attributes": {"POSITION": 0}, "indices": 1, "material": m}]}
                   for m, name in enumerate(("A", "Prop", "C"))],
        "nodes": [{"name": name, "mesh": m, "translation": [2.0 * (m - 1), 0, 0]}
                  for m, name in enumerate(("A", "Prop", "C"))],
        "scenes": [{"nodes": [0, 1, 2]}],
        "animations": [{"name": "fold",
                        "samplers": [{"input": 2, "output": 3, "interpolation": "LINEAR"}],
                        "channels": [{"sampler": 0, "target": {"node": 1, "path": "scale"}}]}],
    }
    path.write_text(json.dumps(gltf))
    return path


def test_a_mesh_a_pose_collapses_keeps_every_id_as_at_rest(tmp_path):
    # A frame's animation loads the scene again in its pose: one that collapses a whole mesh (Prop, scaled to 0) draws
    # nothing, and every mesh, object and triangle keeps the id it has at rest, so the labels of an animation's frames
    # agree. Still.meshes says which meshes the still drew.
    scene = inkgraph.Scene.load(three_quads_gltf(tmp_path / "three.gltf"))
    assert [mesh["name"] for mesh in scene.meshes] == ["A", "Prop", "C"]
    assert all(mesh["drawn"] for mesh in scene.meshes)
    look = inkgraph.Look()
    at_rest = inkgraph.Frame(SIZE, SIZE, eye=(0, 0, 9), target=(0, 0, 0))
    folded = inkgraph.Frame(SIZE, SIZE, eye=(0, 0, 9), target=(0, 0, 0), animation="fold", time=1.0)
    renderer = inkgraph.default_renderer()
    buffers = ["meshId", "triangleId", "objectId"]
    rest = renderer.render(scene, look, at_rest, buffers=buffers)
    assert rest.meshes == scene.meshes and rest.objects == scene.objects
    with pytest.warns(inkgraph.InkgraphWarning, match="mesh 'Prop': all 2 triangles are degenerate"):
        still = renderer.render(scene, look, folded, buffers=buffers)
    assert "mesh-degenerate" in [warning.code for warning in still.warnings]
    assert [(mesh["id"], mesh["drawn"], mesh["name"], mesh["first_triangle"]) for mesh in still.meshes] == [
        (1, True, "A", 0),
        (2, False, "Prop", 2),
        (3, True, "C", 4),
    ]
    assert still.objects == scene.objects
    ids, rest_ids = still.buffer("meshId"), rest.buffer("meshId")
    assert set(np.unique(rest_ids).tolist()) == {0.0, 1.0, 2.0, 3.0}
    assert set(np.unique(ids).tolist()) == {0.0, 1.0, 3.0}
    # A and C lie where they lay at rest, so their pixels have the ids, objects and triangles they had at rest.
    kept = (rest_ids == 1) | (rest_ids == 3)
    for name in buffers:
        assert np.array_equal(still.buffer(name)[kept], rest.buffer(name)[kept]), name
    columns = np.nonzero(ids)[1]
    assert (columns[ids[ids > 0] == 3] > SIZE * 0.6).all()
    triangles = still.buffer("triangleId")
    for mesh in still.meshes:
        mine = triangles[ids == mesh["id"]]
        assert mine.size > 0 if mesh["drawn"] else mine.size == 0
        assert ((mine > mesh["first_triangle"]) & (mine <= mesh["first_triangle"] + mesh["triangle_count"])).all()
