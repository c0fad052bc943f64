"""What a still has to say reaches the library's caller as it reaches the command line's (issue 31): a texture wider
than the driver's largest is downscaled with a warning (it raised RenderError before), and a file camera that sees
none of the model is named."""

from __future__ import annotations

import struct
import zlib

import pytest

import inkgraph
from conftest import SIZE


def _png(width: int, height: int, rgba: bytes) -> bytes:
    """An 8-bit RGBA PNG of `rgba` (width x height x 4 bytes, rows top first), unfiltered."""

    def chunk(kind: bytes, data: bytes) -> bytes:
        return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data))

    stride = width * 4
    raw = b"".join(b"\0" + rgba[row * stride:(row + 1) * stride] for row in range(height))
    header = struct.pack(">IIBBBBB", width, height, 8, 6, 0, 0, 0)
    return b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", header) + chunk(b"IDAT", zlib.compress(raw)) + chunk(b"IEND", b"")


@pytest.mark.filterwarnings("ignore::inkgraph.InkgraphWarning")
def test_a_texture_wider_than_the_driver_takes_is_downscaled_with_a_warning(tmp_path):
    (tmp_path / "strip.png").write_bytes(_png(17000, 1, b"\xff\x80\x00\xff" * 17000))
    (tmp_path / "tri.mtl").write_text("newmtl skin\nmap_Kd strip.png\n")
    (tmp_path / "tri.obj").write_text(
        "mtllib tri.mtl\nusemtl skin\nv 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 0 1\nf 1/1 2/2 3/3\n")
    result = inkgraph.render(str(tmp_path / "tri.obj"), size=(SIZE, SIZE), lines=["none"])
    warnings = result.still.warnings
    assert any("image 0 'strip.png' is 17000x1 pixels" in w.message and "downscaled to 16384x1" in w.message
               for w in warnings), warnings
    assert "texture-downscaled" in [w.code for w in warnings]
    # The orange texture reached the picture: some pixel is orange (red above green above blue).
    picture = result.picture
    orange = (picture[..., 0] > picture[..., 1]) & (picture[..., 1] > picture[..., 2])
    assert orange.any()


@pytest.mark.filterwarnings("ignore::inkgraph.InkgraphWarning")
def test_a_file_camera_that_sees_none_of_the_model_is_a_warning_of_the_still(tmp_path):
    # The library says what the command line says (issue 31): the glTF camera 5 units behind the triangle's plane,
    # looking away from it, renders blank paper, and the still's warnings name the camera.
    import base64
    import json

    positions = struct.pack("<9f", 0, 0, 0, 1, 0, 0, 0, 1, 0)
    gltf = {
        "asset": {"version": "2.0"},
        "buffers": [{"uri": "data:application/octet-stream;base64," + base64.b64encode(positions).decode(),
                     "byteLength": 36}],
        "bufferViews": [{"buffer": 0, "byteLength": 36}],
        "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3",
                       "min": [0, 0, 0], "max": [1, 1, 0]}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0}}]}],
        "cameras": [{"type": "perspective", "perspective": {"yfov": 0.8, "znear": 0.1}}],
        "nodes": [{"mesh": 0}, {"camera": 0, "translation": [0, 0, -5]}],
        "scenes": [{"nodes": [0, 1]}],
        "scene": 0,
    }
    (tmp_path / "away.gltf").write_text(json.dumps(gltf))
    result = inkgraph.render(str(tmp_path / "away.gltf"), size=(SIZE, SIZE))
    assert any("sees none of the model" in w.message for w in result.still.warnings), result.still.warnings
