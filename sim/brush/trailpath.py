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
  rounding: never the first of equals) and the same distance, bit for bit;
- many steps' pixels, each step with its own path, are measured together
  (``signed_distances_many``): every pixel against its own step's segments, in one pass of
  numpy calls instead of one per step (issue 28), the same numbers as step by step."""

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


def _clip_t(raw, at_first, at_last, seg):
    """``raw`` clipped to the bounds of t of its segments: [0, 1], but at ``at_first`` and
    ``at_last`` (indices into raw: the elements of the first and the last segment) the rays'
    bounds; as np.clip with the bounds of every element (the same comparisons; np.clip with
    bounds that are one number runs faster than with an array of them)."""
    lo, hi = seg[3], seg[4]
    t = np.clip(raw, 0.0, 1.0)
    t[at_first] = np.clip(raw[at_first], lo[0], hi[0])
    t[at_last] = np.clip(raw[at_last], lo[-1], hi[-1])
    return t


def _measure(x, y, seg, s0, s1):
    """The plain measure of points (x, y) against segments s0..s1: (the nearest's index among
    them, the signed distance to it), float64."""
    a, d, dd = (v[s0:s1] for v in seg[:3])
    rx = x[:, None] - a[None, :, 0]
    ry = y[:, None] - a[None, :, 1]
    n_seg = len(seg[0])
    cols = (
        (slice(None), slice(0, 1 if s0 == 0 else 0)),
        (slice(None), slice(n_seg - 1 - s0, s1 - s0)),
    )
    t = _clip_t((rx * d[:, 0] + ry * d[:, 1]) / dd, *cols, seg)
    ex, ey = rx - t * d[:, 0], ry - t * d[:, 1]
    dist2 = ex * ex + ey * ey
    k = np.argmin(dist2, axis=1)
    rows = np.arange(k.size)
    side = d[k, 0] * ry[rows, k] - d[k, 1] * rx[rows, k]
    return k, np.sqrt(dist2[rows, k]) * np.where(side < 0, -1, 1)


def _measure_runs(x, y, seg, first, width):
    """The plain measure of points (x, y), each against its own run of ``width`` segments from
    ``first``: the same arithmetic as ``_measure`` on every (point, segment) pair, and the
    first of the nearest in each run (as np.argmin over all segments)."""
    n = width.size
    start = np.cumsum(width) - width  # every point's first pair
    pt = np.repeat(np.arange(n), width)
    idx = np.arange(pt.size) + np.repeat(first - start, width)  # the pair's segment
    a, d, dd = seg[:3]
    d0, d1 = d[idx, 0], d[idx, 1]
    rx = x[pt] - a[idx, 0]
    ry = y[pt] - a[idx, 1]
    ends = start + width - 1
    at = start[first == 0], ends[first + width == len(seg[0])]  # the rays' pairs
    t = _clip_t((rx * d0 + ry * d1) / dd[idx], *at, seg)
    ex, ey = rx - t * d0, ry - t * d1
    dist2 = ex * ex + ey * ey
    best = np.minimum.reduceat(dist2, start)
    hit = np.flatnonzero(dist2 == np.repeat(best, width))
    k = hit[np.r_[True, pt[hit[1:]] != pt[hit[:-1]]]]  # the first nearest pair of each point
    side = d0[k] * ry[k] - d1[k] * rx[k]
    return np.sqrt(dist2[k]) * np.where(side < 0, -1, 1)


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
    uniq, inverse = _each_once(key, hb * wb)
    ur, uc = uniq // wb, uniq % wb
    x = (uc + c0 + 0.5) / ppm  # as (column + 0.5) / ppm: the same doubles
    y = (ur + r0 + 0.5) / ppm
    n_seg = len(seg[0])
    if uniq.size * n_seg <= PLAIN_ELEMENTS:  # few pixels: sorting out segments costs more
        _, lat = _measure(x, y, seg, 0, n_seg)
        out[:] = lat[inverse]
        return out
    lo_s, hi_s = _segment_ranges(seg, ur, uc, r0, c0, ppm, path)
    out[:] = _in_blocks(_measure_runs, x, y, seg, lo_s, hi_s - lo_s)[inverse]
    return out


def _each_once(key, size: int):
    """The distinct ``key``s (ints in [0, size)) ascending and where each key is among them:
    through a mask of the box when it is not too large for the keys, else by sorting."""
    if size <= 8 * key.size + (1 << 20):
        seen = np.zeros(size, dtype=bool)
        seen[key] = True
        return np.flatnonzero(seen), (np.cumsum(seen) - 1)[key]
    return np.unique(key, return_inverse=True)


def _in_blocks(measure, x, y, seg, first, width) -> np.ndarray:
    """``measure(x, y, seg, first, width)`` of the points in blocks of about BLOCK_ELEMENTS
    (point, segment) pairs (point i against ``width[i]`` segments from ``first[i]``)."""
    lat = np.empty(x.size)
    ends = np.cumsum(width)
    at = 0
    while at < x.size:
        stop = max(int(np.searchsorted(ends, ends[at] - width[at] + BLOCK_ELEMENTS)), at + 1)
        blk = slice(at, stop)
        lat[blk] = measure(x[blk], y[blk], seg, first[blk], width[blk])
        at = stop
    return lat


def signed_distances_many(paths, owner, rows, cols, ppm: float) -> np.ndarray:
    """``signed_distances`` of pixels of many steps at once, bit for bit as step by step:
    pixel i (rows[i], cols[i]) is measured from the polyline ``paths[owner[i]]`` (each of
    k >= 2 points, mm). Every step's pixels are taken once each; the segments of all paths
    are one table, each with its bounds of t (a path's first segment a ray going back, its
    last one going on ahead), so each pixel is measured against a run of its own path's
    segments (those its tile can have nearest, see the module's note)."""
    out = np.empty(rows.size, dtype=np.float32)
    if rows.size == 0:
        return out
    parts = [segments(np.asarray(p, dtype=float)) for p in paths]
    n_seg = np.array([len(p[0]) for p in parts])
    seg_at = np.cumsum(n_seg) - n_seg  # every path's first segment in the table
    seg = tuple(np.concatenate(f) for f in zip(*parts, strict=True))
    # every step's pixels in a box of its own (as step by step), the boxes one after another
    box = _boxes(owner, rows, cols, len(paths))
    r0, c0, wb, base = (v[owner] for v in box[:4])
    key = base + (rows - r0) * wb + (cols - c0)
    size = int(box[3][-1] + (box[4][-1] if len(paths) else 0))
    uniq, inverse = _each_once(key, size)  # each pixel once a step
    us = np.searchsorted(box[3], uniq, side="right") - 1  # the pixel's step
    ur, uc = np.divmod(uniq - box[3][us], box[2][us])  # its row and column in the step's box
    x = (uc + box[1][us] + 0.5) / ppm  # as (column + 0.5) / ppm: the same doubles
    y = (ur + box[0][us] + 0.5) / ppm
    lo_s, hi_s = _segment_ranges_many(seg, seg_at, n_seg, (us, ur, uc), box[:2], ppm, paths)
    out[:] = _in_blocks(_measure_own_runs, x, y, seg, lo_s, hi_s - lo_s)[inverse]
    return out


def _boxes(owner, rows, cols, steps: int):
    """Every step's box of pixels: its first row and column, its width, where its cells begin
    among all steps' cells (rows by columns, one step after another), and its cells."""
    has, r0 = _per_step(np.minimum, rows, owner, steps, 0)
    _, c0 = _per_step(np.minimum, cols, owner, steps, 0)
    _, r1 = _per_step(np.maximum, rows, owner, steps, -1)
    _, c1 = _per_step(np.maximum, cols, owner, steps, -1)
    r0, c0 = np.where(has, r0, 0), np.where(has, c0, 0)
    cells = np.where(has, (r1 - r0 + 1) * (c1 - c0 + 1), 0)
    wb = np.where(has, c1 - c0 + 1, 1)
    return r0, c0, wb, np.cumsum(cells) - cells, cells


def _clip_own(raw, idx, seg):
    """``raw`` clipped to the bounds of t of its segments ``idx`` (as ``_clip_t``: [0, 1], a
    path's first and last segments the rays' bounds; np.clip only picks a bound or the value,
    so the bounds one number or many give the same)."""
    lo, hi = seg[3], seg[4]
    t = np.clip(raw, 0.0, 1.0)
    ray = np.flatnonzero((lo != 0.0)[idx] | (hi != 1.0)[idx])
    t[ray] = np.clip(raw[ray], lo[idx[ray]], hi[idx[ray]])
    return t


def _per_step(op, values, owner, steps: int, empty):
    """(which steps have values, ``op``.reduce of every step's values or ``empty``); ``owner``
    (the step of every value) ascending."""
    start = np.searchsorted(owner, np.arange(steps))
    has = np.r_[start[1:], len(owner)] > start
    out = np.full(steps, empty, dtype=np.asarray(values).dtype)
    if has.any():
        out[has] = op.reduceat(values, start[has])
    return has, out


def _measure_own_runs(x, y, seg, first, width):
    """``_measure_runs`` with every segment's own bounds of t (segments of many paths)."""
    start = np.cumsum(width) - width  # every point's first pair
    pt = np.repeat(np.arange(width.size), width)
    idx = np.arange(pt.size) + np.repeat(first - start, width)  # the pair's segment
    a, d, dd = seg[:3]
    d0, d1 = d[idx, 0], d[idx, 1]
    rx = x[pt] - a[idx, 0]
    ry = y[pt] - a[idx, 1]
    t = _clip_own((rx * d0 + ry * d1) / dd[idx], idx, seg)
    ex, ey = rx - t * d0, ry - t * d1
    dist2 = ex * ex + ey * ey
    best = np.minimum.reduceat(dist2, start)
    hit = np.flatnonzero(dist2 == np.repeat(best, width))
    k = hit[np.r_[True, pt[hit[1:]] != pt[hit[:-1]]]]  # the first nearest pair of each point
    side = d0[k] * ry[k] - d1[k] * rx[k]
    return np.sqrt(dist2[k]) * np.where(side < 0, -1, 1)


def _segment_ranges_many(seg, seg_at, n_seg, pixels, origin, ppm, paths):
    """``_segment_ranges`` of pixels of many steps (``pixels``: each one's step, and its row
    and column in its step's box, whose first row and column are ``origin``): the run
    [lo, hi) of the table's segments, all of its own step's path, that can be nearest to it,
    as its tile (of its step's box) keeps them."""
    us, ur, uc = pixels
    r0, c0 = origin
    ts = max(int(round(TILE_MM * ppm)), 4)  # tile side, pixels
    ty, tx = ur // ts, uc // ts
    S = len(paths)
    nty = _per_step(np.maximum, ty + 1, us, S, 0)[1]
    ntx = _per_step(np.maximum, tx + 1, us, S, 0)[1]
    cells = nty * ntx
    tbase = np.cumsum(cells) - cells
    tid = tbase[us] + ty * ntx[us] + tx
    occupied = np.zeros(int(cells.sum()), dtype=bool)
    occupied[tid] = True
    tiles = np.flatnonzero(occupied)
    tslot = np.cumsum(occupied) - 1
    t_step = np.searchsorted(tbase, tiles, side="right") - 1
    t_y, t_x = np.divmod(tiles - tbase[t_step], ntx[t_step])
    # the tiles' centres (mm) and reach: the farthest pixel centre of a whole tile
    cy = (r0[t_step] + t_y * ts + 0.5 * (ts - 1) + 0.5) / ppm
    cx = (c0[t_step] + t_x * ts + 0.5 * (ts - 1) + 0.5) / ppm
    reach = 0.5 * (ts - 1) * np.sqrt(2.0) / ppm
    # every tile against every segment of its step's path
    width = n_seg[t_step]
    start = np.cumsum(width) - width
    pt = np.repeat(np.arange(tiles.size), width)
    idx = np.arange(pt.size) + np.repeat(seg_at[t_step] - start, width)
    a, d, dd = seg[:3]
    rx = cx[pt] - a[idx, 0]
    ry = cy[pt] - a[idx, 1]
    t = _clip_own((rx * d[idx, 0] + ry * d[idx, 1]) / dd[idx], idx, seg)
    ex, ey = rx - t * d[idx, 0], ry - t * d[idx, 1]
    dist = np.sqrt(ex * ex + ey * ey)
    # the rounding allowance of each step (its path's and its tiles' largest coordinates)
    scale = 1.0 + np.array([float(np.abs(p).max()) for p in paths])
    big = _per_step(np.maximum, np.maximum(np.abs(cx), np.abs(cy)), t_step, S, 0.0)[1]
    bound = np.minimum.reduceat(dist + reach, start) + SLACK * (scale + 2.0 * big)[t_step]
    keep = dist - reach <= bound[pt]
    first = np.minimum.reduceat(np.where(keep, idx, idx.size + len(seg[0])), start)
    last = np.maximum.reduceat(np.where(keep, idx, -1), start) + 1
    slot = tslot[tid]
    return first[slot], last[slot]


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
    a, d, dd = seg[:3]
    rx = cx[:, None] - a[None, :, 0]
    ry = cy[:, None] - a[None, :, 1]
    t = _clip_t((rx * d[:, 0] + ry * d[:, 1]) / dd, np.s_[:, :1], np.s_[:, -1:], seg)
    ex, ey = rx - t * d[:, 0], ry - t * d[:, 1]
    dist = np.sqrt(ex * ex + ey * ey)
    scale = 1.0 + float(np.abs(path).max()) + float(np.abs(cx).max()) + float(np.abs(cy).max())
    bound = (dist + reach).min(axis=1, keepdims=True) + SLACK * scale
    keep = dist - reach <= bound
    first = np.argmax(keep, axis=1)
    last = n_seg - np.argmax(keep[:, ::-1], axis=1)
    slot = tslot[tid]
    return first[slot], last[slot]
