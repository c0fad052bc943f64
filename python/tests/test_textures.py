"""Textures through the Python module (issue 31): one wider than the driver's largest texture is downscaled with a
warning the still carries, where it raised RenderError before."""

from __future__ import annotations

import struct
import zlib

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


def test_a_texture_wider_than_the_driver_takes_is_downscaled_with_a_warning(tmp_path):
    (tmp_path / "strip.png").write_bytes(_png(17000, 1, b"\xff\x80\x00\xff" * 17000))
    (tmp_path / "tri.mtl").write_text("newmtl skin\nmap_Kd strip.png\n")
    (tmp_path / "tri.obj").write_text(
        "mtllib tri.mtl\nusemtl skin\nv 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 0 1\nf 1/1 2/2 3/3\n")
    result = inkgraph.render(str(tmp_path / "tri.obj"), size=(SIZE, SIZE), lines=["none"])
    warnings = result.still.warnings
    assert any("image 0 'strip.png' is 17000x1 pixels" in w and "downscaled to 16384x1" in w for w in warnings), \
        warnings
    # The orange texture reached the picture: some pixel is orange (red above green above blue).
    picture = result.picture
    orange = (picture[..., 0] > picture[..., 1]) & (picture[..., 1] > picture[..., 2])
    assert orange.any()
