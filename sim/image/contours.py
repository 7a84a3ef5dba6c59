# SPDX-License-Identifier: GPL-3.0-or-later
"""Closed contours of a grey image at a level (issue 29.4: the ink's outline for cutters and
engravers): marching squares with the crossings interpolated along the pixel edges, saddles
decided by the cell's mean, every segment directed with the inside on its left (so outer
outlines and holes run opposite ways), linked into loops; then simplified (Ramer-Douglas-Peucker)
and measured. numpy only; the linking walks the segments once."""

from __future__ import annotations

import numpy as np

# corners of a cell, in (x, y) with y down: tl, tr, br, bl; a case's bit for each
_CORNERS = np.array([(0.0, 0.0), (1.0, 0.0), (1.0, 1.0), (0.0, 1.0)])
_BITS = (8, 4, 2, 1)
# edges: T (tl-tr), R (tr-br), B (bl-br), L (tl-bl); their midpoints
_MID = {"T": (0.5, 0.0), "R": (1.0, 0.5), "B": (0.5, 1.0), "L": (0.0, 0.5)}
# the unoriented segments of each case; saddles (5, 10) by whether the centre is inside
_SEGMENTS = {
    1: ["LB"],
    2: ["BR"],
    3: ["LR"],
    4: ["TR"],
    6: ["TB"],
    7: ["TL"],
    8: ["TL"],
    9: ["TB"],
    11: ["TR"],
    12: ["LR"],
    13: ["BR"],
    14: ["LB"],
    (5, True): ["TL", "BR"],
    (5, False): ["TR", "LB"],
    (10, True): ["TR", "LB"],
    (10, False): ["TL", "BR"],
}


def _oriented(case: int, seg: str) -> tuple[str, str]:
    """The segment directed so that the inside lies on its left (cross product > 0 in x right,
    y down), judged by the corner it cuts off alone, or by its side's corners."""
    p, q = np.array(_MID[seg[0]]), np.array(_MID[seg[1]])
    inside = [bool(case & b) for b in _BITS]
    side = [np.cross(q - p, c - p) > 0 for c in _CORNERS]
    left = [i for i in range(4) if side[i]]
    right = [i for i in range(4) if not side[i]]
    lone = left if len(left) == 1 else right if len(right) == 1 else left
    lone_inside = inside[lone[0]]
    inside_is_left = lone_inside == (lone is left)
    return (seg[0], seg[1]) if inside_is_left else (seg[1], seg[0])


_TABLE = {key: [_oriented(key if isinstance(key, int) else key[0], s) for s in segs]
          for key, segs in _SEGMENTS.items()}  # fmt: skip


def trace(field, level: float) -> list[np.ndarray]:
    """The closed contours of ``field >= level`` (H, W), as (N, 2) arrays of (x, y) in pixel
    coordinates (pixel centres at integers, y down the rows), the inside on the left of the
    way round: the image is taken as surrounded by outside."""
    f = np.asarray(field, dtype=np.float64)
    h, w = f.shape
    g = np.full((h + 2, w + 2), level - 1.0)
    g[1:-1, 1:-1] = f
    inside = g >= level
    case = inside[:-1, :-1] * 8 + inside[:-1, 1:] * 4 + inside[1:, 1:] * 2 + inside[1:, :-1] * 1
    n_h = (h + 2) * (w + 1)  # horizontal edges come first in the edge numbering

    def edge_ids(i, j, edge):
        return {
            "T": i * (w + 1) + j,
            "B": (i + 1) * (w + 1) + j,
            "L": n_h + i * (w + 2) + j,
            "R": n_h + i * (w + 2) + j + 1,
        }[edge]

    starts, ends = [], []
    centre = (g[:-1, :-1] + g[:-1, 1:] + g[1:, 1:] + g[1:, :-1]) / 4 >= level
    for key, segs in _TABLE.items():
        c = key if isinstance(key, int) else key[0]
        sel = case == c
        if not isinstance(key, int):
            sel &= centre == key[1]
        i, j = np.nonzero(sel)
        for a, b in segs:
            starts.append(edge_ids(i, j, a))
            ends.append(edge_ids(i, j, b))
    if not starts:
        return []
    start, end = np.concatenate(starts), np.concatenate(ends)
    xy = _crossings(g, level, w, n_h, start)
    order = np.argsort(start)
    nxt = order[np.searchsorted(start[order], end)]  # the segment that starts where s ends
    return [xy[loop] for loop in _loops(nxt)]


def _crossings(g, level, w, n_h, edges) -> np.ndarray:
    """(x, y) where the level crosses each edge (image pixel coordinates)."""
    horiz = edges < n_h
    i = np.where(horiz, edges // (w + 1), (edges - n_h) // (w + 2))
    j = np.where(horiz, edges % (w + 1), (edges - n_h) % (w + 2))
    a = g[i, j]
    b = np.where(horiz, g[i, np.minimum(j + 1, w + 1)], g[np.minimum(i + 1, g.shape[0] - 1), j])
    t = np.clip((level - a) / np.where(b != a, b - a, 1.0), 0.0, 1.0)
    x = j - 1.0 + np.where(horiz, t, 0.0)
    y = i - 1.0 + np.where(horiz, 0.0, t)
    return np.stack([x, y], axis=1)


def _loops(nxt: np.ndarray) -> list[np.ndarray]:
    """The cycles of the permutation ``nxt`` (each segment's successor), as index arrays."""
    seen = np.zeros(len(nxt), bool)
    out = []
    nxt_list = nxt.tolist()
    for s0 in range(len(nxt)):
        if seen[s0]:
            continue
        loop, s = [], s0
        while not seen[s]:
            seen[s] = True
            loop.append(s)
            s = nxt_list[s]
        out.append(np.array(loop))
    return out


def area(loop: np.ndarray) -> float:
    """The signed area of a closed polygon (shoelace); positive for the inside on the left in
    x right, y down (an outer outline of ``trace``), negative for a hole."""
    x, y = loop[:, 0], loop[:, 1]
    return float(0.5 * (np.add.reduce(x * np.roll(y, -1)) - np.add.reduce(y * np.roll(x, -1))))


def simplify(loop: np.ndarray, tol: float) -> np.ndarray:
    """A closed polygon with the points dropped that lie within ``tol`` of the line between the
    points kept around them (Ramer-Douglas-Peucker, from the two points farthest apart)."""
    n = len(loop)
    if n <= 4:
        return loop
    far = int(np.argmax(np.sum((loop - loop[0]) ** 2, axis=1)))
    keep = np.zeros(n, bool)
    keep[[0, far]] = True
    ring = np.r_[np.arange(n), 0]
    stack = [(0, far), (far, n)]
    while stack:
        a, b = stack.pop()
        if b - a < 2:
            continue
        p, q = loop[ring[a]], loop[ring[b]]
        mid = loop[ring[a + 1 : b]]
        d = q - p
        ln = np.hypot(*d)
        if ln > 0:
            dist = np.abs(d[0] * (mid[:, 1] - p[1]) - d[1] * (mid[:, 0] - p[0])) / ln
        else:
            dist = np.hypot(mid[:, 0] - p[0], mid[:, 1] - p[1])
        k = int(np.argmax(dist))
        if dist[k] > tol:
            m = a + 1 + k
            keep[ring[m]] = True
            stack += [(a, m), (m, b)]
    return loop[keep]
