# SPDX-License-Identifier: GPL-3.0-or-later
"""What a work's image has besides the ink: the practice grid printed faintly in red on the
paper under each cell (米字格: border, centre cross and diagonals; 田字格: border and centre
cross; the inner lines dashed, as on practice sheets), and the seal stamped over the writing.
Both are drawn from the work's record in the recording (``work_image8``), so ``sim render``
and ``sim compose`` make the same image bit for bit; the ink itself is the paper's.

The grid is part of the paper (under the ink: the paper's colour times the grid's); the seal
paste lies over the ink (its colour times what is under it)."""

from __future__ import annotations

import math

import numpy as np

from ...image.png import to_uint8
from .seal import VERMILION, stamp

GRID_COLOR = (0.86, 0.28, 0.22)
GRID_ALPHA = 0.45  # the border's
INNER_ALPHA = 0.32  # the inner lines'
GRID_LINE = 0.011  # the border's width, share of the box (at least a pixel)
DASHES = 9  # dashes along an inner line


MAX_SEAL_PATH = 20_000  # characters of a seal glyph's stroke outline (as stroke data's)


def _seal_glyphs(glyphs) -> list[dict]:
    """The seal's glyphs as the recording keeps them ({"strokes": [SVG outline, ...]} each),
    checked: ParameterError names what is wrong."""
    from ...core.params import ParameterError
    from ..outline import parse_path
    from .seal import MAX_SEAL_CHARS

    ok = isinstance(glyphs, list) and len(glyphs) <= MAX_SEAL_CHARS
    for g in glyphs if ok else ():
        strokes = g.get("strokes") if isinstance(g, dict) else None
        ok = isinstance(strokes, list) and 0 < len(strokes) <= 64
        for path in strokes if ok else ():
            try:
                ok = ok and isinstance(path, str) and len(path) <= MAX_SEAL_PATH
                ok = ok and bool(parse_path(path))
            except ValueError:
                ok = False
    if not ok:
        raise ParameterError("'work.seal_glyphs' must be a list of {\"strokes\": [SVG path]}")
    return glyphs


class Overlay:
    """A work's grid and seal in pixels of a paper of ``width_px`` x ``height_px`` at ``ppm``
    (top row first)."""

    def __init__(self, work: dict, width_px: int, height_px: int, ppm: float, seed: int):
        from .layout import Layout

        lay = Layout.from_dict(work["layout"])
        self.W, self.H, self.ppm = width_px, height_px, ppm
        self.kind = lay.grid
        self.boxes = [self._px(b) for b in lay.grid_boxes()]
        self.seal = None
        seal = lay.seal
        if seal and work.get("seal_glyphs"):
            x0, y0, x1, y1 = self._px(seal["box"])
            side = x1 - x0
            alpha = stamp(_seal_glyphs(work["seal_glyphs"]), seal["style"], side, seed)
            n = alpha.shape[0]
            self.seal = (int(round((x0 + x1 - n) / 2)), int(round((y0 + y1 - n) / 2)), alpha)

    def _px(self, box) -> tuple[float, float, float, float]:
        """(x0, y0, x1, y1) mm, y up -> (left, top, right, bottom) in pixels, rows from the top."""
        x0, y0, x1, y1 = box
        p = self.ppm
        return x0 * p, self.H - y1 * p, x1 * p, self.H - y0 * p

    def apply(self, vis: np.ndarray, r0: int) -> np.ndarray:
        """``vis``: the visible colour of rows r0.. (top first), float32; the grid under, the
        seal over."""
        r1 = r0 + vis.shape[0]
        if self.boxes:
            a = np.zeros(vis.shape[:2], dtype=np.float32)
            for box in self.boxes:
                self._grid_box(a, box, r0, r1)
            vis = vis * (1.0 - a[..., None] * (1.0 - np.asarray(GRID_COLOR, np.float32)))
        if self.seal is not None:
            sx, sy, alpha = self.seal
            ya, yb = max(sy, r0), min(sy + alpha.shape[0], r1)
            xa, xb = max(sx, 0), min(sx + alpha.shape[1], self.W)
            if ya < yb and xa < xb:
                al = alpha[ya - sy : yb - sy, xa - sx : xb - sx, None]
                red = np.asarray(VERMILION, dtype=np.float32)
                vis[ya - r0 : yb - r0, xa:xb] *= 1.0 - al + al * red
        return vis

    def _grid_box(self, a: np.ndarray, box, r0: int, r1: int) -> None:
        """One grid box's lines into the band's alpha ``a`` (rows r0..r1), as the larger alpha."""
        left, top, right, bottom = box
        side = right - left
        w_out = max(GRID_LINE * side, 1.0)
        w_in = max(0.7 * w_out, 0.8)
        reach = w_out
        ya, yb = max(int(math.floor(top - reach)), r0), min(int(math.ceil(bottom + reach)), r1)
        xa, xb = max(int(math.floor(left - reach)), 0), min(int(math.ceil(right + reach)), self.W)
        if ya >= yb or xa >= xb:
            return
        y = (np.arange(ya, yb, dtype=np.float64) + 0.5)[:, None]
        x = (np.arange(xa, xb, dtype=np.float64) + 0.5)[None, :]
        u, v = (x - left) / side, (y - top) / side
        outside = np.hypot(
            np.maximum(np.maximum(-u, u - 1), 0), np.maximum(np.maximum(-v, v - 1), 0)
        )
        inside = np.minimum(np.minimum(u, 1 - u), np.minimum(v, 1 - v))
        d = np.where(outside > 0, outside, inside) * side
        alpha = GRID_ALPHA * np.clip(w_out / 2 - d + 0.5, 0, 1)
        inner = [(np.abs(u - 0.5) * side, v), (np.abs(v - 0.5) * side, u)]
        if self.kind == "mi":
            inner += [
                (np.abs(u - v) * side / math.sqrt(2), u),
                (np.abs(u + v - 1) * side / 2**0.5, u),
            ]
        within = (u > 0) & (u < 1) & (v > 0) & (v < 1)
        for dist, t in inner:
            dash = np.mod(t * DASHES, 1.0) < 0.55
            line = INNER_ALPHA * np.clip(w_in / 2 - dist + 0.5, 0, 1)
            alpha = np.maximum(alpha, np.where(within & dash, line, 0.0))
        sub = a[ya - r0 : yb - r0, xa:xb]
        np.maximum(sub, alpha.astype(np.float32), out=sub)


def work_image8(paper, work: dict | None, seed: int, chunk_rows: int = 256) -> np.ndarray:
    """The image of a paper (``sim.paper.Paper``) with its work's grid and seal: RGB uint8,
    (H, W, 3), top row first, made a band of rows at a time. Without a work (or one with
    neither) it is the paper's own image."""
    over = None
    if work is not None:
        over = Overlay(work, paper.W, paper.H, paper.ppm, seed)
        if not over.boxes and over.seal is None:
            over = None
    if over is None:
        return paper.rgb8(chunk_rows)
    out = np.empty((paper.H, paper.W, 3), dtype=np.uint8)
    for y0 in range(0, paper.H, chunk_rows):
        y1 = min(y0 + chunk_rows, paper.H)
        rows = slice(paper.H - y1, paper.H - y0)
        band = paper.visible(paper.ink[rows], rows, slice(0, paper.W))[::-1]
        out[y0:y1] = to_uint8(over.apply(band, y0))
    return out
