# SPDX-License-Identifier: GPL-3.0-or-later
"""Punctuation marks as stroke data, for ``--punctuation keep``: each mark a few strokes (a
median and its half-width, in a unit cell u right, v up) placed as a calligrapher places them -
small marks (，。、) in a corner of their cell (lower left in a row, upper right in a column),
brackets, dashes and ellipses turned upright in a column - and outlined as capsules, so that the
writer writes them with the brush like any character."""

from __future__ import annotations

import numpy as np

from ...core import exact
from ..outline import EM, TOP

DOT = 0.045  # half-width of a dot, in cells
LINE = 0.028  # half-width of a bracket's or a dash's line


def _arc(cu, cv, r, a0, a1, n=12):
    t = np.radians(np.linspace(a0, a1, n))
    return [(cu + r * exact.cos(a), cv + r * exact.sin(a)) for a in t]


# mark: (placement, [(median points in the unit cell, half-width), ...]) as written in a row;
# placement "corner": moved to the upper right in a column; "turn": turned upright in a column;
# "centre": moved to the cell's middle column in a column
_HOOK = ((0.2, 0.7), (0.3, 0.83), (0.45, 0.8), (0.47, 0.65), (0.36, 0.52), (0.34, 0.38))
_WAVE = tuple(_arc(0.3, 0.4, 0.2, 160, 20, 8)) + tuple(_arc(0.7, 0.6, 0.2, 200, 340, 8))


def _chevron(u, sign):
    """An angle bracket's line from the top at u to its point (toward +u for sign 1)."""
    return ((u, 0.9), (u + sign * 0.35, 0.5), (u, 0.1))


_COMMA = [((0.17, 0.19), (0.175, 0.15), (0.14, 0.07)), DOT]
_SHAPES = {
    "，": ("corner", [_COMMA]),
    "、": ("corner", [(((0.12, 0.19), (0.19, 0.12)), DOT)]),
    "。": ("corner", [(tuple(_arc(0.18, 0.16, 0.075, 90, 450, 20)), 0.022)]),
    "．": ("corner", [(((0.18, 0.14),), DOT)]),
    "：": ("centre", [(((0.25, 0.6),), DOT), (((0.25, 0.28),), DOT)]),
    "；": ("centre", [(((0.25, 0.6),), DOT), [((0.25, 0.3), (0.255, 0.26), (0.22, 0.18)), DOT]]),
    "！": ("centre", [(((0.3, 0.86), (0.3, 0.38)), 0.04), (((0.3, 0.18),), DOT)]),
    "？": (
        "centre",
        [
            (_HOOK, 0.03),
            (((0.34, 0.18),), DOT),
        ],
    ),
    "「": ("turn", [(((0.88, 0.9), (0.58, 0.9), (0.58, 0.42)), LINE)]),
    "」": ("turn", [(((0.42, 0.58), (0.42, 0.1), (0.12, 0.1)), LINE)]),
    "『": (
        "turn",
        [
            (((0.9, 0.92), (0.55, 0.92), (0.55, 0.4)), LINE),
            (((0.9, 0.8), (0.67, 0.8), (0.67, 0.4)), LINE),
        ],
    ),
    "』": (
        "turn",
        [
            (((0.45, 0.6), (0.45, 0.08), (0.1, 0.08)), LINE),
            (((0.33, 0.6), (0.33, 0.2), (0.1, 0.2)), LINE),
        ],
    ),
    "（": ("turn", [(tuple(_arc(1.05, 0.5, 0.48, 125, 235)), LINE)]),
    "）": ("turn", [(tuple(_arc(-0.05, 0.5, 0.48, 55, -55)), LINE)]),
    "〈": ("turn", [(((0.75, 0.9), (0.4, 0.5), (0.75, 0.1)), LINE)]),
    "〉": ("turn", [(((0.25, 0.9), (0.6, 0.5), (0.25, 0.1)), LINE)]),
    "《": (
        "turn",
        [(_chevron(0.68, -1), LINE), (_chevron(0.88, -1), LINE)],
    ),
    "》": (
        "turn",
        [(_chevron(0.32, 1), LINE), (_chevron(0.12, 1), LINE)],
    ),
    "…": ("turn", [(((u, 0.5),), 0.035) for u in (0.2, 0.5, 0.8)]),
    "—": ("turn", [(((0.04, 0.5), (0.96, 0.5)), LINE)]),
    "·": ("centre", [(((0.5, 0.5),), 0.04)]),
    "～": ("turn", [(_WAVE, LINE)]),
}
# marks written as another one: ASCII and full-width forms, quotes as the corner brackets
# of Chinese text
_SAME = {
    ",": "，",
    "﹐": "，",
    "､": "、",
    ".": "．",
    "｡": "。",
    ":": "：",
    ";": "；",
    "!": "！",
    "?": "？",
    "“": "「",
    "”": "」",
    "‘": "『",
    "’": "』",
    "﹁": "「",
    "﹂": "」",
    "﹃": "『",
    "﹄": "』",
    "(": "（",
    ")": "）",
    "<": "〈",
    ">": "〉",
    "‥": "…",
    "⋯": "…",
    "–": "—",
    "―": "—",
    "・": "·",
    "•": "·",
    "~": "～",
}
MARKS = frozenset(_SHAPES) | frozenset(_SAME)


def _place(pts, placement: str, vertical: bool):
    p = np.asarray(pts, dtype=float)
    if not vertical:
        return p
    if placement == "corner":
        return p + 0.64
    if placement == "centre":
        return p + [0.5 - 0.3, 0.0]
    if placement == "turn":  # a quarter turn clockwise about the cell's centre
        return np.stack([p[:, 1], 1.0 - p[:, 0]], axis=1)
    return p


def _capsule(median, r: float, n: int = 10) -> list[np.ndarray]:
    """Outline polygons (unit cell) of a stroke of half-width r along ``median``: a disc for a
    dot, a ring for a closed median, else the two offsets joined by round caps."""
    m = np.asarray(median, dtype=float)
    if len(m) == 1 or np.ptp(m, axis=0).max() < 1e-9:
        return [np.array(_arc(m[0, 0], m[0, 1], r, 0, 360, 4 * n)[:-1])]
    if np.allclose(m[0], m[-1]):  # a ring: outer and inner circles (even-odd fill)
        c = m[:-1].mean(axis=0)
        rad = float(np.linalg.norm(m[:-1] - c, axis=1).mean())
        outer = np.array(_arc(c[0], c[1], rad + r, 0, 360, 4 * n)[:-1])
        inner = np.array(_arc(c[0], c[1], max(rad - r, 1e-3), 0, 360, 4 * n)[:-1])
        return [outer, inner[::-1]]
    d = np.gradient(m, axis=0)
    d /= np.maximum(np.linalg.norm(d, axis=1, keepdims=True), 1e-12)
    nrm = np.stack([-d[:, 1], d[:, 0]], axis=1)
    left, right = m + r * nrm, m - r * nrm
    a_end = np.degrees(exact.arctan2(nrm[-1, 1], nrm[-1, 0]))
    a_start = np.degrees(exact.arctan2(-nrm[0, 1], -nrm[0, 0]))
    end_cap = _arc(m[-1, 0], m[-1, 1], r, a_end, a_end - 180, n)[1:-1]
    start_cap = _arc(m[0, 0], m[0, 1], r, a_start, a_start - 180, n)[1:-1]
    return [np.concatenate([left, end_cap, right[::-1], start_cap])]


def _to_data(p) -> np.ndarray:
    """Unit cell (u right, v up) -> the 1024-unit em box of the stroke data (y up)."""
    p = np.asarray(p, dtype=float)
    return np.stack([p[:, 0] * EM, (TOP - EM) + p[:, 1] * EM], axis=1)


def _svg(polys) -> str:
    parts = []
    for poly in polys:
        pts = [f"{x:.1f} {y:.1f}" for x, y in _to_data(poly)]
        parts.append("M " + pts[0] + " L " + " L ".join(pts[1:]) + " Z")
    return " ".join(parts)


def mark_char(mark: str, vertical: bool) -> dict:
    """The stroke data of a punctuation mark (hanzi-writer's form: 'strokes' as SVG outlines,
    'medians'), placed for a row or a column. KeyError for a mark without a shape."""
    placement, strokes = _SHAPES[_SAME.get(mark, mark)]
    outlines, medians = [], []
    for median, r in strokes:
        m = _place(median, placement, vertical)
        outlines.append(_svg(_capsule(m, r)))
        medians.append([[round(float(x), 1), round(float(y), 1)] for x, y in _to_data(m)])
    return {"strokes": outlines, "medians": medians}
