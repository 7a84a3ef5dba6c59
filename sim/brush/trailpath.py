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
- the tiles are sorted out in levels: blocks of tiles against all their path's segments, each
  tile only against the run of segments its block keeps (a segment no pixel of the block can
  have nearest is nearest to none of the tile's): writing 生 at 512 px measures 10.5 M
  (cell or pixel, segment) pairs instead of 14.6 M (issue 28);
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

from typing import NamedTuple

import numpy as np

from ..core.frames import clip

TILE_MM = 0.4  # about the side of the tiles the segments are sorted out by
TILE_MIN = 3  # pixels, at least
TILE_LEVELS = 2  # levels of tiles, each GROUP times the side of the next (_tile_sides)
GROUP = 4  # the side of a level's cells, in cells of the level below
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


def signed_distances(path, rows, cols, ppm: float) -> np.ndarray:
    """float32 signed distance (mm) of the centres of pixels (rows, cols) of the paper (ints,
    repeats allowed) from the polyline ``path`` (k >= 2 points, mm): to the nearest point of
    the nearest segment (the first of equals; the first segment going back without end, the
    last on ahead), positive to the left of the way the path goes."""
    out = np.empty(rows.size, dtype=np.float32)
    if rows.size == 0:
        return out
    n_seg = len(path) - 1
    if rows.size * n_seg <= PLAIN_ELEMENTS:  # few pixels: sorting out segments costs more
        seg = segments(path)
        r0, c0 = int(rows.min()), int(cols.min())
        hb, wb = int(rows.max()) - r0 + 1, int(cols.max()) - c0 + 1
        key = (rows - r0).astype(np.int64) * wb + (cols - c0)
        uniq, inverse = _each_once(key, hb * wb)
        x = (uniq % wb + c0 + 0.5) / ppm  # as (column + 0.5) / ppm: the same doubles
        y = (uniq // wb + r0 + 0.5) / ppm
        _, lat = _measure(x, y, seg, 0, n_seg)
        out[:] = lat[inverse]
        return out
    return signed_distances_many([path], np.zeros(rows.size, np.intp), rows, cols, ppm)


def _each_once(key, size: int):
    """The distinct ``key``s (ints in [0, size)) ascending and where each key is among them:
    through a mask of the box when it is not too large for the keys, else by sorting."""
    if size <= 8 * key.size + (1 << 20):
        seen = np.zeros(size, dtype=bool)
        seen[key] = True
        return np.flatnonzero(seen), (np.cumsum(seen) - 1)[key]
    return np.unique(key, return_inverse=True)


class _Table(NamedTuple):
    """The segments of many paths as one table, a column a field: segment i is
    (ax, ay) + t (dx, dy), t within [lo, hi] ([0, 1], a path's first segment going back
    without end and its last on ahead: ``opens``, ``closes``), dd = |d|^2 (at least 1e-12)."""

    ax: np.ndarray
    ay: np.ndarray
    dx: np.ndarray
    dy: np.ndarray
    dd: np.ndarray
    lo: np.ndarray
    hi: np.ndarray
    opens: np.ndarray  # bool: a path's first segment (its t has no lower bound)
    closes: np.ndarray  # bool: a path's last segment (its t has no upper bound)


def _table(seg) -> _Table:
    """The ``_Table`` of segments (a, d, dd, lo, hi) (``segments``, of one path or many)."""
    a, d, dd, lo, hi = seg
    cols = (np.ascontiguousarray(v) for v in (a[:, 0], a[:, 1], d[:, 0], d[:, 1]))
    return _Table(*cols, dd, lo, hi, lo != 0.0, hi != 1.0)


def _in_blocks(measure, x, y, tab, first, width) -> np.ndarray:
    """``measure(x, y, tab, first, width)`` of the points in blocks of about BLOCK_ELEMENTS
    (point, segment) pairs (point i against ``width[i]`` segments from ``first[i]``)."""
    lat = np.empty(x.size)
    ends = np.cumsum(width)
    at = 0
    while at < x.size:
        stop = max(int(np.searchsorted(ends, ends[at] - width[at] + BLOCK_ELEMENTS)), at + 1)
        blk = slice(at, stop)
        lat[blk] = measure(x[blk], y[blk], tab, first[blk], width[blk])
        at = stop
    return lat


def signed_distances_many(paths, owner, rows, cols, ppm: float) -> np.ndarray:
    """``signed_distances`` of pixels of many steps at once, bit for bit as step by step:
    pixel i (rows[i], cols[i]) is measured from the polyline ``paths[owner[i]]`` (each of
    k >= 2 points, mm; ``owner`` ascending). Every step's pixels are taken once each; the
    segments of all paths are one table, each with its bounds of t (a path's first segment a
    ray going back, its last one going on ahead), so each pixel is measured against a run of
    its own path's segments (those its tile can have nearest, see the module's note)."""
    out = np.empty(rows.size, dtype=np.float32)
    if rows.size == 0:
        return out
    tab, n_seg, seg_at = _table_of(paths)
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
    lo_s, hi_s = _segment_ranges_many(tab, seg_at, n_seg, (us, ur, uc), box[:2], ppm, paths)
    out[:] = _in_blocks(_measure_runs, x, y, tab, lo_s, hi_s - lo_s)[inverse]
    return out


def _table_of(paths):
    """The ``_Table`` of the segments of all ``paths`` (``segments`` of each, one after
    another: the same subtractions and sums, done on all points at once), the number of
    segments of every path and where its first one is in the table."""
    pts = [np.asarray(p, dtype=float) for p in paths]
    n_pts = np.array([len(p) for p in pts])
    n_seg = n_pts - 1
    seg_at = np.cumsum(n_seg) - n_seg
    allp = np.concatenate(pts)
    # a segment from every point but each path's last: drop the steps from path to path
    keep = np.ones(len(allp) - 1, dtype=bool)
    keep[np.cumsum(n_pts)[:-1] - 1] = False
    a, d = allp[:-1][keep], np.diff(allp, axis=0)[keep]
    dd = np.maximum(np.einsum("ij,ij->i", d, d), 1e-12)
    lo = np.zeros(len(a))
    hi = np.ones(len(a))
    lo[seg_at], hi[seg_at + n_seg - 1] = -np.inf, np.inf
    return _table((a, d, dd, lo, hi)), n_seg, seg_at


def _boxes(owner, rows, cols, steps: int):
    """Every step's box of pixels: its first row and column, its width, where its cells begin
    among all steps' cells (rows by columns, one step after another), and its cells."""
    st = _steps(owner, steps)
    has = st.has
    r0, c0 = _per_step(np.minimum, rows, st, 0), _per_step(np.minimum, cols, st, 0)
    r1, c1 = _per_step(np.maximum, rows, st, -1), _per_step(np.maximum, cols, st, -1)
    r0, c0 = np.where(has, r0, 0), np.where(has, c0, 0)
    cells = np.where(has, (r1 - r0 + 1) * (c1 - c0 + 1), 0)
    wb = np.where(has, c1 - c0 + 1, 1)
    return r0, c0, wb, np.cumsum(cells) - cells, cells


class _Steps(NamedTuple):
    """Where every step's items begin among items sorted by step (``_steps``)."""

    has: np.ndarray  # (steps,) bool: the step has items
    start: np.ndarray  # the first item of every step that has items
    steps: int


def _steps(owner, steps: int) -> _Steps:
    """The ``_Steps`` of items of the steps ``owner`` (ascending)."""
    start = owner.searchsorted(np.arange(steps))
    has = np.concatenate([start[1:], [len(owner)]]) > start
    return _Steps(has, start[has], steps)


def _per_step(op, values, st: _Steps, empty):
    """``op``.reduce of every step's values (``st``: their steps), ``empty`` for a step with
    none."""
    out = np.full(st.steps, empty, dtype=values.dtype)
    if st.start.size:
        out[st.has] = op.reduceat(values, st.start)
    return out


class _Pairs(NamedTuple):
    """Points each against its run of segments, pair by pair: every point's first pair, every
    pair's segment, the pair's t on it (clipped to its bounds), the point less the segment's
    start (rx, ry) and the square of its distance from the segment."""

    start: np.ndarray
    idx: np.ndarray
    rx: np.ndarray
    ry: np.ndarray
    dist2: np.ndarray


def _pairs(x, y, tab: _Table, first, width) -> _Pairs:
    """Points (x, y) each against its run of ``width`` segments from ``first`` (never empty,
    within one path): the arithmetic of ``_measure``, pair by pair. A run holds its path's
    first segment only as its first pair and its last only as its last, so only those pairs
    take the rays' bounds of t; every other pair's bounds are [0, 1]."""
    start = np.cumsum(width) - width  # every point's first pair
    idx = np.arange(int(start[-1] + width[-1])) + np.repeat(first - start, width)
    last = first + width - 1
    d0, d1 = tab.dx.take(idx), tab.dy.take(idx)
    rx = np.repeat(x, width) - tab.ax.take(idx)
    ry = np.repeat(y, width) - tab.ay.take(idx)
    raw = (rx * d0 + ry * d1) / tab.dd.take(idx)
    t = clip(raw, 0.0, 1.0)
    ray = np.concatenate([start[tab.opens[first]], (start + width - 1)[tab.closes[last]]])
    if ray.size:  # as np.clip with every pair's own bounds (the same picks)
        seg = idx[ray]
        t[ray] = clip(raw[ray], tab.lo[seg], tab.hi[seg])
    ex, ey = rx - t * d0, ry - t * d1
    return _Pairs(start, idx, rx, ry, ex * ex + ey * ey)


def _measure_runs(x, y, tab: _Table, first, width):
    """The plain measure of points (x, y), each against its own run of ``width`` segments from
    ``first``: the same arithmetic as ``_measure`` on every (point, segment) pair, and the
    first of the nearest in each run (as np.argmin over all segments)."""
    p = _pairs(x, y, tab, first, width)
    best = np.minimum.reduceat(p.dist2, p.start)
    hit = np.flatnonzero(p.dist2 == np.repeat(best, width))
    k = hit[np.searchsorted(hit, p.start)]  # the first nearest pair of each point (in its run)
    seg = p.idx[k]
    side = tab.dx.take(seg) * p.ry[k] - tab.dy.take(seg) * p.rx[k]
    return np.sqrt(p.dist2[k]) * np.where(side < 0, -1, 1)


def _segment_ranges_many(tab, seg_at, n_seg, pixels, origin, ppm, paths):
    """``_segment_ranges`` of pixels of many steps (``pixels``: each one's step, and its row
    and column in its step's box, whose first row and column are ``origin``): the run
    [lo, hi) of the table's segments, all of its own step's path, that can be nearest to it,
    as its tile (of its step's box) keeps them. The tiles are sorted out level by level
    (``_tile_sides``): the largest cells against all their path's segments, each smaller
    cell against the run its cell of the level above keeps (a segment no pixel of a cell can
    have nearest is nearest to none of its parts' pixels: far fewer segments measured)."""
    us, ur, uc = pixels
    r0, c0 = origin
    S = len(paths)
    sides = _tile_sides(ppm)
    levels = [_cells(us, ur // sides[-1], uc // sides[-1], S)]  # every pixel's tile
    for side, finer in zip(sides[-2::-1], sides[:0:-1], strict=True):
        c = levels[0]  # the next finer level's cells, each in a cell of this level
        levels.insert(0, _cells(c.step, c.y * finer // side, c.x * finer // side, S))
    # the rounding allowance of each step (its path's and its cells' largest coordinates)
    scale = 1.0 + np.array([float(np.abs(p).max()) for p in paths])
    top = levels[0]
    cx, cy = _centres(top, r0, c0, sides[0], ppm)
    big = _per_step(np.maximum, np.maximum(np.abs(cx), np.abs(cy)), _steps(top.step, S), 0.0)
    allow = SLACK * (scale + 2.0 * (big + sides[0] / ppm))
    lo, hi = seg_at[top.step], seg_at[top.step] + n_seg[top.step]
    for j, (cells, side) in enumerate(zip(levels, sides, strict=True)):
        if j:  # every cell's run: its cell's of the level above
            up = levels[j - 1]
            parent = up.slot[up.id]
            lo, hi = lo[parent], hi[parent]
            cx, cy = _centres(cells, r0, c0, side, ppm)
        lo, hi = _kept_runs(tab, (cx, cy), _reach(side, ppm), (lo, hi - lo), allow[cells.step])
    tile = levels[-1]
    slot = tile.slot[tile.id]
    return lo[slot], hi[slot]


def _tile_sides(ppm) -> list:
    """The sides (pixels) of the cells of each level of tiles, largest first: the smallest
    about TILE_MM (at least TILE_MIN pixels), each level GROUP times the next."""
    ts = max(int(round(TILE_MM * ppm)), TILE_MIN)
    return [ts * GROUP**k for k in range(TILE_LEVELS - 1, -1, -1)]


class _Cells(NamedTuple):
    """Occupied cells of every step's grid (tiles of its box, or blocks of tiles): each
    item's cell ``id``, the cells' ``slot`` (id -> place among the occupied cells), and every
    occupied cell's step and row and column in its step's grid."""

    id: np.ndarray
    slot: np.ndarray
    step: np.ndarray
    y: np.ndarray
    x: np.ndarray


def _cells(step, y, x, steps: int) -> _Cells:
    """The occupied cells (y, x) of the items of ``step`` (ascending)."""
    st = _steps(step, steps)
    ny, nx = _per_step(np.maximum, y + 1, st, 0), _per_step(np.maximum, x + 1, st, 0)
    cells = ny * nx
    base = np.cumsum(cells) - cells
    cid = base[step] + y * nx[step] + x
    occupied = np.zeros(int(cells.sum()), dtype=bool)
    occupied[cid] = True
    ids = np.flatnonzero(occupied)
    c_step = np.searchsorted(base, ids, side="right") - 1
    c_y, c_x = np.divmod(ids - base[c_step], nx[c_step])
    return _Cells(cid, np.cumsum(occupied) - 1, c_step, c_y, c_x)


def _centres(cells: _Cells, r0, c0, side: int, ppm):
    """The cells' centres (mm): the middle of their ``side`` x ``side`` pixels."""
    cy = (r0[cells.step] + cells.y * side + 0.5 * (side - 1) + 0.5) / ppm
    cx = (c0[cells.step] + cells.x * side + 0.5 * (side - 1) + 0.5) / ppm
    return cx, cy


def _reach(side: int, ppm) -> float:
    """The farthest pixel centre of a whole cell of ``side`` pixels from its centre (mm)."""
    return 0.5 * (side - 1) * np.sqrt(2.0) / ppm


def _kept_runs(tab, centres, reach, runs, allow):
    """Cells (``centres``, mm, each with pixels within ``reach`` of it) measured against
    their runs of segments (``runs``: first, width; never empty): the run [lo, hi) each keeps,
    from the first to the last segment whose distance from the centre, less the reach,
    is at most the smallest (distance + reach) of its run plus ``allow`` (rounding)."""
    p = _pairs(*centres, tab, *runs)
    dist = np.sqrt(p.dist2)
    bound = np.minimum.reduceat(dist + reach, p.start) + allow
    keep = dist - reach <= np.repeat(bound, runs[1])
    lo = np.minimum.reduceat(np.where(keep, p.idx, len(tab.dx)), p.start)
    hi = np.maximum.reduceat(np.where(keep, p.idx, -1), p.start) + 1
    return lo, hi


def _segment_ranges(seg, ur, uc, r0, c0, ppm, path):
    """For every pixel (rows ur, columns uc from (r0, c0)), the segments [lo, hi) that can be
    nearest to it: those its tile keeps (see the module's note), as one contiguous run
    (``_segment_ranges_many`` of one step)."""
    one = np.zeros(ur.size, dtype=np.intp)
    origin = (np.array([r0]), np.array([c0]))
    n_seg = np.array([len(seg[0])])
    return _segment_ranges_many(
        _table(seg), np.zeros(1, np.intp), n_seg, (one, ur, uc), origin, ppm, [path]
    )
