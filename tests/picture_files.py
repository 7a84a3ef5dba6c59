# SPDX-License-Identifier: GPL-3.0-or-later
"""Pictures of writing in the file kinds artists have (issue 29.2): PNG of 8 or 16 bits, grey,
grey and alpha, RGB, RGBA, palette, interlaced (written here, byte by byte, as the PNG
specification says), and JPEG and TIFF through Pillow."""

from __future__ import annotations

import struct
import zlib

import numpy as np

ADAM7 = ((0, 0, 8, 8), (4, 0, 8, 8), (0, 4, 4, 8), (2, 0, 4, 4), (0, 2, 2, 4), (1, 0, 2, 2))
ADAM7 += ((0, 1, 1, 2),)  # (x0, y0, dx, dy) of the seven passes
COLOUR_TYPE = {1: 0, 2: 4, 3: 2, 4: 6}  # channels -> PNG colour type (palette: 3)


def _chunk(tag: bytes, data: bytes) -> bytes:
    return struct.pack(">I", len(data)) + tag + data + struct.pack(">I", zlib.crc32(tag + data))


def _rows(a: np.ndarray, depth: int) -> bytes:
    """Rows of samples, each after a filter byte 0 (None), big-endian at 16 bits."""
    h = a.shape[0]
    body = a.astype(">u2" if depth == 16 else np.uint8).reshape(h, -1).view(np.uint8)
    return np.concatenate([np.zeros((h, 1), np.uint8), body], axis=1).tobytes()


def png_bytes(a: np.ndarray, depth: int = 8, interlace: bool = False, palette=None) -> bytes:
    """A PNG of ``a`` (H, W, C) unsigned samples of ``depth`` bits (C = 1: grey, 2: grey and
    alpha, 3: RGB, 4: RGBA); with ``palette`` (K, 3) uint8, ``a`` (H, W, 1) holds indices."""
    h, w, c = a.shape
    ctype = 3 if palette is not None else COLOUR_TYPE[c]
    head = struct.pack(">IIBBBBB", w, h, depth, ctype, 0, 0, int(interlace))
    if interlace:
        raw = b"".join(
            _rows(a[y0::dy, x0::dx], depth) for x0, y0, dx, dy in ADAM7 if a[y0::dy, x0::dx].size
        )
    else:
        raw = _rows(a, depth)
    out = b"\x89PNG\r\n\x1a\n" + _chunk(b"IHDR", head)
    if palette is not None:
        out += _chunk(b"PLTE", np.asarray(palette, np.uint8).tobytes())
    return out + _chunk(b"IDAT", zlib.compress(raw)) + _chunk(b"IEND", b"")


def png_kinds(grey: np.ndarray) -> dict:
    """The PNG files of a grey picture (H, W) in [0, 1], by name: {name: bytes}."""
    g8 = np.round(grey * 255).astype(np.uint8)[..., None]
    g16 = np.round(grey * 65535).astype(np.uint16)[..., None]
    opaque8, opaque16 = np.full_like(g8, 255), np.full_like(g16, 65535)
    levels = np.unique(g8)
    index = np.searchsorted(levels, g8).astype(np.uint8)
    return {
        "grey8": png_bytes(g8),
        "grey16": png_bytes(g16, 16),
        "grey_alpha8": png_bytes(np.concatenate([g8, opaque8], axis=2)),
        "rgb16": png_bytes(np.repeat(g16, 3, axis=2), 16),
        "rgba16_interlaced": png_bytes(
            np.concatenate([np.repeat(g16, 3, axis=2), opaque16], axis=2), 16, interlace=True
        ),
        "rgb8_interlaced": png_bytes(np.repeat(g8, 3, axis=2), interlace=True),
        "palette": png_bytes(index, palette=np.repeat(levels[:, None], 3, axis=1)),
    }
