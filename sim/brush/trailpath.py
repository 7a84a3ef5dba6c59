# SPDX-License-Identifier: GPL-3.0-or-later
"""Signed distances of pixels from the hair's recent path (the trail of ``bristles``), fast.

``bristles.across`` gives every pixel of a step's marks its signed distance from the trail's
polyline: the nearest of its segments (the first of equals, its ends going on straight), the
distance to it, its sign by the side. Done plainly, every pixel is measured against every
segment, and a pixel under several primitives' marks once for each. Here the same numbers
come from less work (an addition for speed, not a change of the model):

- every pixel is measured once per step, however many marks cover it;
- the pixels are grouped into square tiles; a segment whose distance from the tile's centre,
  less the tile's reach, exceeds the smallest (distance + reach) of any segment by more than
  rounding can be nearest to none of the tile's pixels (the distance to a segment, or a ray,
  changes by at most the move of the point), so it is left out;
- every pixel is measured against the run of segments from the first to the last its tile
  keeps (the pixels with runs of about the same length together, the runs stopped at the last
  segment, where a segment measured twice is met first at its own place), and a few pixels
  against all segments: the same arithmetic, element by element, as against all segments, so
  the same nearest segment (a segment left out is farther than the nearest by more than
  rounding: never the first of equals) and the same distance, bit for bit."""

from __future__ import annotations

import numpy as np

TILE_MM = 0.5  # about the side of the tiles the segments are sorted out by
BLOCK_ELEMENTS = 1 << 16  # (pixel, segment) pairs measured at once
PLAIN_ELEMENTS = 1 << 14  # up to this many pairs, every pixel is measured against every segment
# how much farther than the nearest segment (mm, at unit scale) a segment must be to be left
# out: far above the rounding of a distance in float64 (about 1e-16 of the coordinates)
SLACK = 1e-9


def segments(path):
    """The polyline ``path`` (k, 2) as segments a + t d: (a, d, |d|^2 (at least 1e-12), and
    the bounds of t: [0, 1], the first going back without end and the last on ahead)."""
    a, d = path[:-1], np.diff(path, axis=0)
    dd = np.maximum(np.einsum("ij,ij->i", d, d), 1e-12)
    lo = np.zeros(len(a))
    hi = np.ones(len(a))
    lo[0], hi[-1] = -np.inf, np.inf
    return a, d, dd, lo, hi


def _measure(x, y, seg, s0, s1):
    """The plain measure of points (x, y) against segments s0..s1: (the nearest's index among
    them, the signed distance to it), float64."""
    a, d, dd, lo, hi = (v[s0:s1] for v in seg)
    rx = x[:, None] - a[None, :, 0]
    ry = y[:, None] - a[None, :, 1]
    t = np.clip((rx * d[:, 0] + ry * d[:, 1]) / dd, lo, hi)
    ex, ey = rx - t * d[:, 0], ry - t * d[:, 1]
    dist2 = ex * ex + ey * ey
    k = np.argmin(dist2, axis=1)
    rows = np.arange(k.size)
    side = d[k, 0] * ry[rows, k] - d[k, 1] * rx[rows, k]
    return k, np.sqrt(dist2[rows, k]) * np.where(side < 0, -1, 1)


def _measure_runs(x, y, seg, first, w, n_seg):
    """The plain measure of points (x, y), each against its own run of w segments from
    ``first`` (the runs cut at the last segment: a segment met twice is met at its first
    place, so the first of equals is the same); the same arithmetic as ``_measure``."""
    idx = np.minimum(first[:, None] + np.arange(w), n_seg - 1)
    a, d, dd, lo, hi = seg
    d0, d1 = d[idx, 0], d[idx, 1]
    rx = x[:, None] - a[idx, 0]
    ry = y[:, None] - a[idx, 1]
    t = np.clip((rx * d0 + ry * d1) / dd[idx], lo[idx], hi[idx])
    ex, ey = rx - t * d0, ry - t * d1
    dist2 = ex * ex + ey * ey
    k = np.argmin(dist2, axis=1)
    rows = np.arange(k.size)
    side = d0[rows, k] * ry[rows, k] - d1[rows, k] * rx[rows, k]
    return np.sqrt(dist2[rows, k]) * np.where(side < 0, -1, 1)


def signed_distances(path, rows, cols, ppm: float) -> np.ndarray:
    """float32 signed distance (mm) of the centres of pixels (rows, cols) of the paper (ints,
    repeats allowed) from the polyline ``path`` (k >= 2 points, mm): to the nearest point of
    the nearest segment (the first of equals; the first segment going back without end, the
    last on ahead), positive to the left of the way the path goes."""
    out = np.empty(rows.size, dtype=np.float32)
    if rows.size == 0:
        return out
    seg = segments(path)
    r0, c0 = int(rows.min()), int(cols.min())
    hb, wb = int(rows.max()) - r0 + 1, int(cols.max()) - c0 + 1
    key = (rows - r0).astype(np.int64) * wb + (cols - c0)
    if hb * wb <= 8 * rows.size + (1 << 20):  # each pixel once: a mask of the box
        seen = np.zeros(hb * wb, dtype=bool)
        seen[key] = True
        uniq = np.flatnonzero(seen)
        slot = np.cumsum(seen) - 1
        inverse = slot[key]
    else:  # marks far apart: sort instead
        uniq, inverse = np.unique(key, return_inverse=True)
    ur, uc = uniq // wb, uniq % wb
    x = (uc + c0 + 0.5) / ppm  # as (column + 0.5) / ppm: the same doubles
    y = (ur + r0 + 0.5) / ppm
    lat = np.empty(uniq.size)
    n_seg = len(seg[0])
    if uniq.size * n_seg <= PLAIN_ELEMENTS:  # few pixels: sorting out segments costs more
        _, lat = _measure(x, y, seg, 0, n_seg)
        out[:] = lat[inverse]
        return out
    lo_s, hi_s = _segment_ranges(seg, ur, uc, r0, c0, ppm, path)
    width = hi_s - lo_s
    w = 1
    while True:  # pixels by the length of their runs: those of up to w segments together
        sel = (
            np.flatnonzero((width <= w) & (width > w // 2)) if w > 1 else np.flatnonzero(width <= 1)
        )
        for at in range(0, sel.size, max(BLOCK_ELEMENTS // w, 1)):
            blk = sel[at : at + BLOCK_ELEMENTS // w]
            lat[blk] = _measure_runs(x[blk], y[blk], seg, lo_s[blk], w, n_seg)
        if w >= n_seg:
            break
        w *= 2
    out[:] = lat[inverse]
    return out


def _segment_ranges(seg, ur, uc, r0, c0, ppm, path):
    """For every pixel (rows ur, columns uc from (r0, c0)), the segments [lo, hi) that can be
    nearest to it: those its tile keeps (see the module's note), as one contiguous run."""
    n_seg = len(seg[0])
    ts = max(int(round(TILE_MM * ppm)), 4)  # tile side, pixels
    ty, tx = ur // ts, uc // ts
    ntx = int(tx.max()) + 1
    tid = ty * ntx + tx
    occupied = np.zeros((int(ty.max()) + 1) * ntx, dtype=bool)
    occupied[tid] = True
    tiles = np.flatnonzero(occupied)
    tslot = np.cumsum(occupied) - 1
    # the tiles' centres (mm) and reach: the farthest pixel centre of a whole tile
    cy = (r0 + (tiles // ntx) * ts + 0.5 * (ts - 1) + 0.5) / ppm
    cx = (c0 + (tiles % ntx) * ts + 0.5 * (ts - 1) + 0.5) / ppm
    reach = 0.5 * (ts - 1) * np.sqrt(2.0) / ppm
    a, d, dd, lo, hi = seg
    rx = cx[:, None] - a[None, :, 0]
    ry = cy[:, None] - a[None, :, 1]
    t = np.clip((rx * d[:, 0] + ry * d[:, 1]) / dd, lo, hi)
    dist = np.hypot(rx - t * d[:, 0], ry - t * d[:, 1])
    scale = 1.0 + float(np.abs(path).max()) + float(np.abs(cx).max()) + float(np.abs(cy).max())
    bound = (dist + reach).min(axis=1, keepdims=True) + SLACK * scale
    keep = dist - reach <= bound
    first = np.argmax(keep, axis=1)
    last = n_seg - np.argmax(keep[:, ::-1], axis=1)
    slot = tslot[tid]
    return first[slot], last[slot]
