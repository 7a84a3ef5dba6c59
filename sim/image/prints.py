# SPDX-License-Identifier: GPL-3.0-or-later
"""The paper (or its ink matte) at a chosen print size and DPI (issue 29.4), as PNG or TIFF with
the DPI in the file.

The ink density is resampled (``resample``: Mitchell-Netravali, widened when reducing), and the
picture made from the resampled density afterwards: the paper's colour x (1 - density), or the
matte (``matte``). Density is what the ink *is* (both the visible colour and the matte's
premultiplied colour, alpha - density, are linear in it), so a resampled matte has no fringes,
as resampling unpremultiplied colour would give. Done a band of output rows at a time: an A4
sheet at 600 dpi needs its output and a band of temporaries, not float copies of it."""

from __future__ import annotations

import os

import numpy as np

from .matte import ink_matte, mean_ink_colour
from .png import png_bytes
from .resample import resample_rows, weights
from .tiff import tiff_bytes

MM_PER_INCH = 25.4
MAX_PRINT_SIDE_PX = 30000  # a side of a print, in pixels (2.5 m at 300 dpi)
BAND_ROWS = 128
FORMATS = {".png": "PNG", ".tif": "TIFF", ".tiff": "TIFF"}


class PrintError(ValueError):
    """A print size, DPI, depth or file name that cannot be made (the message says which)."""


def print_size_px(width_mm: float, height_mm: float, dpi: float) -> tuple[int, int]:
    """(width, height) in pixels of a print of that size at that DPI."""
    if not (np.isfinite(dpi) and 1.0 <= dpi <= 10000.0):
        raise PrintError(f"DPI must lie in [1, 10000], got {dpi}")
    if not (np.isfinite(width_mm) and np.isfinite(height_mm) and width_mm > 0 and height_mm > 0):
        raise PrintError(f"a print of {width_mm} x {height_mm} mm has no size")
    w = max(1, int(round(width_mm / MM_PER_INCH * dpi)))
    h = max(1, int(round(height_mm / MM_PER_INCH * dpi)))
    if max(w, h) > MAX_PRINT_SIDE_PX:
        raise PrintError(
            f"a print of {width_mm:g} x {height_mm:g} mm at {dpi:g} dpi is {w} x {h} px: at "
            f"most {MAX_PRINT_SIDE_PX} px a side (lower the DPI or the size)"
        )
    return w, h


def print_image(
    paper, width_px: int, height_px: int, matte: bool = False, bits: int = 8, progress=None
):
    """The paper resampled to width_px x height_px, top row first: RGB (the paper as it shows)
    or straight-alpha RGBA (the ink matte), uint8 or uint16 (``bits``). ``paper``: a
    sim.paper.Paper, or anything with its ``ink`` (bottom row first) and ``color``;
    ``progress(fraction)`` is told how far it is, a band at a time."""
    if bits not in (8, 16):
        raise PrintError(f"a print has 8 or 16 bits a channel, not {bits}")
    ink = paper.ink[::-1]  # top row first, a view
    iy, wy = weights(ink.shape[0], height_px)
    ix, wx = weights(ink.shape[1], width_px)
    fill = mean_ink_colour(paper.ink) if matte else None
    top = (1 << bits) - 1
    out = np.empty((height_px, width_px, 4 if matte else 3), np.uint16 if bits == 16 else np.uint8)
    for y0 in range(0, height_px, BAND_ROWS):
        if progress is not None:
            progress(y0 / height_px)
        rows = iy[y0 : y0 + BAND_ROWS]
        lo, hi = int(rows.min()), int(rows.max()) + 1
        band = resample_rows(ink[lo:hi].astype(np.float32), rows - lo, wy[y0 : y0 + BAND_ROWS])
        band = np.moveaxis(resample_rows(np.moveaxis(band, 1, 0), ix, wx), 0, 1)
        density = np.clip(band, 0.0, 1.0)
        if matte:
            pic = ink_matte(density, fill)
        else:
            pic = _sheet(paper, band.shape, y0, height_px) * (1.0 - density)
        out[y0 : y0 + BAND_ROWS] = np.floor(pic * top + 0.5)
    return out


def _sheet(paper, shape, y0: int, height_px: int) -> np.ndarray:
    """The paper's colour at rows y0.. (top first) of a print ``height_px`` high (``shape``:
    the band's (rows, columns)): the sheet with its texture (``Paper.sheet``) made at the
    print's own resolution, so its clouds and fibres keep their size in millimetres; the flat
    colour for a paper without one."""
    if getattr(paper, "sheet", None) is None:
        return np.asarray(paper.color, np.float32)
    rows, cols = shape[0], shape[1]
    ppm = paper.ppm * height_px / paper.ink.shape[0]
    bottom = slice(height_px - y0 - rows, height_px - y0)  # paper rows count from the bottom
    return paper.sheet(bottom, slice(0, cols), ppm)[::-1]


def print_format(path) -> str:
    """'PNG' or 'TIFF', as the file's name says; PrintError for any other name."""
    fmt = FORMATS.get(os.path.splitext(str(path))[1].lower())
    if fmt is None:
        raise PrintError(f"{path}: a print is a .png, .tif or .tiff file")
    return fmt


def print_bytes(img, path, dpi: float) -> bytes:
    """The file's bytes in the format its name says (.png, .tif, .tiff), the DPI in it."""
    fmt = print_format(path)
    bits = 16 if img.dtype == np.uint16 else 8
    return png_bytes(img, bits=bits, dpi=dpi) if fmt == "PNG" else tiff_bytes(img, dpi)


def write_file(path, data: bytes):
    """Write all of ``data`` to ``path`` or nothing: into a temporary file beside it, then
    renamed over it (an existing file is never left half written)."""
    path = os.fspath(path)
    tmp = os.path.join(os.path.dirname(os.path.abspath(path)), f".{os.path.basename(path)}.part")
    try:
        with open(tmp, "wb") as f:
            f.write(data)
        os.replace(tmp, path)
    finally:
        if os.path.exists(tmp):
            os.remove(tmp)


def write_print(
    path, paper, width_mm: float, dpi: float, matte: bool = False, bits: int = 8, progress=None
) -> tuple[int, int]:
    """The paper (or its matte) printed width_mm wide (the height follows the paper's aspect)
    at ``dpi`` into ``path`` (.png or .tif); returns the size in pixels."""
    height_mm = width_mm * paper.ink.shape[0] / paper.ink.shape[1]
    w, h = print_size_px(width_mm, height_mm, dpi)
    print_format(path)  # the name is checked before the work
    img = print_image(paper, w, h, matte=matte, bits=bits, progress=progress)
    write_file(path, print_bytes(img, path, dpi))
    return w, h
