# SPDX-License-Identifier: GPL-3.0-or-later
"""A baseline TIFF writer for prints (issue 29.4), numpy and zlib only: grey, RGB or RGBA (the
alpha marked unassociated: straight, as the ink matte is), 8 or 16 bits a sample, little-endian,
Deflate-compressed strips (compression 8, which every TIFF reader of the last twenty years
reads), and the print resolution in XResolution/YResolution with the unit inch."""

from __future__ import annotations

import struct
import zlib

import numpy as np

STRIP_BYTES = 1 << 18  # about this much image data a strip
SOFTWARE = b"Virtual Hairy Brush\0"

# tag: (TIFF type, ...): 3 SHORT, 4 LONG, 5 RATIONAL, 2 ASCII
SHORT, LONG, RATIONAL, ASCII = 3, 4, 5, 2
_SIZES = {SHORT: 2, LONG: 4, RATIONAL: 8, ASCII: 1}


def _rational(v: float) -> tuple[int, int]:
    den = 10000
    return int(round(float(v) * den)), den


def tiff_bytes(img, dpi: float, level: int = 6) -> bytes:
    """A whole TIFF file's bytes: img (H, W[, 1|3|4]) uint8 or uint16, top row first."""
    a = np.asarray(img)
    if a.dtype not in (np.uint8, np.uint16):
        raise ValueError(f"a TIFF print holds uint8 or uint16 samples, not {a.dtype}")
    if a.ndim == 2:
        a = a[..., None]
    h, w, c = a.shape
    if c not in (1, 3, 4):
        raise ValueError(f"a TIFF print is grey, RGB or RGBA, not {c} channels")
    bits = a.dtype.itemsize * 8
    a = a.astype("<u2" if bits == 16 else np.uint8)
    rows = max(1, STRIP_BYTES // (w * c * a.dtype.itemsize))
    strips = [zlib.compress(a[y : y + rows].tobytes(), level) for y in range(0, h, rows)]
    tags = [
        (256, LONG, [w]),
        (257, LONG, [h]),
        (258, SHORT, [bits] * c),
        (259, SHORT, [8]),  # Adobe Deflate
        (262, SHORT, [1 if c == 1 else 2]),  # BlackIsZero grey, or RGB
        (273, LONG, [0] * len(strips)),  # strip offsets: filled in below
        (277, SHORT, [c]),
        (278, LONG, [rows]),
        (279, LONG, [len(s) for s in strips]),
        (282, RATIONAL, [_rational(dpi)]),
        (283, RATIONAL, [_rational(dpi)]),
        (284, SHORT, [1]),  # chunky: RGBRGB...
        (296, SHORT, [2]),  # inch
        (305, ASCII, list(SOFTWARE)),
    ]
    if c == 4:
        tags.append((338, SHORT, [2]))  # the extra sample is unassociated (straight) alpha
    tags.append((339, SHORT, [1] * c))  # unsigned integers
    return _assemble(sorted(tags), strips)


def _assemble(tags, strips) -> bytes:
    """Header, the strips, then the one IFD whose values that do not fit in 4 bytes follow it."""
    data_at = 8
    offsets, pos = [], data_at
    for s in strips:
        offsets.append(pos)
        pos += len(s) + (len(s) & 1)  # words start on even offsets
    ifd_at = pos
    extra_at = ifd_at + 2 + 12 * len(tags) + 4
    entries, extra = [], b""
    for tag, typ, values in tags:
        if tag == 273:
            values = offsets
        payload = _pack(typ, values)
        count = len(values)
        if len(payload) <= 4:
            field = payload.ljust(4, b"\0")
        else:
            field = struct.pack("<I", extra_at + len(extra))
            extra += payload + (b"\0" if len(payload) & 1 else b"")
        entries.append(struct.pack("<HHI", tag, typ, count) + field)
    out = [b"II*\0" + struct.pack("<I", ifd_at)]
    for s in strips:
        out.append(s + (b"\0" if len(s) & 1 else b""))
    out.append(struct.pack("<H", len(entries)) + b"".join(entries) + struct.pack("<I", 0))
    out.append(extra)
    return b"".join(out)


def _pack(typ: int, values) -> bytes:
    if typ == SHORT:
        return struct.pack(f"<{len(values)}H", *values)
    if typ == LONG:
        return struct.pack(f"<{len(values)}I", *values)
    if typ == ASCII:
        return bytes(values)
    return b"".join(struct.pack("<II", n, d) for n, d in values)  # RATIONAL
