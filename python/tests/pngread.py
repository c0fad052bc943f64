"""A PNG reader for the tests, from the PNG specification: 8-bit grey, grey+alpha, RGB and RGBA, not interlaced
(what inkgraph writes), so the tests read back what the module wrote without an image library."""

from __future__ import annotations

import pathlib
import struct
import zlib

import numpy as np

SIGNATURE = b"\x89PNG\r\n\x1a\n"
CHANNELS = {0: 1, 4: 2, 2: 3, 6: 4}  # colour type -> channels


def read_png(path: str | pathlib.Path) -> np.ndarray:
    """The pixels of an 8-bit PNG: height x width for grey, height x width x channels otherwise."""
    data = pathlib.Path(path).read_bytes()
    assert data[:8] == SIGNATURE, f"{path}: not a PNG"
    position, header, compressed = 8, None, b""
    while position < len(data):
        (length,) = struct.unpack(">I", data[position : position + 4])
        kind = data[position + 4 : position + 8]
        body = data[position + 8 : position + 8 + length]
        position += 12 + length
        if kind == b"IHDR":
            header = struct.unpack(">IIBBBBB", body)
        elif kind == b"IDAT":
            compressed += body
        elif kind == b"IEND":
            break
    assert header is not None, f"{path}: no IHDR"
    width, height, depth, colour, _, _, interlace = header
    assert depth == 8 and colour in CHANNELS and interlace == 0, f"{path}: unsupported PNG {header}"
    channels = CHANNELS[colour]
    stride = width * channels
    raw = zlib.decompress(compressed)
    assert len(raw) == height * (stride + 1), f"{path}: {len(raw)} bytes of image data for {width}x{height}"
    rows = np.zeros((height, stride), dtype=np.int32)
    previous = np.zeros(stride, dtype=np.int32)
    for y in range(height):
        line = raw[y * (stride + 1) : (y + 1) * (stride + 1)]
        kind, row = line[0], np.frombuffer(line[1:], dtype=np.uint8).astype(np.int32)
        if kind == 0:  # None
            current = row
        elif kind == 2:  # Up
            current = (row + previous) & 0xFF
        else:  # Sub, Average, Paeth depend on the pixel to the left: byte by byte
            current = np.zeros(stride, dtype=np.int32)
            for x in range(stride):
                left = current[x - channels] if x >= channels else 0
                up = previous[x]
                upper_left = previous[x - channels] if x >= channels else 0
                if kind == 1:
                    predicted = left
                elif kind == 3:
                    predicted = (left + up) // 2
                elif kind == 4:
                    estimate = left + up - upper_left
                    distances = (abs(estimate - left), abs(estimate - up), abs(estimate - upper_left))
                    predicted = (left, up, upper_left)[distances.index(min(distances))]
                else:
                    raise AssertionError(f"{path}: filter type {kind} in row {y}")
                current[x] = (row[x] + predicted) & 0xFF
        rows[y] = current
        previous = current
    pixels = rows.astype(np.uint8).reshape(height, width, channels)
    return pixels[:, :, 0] if channels == 1 else pixels
