"""Buffers as NumPy arrays: the G-buffer's normal, depth and n.v, the line masks, and how the arrays hold the still."""

from __future__ import annotations

import gc

import numpy as np
import pytest

import inkgraph
from conftest import SIZE


@pytest.fixture(scope="module")
def gbuffer(suzanne):
    return inkgraph.render(suzanne, size=SIZE, buffers=["normal", "view", "depth", "nDotV", "coverage"]).buffers


def test_buffers_come_by_the_names_asked_for_with_their_shapes_and_types(gbuffer):
    assert list(gbuffer) == ["normal", "view", "depth", "nDotV", "coverage"]
    assert gbuffer["normal"].shape == (SIZE, SIZE, 4) and gbuffer["normal"].dtype == np.float32
    assert gbuffer["view"].shape == (SIZE, SIZE, 4) and gbuffer["view"].dtype == np.float32
    assert gbuffer["depth"].shape == (SIZE, SIZE) and gbuffer["depth"].dtype == np.float32
    assert gbuffer["nDotV"].shape == (SIZE, SIZE) and gbuffer["nDotV"].dtype == np.float32
    assert gbuffer["coverage"].shape == (SIZE, SIZE)


def test_normal_is_unit_length_where_covered(gbuffer):
    normal = gbuffer["normal"]
    covered = normal[:, :, 3] > 0.5  # the normal's alpha is coverage
    assert 0.05 < covered.mean() < 0.9
    lengths = np.linalg.norm(normal[:, :, :3], axis=2)
    assert np.abs(lengths[covered] - 1).max() < 1e-3
    assert (normal[~covered] == 0).all()
    # The coverage buffer covers the same pixels.
    assert np.array_equal(gbuffer["coverage"] > 0, covered)


def test_depth_is_positive_on_the_model_and_zero_off_it(gbuffer):
    covered = gbuffer["normal"][:, :, 3] > 0.5
    depth = gbuffer["depth"]
    assert (depth[covered] > 0).all()
    assert (depth[~covered] == 0).all()
    # Auto-framing puts the whole model in front of the camera, well within the depth range it fits.
    assert depth[covered].max() / depth[covered].min() < 2


def test_n_dot_v_is_the_normal_dotted_with_the_view_vector(gbuffer):
    covered = gbuffer["normal"][:, :, 3] > 0.5
    n_dot_v = gbuffer["nDotV"][covered]
    assert (np.abs(n_dot_v) <= 1 + 1e-5).all()
    expected = np.sum(gbuffer["normal"][:, :, :3] * gbuffer["view"][:, :, :3], axis=2)[covered]
    assert np.abs(n_dot_v - expected).max() < 1e-3
    assert (n_dot_v > 0).mean() > 0.9  # what the camera sees mostly faces it


def test_line_masks_are_the_lines_coverage_as_composited_into_the_picture(suzanne):
    lines = ["silhouette", "contour", "suggestive"]
    result = inkgraph.render(suzanne, size=SIZE, shading="none", lines=lines, buffers=[f"lines.{t}" for t in lines])
    masks = [result.buffers[f"lines.{name}"] for name in lines]
    for name, mask in zip(lines, masks):
        assert mask.shape == (SIZE, SIZE) and mask.dtype == np.uint8
        # Strokes are antialiased: 255 inside a line, partial coverage along its edges (and where a line thins).
        assert (mask > 0).sum() > 50, name
    assert (masks[0] == 255).sum() > 50 and (masks[1] == 255).sum() > 50
    # Black lines drawn in turn over white paper and an unshaded (white) model: every channel of the picture is
    # 255 x the product of (1 - coverage) over the types, to rounding.
    uncovered = np.prod([1 - mask / 255 for mask in masks], axis=0)
    picture = result.picture[:, :, :3].astype(float)
    for channel in range(3):
        assert np.abs(picture[:, :, channel] - 255 * uncovered).max() <= 1.5


def test_line_masks_are_dark_in_a_shaded_picture(suzanne):
    result = inkgraph.render(suzanne, size=SIZE, look={"shading": "cel"}, lines=["silhouette", "contour"],
                             buffers=["lines.silhouette", "lines.contour"])
    covered = (result.buffers["lines.silhouette"] == 255) | (result.buffers["lines.contour"] == 255)
    assert covered.sum() > 100
    assert (result.picture[covered][:, :3] == 0).all()
    # Cel shading itself has no black: the rest of the picture is lighter.
    none = (result.buffers["lines.silhouette"] == 0) & (result.buffers["lines.contour"] == 0)
    assert (result.picture[none][:, :3].max(axis=1) > 64).all()


def test_a_line_mask_follows_the_lines_width(suzanne):
    def silhouette_pixels(width: float) -> int:
        look = {"silhouette-width": width}
        result = inkgraph.render(suzanne, look=look, size=SIZE, lines=["silhouette"], buffers=["lines.silhouette"])
        return int((result.buffers["lines.silhouette"] == 255).sum())

    thin, thick = silhouette_pixels(1), silhouette_pixels(4)
    assert 2.5 < thick / thin < 5.5


def test_arrays_share_the_still_read_only_and_keep_it_alive(suzanne):
    result = inkgraph.render(suzanne, size=SIZE, buffers=["depth"])
    depth = result.buffers["depth"]
    assert not depth.flags.writeable and not result.picture.flags.writeable
    with pytest.raises(ValueError):
        depth[0, 0] = 1
    # No copy: the array's base is the Still, and asking again gives the same pixels at the same address.
    assert depth.base is result.still
    assert result.still.buffer("depth").ctypes.data == depth.ctypes.data
    copy = depth.copy()
    del result
    gc.collect()
    assert np.array_equal(depth, copy)


def test_wildcards_give_every_buffer_by_its_own_name(suzanne):
    result = inkgraph.render(suzanne, size=SIZE, buffers=["gbuffer.*", "lines.*"])
    names = set(result.buffers)
    assert {"normal", "depth", "nDotV", "lines.silhouette", "lines.contour"} <= names, names


def test_buffer_names_lists_what_a_look_can_return():
    names = inkgraph.buffer_names(inkgraph.Look(lines=["silhouette", "contour"]))
    for name in ("normal", "depth", "nDotV", "lines.contour", "lines.silhouette", "picture"):
        assert name in names, names
    assert "lines.crease" not in names


def test_object_ids_are_the_scenes_objects(suzanne, tmp_path):
    # Issue 36: an OBJ file's `o` objects are its objects; the objectId buffer holds their ids, 0 off the model.
    (tmp_path / "two.obj").write_text(
        "v -2 0 0\nv -1 0 0\nv -2 1 0\nv 1 0 0\nv 2 0 0\nv 1 1 0\no left\nf 1 2 3\no right\nf 4 5 6\n"
    )
    scene = inkgraph.Scene.load(tmp_path / "two.obj")
    assert scene.objects == [
        {"id": 1, "name": "left", "node_path": ["left"], "meshes": ["left"]},
        {"id": 2, "name": "right", "node_path": ["right"], "meshes": ["right"]},
    ]
    ids = inkgraph.render(scene, size=SIZE, camera=["--eye", "0,0.5,8", "--target", "0,0.5,0"], buffers=["objectId"])
    values = set(np.unique(ids.buffers["objectId"]).tolist())
    assert values == {0.0, 1.0, 2.0}, values
    assert [object["name"] for object in suzanne.objects] == ["suzanne_npm_4k"]
