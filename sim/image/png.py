# SPDX-License-Identifier: GPL-3.0-or-later
"""Minimal PNG writer and reader (8-bit grey/RGB/RGBA/palette, no interlace), numpy only, so
that it runs inside Blender too.

Reading is bounded: the size in the header is checked before anything is decompressed, the
decompressed data is capped at exactly what that size needs, every chunk's length and CRC are
checked, and every fault ends in ``PNGError`` naming the file."""

from __future__ import annotations

import os
import struct
import zlib

import numpy as np

from ..core.files import write_atomic
from ..core.params import MAX_PAPER_PIXELS, MAX_PAPER_SIDE_PX

SIGNATURE = b"\x89PNG\r\n\x1a\n"
CHANNELS = {0: 1, 2: 3, 3: 1, 4: 2, 6: 4}  # colour type -> samples a pixel
METADATA_BYTES = 16 * 2**20  # room for chunks other than the image data


class PNGError(ValueError):
    """A PNG file is unreadable, damaged, too large, or of a kind this reader does not take."""


class PNGKindError(PNGError):
    """A PNG of a kind this reader does not take (16-bit, interlaced): Pillow and Blender read
    it."""


def _chunk(tag: bytes, data: bytes) -> bytes:
    return struct.pack(">I", len(data)) + tag + data + struct.pack(">I", zlib.crc32(tag + data))


def to_uint8(rgb) -> np.ndarray:
    """float [0, 1] -> uint8 with round-half-up, deterministic."""
    return np.floor(np.clip(np.asarray(rgb, dtype=np.float32), 0.0, 1.0) * 255.0 + 0.5).astype(
        np.uint8
    )


def write_png(path, img, level: int = 6) -> None:
    """img: (H, W[, 1|2|3|4]) uint8 or float in [0, 1] (grey, grey + alpha, RGB, RGBA), top
    row first. Written whole or not at all (``write_atomic``): a failure keeps the old file."""
    a = np.asarray(img)
    if a.dtype != np.uint8:
        a = to_uint8(a)
    if a.ndim == 2:
        a = a[..., None]
    h, w, c = a.shape
    ctype = {1: 0, 2: 4, 3: 2, 4: 6}[c]
    z = zlib.compressobj(level)
    parts = []
    band = max(1, (1 << 22) // max(w * c, 1))  # about 4 MB of rows per band
    for y0 in range(0, h, band):
        rows = a[y0 : y0 + band].reshape(-1, w * c)
        raw = np.zeros((rows.shape[0], 1 + w * c), dtype=np.uint8)  # filter byte 0 per row
        raw[:, 1:] = rows
        parts.append(z.compress(raw.tobytes()))
    parts.append(z.flush())

    def write(f):
        f.write(SIGNATURE)
        f.write(_chunk(b"IHDR", struct.pack(">IIBBBBB", w, h, 8, ctype, 0, 0, 0)))
        f.write(_chunk(b"IDAT", b"".join(parts)))
        f.write(_chunk(b"IEND", b""))

    write_atomic(path, write)


def png_bytes(img, bits: int = 8, dpi: float | None = None, level: int = 6) -> bytes:
    """A whole PNG file's bytes, for prints (issue 29.4): img (H, W[, 1|2|3|4]) grey, grey +
    alpha, RGB or RGBA, top row first, as uint8 (``bits`` 8) or uint16 (``bits`` 16), or float
    in [0, 1] (rounded to the depth); ``dpi`` goes in a pHYs chunk (pixels per metre, as PNG
    keeps it) so that print and layout programs place it at its size."""
    a = np.asarray(img)
    if bits not in (8, 16):
        raise ValueError(f"a PNG holds 8 or 16 bits a sample, not {bits}")
    top = (1 << bits) - 1
    if a.dtype.kind == "f":
        a = np.floor(np.clip(a, 0.0, 1.0) * top + 0.5)
    a = a.astype(">u2" if bits == 16 else np.uint8)
    if a.ndim == 2:
        a = a[..., None]
    h, w, c = a.shape
    row = w * c * (bits // 8)
    z = zlib.compressobj(level)
    parts = []
    band = max(1, (1 << 22) // max(row, 1))
    for y0 in range(0, h, band):
        rows = a[y0 : y0 + band].reshape(-1, w * c).view(np.uint8)
        raw = np.zeros((rows.shape[0], 1 + row), dtype=np.uint8)  # filter byte 0 per row
        raw[:, 1:] = rows
        parts.append(z.compress(raw.tobytes()))
    parts.append(z.flush())
    head = _chunk(
        b"IHDR", struct.pack(">IIBBBBB", w, h, bits, {1: 0, 2: 4, 3: 2, 4: 6}[c], 0, 0, 0)
    )
    if dpi is not None:
        ppm = int(round(float(dpi) / 0.0254))
        head += _chunk(b"pHYs", struct.pack(">IIB", ppm, ppm, 1))
    return SIGNATURE + head + _chunk(b"IDAT", b"".join(parts)) + _chunk(b"IEND", b"")


def png_header(
    path,
    max_side: int = MAX_PAPER_SIDE_PX,
    max_pixels: int = MAX_PAPER_PIXELS,
    any_kind: bool = False,
):
    """(width, height, colour type) from a PNG's header, checked, without reading the rest;
    ``any_kind``: a 16-bit or interlaced PNG passes too (its size is what is checked)."""
    try:
        with open(path, "rb") as f:
            head = f.read(33)
    except OSError as exc:
        raise PNGError(f"cannot read image {path}: {exc.strerror or exc}") from None
    return _ihdr(head, path, max_side, max_pixels, any_kind)


def _ihdr(head: bytes, path, max_side: int, max_pixels: int, any_kind: bool = False):
    if head[:8] != SIGNATURE:
        raise PNGError(f"{path}: not a PNG file")
    if len(head) < 33 or head[8:16] != b"\x00\x00\x00\rIHDR":
        raise PNGError(f"{path}: the PNG header (IHDR) is missing or truncated")
    if zlib.crc32(head[12:29]) != struct.unpack(">I", head[29:33])[0]:
        raise PNGError(f"{path}: the PNG header (IHDR) is damaged (CRC mismatch)")
    w, h, depth, ctype, comp, filt, interlace = struct.unpack(">IIBBBBB", head[16:29])
    if ctype not in CHANNELS:
        raise PNGError(f"{path}: PNG colour type {ctype} does not exist")
    if comp or filt:
        raise PNGError(f"{path}: unknown PNG compression or filter method")
    if not any_kind and (depth != 8 or interlace):
        raise PNGKindError(
            f"{path}: only 8-bit non-interlaced PNG is supported (this one: {depth}-bit"
            f"{', interlaced' if interlace else ''})"
        )
    if not (1 <= w <= max_side and 1 <= h <= max_side and w * h <= max_pixels):
        raise PNGError(
            f"{path}: image of {w} x {h} px is empty or too large (at most {max_side} px a side)"
        )
    return w, h, ctype


def _chunks(data: bytes, path):
    """(tag, body) of every chunk after the header, lengths and CRCs checked, up to IEND."""
    pos = 33
    while True:
        if pos + 12 > len(data):
            raise PNGError(f"{path}: the PNG file is truncated (no IEND chunk)")
        (n,) = struct.unpack(">I", data[pos : pos + 4])
        tag = data[pos + 4 : pos + 8]
        if pos + 12 + n > len(data):
            raise PNGError(f"{path}: the PNG file is truncated (in chunk {tag!r})")
        body = data[pos + 8 : pos + 8 + n]
        (crc,) = struct.unpack(">I", data[pos + 8 + n : pos + 12 + n])
        if zlib.crc32(tag + body) != crc:
            raise PNGError(f"{path}: PNG chunk {tag!r} is damaged (CRC mismatch)")
        if tag == b"IEND":
            return
        yield tag, body
        pos += 12 + n


def _inflate(idat, size: int, path) -> np.ndarray:
    """The image data, decompressed chunk by chunk to exactly ``size`` bytes and no more."""
    z = zlib.decompressobj()
    out = bytearray()
    try:
        for body in idat:
            out += z.decompress(body, size + 1 - len(out))
            if len(out) > size or z.unconsumed_tail:
                raise PNGError(f"{path}: the PNG holds more image data than its size needs")
    except zlib.error as exc:
        raise PNGError(f"{path}: the PNG's image data is damaged ({exc})") from None
    if len(out) < size:
        raise PNGError(f"{path}: the PNG's image data is truncated")
    return np.frombuffer(bytes(out), dtype=np.uint8)


def read_png(path, max_side: int = MAX_PAPER_SIDE_PX, max_pixels: int = MAX_PAPER_PIXELS):
    """Read an 8-bit, non-interlaced PNG into (H, W, C) uint8, top row first (a palette image
    as RGB). Raises PNGError on anything else, before any large work."""
    try:
        with open(path, "rb") as f:
            w, h, ctype = _ihdr(f.read(33), path, max_side, max_pixels)
            c = CHANNELS[ctype]
            size = h * (1 + w * c)
            if os.fstat(f.fileno()).st_size > 2 * size + METADATA_BYTES:
                raise PNGError(f"{path}: the PNG file is far larger than its image needs")
            f.seek(0)
            data = f.read()
    except OSError as exc:
        raise PNGError(f"cannot read image {path}: {exc.strerror or exc}") from None
    idat, palette = [], None
    for tag, body in _chunks(data, path):
        if tag == b"IDAT":
            idat.append(body)
        elif tag == b"PLTE":
            if len(body) % 3 or not 3 <= len(body) <= 768:
                raise PNGError(f"{path}: the PNG's palette (PLTE) is malformed")
            palette = np.frombuffer(body, dtype=np.uint8).reshape(-1, 3)
    if ctype == 3 and palette is None:
        raise PNGError(f"{path}: a palette PNG without its palette (PLTE)")
    raw = _inflate(idat, size, path).reshape(h, 1 + w * c)
    if raw[:, 0].max() > 4:
        raise PNGError(f"{path}: the PNG has an unknown row filter {int(raw[:, 0].max())}")
    img = _unfilter(raw, h, w, c)
    if ctype == 3:
        if img.max() >= len(palette):
            raise PNGError(f"{path}: a pixel's palette index lies beyond the palette")
        img = palette[img[..., 0]]
    return img


def _unfilter(raw: np.ndarray, h: int, w: int, c: int) -> np.ndarray:
    """Undo the rows' filters (None, Sub, Up, Average, Paeth): (H, W, C) uint8.

    A pixel depends on its left, upper and upper-left neighbours, so the pixels of one
    anti-diagonal (x + y constant) are independent: the image is decoded a diagonal at a time
    (h + w - 1 vector steps instead of h x w x c scalar ones)."""
    ft = raw[:, 0]
    data = raw[:, 1:].reshape(h, w, c)
    if not ft.any():
        return data.copy()
    out = np.zeros((h + 1, w + 1, c), dtype=np.uint8)  # a row and a column of zeros before
    for s in range(h + w - 1):
        ys = np.arange(max(0, s - w + 1), min(h, s + 1))
        xs = s - ys
        a = out[ys + 1, xs].astype(np.int16)  # left
        b = out[ys, xs + 1].astype(np.int16)  # up
        cc = out[ys, xs].astype(np.int16)  # up-left
        pa, pb, pc = np.abs(b - cc), np.abs(a - cc), np.abs(a + b - 2 * cc)
        paeth = np.where((pa <= pb) & (pa <= pc), a, np.where(pb <= pc, b, cc))
        f = ft[ys][:, None]
        pred = np.select([f == 1, f == 2, f == 3, f == 4], [a, b, (a + b) >> 1, paeth], default=0)
        out[ys + 1, xs + 1] = (data[ys, xs] + pred) & 255
    return out[1:, 1:]
