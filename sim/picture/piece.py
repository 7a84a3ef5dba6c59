# SPDX-License-Identifier: GPL-3.0-or-later
"""A piece of several characters: its characters found in the traditional reading order
(columns right to left, each top to bottom; ``piece_boxes``), each read on its own em box and
set in its own square of the sheet (``read_piece``)."""

from __future__ import annotations

import numpy as np

from ..image import morph as M
from ..writing.hanzi import MAX_STROKES
from ..writing.outline import EM, TOP
from .ink import Ink, PictureError
from .outline import read_strokes

PIECE_GAP = 0.02  # of the em box: a free band this wide may part two columns or characters
SQUARE = 1.25  # a character is at most this times as tall as its column is wide
NARROW = 0.5  # a column narrower than this share of the widest is part of its neighbour
PIECE_FILL = 0.8  # a character fills this share of its own square (as in a font's em box)


# ---------------------------------------------------------- a piece of several characters
def _runs(weight: np.ndarray, gap: int) -> list[tuple[int, int]]:
    """The inked runs of a projection, parted where it is free for ``gap`` or more."""
    inked = np.flatnonzero(weight > 0)
    if inked.size == 0:
        return []
    cut = np.flatnonzero(np.diff(inked) > gap)
    starts = np.concatenate([[inked[0]], inked[cut + 1]])
    ends = np.concatenate([inked[cut], [inked[-1]]]) + 1
    return [(int(a), int(b)) for a, b in zip(starts, ends, strict=True)]


def piece_boxes(mask: np.ndarray) -> list[tuple[int, int, int, int]]:
    """The characters of a piece, (y0, y1, x0, x1) each, in the traditional reading order:
    columns right to left (parted by free bands of PIECE_GAP; a column narrower than NARROW of
    the widest, such as a 亻 standing apart, is part of its neighbour), and in each column
    top to bottom: free bands part characters where the character above would otherwise grow
    taller than SQUARE times the column's width (三's gaps stay inside one character)."""
    gap = max(int(PIECE_GAP * mask.shape[0]), 2)
    cols = _runs(mask.sum(axis=0), gap)
    if not cols:
        return []
    widest = max(b - a for a, b in cols)
    merged: list[tuple[int, int]] = []
    for a, b in cols:
        if merged and min(b - a, merged[-1][1] - merged[-1][0]) < NARROW * widest:
            merged[-1] = (merged[-1][0], b)
        else:
            merged.append((a, b))
    boxes = []
    for x0, x1 in reversed(merged):
        chars: list[tuple[int, int]] = []
        for y0, y1 in _runs(mask[:, x0:x1].sum(axis=1), gap):
            if chars and y1 - chars[-1][0] <= SQUARE * (x1 - x0):
                chars[-1] = (chars[-1][0], y1)
            else:
                chars.append((y0, y1))
        boxes += [(y0, y1, x0, x1) for y0, y1 in chars]
    return boxes


def _character_ink(ink: Ink, box, n: int) -> Ink:
    """One character of a piece on its own n x n em box (filling PIECE_FILL of it): the
    piece's darkness round it resampled, thresholded as the piece's."""
    from .ink import _clean

    y0, y1, x0, x1 = box
    side = int(np.ceil(max(y1 - y0, x1 - x0) / PIECE_FILL))
    cy, cx = (y0 + y1) // 2, (x0 + x1) // 2
    dark = np.zeros((side, side))
    keep = np.zeros(ink.mask.shape, dtype=bool)
    keep[y0:y1, x0:x1] = True
    src = np.where(keep, ink.darkness, 0.0)
    ya, xa = cy - side // 2, cx - side // 2
    yb, xb = ya + side, xa + side
    H, W = src.shape
    dark[max(-ya, 0) : side - max(yb - H, 0), max(-xa, 0) : side - max(xb - W, 0)] = src[
        max(ya, 0) : min(yb, H), max(xa, 0) : min(xb, W)
    ]
    big = M.resize(dark, n, n)
    return Ink(_clean(big > ink.threshold), big, ink.threshold, ink.separation)


def _placed(char: dict, cell: tuple[float, float, float]) -> dict:
    """A character's data (its own em box) moved into a cell of the sheet's em box: (x, y of
    the cell's top left corner from the em box's top left, side), in data units."""
    import re

    x0, y0, k = cell[0], cell[1], cell[2] / EM

    def at(x: float, y: float) -> tuple[float, float]:
        return x0 + x * k, TOP - (y0 + (TOP - y) * k)

    def svg(path: str) -> str:
        def pair(m):
            x, y = at(float(m.group(1)), float(m.group(2)))
            return f"{x:.1f} {y:.1f}"

        return re.sub(r"(-?[\d.]+) (-?[\d.]+)", pair, path)

    return {
        "strokes": [svg(p) for p in char["strokes"]],
        "medians": [[[round(v, 1) for v in at(x, y)] for x, y in m] for m in char["medians"]],
    }


def read_piece(ink: Ink) -> tuple[list, list, dict] | None:
    """A piece of several characters (``piece_boxes``): each read on its own em box, then set
    in its own square of the sheet - columns right to left, top to bottom - and written in that
    order. None when the picture holds one character."""
    n = ink.mask.shape[0]
    boxes = piece_boxes(ink.mask)
    if len(boxes) < 2:
        return None
    col_of = {}
    for y0, y1, x0, x1 in boxes:
        col_of.setdefault((x0, x1), []).append((y0, y1))
    cols, rows = len(col_of), max(len(v) for v in col_of.values())
    side = EM / max(cols, rows)
    left, top = (EM - cols * side) / 2, (EM - rows * side) / 2
    strokes, regions, medians, outlines = [], [], [], []
    for c, (span, chars) in enumerate(col_of.items()):
        for r, (y0, y1) in enumerate(chars):
            s, reg, char = read_strokes(_character_ink(ink, (y0, y1, *span), n))
            placed = _placed(char, (left + (cols - 1 - c) * side, top + r * side, side))
            strokes += s
            regions += reg
            medians += placed["medians"]
            outlines += placed["strokes"]
    if len(outlines) > MAX_STROKES:
        raise PictureError(
            f"the piece's {len(boxes)} characters make {len(outlines)} strokes; at most "
            f"{MAX_STROKES} on one sheet"
        )
    return strokes, regions, {"strokes": outlines, "medians": medians}
