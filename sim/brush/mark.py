# SPDX-License-Identifier: GPL-3.0-or-later
"""The current drawing mark (Sec. 6): each writing primitive's sweep surface SS(s, t) cut by the
paper plane psi (z = 0), and the ink information of every pixel inside the cut.

1. The surface is evaluated on its fixed (s, t) grid: every row is c(s) + U(s) Cx(t) + V(s) Cy(t)
   (see ``nurbs``). Marching squares on the grid's z values gives the intersection curve cur_u
   as a set of segments in the paper plane (one contour per closed curve).
2. Within the curve's bounding box, a pixel is inked when some section of the solid contains it
   (the solid is the union of its sections, also where a bent axis folds the surface). Only the
   pixels of each scanline near cur_u are looked at; a mark whose inked pixels reach the end of
   that span is looked at again over its whole bounding box. ``cut_marks`` does step 1 (the
   dynamics need the cut's size at once); ``fill_marks`` does steps 2 and 3 for all primitives
   of several samples in one pass.
3. Each inside pixel tau is placed on the segment from V^ (on the middle control axis, in the
   section plane through tau) to V (on the surface, in tau's direction): with f = |tau - V^| /
   |V - V^|, V^ takes its ink from the two nearest key points (Eq. 21), V from V^'s texture
   function (Eq. 22), and tau = (1 - f) info(V^) + f info(V) (Eq. 23).

Symbols: cur_u the intersection curve; tau a pixel's centre on the paper; V^ a point of the
middle control axis and V one of the surface; a slab is the solid between two neighbouring grid
rows, lam the position between them (0 at the first, 1 at the second); Hd a pixel's signed
distance to a row's plane; S_i and hei_i the cut's bounding-box area and its distance to the tip
(Eq. 10). The ink fields (wet, col, wr, cr, wv, cv) are named in ``brush_state``.
"""

from __future__ import annotations

import math
from collections import namedtuple
from dataclasses import dataclass
from typing import NamedTuple

import numpy as np

from ..core import exact
from ..core.exact import matmul
from ..core.frames import dot, norm, per_pixel, stack1
from .ink import LOAD, TEXTURE, TEXTURE_NAMES
from .state import INK_FIELDS

# marching-squares edges: 0 = (i,j)-(i,j+1), 1 = (i,j+1)-(i+1,j+1), 2 = (i+1,j)-(i+1,j+1),
# 3 = (i,j)-(i+1,j); case bits: 1 = (i,j), 2 = (i,j+1), 4 = (i+1,j+1), 8 = (i+1,j) inside.
_CASES = {
    1: [(0, 3)],
    2: [(0, 1)],
    3: [(1, 3)],
    4: [(1, 2)],
    6: [(0, 2)],
    7: [(2, 3)],
    8: [(2, 3)],
    9: [(0, 2)],
    11: [(1, 2)],
    12: [(1, 3)],
    13: [(0, 1)],
    14: [(0, 3)],
    5: [(0, 1), (2, 3)],
    10: [(0, 3), (1, 2)],
}
# kept on each side of cur_u's extent on a scanline, besides the grid's chord error. Where the
# surface grazes the paper a section between two grid rows can reach further past the grid's
# contour (measured up to 1.7 mm); a mark whose inside pixels touch the end of a span is then
# scanned again over the cut's whole bounding box (see fill_marks)
SPAN_MARGIN_PX = 2.0
# span pixels evaluated together (all primitives' marks at once, in groups of about this many)
BATCH_PIXELS = 1 << 17
# per-pixel stages (the section solve, the cover) run over runs of whole intervals of about this
# many entries at a time, so that their dozens of temporaries stay in the processor's cache
# instead of streaming through memory; every entry's arithmetic is its own, so the grouping
# changes no bit (issue 28)
CHUNK_ENTRIES = 1 << 13

_SEG_A = np.full((16, 2), -1)
_SEG_B = np.full((16, 2), -1)
for _c, _pairs in _CASES.items():
    for _k, (_e0, _e1) in enumerate(_pairs):
        _SEG_A[_c, _k] = _e0
        _SEG_B[_c, _k] = _e1


@dataclass(kw_only=True)
class Mark:
    """One primitive's current drawing mark, rasterised into a pixel window of the paper."""

    primitive: int
    iy0: int  # window origin (row from the bottom of the paper, column from the left)
    ix0: int
    rows: np.ndarray  # (P,) pixel rows inside the window
    cols: np.ndarray  # (P,)
    wet: np.ndarray  # (P,) wetness of the brush at tau (Eq. 23)
    col: np.ndarray  # (P, 3) ink density of the brush at tau (Eq. 23)
    lateral: np.ndarray  # (P,) across the major axis, [-1, 1] (bristles.across: mm off the path)
    depth: np.ndarray  # (P,) Eq. 23's f = |tau - V^| / |V - V^|: 0 on the axis, 1 at the surface
    shape: tuple  # window (h, w)
    segments: np.ndarray  # (M, 2, 2) the intersection curve cur_u, mm
    area_bbox: float  # S_i: area of the section's bounding box (mm^2), Eq. 10
    height: float  # hei_i: distance from the section to the tip line's midpoint (mm)
    skip: np.ndarray | None = None  # (P,) no ink this step (Eq. 27, set by bristles.lay)
    rich: np.ndarray | None = None  # (P,) the liquid's pigment per unit of wet (bristles.lay)


def slice_grids(X):
    """Where the periodic-in-t grids X (k, Ns, Nt, 3) cross z = 0 (marching squares, all
    primitives at once). Returns segments (M, 2, 3) and the grid each belongs to (M,)."""
    Xw = np.concatenate([X, X[:, :, :1]], axis=2)  # periodic in t: column Nt is column 0
    inw = Xw[..., 2] <= 0.0
    c00, c01 = inw[:, :-1, :-1], inw[:, :-1, 1:]
    c10, c11 = inw[:, 1:, :-1], inw[:, 1:, 1:]
    case = c00 * 1 + c01 * 2 + c11 * 4 + c10 * 8
    gg, ii, jj = np.nonzero((case != 0) & (case != 15))
    if ii.size == 0:
        return np.zeros((0, 2, 3)), np.zeros(0, dtype=np.intp)
    cs = case[gg, ii, jj]
    p00, p01 = Xw[gg, ii, jj], Xw[gg, ii, jj + 1]
    p10, p11 = Xw[gg, ii + 1, jj], Xw[gg, ii + 1, jj + 1]

    # crossing points of the four edges of each cell (computed per edge, so shared edges agree)
    e0 = crossing(p00, p01)
    e1 = crossing(p01, p11)
    e2 = crossing(p10, p11)
    e3 = crossing(p00, p10)
    E = stack1([e0, e1, e2, e3])  # (C, 4, 3)
    segs, owner = [], []
    for k in range(2):
        a, b = _SEG_A[cs, k], _SEG_B[cs, k]
        ok = a >= 0
        if ok.any():
            r = np.nonzero(ok)[0]
            segs.append(stack1([E[r, a[ok]], E[r, b[ok]]]))
            owner.append(gg[r])
    return np.concatenate(segs, axis=0), np.concatenate(owner)


def crossing(pa, pb):
    """Where the grid edges pa -> pb (P, 3) cross z = 0 (linear along the edge)."""
    za, zb = pa[:, 2], pb[:, 2]
    t = za / np.where(za != zb, za - zb, 1.0)
    return pa + t[:, None] * (pb - pa)


def edge_crossings(X):
    """Where the edges of the periodic-in-t grids X (k, Ns, Nt, 3) cross z = 0, each edge once
    and oriented as ``slice_grids`` computes it (along t, and from row to row): the points
    (P, 2) in the paper plane and the grid of each. They are the ends of ``slice_grids``'s
    segments (every cell of marching squares joins all its crossing edges), so their bounding
    box is the segments' - what the dynamics need of the cut (Eq. 10) - without joining them
    (issue 28: ``fill_marks`` joins them for many samples at once)."""
    Xw = np.concatenate([X, X[:, :, :1]], axis=2)  # periodic in t: column Nt is column 0
    inw = Xw[..., 2] <= 0.0
    gh, ih, jh = np.nonzero(inw[:, :, :-1] != inw[:, :, 1:])  # along t
    gv, iv, jv = np.nonzero(inw[:, :-1, :-1] != inw[:, 1:, :-1])  # from row to row
    pts = np.concatenate(
        [crossing(Xw[gh, ih, jh], Xw[gh, ih, jh + 1]), crossing(Xw[gv, iv, jv], Xw[gv, iv + 1, jv])]
    )
    return pts[:, :2], np.concatenate([gh, gv])


def slice_grid(X) -> np.ndarray:
    """Segments (M, 2, 3) where one periodic-in-t grid X (Ns, Nt, 3) crosses z = 0."""
    return slice_grids(X[None])[0]


def _scanline_spans(xy, owner, ppm, win, margin_px):
    """Pixel columns [lo, hi) of every pixel row of every window that can lie inside a cut.

    A section's boundary is its cur_u, so every inside point of a scanline has cur_u on both
    sides of it on that scanline: the pixels outside the x range of the parts of the segments
    within ``margin_px`` of the scanline, widened by ``margin_px``, are outside (the margin
    covers the grid's chords against the true surface, and a section that reaches a little past
    the grid's contour where it grazes the paper). (Taking only the segments that cross the
    scanline missed, where a bent, split primitive grazed the paper, a run of inside pixels
    that the contour of the next rows reached.) All windows at once: ``xy`` (M, 2, 2)
    segments, ``owner`` (M,) their window, ``win`` (k, 4) windows (iy0, ix0, h, w),
    ``margin_px`` (k,). Returns lo, hi over the windows' rows stacked in window order."""
    m = (margin_px / ppm)[owner]
    x0, y0, x1, y1 = xy[:, 0, 0], xy[:, 0, 1], xy[:, 1, 0], xy[:, 1, 1]
    ylo = np.minimum(y0, y1) - m
    yhi = np.maximum(y0, y1) + m
    iy0, ix0, h, w = (win[:, j] for j in range(4))
    start = np.cumsum(h) - h  # first stacked row of each window
    # rows r of the segment's window with ylo <= (iy0 + r + 0.5) / ppm <= yhi (one row more on
    # each side against rounding: the spans only need to contain the cut)
    r0 = np.clip(np.ceil(ylo * ppm - 0.5).astype(np.int64) - 1 - iy0[owner], 0, h[owner])
    r1 = np.clip(np.floor(yhi * ppm - 0.5).astype(np.int64) + 2 - iy0[owner], 0, h[owner])
    n = np.maximum(r1 - r0, 0)
    seg = np.repeat(np.arange(len(owner)), n)
    local = np.arange(int(n.sum())) - np.repeat(np.cumsum(n) - n - r0, n)  # window row
    row = start[owner][seg] + local
    yc = (iy0[owner][seg] + local + 0.5) / ppm
    ms = m[seg]
    sx0, sy0, dx, dy = x0[seg], y0[seg], (x1 - x0)[seg], (y1 - y0)[seg]
    total = int(h.sum())
    flat = dy == 0
    ddy = np.where(flat, 1.0, dy)
    # the part of the segment within the margin around the scanline, widened by the margin
    ta = np.where(flat, 0.0, (yc - ms - sy0) / ddy)
    tb = np.where(flat, 1.0, (yc + ms - sy0) / ddy)
    t0, t1 = np.minimum(ta, tb), np.maximum(ta, tb)
    xa, xb = sx0 + np.clip(t0, 0.0, 1.0) * dx, sx0 + np.clip(t1, 0.0, 1.0) * dx
    lo_mm = np.full(total, np.inf)
    hi_mm = np.full(total, -np.inf)
    np.minimum.at(lo_mm, row, np.minimum(xa, xb) - ms)
    np.maximum.at(hi_mm, row, np.maximum(xa, xb) + ms)
    seen = np.isfinite(lo_mm)
    wx0 = np.repeat(ix0, h)
    ww = np.repeat(w, h)
    lo_mm = np.where(seen, lo_mm, 0.0)
    hi_mm = np.where(seen, hi_mm, 0.0)
    lo = np.clip(np.floor(lo_mm * ppm - 0.5).astype(np.int64) + 1 - wx0, 0, ww)
    hi = np.clip(np.floor(hi_mm * ppm - 0.5).astype(np.int64) + 1 - wx0, 0, ww)
    hi = np.where(seen, hi, lo)
    return lo, np.maximum(hi, lo)


class SurfaceRows(NamedTuple):
    """The surface's grid rows of the primitives (see ``nurbs``): row s is the ellipse
    centre(s) + U(s) Cx(t) + V(s) Cy(t) in the plane through centre(s) normal to T(s)."""

    centre: np.ndarray  # (m, Ns, 3) axis points V^
    U: np.ndarray  # (m, Ns, 3) semi-major axis vectors
    V: np.ndarray  # (m, Ns, 3) semi-minor axis vectors
    T: np.ndarray  # (m, Ns, 3) unit tangents
    zmin: np.ndarray  # (m, Ns) lowest z of each row
    ink: np.ndarray  # (m, Ns, INK_WIDTH) the ink at V^ (Eq. 21), laid out as INK_FIELDS


@dataclass(kw_only=True)
class Cut:
    """The first half of one step's marks: where every primitive's solid meets the paper
    (cur_u, S_i and hei_i for the dynamics, Eq. 10). ``fill_marks`` then finds the cuts' pixel
    windows (``_windows``), the scanline spans, the inked pixels and their ink, for many steps
    at once (issue 28: what only the marks need waits for them)."""

    prims: np.ndarray  # (k,) primitives with a cut
    box: np.ndarray  # (k, 4) each cut's bounding box, mm: xmin, xmax, ymin, ymax
    paper: tuple  # the paper's (H, W), pixels
    ring: np.ndarray  # (Nt, 2) the unit circle at the grid's points around each row
    touching: np.ndarray  # the primitives whose solid reaches the paper (their grids are cut)
    near: tuple  # the rows (first, end) next to one that reaches the paper: where cur_u can be
    rows: SurfaceRows  # the surface rows of every primitive
    area: np.ndarray  # (k,) S_i
    height: np.ndarray  # (k,) hei_i
    centre: np.ndarray  # (k, 2) mm: the middle of each cut's bounding box
    extent: np.ndarray  # (k, 2) mm: each cut's bounding box's width and height
    # (params, keys): where ``rows.ink`` is still to be interpolated from (Eq. 21), or None
    ink_source: tuple | None = None

    def contact(self):
        """The middle of the hair's contact with the paper (mm): the cuts' middles, weighted
        by their S_i."""
        if len(self.area) == 1:  # one cut: the same numbers on Python floats
            a = float(self.area[0])
            w = 1e-12 if a < 1e-12 else a  # np.maximum's pick (NaN stays)
            cx, cy = self.centre[0].tolist()
            return np.array([cx * w / w, cy * w / w])
        w = np.maximum(self.area, 1e-12)
        return (self.centre * w[:, None]).sum(axis=0) / w.sum()

    def widths(self, m: int, across) -> np.ndarray:
        """Every primitive's contact width (mm) along the unit vector ``across`` (its bounding
        box's extent that way; 0 for those off the paper)."""
        if m == 1 and len(self.prims) == 1:  # ``matmul``'s sum on Python floats
            (ex, ey), (ax, ay) = self.extent[0].tolist(), across
            return np.array([ex * abs(ax) + ey * abs(ay)])
        out = np.zeros(m)
        out[self.prims] = matmul(self.extent, np.abs(np.asarray(across, dtype=float)))
        return out

    def sizes(self, m: int):
        """S_i and hei_i of all m primitives (0 for those off the paper)."""
        if len(self.prims) == m:  # every primitive cut (``prims`` ascends): 0, 1, ..., m - 1
            return self.area.copy(), self.height.copy()
        area = np.zeros(m)
        height = np.zeros(m)
        area[self.prims] = self.area
        height[self.prims] = self.height
        return area, height


def cut_marks(brush, sec, ink_rows, ppm: float, paper_shape) -> Cut | None:
    """Every primitive's cut by the paper (Sec. 6): None when no primitive reaches it."""
    lay = brush.layout
    H, W = paper_shape
    ring = lay.ring
    rows_c, rows_U, rows_V, rows_T = sec.rows_c, sec.rows_U, sec.rows_V, sec.rows_T
    # z of the whole grid for all primitives at once
    Zmin = rows_c[..., 2] - np.hypot(rows_U[..., 2], rows_V[..., 2])  # lowest point of each row
    touching = np.nonzero(Zmin.min(axis=1) <= 0.0)[0]
    if touching.size == 0:
        return None
    # only cells next to a row that reaches the paper can be cut (a ring point is never below
    # its row's lowest point)
    low = np.nonzero((Zmin[touching] <= 1e-9).any(axis=0))[0]  # (rounding of the ring)
    r0, r1 = max(int(low[0]) - 1, 0), int(low[-1]) + 2
    X = _grid_of(rows_c[touching, r0:r1], rows_U[touching, r0:r1], rows_V[touching, r0:r1], ring)
    pts, grid = edge_crossings(X)
    if grid.size == 0:
        return None
    near = (r0, min(r1, rows_c.shape[1]))
    rows = SurfaceRows(rows_c, rows_U, rows_V, rows_T, Zmin, ink_rows)
    # each touching primitive's cut: bounding box, S_i and hei_i (Eq. 10)
    if len(touching) == 1:
        return _one_cut(brush, pts, touching, (H, W), ring, near, rows)
    order = np.argsort(grid, kind="stable")
    grid, pts = grid[order], pts[order]
    first = np.flatnonzero(np.r_[True, grid[1:] != grid[:-1]])
    cuts = grid[first]  # grids with a cut
    xmin = np.minimum.reduceat(pts[:, 0], first)
    xmax = np.maximum.reduceat(pts[:, 0], first)
    ymin = np.minimum.reduceat(pts[:, 1], first)
    ymax = np.maximum.reduceat(pts[:, 1], first)
    prims = touching[cuts]
    area = (xmax - xmin) * (ymax - ymin)
    centroid = stack1([(xmin + xmax) / 2, (ymin + ymax) / 2, np.zeros(len(cuts))])
    height = norm(brush.cc[prims, -1] - centroid)
    return Cut(
        prims=prims,
        box=stack1([xmin, xmax, ymin, ymax]),
        paper=(H, W),
        ring=ring,
        touching=touching,
        near=near,
        rows=rows,
        area=area,
        height=height,
        centre=centroid[:, :2],
        extent=stack1([xmax - xmin, ymax - ymin]),
    )


def _one_cut(brush, pts, touching, paper, ring, near, rows) -> Cut:
    """``cut_marks``'s Cut where one primitive's grid is cut (``pts``: its crossings): the
    same numbers on Python floats, a numpy call each saved (the brush's step; issue 28)."""
    xs, ys = pts[:, 0], pts[:, 1]
    xmin, xmax, ymin, ymax = float(xs.min()), float(xs.max()), float(ys.min()), float(ys.max())
    cx, cy = (xmin + xmax) / 2, (ymin + ymax) / 2
    tx, ty, tz = brush.cc[int(touching[0]), -1].tolist()
    dx, dy, dz = tx - cx, ty - cy, tz - 0.0
    return Cut(
        prims=touching.copy(),
        box=np.array([[xmin, xmax, ymin, ymax]]),
        paper=paper,
        ring=ring,
        touching=touching,
        near=near,
        rows=rows,
        area=np.array([(xmax - xmin) * (ymax - ymin)]),
        height=np.array([math.sqrt((dx * dx + dy * dy) + dz * dz)]),  # ``norm``'s sums
        centre=np.array([[cx, cy]]),
        extent=np.array([[xmax - xmin, ymax - ymin]]),
    )


class Windows(NamedTuple):
    """The pixel windows of cuts (``_windows``), one row per cut of a primitive."""

    win: np.ndarray  # (k, 4) windows (iy0, ix0, rows, cols), rows 0 if there are no columns
    shape: np.ndarray  # (k, 2) window (h, w)
    chord: np.ndarray  # (k,) the grid's chord error against the true sections, pixels


def _windows(cuts: list[Cut], ppm: float) -> Windows:
    """The pixel windows of the cuts of many steps (the paper's pixels around each bounding
    box), and each one's chord error of the grid's polygon against the true sections: every
    cut's numbers are its own, so all steps' at once are each step's."""
    xmin, xmax, ymin, ymax = np.concatenate([c.box for c in cuts]).T
    hw = np.repeat(np.array([c.paper for c in cuts]), [len(c.prims) for c in cuts], axis=0)
    H, W = hw[:, 0], hw[:, 1]
    ix0 = np.maximum(np.floor(xmin * ppm - 0.5).astype(np.int64), 0)
    iy0 = np.maximum(np.floor(ymin * ppm - 0.5).astype(np.int64), 0)
    ix1 = np.minimum(np.ceil(xmax * ppm - 0.5).astype(np.int64) + 1, W)
    iy1 = np.minimum(np.ceil(ymax * ppm - 0.5).astype(np.int64) + 1, H)
    h = np.maximum(iy1 - iy0, 0)
    w = np.maximum(ix1 - ix0, 0)
    sag = 1.0 - exact.cos(np.pi / cuts[0].ring.shape[0])
    U = np.concatenate([c.rows.U[c.prims] for c in cuts])
    V = np.concatenate([c.rows.V[c.prims] for c in cuts])
    semi = np.max(np.hypot(norm(U), norm(V)), axis=1)
    hh = np.where(w > 0, h, 0)  # a window without columns has no pixels
    return Windows(stack1([iy0, ix0, hh, w]), stack1([h, w]), sag * semi * ppm)


def _cur_u(cuts: list[Cut]):
    """The intersection curves cur_u of the cuts of many steps, by marching squares over all
    their grids at once (``slice_grids``): (segments (M, 2, 2) grouped by cut, in each cut's
    order, and the segments of every cut). Every grid is taken over the rows near the paper in
    any of the steps: a row that reaches no lower than 1e-9 above the paper has every ring point
    above it (rounding is far smaller), so the rows ``cut_marks`` left out of a step's grids add
    only cells wholly off the paper, and each cut's segments are the same, in the same order."""
    r0 = min(c.near[0] for c in cuts)
    r1 = max(c.near[1] for c in cuts)
    ring = cuts[0].ring
    if all(c.ring is ring or np.array_equal(c.ring, ring) for c in cuts):
        # one ring for all: the grids of all cuts at once (each point's sums as ``_grid``'s)
        c, U, V = (
            np.concatenate([getattr(k.rows, f)[k.touching, r0:r1] for k in cuts])
            for f in ("centre", "U", "V")
        )
        X = _grid_of(c, U, V, ring)
    else:
        X = np.concatenate([_grid(c, r0, r1) for c in cuts])
    segs, owner = slice_grids(X)
    order = np.argsort(owner, kind="stable")
    count = np.bincount(owner, minlength=len(X))
    count = count[count > 0]
    if len(count) != sum(len(c.prims) for c in cuts):  # the grids cut_marks found cut
        raise RuntimeError("cur_u: the cuts' grids and their segments disagree")
    return segs[:, :, :2][order], count


def _grid(c: Cut, r0: int, r1: int) -> np.ndarray:
    """The surface grid (k, r1 - r0, Nt, 3) of a cut's touching primitives, rows r0..r1."""
    t, r = c.touching, c.rows
    return _grid_of(r.centre[t, r0:r1], r.U[t, r0:r1], r.V[t, r0:r1], c.ring)


def _grid_of(centre, U, V, ring) -> np.ndarray:
    """The grid (k, rows, Nt, 3) of rows centre + U Cx(t) + V Cy(t) at the ring's points."""
    return (
        centre[:, :, None, :]
        + U[:, :, None, :] * ring[None, None, :, 0, None]
        + V[:, :, None, :] * ring[None, None, :, 1, None]
    )


def fill_marks(cuts: list[Cut | None], ppm: float) -> list[list[Mark]]:
    """The inked pixels of many steps' cuts and their ink (Eq. 21-23), evaluated together:
    the rows of all steps are stacked and every cut is one more window. Each pixel's values
    do not depend on what else is evaluated with it, so any grouping gives the same marks,
    bit for bit."""
    real = [c for c in cuts if c is not None]
    if not real:
        return [[] for _ in cuts]
    win, shape, chord = _windows(real, ppm)
    xy, count = _cur_u(real)
    seg_win = np.repeat(np.arange(len(count)), count)  # the cut of every segment
    seg_at = (count.cumsum() - count).tolist()
    if len(real) == 1:
        c = real[0]
        prims, rows = c.prims, c.rows
    else:
        offs = np.cumsum([0] + [c.rows.centre.shape[0] for c in real[:-1]])
        prims = np.concatenate([c.prims + o for c, o in zip(real, offs, strict=True)])
        rows = SurfaceRows._make(
            np.concatenate(parts) for parts in zip(*(c.rows for c in real), strict=True)
        )
    lo, hi = _scanline_spans(xy, seg_win, ppm, win, SPAN_MARGIN_PX + chord)
    pixels, edge = _marks_ink_batched(prims, win, lo, hi, ppm, rows)
    redo = np.nonzero(edge)[0]
    if redo.size:  # the solid reaches past a span: scan those cuts' whole bounding boxes
        whole = win[redo]
        lo_hi = (
            np.zeros(int(whole[:, 2].sum()), dtype=np.int64),
            np.repeat(whole[:, 3], whole[:, 2]),
        )
        again = _marks_ink_batched(prims[redo], whole, *lo_hi, ppm, rows).pixels
        for jj, j in enumerate(redo.tolist()):
            pixels[j] = again[jj]
    out, at = [], 0
    win_l, shape_l, count_l = win.tolist(), shape.tolist(), count.tolist()
    for c in cuts:
        if c is None:
            out.append([])
            continue
        marks = []
        for j, i in enumerate(c.prims.tolist()):
            px = pixels[at + j]
            marks.append(
                Mark(
                    primitive=i,
                    iy0=win_l[at + j][0],
                    ix0=win_l[at + j][1],
                    rows=px.rows,
                    cols=px.cols,
                    wet=px.wet,
                    col=px.col,
                    lateral=px.lateral,
                    depth=px.depth,
                    shape=tuple(shape_l[at + j]),
                    segments=xy[seg_at[at + j] : seg_at[at + j] + count_l[at + j]],
                    area_bbox=float(c.area[j]),
                    height=float(c.height[j]),
                )
            )
        out.append(marks)
        at += len(c.prims)
    return out


def compute_marks(brush, sec, ink_rows, ppm: float, paper_shape) -> list[Mark]:
    """The current drawing mark of every primitive that reaches the paper."""
    return fill_marks([cut_marks(brush, sec, ink_rows, ppm, paper_shape)], ppm)[0]


class PixelInk(NamedTuple):
    """The inked pixels of one window and their ink (Eq. 23)."""

    rows: np.ndarray  # (P,) window rows
    cols: np.ndarray  # (P,) window columns
    wet: np.ndarray  # (P,) float32
    col: np.ndarray  # (P, 3) float32 ink density
    lateral: np.ndarray  # (P,) position across the major axis, [-1, 1]
    depth: np.ndarray  # (P,) Eq. 23's f: 0 on the middle control axis, 1 at the surface


class WindowsInk(NamedTuple):
    """``_marks_ink``'s answer: every window's inked pixels, and whether an inked pixel of the
    window lies at the end of a span that the window could extend (the span may then have cut
    the solid short)."""

    pixels: list  # [PixelInk] one per window
    edge: np.ndarray  # (k,) bool


def _marks_ink_batched(prims, win, lo, hi, ppm, rows) -> WindowsInk:
    """``_marks_ink`` over bands of scanlines of at most about BATCH_PIXELS span pixels (one
    band unless the marks are many and large), so that memory stays bounded; a band may cut a
    window in two, whose pieces are joined again."""
    k = len(prims)
    h = win[:, 2]
    lens = hi - lo
    total = int(lens.sum())
    if total <= BATCH_PIXELS:
        return _marks_ink(prims, win, lo, hi, ppm, rows)
    band = (np.cumsum(lens) - lens) // BATCH_PIXELS  # band of every stacked scanline
    scan_win = np.repeat(np.arange(k), h)
    start = np.cumsum(h) - h
    # pieces: maximal runs of scanlines of one window in one band
    brk = np.r_[True, (band[1:] != band[:-1]) | (scan_win[1:] != scan_win[:-1])]
    p0 = np.nonzero(brk)[0]
    p1 = np.r_[p0[1:], len(band)]
    pw = scan_win[p0]  # window of each piece
    pieces = [[] for _ in range(k)]
    edge = np.zeros(k, dtype=bool)
    for b in np.unique(band[p0]).tolist():
        sel = np.nonzero(band[p0] == b)[0]
        js = pw[sel]
        off = p0[sel] - start[js]  # first row of each piece in its window
        wp = win[js].copy()
        wp[:, 0] += off
        wp[:, 2] = p1[sel] - p0[sel]
        r = np.concatenate([np.arange(p0[s], p1[s]) for s in sel.tolist()])
        part = _marks_ink(prims[js], wp, lo[r], hi[r], ppm, rows)
        edge[js] |= part.edge
        for t, j in enumerate(js.tolist()):
            px = part.pixels[t]
            pieces[j].append(px._replace(rows=px.rows + off[t]))  # rows in the window's frame
    none = _no_ink(1).pixels[0]  # a window without rows (no columns on the paper)
    joined = [
        PixelInk._make(np.concatenate(f) for f in zip(*p, strict=True)) if p else none
        for p in pieces
    ]
    return WindowsInk(joined, edge)


def _no_ink(k) -> WindowsInk:
    """``_marks_ink``'s answer for k windows without a pixel inside."""
    none_i, none_f = np.zeros(0, dtype=np.int64), np.zeros(0)
    wet, col = np.zeros(0, dtype=np.float32), np.zeros((0, 3), dtype=np.float32)
    return WindowsInk(
        [PixelInk(none_i, none_i, wet, col, none_f, none_f)] * k, np.zeros(k, dtype=bool)
    )


class Scanlines(NamedTuple):
    """The pixel rows of all windows, stacked in window order, and their spans."""

    win: np.ndarray  # (S,) window of every scanline
    row: np.ndarray  # (S,) its row in the window
    x0: np.ndarray  # (S,) the window's first paper column
    y: np.ndarray  # (S,) y of the pixel centres, mm
    lo: np.ndarray  # (S,) span [lo, hi) in window columns
    hi: np.ndarray
    first: np.ndarray  # (S,) the scanline's first pixel among all span pixels


class ContactRows(NamedTuple):
    """The surface rows of every window's primitive that can bound a slab that counts (the
    rows next to one that reaches the paper): rows j0..j1 of the surface."""

    c: np.ndarray  # (k, Ns, 3) row centres V^
    U: np.ndarray  # (k, Ns, 3) semi-axis vectors
    V: np.ndarray
    T: np.ndarray  # (k, Ns, 3) unit tangents: the normals of the rows' planes
    slab_ok: np.ndarray  # (k, Ns - 1) slabs between rows that reach the paper
    j0: int
    j1: int


class RowPlanes(NamedTuple):
    """Every row's plane on every scanline: the signed distance of the pixel at x (mm) is
    Hd = x tx + h; it is >= 0 on window columns [start, stop)."""

    tx: np.ndarray  # (S, Ns)
    h: np.ndarray  # (S, Ns)
    start: np.ndarray  # (S, Ns)
    stop: np.ndarray  # (S, Ns)


class Entries(NamedTuple):
    """The crossing pixels of the slabs, interval by interval: a crossing interval is a run of
    columns of one scanline in one slab; an entry is one pixel of one interval."""

    scan: np.ndarray  # (I,) scanline of every interval
    slab: np.ndarray  # (I,) its slab, counted from the window's row j0
    win: np.ndarray  # (I,) its window
    count: np.ndarray  # (I,) its entries (after dropping a fold's middle slabs)
    cols: np.ndarray  # (E,) window column of every entry
    entry_scan: np.ndarray  # (E,) scanline of every entry
    interval: np.ndarray  # (E,) interval of every entry
    pair: tuple | None  # (first, last) entries of the pixels in several slabs, or None


# |U|^2, |V|^2 and U.V as quadratics in lam (uu0 + lam uu1 + lam^2 uu2 ...): the fields
# ``SlabQuadratics`` and ``IntervalQuadratics`` begin with
_GRAM_FIELDS = "uu0 uu1 uu2 vv0 vv1 vv2 uv0 uv1 uv2 "
_SLAB_FIELDS = "ux0 uy0 cu0 ux1 uy1 cu1 cu2 vx0 vy0 cv0 vx1 vy1 cv1 cv2"
_INTERVAL_FIELDS = "ux0 du0 ux1 du1 cu2 vx0 dv0 vx1 dv1 cv2 tx0 h0 tx1 h1"


class SlabQuadratics(namedtuple("SlabQuadratics", _GRAM_FIELDS + _SLAB_FIELDS)):
    """The section solve's dot products as quadratics in lam, one column per slab. Between rows
    j and j + 1 the section's centre V^ = c0 + lam dc, U = U0 + lam dU and V = V0 + lam dV, so
    with tau = (x, y, 0) on the paper:
    |U|^2 = uu0 + lam uu1 + lam^2 uu2, |V|^2 likewise (vv), U.V likewise (uv), and
    (tau - V^).U = x (ux0 + lam ux1) + y (uy0 + lam uy1) - (cu0 + lam cu1 + lam^2 cu2),
    (tau - V^).V likewise (vx, vy, cv)."""

    __slots__ = ()


class IntervalQuadratics(namedtuple("IntervalQuadratics", _GRAM_FIELDS + _INTERVAL_FIELDS)):
    """``SlabQuadratics`` on one scanline (y fixed), one column per interval or per entry:
    (tau - V^).U = x ux0 + du0 + lam (x ux1 + du1 - lam cu2), likewise (tau - V^).V, and the
    planes of rows j and j + 1 on the scanline (Hd = x tx + h)."""

    __slots__ = ()


class SectionSolve(NamedTuple):
    """Every entry placed in its slab: tau - V^ = p U + q V in the section plane at lam."""

    lam: np.ndarray  # (E,) position between rows j and j + 1
    p: np.ndarray  # (E,)
    q: np.ndarray  # (E,)
    f2: np.ndarray  # (E,) p^2 + q^2: inside the section where <= 1


def _marks_ink(prims, win, lo, hi, ppm, rows: SurfaceRows) -> WindowsInk:
    """Which pixels of the windows' spans lie inside their primitive's solid, and their ink
    (Eq. 21-23), for all primitives at once.

    A pixel lies in the section plane through it between two rows of the surface where its
    signed distance Hd to the rows' planes changes sign; the full evaluation runs on the first
    and the last such slab (a fold of the bent axis gives two: the solid is the union of its
    sections). Hd = x T_x + (y T_y - c.T) is affine in the pixel's column on a scanline and,
    rounded, still monotone in it: so each row's sign changes at one column per scanline, found
    from the row's plane and confirmed with the same rounded formula, and every slab's
    crossing pixels on a scanline are at most two column intervals. The work is per scanline
    and row plus per pixel, never per pixel and row. Only slabs between rows that reach the
    paper count. The stages: ``_crossing_columns``, ``_slab_intervals``, ``_section_solve``,
    ``_pixel_ink``."""
    k = len(prims)
    sc = _scanlines(win, lo, hi, ppm)
    N = int((hi - lo).sum())
    if N == 0:
        return _no_ink(k)
    rows_k = _contact_rows(prims, rows)
    if rows_k is None:
        return _no_ink(k)
    planes = _crossing_columns(sc, rows_k, ppm)
    ent = _slab_intervals(sc, planes, rows_k.slab_ok, N)
    if ent is None:
        return _no_ink(k)
    Ns = rows_k.j1 - rows_k.j0
    slab = ent.win * (Ns - 1) + ent.slab  # every interval's slab in the tables
    x = (sc.x0[ent.entry_scan] + ent.cols + 0.5) / ppm
    iq = _interval_quadratics(rows_k, planes, ent, sc.y[ent.scan], slab)
    sol = _section_solve(iq, ent.count, x)
    keep = np.ones(len(sol.f2), dtype=bool)
    if ent.pair is not None:  # of the first and the last slab, the more inside: union of sections
        fi, la = ent.pair
        keep[np.where(sol.f2[la] < sol.f2[fi], fi, la)] = False
    inside = keep & (sol.f2 <= 1.0)
    edge = _span_edges(sc, ent, inside, win[:, 3], k)
    ok = np.nonzero(inside)[0]
    n_ok = np.bincount(ent.interval[ok], minlength=len(ent.scan))  # inked pixels per interval
    cols = ent.cols[ok]
    inkp = rows.ink[prims, rows_k.j0 : rows_k.j1]
    wet, col = _pixel_ink(inkp, rows_k, sc, ent, slab, n_ok, sol.lam[ok], cols, ppm)
    cover = _cover(rows_k, slab, n_ok, sol.lam[ok], sol.p[ok], sol.q[ok], ppm)
    col = per_pixel(col, cover.astype(np.float32))
    lateral = np.clip(sol.p[ok], -1.0, 1.0)
    depth = np.sqrt(sol.f2[ok])
    rws = sc.row[ent.entry_scan[ok]]
    ends = np.cumsum(np.bincount(ent.win, weights=n_ok, minlength=k)).astype(np.int64).tolist()
    fields = (rws, cols, wet, col, lateral, depth)  # every window's run of them (views)
    starts = [0, *ends[:-1]]
    pixels = [PixelInk._make(a[s:e] for a in fields) for s, e in zip(starts, ends, strict=True)]
    return WindowsInk(pixels, edge)


def _scanlines(win, lo, hi, ppm) -> Scanlines:
    iy0, ix0, h = win[:, 0], win[:, 1], win[:, 2]
    scan_win = np.repeat(np.arange(len(win)), h)
    scan_row = np.arange(len(lo)) - np.repeat(np.cumsum(h) - h, h)
    lens = hi - lo
    return Scanlines(
        win=scan_win,
        row=scan_row,
        x0=ix0[scan_win],
        y=(iy0[scan_win] + scan_row + 0.5) / ppm,
        lo=lo,
        hi=hi,
        first=np.cumsum(lens) - lens,
    )


def _contact_rows(prims, rows: SurfaceRows) -> ContactRows | None:
    """Only the rows next to one that reaches the paper can bound a slab that counts."""
    reach = rows.zmin[prims] <= 0.0
    near = np.nonzero(reach.any(axis=0))[0]
    if near.size == 0:
        return None
    j0, j1 = max(int(near[0]) - 1, 0), min(int(near[-1]) + 2, rows.centre.shape[1])
    reach = reach[:, j0:j1]
    c, U, V, T = (a[prims, j0:j1] for a in (rows.centre, rows.U, rows.V, rows.T))
    return ContactRows(c, U, V, T, reach[:, :-1] | reach[:, 1:], j0, j1)


def _crossing_columns(sc: Scanlines, rk: ContactRows, ppm) -> RowPlanes:
    """The column where every row's Hd changes sign on every scanline: estimated from the
    row's plane, then confirmed with the rounded formula itself (monotone in the column)."""
    cT = dot(rk.c, rk.T)  # (k, Ns)
    T0 = rk.T[sc.win, :, 0]  # (S, Ns)
    bk = sc.y[:, None] * rk.T[sc.win, :, 1] - cT[sc.win]
    sl, sh = sc.lo[:, None], sc.hi[:, None]
    x0 = sc.x0[:, None]
    rise = T0 > 0  # Hd >= 0 on a suffix of the scanline (a prefix when T0 < 0)
    with np.errstate(divide="ignore", invalid="ignore"):
        cstar = np.where(T0 != 0, (-bk / np.where(T0 != 0, T0, 1.0)) * ppm - x0 - 0.5, 0.0)
    cstar = np.clip(cstar, -1.0, float(np.max(sc.hi, initial=0)) + 1.0)  # inf where T0 is tiny
    t = np.where(rise, np.ceil(cstar), np.floor(cstar) + 1).astype(np.int64)
    t = np.clip(t, sl, sh)

    def flipped(col):  # True where the column is past the sign change (monotone in col)
        hd = ((x0 + col + 0.5) / ppm) * T0 + bk
        return np.where(rise, hd >= 0, hd < 0)

    for _ in range(4):  # the plane's estimate is off by a column at most: confirm exactly
        back = (t > sl) & flipped(t - 1)
        fwd = (t < sh) & ~flipped(t) & ~back
        if not (back.any() or fwd.any()):
            break
        t = t - back + fwd
    flat = T0 == 0
    A = np.where(rise, t, sl)
    B = np.where(rise, sh, t)
    A = np.where(flat, sl, A)
    B = np.where(flat, np.where(bk >= 0, sh, sl), B)
    return RowPlanes(tx=T0, h=bk, start=A, stop=B)


def _slab_intervals(sc: Scanlines, planes: RowPlanes, slab_ok, N: int) -> Entries | None:
    """The crossing intervals, in order of scanline (so of window), slab and part; every pixel
    of an interval is an entry, and a pixel is an entry of each slab it crosses (a fold: more)."""
    A, B = planes.start, planes.stop
    Ns = A.shape[1]
    # crossing pixels of slab j: [A_j, B_j) xor [A_j+1, B_j+1) = [a0, a1) u [b0, b1)
    a0 = np.minimum(A[:, :-1], A[:, 1:])
    a1 = np.maximum(A[:, :-1], A[:, 1:])
    b0 = np.minimum(B[:, :-1], B[:, 1:])
    b1 = np.maximum(B[:, :-1], B[:, 1:])
    s0 = np.stack([a0, np.maximum(a1, b0)], axis=-1)  # (S, Ns - 1, 2)
    s1 = np.stack([np.minimum(a1, b0), b1], axis=-1)
    ok = slab_ok[sc.win][..., None]
    n = np.where(ok, np.maximum(s1 - s0, 0), 0).ravel()
    if not n.any():
        return None
    iv = np.nonzero(n)[0]
    n = n[iv]
    E = int(n.sum())
    iv_scan = iv // (2 * (Ns - 1))
    step = np.arange(E) - np.repeat(np.cumsum(n) - n, n)  # position in its interval
    cols = np.repeat(s0.ravel()[iv], n) + step  # window column of every entry
    scan_e = np.repeat(iv_scan, n)
    e_iv = np.repeat(np.arange(len(iv)), n)  # interval of every entry
    pid = sc.first[scan_e] + cols - sc.lo[scan_e]  # the entry's pixel among all span pixels
    folds = _first_and_last_slab(pid, N)
    pair, per_iv = None, n
    if folds is not None:
        sel, pair = folds
        cols, scan_e, e_iv = cols[sel], scan_e[sel], e_iv[sel]
        per_iv = np.bincount(e_iv, minlength=len(iv))
    return Entries(
        scan=iv_scan,
        slab=(iv // 2) % (Ns - 1),
        win=sc.win[iv_scan],
        count=per_iv,
        cols=cols,
        entry_scan=scan_e,
        interval=e_iv,
        pair=pair,
    )


def _first_and_last_slab(pid, N: int):
    """A pixel in several slabs (where the axis folds or the rows' planes fan out) keeps only
    its entries of the first and the last slab; in interval order a pixel's entries come by
    increasing slab. None when no pixel is in several slabs, else (the entries kept, and the
    positions among them of every such pixel's first and last entry)."""
    visits = np.bincount(pid, minlength=N)
    if visits.max(initial=0) <= 1:
        return None
    E = len(pid)
    ent = np.arange(E)
    multi_px = np.nonzero(visits > 1)[0]
    fpos = np.full(N, E)
    lpos = np.full(N, -1)
    np.minimum.at(fpos, pid, ent)
    np.maximum.at(lpos, pid, ent)
    keep = (visits[pid] == 1) | (ent == fpos[pid]) | (ent == lpos[pid])
    rank = np.cumsum(keep) - 1  # entry -> position among the kept
    return np.nonzero(keep)[0], (rank[fpos[multi_px]], rank[lpos[multi_px]])


def _slab_quadratics(rk: ContactRows) -> SlabQuadratics:
    """``SlabQuadratics`` of every slab, (k, Ns - 1) each."""
    dc, dU, dV = np.diff(rk.c, axis=1), np.diff(rk.U, axis=1), np.diff(rk.V, axis=1)
    c0, U0, V0 = rk.c[:, :-1], rk.U[:, :-1], rk.V[:, :-1]
    return SlabQuadratics(
        uu0=dot(U0, U0),
        uu1=2 * dot(U0, dU),
        uu2=dot(dU, dU),
        vv0=dot(V0, V0),
        vv1=2 * dot(V0, dV),
        vv2=dot(dV, dV),
        uv0=dot(U0, V0),
        uv1=dot(U0, dV) + dot(dU, V0),
        uv2=dot(dU, dV),
        ux0=U0[..., 0],
        uy0=U0[..., 1],
        cu0=dot(c0, U0),
        ux1=dU[..., 0],
        uy1=dU[..., 1],
        cu1=dot(c0, dU) + dot(dc, U0),
        cu2=dot(dc, dU),
        vx0=V0[..., 0],
        vy0=V0[..., 1],
        cv0=dot(c0, V0),
        vx1=dV[..., 0],
        vy1=dV[..., 1],
        cv1=dot(c0, dV) + dot(dc, V0),
        cv2=dot(dc, dV),
    )


def _interval_quadratics(rk: ContactRows, planes: RowPlanes, ent: Entries, y, slab):
    """``IntervalQuadratics`` of every interval: its slab's, with the scanline's y folded in."""
    sq = _slab_quadratics(rk)
    s = SlabQuadratics._make(np.take(np.stack(sq).reshape(len(sq), -1), slab, axis=1))
    row0 = ent.scan * rk.c.shape[1] + ent.slab
    return IntervalQuadratics(
        *s[:9],
        ux0=s.ux0,
        du0=y * s.uy0 - s.cu0,
        ux1=s.ux1,
        du1=y * s.uy1 - s.cu1,
        cu2=s.cu2,
        vx0=s.vx0,
        dv0=y * s.vy0 - s.cv0,
        vx1=s.vx1,
        dv1=y * s.vy1 - s.cv1,
        cv2=s.cv2,
        tx0=np.take(planes.tx, row0),
        h0=np.take(planes.h, row0),
        tx1=np.take(planes.tx, row0 + 1),
        h1=np.take(planes.h, row0 + 1),
    )


def _interval_chunks(count, size: int = CHUNK_ENTRIES):
    """Runs of whole intervals of about ``size`` entries (at least one interval each): yields
    (first interval, end interval, first entry, end entry) for intervals of ``count`` entries."""
    ends = np.cumsum(count)
    total = int(ends[-1]) if len(ends) else 0
    if total <= size:
        yield 0, len(count), 0, total
        return
    cut = np.searchsorted(ends, np.arange(size, total, size), side="left") + 1
    bounds = np.unique(np.r_[0, np.minimum(cut, len(count)), len(count)]).tolist()
    for i0, i1 in zip(bounds[:-1], bounds[1:], strict=False):
        yield i0, i1, int(ends[i0] - count[i0]), int(ends[i1 - 1])


def _section_solve(iq: IntervalQuadratics, count, x) -> SectionSolve:
    """Every entry's section plane (at lam between its slab's rows, where the rounded Hd of the
    crossing search changes sign) and its place there: tau - V^ = p U + q V (least squares,
    tolerant of the flat tip line). The intervals' quadratics are repeated over their entries
    into contiguous rows, a cache-sized run of intervals at a time (``CHUNK_ENTRIES``)."""
    out = SectionSolve(*(np.empty(len(x)) for _ in SectionSolve._fields))
    table = np.stack(iq)
    for i0, i1, e0, e1 in _interval_chunks(count):
        part = _section_solve_run(table[:, i0:i1], count[i0:i1], x[e0:e1])
        for o, v in zip(out, part, strict=True):
            o[e0:e1] = v
    return out


def _section_solve_run(table, count, x) -> SectionSolve:
    """``_section_solve`` of a run of intervals (``table``: their stacked quadratics)."""
    C = IntervalQuadratics._make(np.repeat(table, count, axis=1))
    h0 = x * C.tx0 + C.h0
    h1 = x * C.tx1 + C.h1
    lam = np.clip(h0 / np.where(h0 != h1, h0 - h1, 1.0), 0.0, 1.0)
    uu = C.uu0 + lam * (C.uu1 + lam * C.uu2) + 1e-12
    vv = C.vv0 + lam * (C.vv1 + lam * C.vv2) + 1e-12
    uv = C.uv0 + lam * (C.uv1 + lam * C.uv2)
    du = x * C.ux0 + C.du0 + lam * (x * C.ux1 + C.du1 - lam * C.cu2)
    dv = x * C.vx0 + C.dv0 + lam * (x * C.vx1 + C.dv1 - lam * C.cv2)
    det = uu * vv - uv * uv
    p = (du * vv - dv * uv) / det
    q = (dv * uu - du * uv) / det
    return SectionSolve(lam=lam, p=p, q=q, f2=p * p + q * q)


def _span_edges(sc: Scanlines, ent: Entries, inside, win_w, k: int) -> np.ndarray:
    """Windows with an inked pixel at the end of a span that the window could extend: the
    first or the last kept entry of an interval."""
    per_iv = ent.count
    has = per_iv > 0
    first = (np.cumsum(per_iv) - per_iv)[has]
    last = first + per_iv[has] - 1
    scan, wh = ent.scan[has], ent.win[has]
    s_lo, s_hi = sc.lo[scan], sc.hi[scan]
    hit = inside[first] & (ent.cols[first] == s_lo) & (s_lo > 0)
    hit |= inside[last] & (ent.cols[last] == s_hi - 1) & (s_hi < win_w[wh])
    return np.bincount(wh[hit], minlength=k) > 0


def _pixel_ink(inkp, rk: ContactRows, sc: Scanlines, ent: Entries, slab, n_ok, lam, cols, ppm):
    """The ink of the inked pixels (Eq. 21-23), in float32 as the paper keeps it. Per
    interval: V^ and its ink at row j and their change to row j + 1 (Eq. 21 along the axis),
    and the pixel's offset from row j's centre at the interval's first column, all small
    numbers (millimetres from the section), repeated over the interval's inked pixels. The
    texture function (wr, cr, wv, cv, Eq. 22) is usually one ink's everywhere: then it is used
    as scalars. ``inkp`` (k, Ns, INK_WIDTH) is the ink at the contact rows' V^."""
    tex = inkp[..., TEXTURE]
    tex0 = tex[0, 0]
    same_tex = bool(np.all(np.abs(tex - tex0) <= 1e-12 * (1.0 + np.abs(tex0))))
    nf = LOAD.stop if same_tex else inkp.shape[-1]  # ink columns carried per pixel
    c0s = rk.c[:, :-1].reshape(-1, 3)[slab]
    dc = np.diff(rk.c, axis=1)
    per = np.concatenate(
        [
            ((sc.x0[ent.scan] + 0.5) / ppm - c0s[:, 0])[None],
            (sc.y[ent.scan] - c0s[:, 1])[None],
            -c0s[:, 2][None],
            dc.reshape(-1, 3)[slab].T,
            inkp[:, :-1, :nf].reshape(-1, nf)[slab].T,
            np.diff(inkp[..., :nf], axis=1).reshape(-1, nf)[slab].T,
        ]
    ).astype(np.float32)
    tex_scalars = None
    if same_tex:
        tex_scalars = {
            n: [np.float32(v) for v in inkp[0, 0, INK_FIELDS[n]].tolist()] for n in TEXTURE_NAMES
        }
    lam = lam.astype(np.float32)
    wet = np.empty(len(lam), dtype=np.float32)
    col = np.empty((len(lam), 3), dtype=np.float32)
    for i0, i1, e0, e1 in _interval_chunks(n_ok):  # cache-sized runs (CHUNK_ENTRIES)
        wet[e0:e1], col[e0:e1] = _pixel_ink_run(
            per[:, i0:i1], n_ok[i0:i1], lam[e0:e1], cols[e0:e1], nf, tex_scalars, ppm
        )
    return wet, col


def _pixel_ink_run(per, n_ok, lam, cols, nf: int, tex_scalars, ppm):
    """``_pixel_ink`` of a run of intervals: ``per`` their rows of per-interval numbers,
    repeated over their inked pixels; ``tex_scalars`` the one texture function (None: each
    pixel's own, from V^'s ink)."""
    D = np.repeat(per, n_ok, axis=1)
    offset, axis_step, ink0, ink_step = D[0:3], D[3:6], D[6 : 6 + nf], D[6 + nf :]
    # tau - V^ (V^ = c0 + lam dc on the axis), then Eq. 22 and 23: V = V^ + (tau - V^) / f lies
    # on the surface and takes its ink from V^'s texture function, and Eq. 23 mixes V^'s and
    # V's by f, which folds into one factor on V^'s ink:
    # (1 - f) a + f a (1 + |V - V^| r + (V - V^).v) = a (1 + |tau - V^| r + (tau - V^).v)
    ox = cols.astype(np.float32) * np.float32(1.0 / ppm) + offset[0] - lam * axis_step[0]
    oy = offset[1] - lam * axis_step[1]
    oz = offset[2] - lam * axis_step[2]
    at = ink0 + lam * ink_step  # Eq. 21: V^'s ink between the two rows around it
    dist = np.sqrt(ox * ox + oy * oy + oz * oz)
    o = (dist, ox, oy, oz)
    if tex_scalars is not None:
        f = tex_scalars
    else:
        f = {n: list(at[INK_FIELDS[n]]) for n in TEXTURE_NAMES}
    w_fac = _factor(o, (*f["wr"], *f["wv"]))  # Eq. 22, 23
    c_fac = _factor(o, (*f["cr"], *f["cv"]))
    wet = at[INK_FIELDS["wet"].start] * w_fac
    np.maximum(wet, 0.0, out=wet)

    col = np.empty((len(lam), 3), dtype=np.float32)
    for ch in range(3):
        np.multiply(at[INK_FIELDS["col"].start + ch], c_fac, out=col[:, ch])
    np.clip(col, 0.0, 1.0, out=col)
    return wet, col


def _cover(rk: ContactRows, slab, n_ok, lam, p, q, ppm) -> np.ndarray:
    """``section_cover`` of the inked pixels, from their sections' semi-axes between the rows
    of their slabs: per interval the twelve components of U, V at row j and their change to
    row j + 1, repeated over its inked pixels as contiguous rows (a cache-sized run of
    intervals at a time), then each component as U0 + lam dU (the same products and sums as
    on (P, 3) vectors)."""
    U0, V0 = (a[:, :-1].reshape(-1, 3)[slab] for a in (rk.U, rk.V))
    dU, dV = (np.diff(a, axis=1).reshape(-1, 3)[slab] for a in (rk.U, rk.V))
    per = np.concatenate([U0.T, V0.T, dU.T, dV.T])  # (12, intervals)
    out = np.empty(len(lam))
    for i0, i1, e0, e1 in _interval_chunks(n_ok):
        D = np.repeat(per[:, i0:i1], n_ok[i0:i1], axis=1)
        L = lam[e0:e1]
        u = [D[c] + L * D[6 + c] for c in range(3)]
        v = [D[3 + c] + L * D[9 + c] for c in range(3)]
        out[e0:e1] = _section_cover(u, v, p[e0:e1], q[e0:e1], ppm)
    return out


def section_cover(U, V, p, q, ppm: float) -> np.ndarray:
    """Model addition: the share of an inked pixel the section covers, from where it lies in
    its section, tau - V^ = p U + q V (U, V the section's semi-axes, (P, 3)). The paper is the
    horizontal line h of the section plane through tau; along it the section ends at the
    nearest t with |(p, q) + t (alpha, beta)| = 1 (h = alpha U + beta V): the pixel is half
    covered where that end passes its centre, wholly a pixel further in. Eq. 23's colour of the
    pixel is scaled by it (a pixel partly under the hair takes part of its colour), so the edge
    a section leaves is as smooth as the section, not the staircase of the pixel centres it
    holds. The section parallel to the paper (no horizontal line) takes h along U."""
    return _section_cover([U[:, 0], U[:, 1], U[:, 2]], [V[:, 0], V[:, 1], V[:, 2]], p, q, ppm)


def _section_cover(u, v, p, q, ppm: float) -> np.ndarray:
    """``section_cover`` of semi-axes given by their components ``u``, ``v`` ([x, y, z],
    arrays of P): the same arithmetic (N = U x V's x and y as ``cross``'s, |U|^2 summed as
    ``dot``'s einsum sums: x, then z, then y)."""
    ux, uy, uz = u
    vx, vy, vz = v
    nx = uy * vz - uz * vy  # (U x V)_x
    ny = uz * vx - ux * vz  # (U x V)_y
    n = np.hypot(nx, ny)
    uu = np.maximum(ux * ux + uz * uz + uy * uy, 1e-12)
    along_u = n <= 1e-9 * uu
    if along_u.any():
        un = np.maximum(np.hypot(ux, uy), 1e-12)
        hx = np.where(along_u, ux / un, ny / np.where(along_u, 1.0, n))
        hy = np.where(along_u, uy / un, -nx / np.where(along_u, 1.0, n))
    else:
        hx, hy = ny / n, -nx / n
    vv = np.maximum(vx * vx + vz * vz + vy * vy, 1e-12)
    alpha = (hx * ux + hy * uy) / uu
    beta = (hx * vx + hy * vy) / vv
    a = np.maximum(alpha * alpha + beta * beta, 1e-12)
    b = p * alpha + q * beta
    c = p * p + q * q - 1.0
    inward = (np.sqrt(np.maximum(b * b - a * c, 0.0)) - np.abs(b)) / a  # mm to the nearer end
    return np.clip(0.5 + inward * ppm, 0.0, 1.0)


def _factor(o, coef):
    """1 + |tau - V^| r + (tau - V^).v of Eq. 22-23, leaving out terms whose scalar is 0."""
    out = None
    for a, c in zip(o, coef, strict=True):
        if np.ndim(c) == 0 and c == 0:
            continue
        out = a * c if out is None else out + a * c
    if out is None:
        return np.float32(1.0)
    out += np.float32(1.0)
    return out
