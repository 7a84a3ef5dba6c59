# SPDX-License-Identifier: GPL-3.0-or-later
"""The image an artist sees, kept in the layout of a Blender image's pixels (RGBA float32, rows
bottom first) and brought up to date from the tiles the paper changed since the last refresh, so
a refresh costs what changed, not the paper's size.

A Blender image holds either 8-bit sRGB-encoded colour or linear float colour. The paper's
visible colour (``Paper.rgb``) is sRGB-encoded, as an image file's bytes are; for a float image it
is decoded to linear light through a table of SRGB_LEVELS steps (finer than the 8-bit image it
replaces), so both kinds show the same colour.
"""

from __future__ import annotations

import numpy as np

from .paper import Paper

SRGB_LEVELS = 4096  # steps of the sRGB -> linear table
BLANK_ROWS = 64  # rows of the blank sheet made at a time (a row of the paper's tiles)


def srgb_to_linear(v) -> np.ndarray:
    """The sRGB transfer function's inverse (IEC 61966-2-1), exact."""
    v = np.asarray(v, dtype=np.float64)
    return np.where(v <= 0.04045, v / 12.92, ((v + 0.055) / 1.055) ** 2.4)


def linear_to_srgb(v) -> np.ndarray:
    v = np.clip(np.asarray(v, dtype=np.float64), 0.0, 1.0)
    return np.where(v <= 0.0031308, v * 12.92, 1.055 * v ** (1 / 2.4) - 0.055)


_TO_LINEAR = srgb_to_linear(np.arange(SRGB_LEVELS) / (SRGB_LEVELS - 1)).astype(np.float32)


def encode(rgb, linear: bool) -> np.ndarray:
    """Visible sRGB colour as the image stores it: itself (8-bit image) or linear (float)."""
    rgb = np.asarray(rgb, dtype=np.float32)
    if not linear:
        return rgb
    idx = np.rint(rgb * np.float32(SRGB_LEVELS - 1)).astype(np.int16)
    return np.take(_TO_LINEAR, idx)


class PaperView:
    """RGBA pixels of a paper, bottom row first, refreshed tile by tile."""

    def __init__(self, linear: bool):
        self.linear = bool(linear)
        self.pixels = None  # (H, W, 4) float32
        self._paper = None
        self._version = -1

    def refresh(self, paper: Paper) -> int:
        """Bring the pixels up to ``paper``; returns the number of pixels rewritten."""
        if self._paper is not paper or self.pixels is None or self.pixels.shape[:2] != paper.shape:
            # a whole refresh: the blank paper's colour, then every tile that ever changed
            if self.pixels is None or self.pixels.shape[:2] != paper.shape:
                self.pixels = np.empty(paper.shape + (4,), dtype=np.float32)
            for y0 in range(0, paper.H, BLANK_ROWS):  # the blank sheet, a band of rows at a time
                ys = slice(y0, min(y0 + BLANK_ROWS, paper.H))
                blank = paper.visible(np.zeros(3, np.float32), ys, slice(0, paper.W))
                self.pixels[ys, :, :3] = encode(blank, self.linear)  # (its tiles' tone is kept)
            self.pixels[..., 3] = 1.0
            self._paper, self._version = paper, 0
        rows = _row_runs(paper.tiles_since(self._version))
        done = 0
        for ty, tx0, tx1 in rows:
            ys = paper.tile_box(ty, tx0)[0]
            xs = slice(paper.tile_box(ty, tx0)[1].start, paper.tile_box(ty, tx1)[1].stop)
            self.pixels[ys, xs, :3] = encode(paper.visible(paper.ink[ys, xs], ys, xs), self.linear)
            done += (ys.stop - ys.start) * (xs.stop - xs.start)
        self._version = paper.version
        return done

    def flat(self) -> np.ndarray:
        """The pixels as one flat array (a view), as ``Image.pixels.foreach_set`` takes them."""
        return self.pixels.reshape(-1)


def _row_runs(tiles: np.ndarray) -> list[tuple[int, int, int]]:
    """(tile row, first column, last column) of each row's changed tiles: one slice a row."""
    if tiles.size == 0:
        return []
    out = []
    for ty in np.unique(tiles[:, 0]):
        cols = tiles[tiles[:, 0] == ty, 1]
        out.append((int(ty), int(cols.min()), int(cols.max())))
    return out
