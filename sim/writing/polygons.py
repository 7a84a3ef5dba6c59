# SPDX-License-Identifier: GPL-3.0-or-later
"""Polygons of the stroke outlines (data units or image pixels): their edges, an even-odd fill
on a pixel grid, point-in-polygon, signed distance to the outline and the distance along a ray
to it, each worked in blocks that bound the memory, and the bands across a median they give
(its centres and widths, ``_bands``: ``outline`` reads the strokes with them)."""

from __future__ import annotations

import numpy as np

BLOCK_ELEMENTS = 1 << 20  # points x edges worked on at once (bounds the memory)


def _blocks(n: int, edges: int):
    """Slices of n rows, each of at most BLOCK_ELEMENTS rows x edges."""
    step = max(BLOCK_ELEMENTS // max(edges, 1), 1)
    for i in range(0, n, step):
        yield slice(i, min(i + step, n))


def _edges(polys):
    """Every edge of closed polygons as start and end points (E, 2) each."""
    a = np.concatenate(polys, axis=0)
    return a, np.concatenate([np.roll(p, -1, axis=0) for p in polys], axis=0)


def fill(polys_img, n: int) -> np.ndarray:
    """Even-odd fill of polygons given in image pixels: (n, n) bool, top row first; a pixel is
    inside when its centre is."""
    out = np.zeros((n, n + 1), dtype=np.int32)
    if not polys_img:
        return out[:, :n] > 0
    a, b = _edges(polys_img)
    for rows in _blocks(n, len(a)):
        _fill_rows(out, rows, a, b, n)
    return np.cumsum(out, axis=1)[:, :n] > 0


def _fill_rows(out, rows: slice, a, b, n: int) -> None:
    """The even-odd crossings of the given rows, as +1 / -1 at their columns in ``out``."""
    yc = np.arange(rows.start, rows.stop) + 0.5
    y0, y1 = a[:, 1], b[:, 1]
    crosses = (y0[None, :] <= yc[:, None]) != (y1[None, :] <= yc[:, None])  # (rows, E)
    dy = np.where(y1 != y0, y1 - y0, 1.0)
    x = a[None, :, 0] + (yc[:, None] - y0[None, :]) * ((b[:, 0] - a[:, 0]) / dy)[None, :]
    x = np.where(crosses, x, np.inf)
    x.sort(axis=1)
    k = crosses.sum(axis=1)
    r, idx = np.nonzero(np.arange(x.shape[1])[None, :] < k[:, None])
    col = np.clip(np.ceil(x[r, idx] - 0.5), 0, n).astype(np.int64)
    sign = np.where(idx % 2 == 0, 1, -1)
    np.add.at(out, (r + rows.start, col), sign)


def _inside(points, polys) -> np.ndarray:
    """Even-odd point-in-polygon for points (K, 2) against polygons (data units)."""
    a, b = _edges(polys)
    dy = np.where(b[:, 1] != a[:, 1], b[:, 1] - a[:, 1], 1.0)
    out = np.zeros(len(points), dtype=bool)
    for sl in _blocks(len(points), len(a)):
        px, py = points[sl, 0:1], points[sl, 1:2]
        cond = (a[None, :, 1] > py) != (b[None, :, 1] > py)
        xc = a[None, :, 0] + (py - a[None, :, 1]) * ((b[:, 0] - a[:, 0]) / dy)[None, :]
        out[sl] = (np.sum(cond & (px < xc), axis=1) % 2) == 1
    return out


def distance_to_outline(points, polys) -> np.ndarray:
    """Signed distance (data units) from points (K, 2) to a stroke's outline: positive inside."""
    pts = np.asarray(points, dtype=float)
    a, b = _edges(polys)
    ab = b - a
    L2 = np.maximum(np.sum(ab * ab, axis=1), 1e-12)
    d = np.empty(len(pts))
    for sl in _blocks(len(pts), len(a)):
        ap = pts[sl, None, :] - a[None, :, :]
        t = np.clip(np.sum(ap * ab[None], axis=2) / L2[None], 0.0, 1.0)
        d[sl] = np.sqrt(np.min(np.sum((ap - t[..., None] * ab[None]) ** 2, axis=2), axis=1))
    return np.where(_inside(pts, polys), d, -d)


def _ray_hits(points, dirs, polys) -> np.ndarray:
    """Distance from each point along its direction to the first outline edge (inf: none)."""
    a, b = _edges(polys)
    e = b - a  # (E, 2)
    out = np.empty(len(points))
    for sl in _blocks(len(points), len(a)):
        p, dr = points[sl], dirs[sl]
        ap = a[None, :, :] - p[:, None, :]  # (P, E, 2)
        den = dr[:, None, 0] * e[None, :, 1] - dr[:, None, 1] * e[None, :, 0]
        ok = np.abs(den) > 1e-12
        den = np.where(ok, den, 1.0)
        t = (ap[..., 0] * e[None, :, 1] - ap[..., 1] * e[None, :, 0]) / den
        u = (ap[..., 0] * dr[:, None, 1] - ap[..., 1] * dr[:, None, 0]) / den
        hit = ok & (t > 1e-9) & (u >= 0.0) & (u <= 1.0)
        out[sl] = np.where(hit, t, np.inf).min(axis=1)
    return out


CUT_OVER_DISC = 1.3  # a cut across the median longer than this many times the inscribed disc
# at its middle (diameter) runs along the stroke, as at a corner or the foot of a hook: there
# the width is held to this many times the disc's diameter and the median point is the centre
# (the "true discs" yardstick reads its radii off the same discs and reaches IoU 0.95)


def _bands(pts, polys) -> tuple[np.ndarray, np.ndarray]:
    """Centres and full widths along points of a median (data units): the outline is cut
    across the median's direction, the median point moved to the middle of the cut. A cut that
    runs along the stroke (at a corner or an end: longer than ``CUT_OVER_DISC`` times the
    diameter of the largest disc inside the outline at the cut's middle or the median point)
    gives way to that disc, on the median point."""
    r = np.maximum(distance_to_outline(pts, polys), 0.0)
    if len(pts) > 1:
        tan = np.gradient(pts, axis=0)
        tan /= np.maximum(np.linalg.norm(tan, axis=1, keepdims=True), 1e-9)
    else:
        tan = np.array([[1.0, 0.0]])
    nrm = np.stack([-tan[:, 1], tan[:, 0]], axis=1)
    left = np.minimum(_ray_hits(pts, nrm, polys), 3.0 * r)
    right = np.minimum(_ray_hits(pts, -nrm, polys), 3.0 * r)
    inside = r > 0
    left, right = np.where(inside, left, 0.0), np.where(inside, right, 0.0)
    cut = left + right
    centre = pts + (0.5 * (left - right))[:, None] * nrm
    disc = 2.0 * np.maximum(distance_to_outline(centre, polys), r)
    along = cut > CUT_OVER_DISC * disc  # the cut runs along the stroke: trust the disc
    centre = np.where(along[:, None], pts, centre)
    width = np.where(along, np.minimum(cut, CUT_OVER_DISC * disc), cut)
    # nor more than CUT_OVER_DISC times the disc where the band is centred (a foot's cut
    # slanting into a 折's outer corner)
    held = CUT_OVER_DISC * 2.0 * np.maximum(distance_to_outline(centre, polys), 0.0)
    return centre, np.minimum(width, held)
