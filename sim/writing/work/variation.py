# SPDX-License-Identifier: GPL-3.0-or-later
"""A character written twice in a work is not a copy of itself: each cell's character is varied
as a calligrapher's hand varies it - its size, its slant, the pressure (how full its strokes
are) and a little of its place - by seeded amounts within what one hand varies over a sheet.
The variation is applied to the stroke data (outlines and medians) before the writer writes it,
so the practice passes aim at the varied character.

The spread of each figure (model addition, not in the paper): measured by eye on classical
kaishu works, where one character's repeats differ by a few per cent in size, a degree or two
in slant and up to a tenth in stroke width, and stay on their column's axis."""

from __future__ import annotations

from typing import NamedTuple

import numpy as np

from ...core import exact
from ...core.exact import matmul
from ..outline import EM, TOP, parse_path

SIZE_SD = 0.025  # relative size, one standard deviation
SLANT_SD_DEG = 1.0  # turn of the character about its centre
WIDTH_SD = 0.05  # relative stroke width (the press)
SHIFT_ALONG_SD = 0.012  # place along the line, in em boxes
SHIFT_ACROSS_SD = 0.004  # across the line: the column stays straight
CLIP_SD = 2.0  # no draw beyond two standard deviations
CENTRE = np.array([EM / 2.0, TOP - EM / 2.0])  # the em box's centre in data units


class Variation(NamedTuple):
    scale: float = 1.0
    slant_deg: float = 0.0
    width: float = 1.0
    shift: tuple = (0.0, 0.0)  # (x, y) in em boxes

    def to_list(self) -> list:
        return [self.scale, self.slant_deg, self.width, *self.shift]


def draw(seed: int, cell_seed: int, vertical: bool, amount: float = 1.0) -> Variation:
    """The variation of a cell: seeded by the work's seed and the cell's own; ``amount`` scales
    every spread (0: none)."""
    rng = np.random.Generator(np.random.PCG64([int(seed), int(cell_seed), 0x7A71]))
    z = np.clip(rng.standard_normal(5), -CLIP_SD, CLIP_SD) * amount
    along, across = z[3] * SHIFT_ALONG_SD, z[4] * SHIFT_ACROSS_SD
    shift = (across, along) if vertical else (along, across)
    return Variation(
        float(1.0 + z[0] * SIZE_SD),
        float(z[1] * SLANT_SD_DEG),
        float(1.0 + z[2] * WIDTH_SD),
        (float(shift[0]), float(shift[1])),
    )


def _nearest_on(points, polyline) -> np.ndarray:
    """For each point (K, 2), the nearest point of the polyline (M, 2)."""
    a = polyline[:-1][None]
    ab = (polyline[1:] - polyline[:-1])[None]
    if ab.shape[1] == 0:
        return np.broadcast_to(polyline[0], points.shape).copy()
    ap = points[:, None, :] - a
    t = np.clip(np.sum(ap * ab, axis=2) / np.maximum(np.sum(ab * ab, axis=2), 1e-12), 0.0, 1.0)
    foot = a + t[..., None] * ab
    k = np.argmin(np.sum((points[:, None, :] - foot) ** 2, axis=2), axis=1)
    return foot[np.arange(len(points)), k]


def apply(char: dict, v: Variation) -> dict:
    """The character's stroke data varied by ``v``: outlines and medians scaled and turned about
    the em box's centre and shifted; each outline widened (or narrowed) about its own median."""
    th = np.radians(v.slant_deg)
    sin_t, cos_t = exact.sin_cos(th)
    rot = np.array([[cos_t, -sin_t], [sin_t, cos_t]]) * v.scale
    move = CENTRE + np.asarray(v.shift, dtype=float) * EM

    def place(p):
        return matmul((np.asarray(p, dtype=float) - CENTRE), rot.T) + move

    strokes, medians = [], []
    for path, med in zip(char["strokes"], char["medians"], strict=True):
        m = np.asarray(med, dtype=float)
        parts = []
        for poly in parse_path(path):
            foot = _nearest_on(poly, m)
            wide = foot + (poly - foot) * v.width
            pts = [f"{x:.1f} {y:.1f}" for x, y in place(wide)]
            parts.append("M " + pts[0] + " L " + " L ".join(pts[1:]) + " Z")
        strokes.append(" ".join(parts))
        medians.append([[round(float(x), 2), round(float(y), 2)] for x, y in place(m)])
    return {"strokes": strokes, "medians": medians}
