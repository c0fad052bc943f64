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


def test_line_masks_are_0_or_255_and_drawn_dark_in_the_picture(suzanne):
    result = inkgraph.render(
        suzanne, size=SIZE, lines=["silhouette", "contour"], buffers=["lines.silhouette", "lines.contour"]
    )
    picture = result.picture
    for name in ("lines.silhouette", "lines.contour"):
        mask = result.buffers[name]
        assert mask.shape == (SIZE, SIZE) and mask.dtype == np.uint8
        assert set(np.unique(mask).tolist()) == {0, 255}, name
        on_line = mask == 255
        assert on_line.sum() > 50, name
        # Lines are black by default, drawn over everything else.
        assert (picture[on_line][:, :3] < 64).all(), name
    # Where no line is, the paper or the model shows: the lines are the only black.
    no_line = (result.buffers["lines.silhouette"] == 0) & (result.buffers["lines.contour"] == 0)
    assert (picture[no_line][:, :3].max(axis=1) > 64).all()


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


def test_gbuffer_star_gives_every_gbuffer_buffer(suzanne):
    result = inkgraph.render(suzanne, size=SIZE, buffers=["gbuffer.*"])
    names = set(result.buffers)
    assert {"gbuffer.normal", "gbuffer.depth", "gbuffer.nDotV"} <= names, names


def test_full_resource_names_and_short_names_are_the_same_buffer(suzanne):
    result = inkgraph.render(suzanne, size=SIZE, buffers=["depth", "gbuffer.depth", "lines.contour"])
    assert np.array_equal(result.buffers["depth"], result.buffers["gbuffer.depth"])
    assert inkgraph.buffer_resource_name("depth") == "gbuffer.depth"
    assert inkgraph.buffer_resource_name("lines.contour") == "strokes.contour"
    assert inkgraph.buffer_resource_name("picture") == "composite.final"
    assert inkgraph.buffer_resource_name("shade.color") == "shade.color"
