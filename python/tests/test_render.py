"""inkgraph.render(): the picture, and every way of giving the look, the lines, the size and the camera."""

from __future__ import annotations

import numpy as np
import pytest

import inkgraph
from conftest import SIZE


def ink(picture: np.ndarray) -> np.ndarray:
    """Where the picture is dark: the default line colour is black, the default paper white."""
    return picture[:, :, :3].max(axis=2) < 64


def test_picture_is_rgba8_with_ink_on_paper(suzanne):
    picture = inkgraph.render(suzanne, size=SIZE).picture
    assert picture.shape == (SIZE, SIZE, 4) and picture.dtype == np.uint8
    assert (picture[:, :, 3] == 255).all()
    # White paper in the corners (the model is framed inside the picture), black lines on the model.
    for corner in (picture[0, 0], picture[0, -1], picture[-1, 0], picture[-1, -1]):
        assert corner.tolist() == [255, 255, 255, 255]
    assert 50 < ink(picture).sum() < SIZE * SIZE / 2


def test_a_path_renders_as_the_loaded_scene(suzanne, suzanne_path):
    from_path = inkgraph.render(suzanne_path, size=SIZE).picture
    assert np.array_equal(from_path, inkgraph.render(suzanne, size=SIZE).picture)


def test_lines_none_leaves_no_ink_and_lines_add_it(suzanne):
    unlined = inkgraph.render(suzanne, size=SIZE, lines=[], shading="flat").picture
    silhouette = inkgraph.render(suzanne, size=SIZE, lines=["silhouette"], shading="flat").picture
    both = inkgraph.render(suzanne, size=SIZE, lines="silhouette,contour", shading="flat").picture
    assert ink(unlined).sum() == 0
    assert ink(silhouette).sum() > 50
    assert ink(both).sum() > ink(silhouette).sum()  # suzanne's contours lie inside her silhouette too
    assert (ink(both) | ~ink(silhouette)).all()  # and the contour is drawn over the silhouette, not instead


def test_look_as_dict_arguments_look_and_style_file_render_the_same(suzanne, tmp_path):
    as_dict = {"shading": "cel", "silhouette-width": 4, "background": (0, 0, 1), "contour-color": [1, 0, 0]}
    arguments = ["--shading", "cel", "--silhouette-width", "4", "--background", "0,0,1", "--contour-color", "1,0,0"]
    style = tmp_path / "look.style"
    style.write_text("shading = cel\nsilhouette-width = 4\nbackground = 0,0,1\ncontour-color = 1,0,0\n")
    pictures = [
        inkgraph.render(suzanne, look=look, size=SIZE).picture
        for look in (as_dict, arguments, inkgraph.Look.from_arguments(arguments), style, str(style))
    ]
    for picture in pictures[1:]:
        assert np.array_equal(picture, pictures[0])
    # The flags took effect: blue paper, red contours, and not the default look.
    assert pictures[0][0, 0].tolist() == [0, 0, 255, 255]
    red = (pictures[0][:, :, 0] > 200) & (pictures[0][:, :, 1] < 50) & (pictures[0][:, :, 2] < 50)
    assert red.sum() > 20
    assert not np.array_equal(pictures[0], inkgraph.render(suzanne, size=SIZE).picture)


def test_dict_keys_take_underscores_and_values_as_the_command_line_writes_them():
    look = inkgraph.make_look({"silhouette_width": 3.5, "shading": "cel", "contour-width": None, "bands": False})
    assert look.arguments == ["--silhouette-width", "3.5", "--shading", "cel"]
    frame = inkgraph.make_frame(64, {"orbit": (30, np.float32(10.5)), "fov": 40, "left-out": False})
    assert frame.orbit == inkgraph.Orbit(30, 10.5) and frame.fov == 40
    assert (frame.width, frame.height) == (64, 64)
    # Enum members and the small value types are written as the command line writes them.
    assert inkgraph.make_look({"shading": inkgraph.Shading.COMIC}).arguments == ["--shading", "comic"]
    assert inkgraph.make_frame(64, {"orbit": inkgraph.Orbit(30, 10)}).orbit == inkgraph.Orbit(30, 10)


def test_a_frame_as_camera_or_frame_and_size_over_it():
    frame = inkgraph.Frame(64, 48, orbit=(30, 10))
    assert inkgraph.make_frame(None, frame).orbit == inkgraph.Orbit(30, 10)
    resized = inkgraph.make_frame((32, 16), frame)
    assert (resized.width, resized.height, frame.width) == (32, 16, 64)  # the caller's frame is not changed
    with pytest.raises(TypeError):
        inkgraph.render("model.obj", camera=frame, frame=frame)


def test_shading_and_lines_arguments_win_over_the_look():
    look = inkgraph.make_look({"shading": "cel", "lines": "contour"}, shading="flat", lines=["silhouette"])
    assert look.shading == inkgraph.Shading.FLAT
    assert look.lines == [inkgraph.LineType.SILHOUETTE]
    assert inkgraph.make_look(lines=[]).lines == []
    assert inkgraph.make_look(lines="outline,contour").lines == [inkgraph.LineType.OUTLINE, inkgraph.LineType.CONTOUR]
    assert inkgraph.make_look(shading=inkgraph.Shading.COMIC).shading == inkgraph.Shading.COMIC


def test_the_callers_look_is_not_changed(suzanne):
    look = inkgraph.Look.from_arguments(["--shading", "cel"])
    inkgraph.render(suzanne, look=look, size=SIZE, lines=["contour"], shading="flat")
    assert look.arguments == ["--shading", "cel"]


def test_shading_changes_the_picture_and_a_scene_serves_two_looks(suzanne):
    cel = inkgraph.render(suzanne, look={"shading": "cel"}, size=SIZE, lines=[]).picture
    flat = inkgraph.render(suzanne, look={"shading": "flat"}, size=SIZE, lines=[]).picture
    again = inkgraph.render(suzanne, look={"shading": "cel"}, size=SIZE, lines=[]).picture
    assert not np.array_equal(cel, flat)
    assert np.array_equal(cel, again)
    # Cel shading has few tones (its bands); flat shading one per face orientation.
    shaded = cel[:, :, 3] > 0
    assert len(np.unique(cel[shaded][:, :3], axis=0)) < len(np.unique(flat[shaded][:, :3], axis=0))


def test_size_is_width_by_height(suzanne):
    result = inkgraph.render(suzanne, size=(96, 64), buffers=["depth"])
    assert result.picture.shape == (64, 96, 4)
    assert result.buffers["depth"].shape == (64, 96)


def test_camera_as_list_or_dict_moves_the_view(suzanne):
    front = inkgraph.render(suzanne, size=SIZE, camera=["--orbit", "0,0"]).picture
    back = inkgraph.render(suzanne, size=SIZE, camera=["--orbit", "180,0"]).picture
    back_from_dict = inkgraph.render(suzanne, size=SIZE, camera={"orbit": (180, 0)}).picture
    assert np.array_equal(back, back_from_dict)
    assert not np.array_equal(front, back)


def test_small_values_in_camera_and_look_dicts_are_the_flags_values(suzanne):
    # An Orbit's distance scale is the flag's xS (its items leave it out: the scale was dropped, the eye at half the
    # distance), and an opaque Color is R,G,B (its alpha made '--background 1,0.9,0.8,1', which is refused).
    orbit = inkgraph.Orbit(30, 10, distance_scale=2)
    from_frame = inkgraph.render(suzanne, frame=inkgraph.Frame(SIZE, SIZE, orbit=orbit))
    from_dict = inkgraph.render(suzanne, size=SIZE, camera={"orbit": orbit})
    assert from_dict.camera.eye == from_frame.camera.eye
    assert np.array_equal(from_dict.picture, from_frame.picture)
    with pytest.raises(ValueError, match="gives a distance and a distance_scale"):
        inkgraph.render(suzanne, size=SIZE, camera={"orbit": inkgraph.Orbit(30, 10, 3, distance_scale=2)})
    with pytest.raises(inkgraph.UsageError, match="a distance and a distanceScale"):
        inkgraph.render(suzanne, frame=inkgraph.Frame(SIZE, SIZE, orbit=inkgraph.Orbit(30, 10, 3, distance_scale=2)))
    paper = inkgraph.Look(paper=(1, 0.9, 0.8)).paper
    tinted = inkgraph.render(suzanne, {"background": paper}, size=SIZE).picture
    assert tuple(tinted[0, 0]) == (255, 230, 204, 255)


def test_wrong_argument_types_are_type_errors(suzanne):
    with pytest.raises(TypeError):
        inkgraph.render(suzanne, size="big")
    with pytest.raises(TypeError):
        inkgraph.render(suzanne, size=SIZE, look=42)
    with pytest.raises(TypeError):
        inkgraph.render(suzanne, size=SIZE, camera="--orbit 0,0")
    with pytest.raises(TypeError):
        inkgraph.render(suzanne, size=SIZE, look={"background": {"r": 1}})
