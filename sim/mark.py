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
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

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
# a segment part this near a scanline (besides the chord error) bounds the scanline's span
SPAN_NEAR_PX = 0.5
# span pixels evaluated together (all primitives' marks at once, in groups of about this many)
BATCH_PIXELS = 1 << 17

_SEG_A = np.full((16, 2), -1)
_SEG_B = np.full((16, 2), -1)
for _c, _pairs in _CASES.items():
    for _k, (_e0, _e1) in enumerate(_pairs):
        _SEG_A[_c, _k] = _e0
        _SEG_B[_c, _k] = _e1


@dataclass
class Mark:
    """One primitive's current drawing mark, rasterised into a pixel window of the paper."""

    primitive: int
    iy0: int  # window origin (row from the bottom of the paper, column from the left)
    ix0: int
    rows: np.ndarray  # (P,) pixel rows inside the window
    cols: np.ndarray  # (P,)
    wet: np.ndarray  # (P,) wetness of the brush at tau (Eq. 23)
    col: np.ndarray  # (P, 3) ink density of the brush at tau (Eq. 23)
    lateral: np.ndarray  # (P,) position across the primitive's major axis, [-1, 1]
    shape: tuple  # window (h, w)
    segments: np.ndarray  # (M, 2, 2) the intersection curve cur_u, mm
    area_bbox: float  # S_i: area of the section's bounding box (mm^2), Eq. 10
    height: float  # hei_i: distance from the section to the tip line's midpoint (mm)


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

    def crossing(pa, pb):
        za, zb = pa[:, 2], pb[:, 2]
        t = za / np.where(za != zb, za - zb, 1.0)
        return pa + t[:, None] * (pb - pa)

    # crossing points of the four edges of each cell (computed per edge, so shared edges agree)
    e0 = crossing(p00, p01)
    e1 = crossing(p01, p11)
    e2 = crossing(p10, p11)
    e3 = crossing(p00, p10)
    E = np.stack([e0, e1, e2, e3], axis=1)  # (C, 4, 3)
    segs, owner = [], []
    for k in range(2):
        a, b = _SEG_A[cs, k], _SEG_B[cs, k]
        ok = a >= 0
        if ok.any():
            r = np.nonzero(ok)[0]
            segs.append(np.stack([E[r, a[ok]], E[r, b[ok]]], axis=1))
            owner.append(gg[r])
    return np.concatenate(segs, axis=0), np.concatenate(owner)


def slice_grid(X) -> np.ndarray:
    """Segments (M, 2, 3) where one periodic-in-t grid X (Ns, Nt, 3) crosses z = 0."""
    return slice_grids(X[None])[0]


def _scanline_spans(xy, owner, ppm, win, margin_px, near_px):
    """Pixel columns [lo, hi) of every pixel row of every window that can lie inside a cut.

    A section's boundary is its cur_u, so every inside point of a scanline has cur_u on both
    sides of it on that scanline: the pixels outside the x range of the parts of the segments
    that come near the scanline are outside (the margins cover the grid's chords against the
    true surface). A segment part is near when it lies within ``near_px`` of the scanline
    (then it is widened by ``margin_px``); a row that no segment comes that near (the top and
    bottom of a cut) takes the parts within ``margin_px`` instead. All windows at once: ``xy``
    (M, 2, 2) segments, ``owner`` (M,) their window, ``win`` (k, 4) windows (iy0, ix0, h, w),
    ``margin_px`` and ``near_px`` (k,). Returns lo, hi over the windows' rows stacked in
    window order."""
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
    ends = []
    for band in (ms, (near_px / ppm)[owner][seg]):
        # the part of the segment within the band around the scanline, widened by the margin
        ta = np.where(flat, 0.0, (yc - band - sy0) / ddy)
        tb = np.where(flat, 1.0, (yc + band - sy0) / ddy)
        t0, t1 = np.minimum(ta, tb), np.maximum(ta, tb)
        xa, xb = sx0 + np.clip(t0, 0.0, 1.0) * dx, sx0 + np.clip(t1, 0.0, 1.0) * dx
        xlo, xhi, rows = np.minimum(xa, xb) - ms, np.maximum(xa, xb) + ms, row
        if ends:  # the near band: only segments that reach it
            near = (t0 <= 1.0) & (t1 >= 0.0) & (~flat | (np.abs(sy0 - yc) <= band))
            xlo, xhi, rows = xlo[near], xhi[near], row[near]
        lo_mm = np.full(total, np.inf)
        hi_mm = np.full(total, -np.inf)
        np.minimum.at(lo_mm, rows, xlo)
        np.maximum.at(hi_mm, rows, xhi)
        ends.append((lo_mm, hi_mm))
    (lo_w, hi_w), (lo_n, hi_n) = ends
    close = np.isfinite(lo_n)
    lo_mm = np.where(close, lo_n, lo_w)
    hi_mm = np.where(close, hi_n, hi_w)
    seen = np.isfinite(lo_mm)
    wx0 = np.repeat(ix0, h)
    ww = np.repeat(w, h)
    lo_mm = np.where(seen, lo_mm, 0.0)
    hi_mm = np.where(seen, hi_mm, 0.0)
    lo = np.clip(np.floor(lo_mm * ppm - 0.5).astype(np.int64) + 1 - wx0, 0, ww)
    hi = np.clip(np.floor(hi_mm * ppm - 0.5).astype(np.int64) + 1 - wx0, 0, ww)
    hi = np.where(seen, hi, lo)
    return lo, np.maximum(hi, lo)


@dataclass
class Cut:
    """The first half of one step's marks: where every primitive's solid meets the paper
    (cur_u, S_i and hei_i for the dynamics, Eq. 10) and its pixel window. ``fill_marks`` then
    finds the scanline spans, the inked pixels and their ink, for many steps at once."""

    prims: np.ndarray  # (k,) primitives with a cut
    win: np.ndarray  # (k, 4) windows (iy0, ix0, rows, cols), rows 0 if there are no columns
    shape: np.ndarray  # (k, 2) window (h, w)
    xy: np.ndarray  # (M, 2, 2) all cuts' cur_u, grouped by cut
    seg_win: np.ndarray  # (M,) the cut of every segment
    chord: np.ndarray  # (k,) the grid's chord error against the true sections, pixels
    rows: tuple  # the surface rows (c, U, V, T, zmin, ink) of every primitive
    segments: list  # (M_i, 2, 2) cur_u of each cut
    area: np.ndarray  # (k,) S_i
    height: np.ndarray  # (k,) hei_i

    def sizes(self, m: int):
        """S_i and hei_i of all m primitives (0 for those off the paper)."""
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
    X = (
        rows_c[touching, r0:r1][:, :, None, :]
        + rows_U[touching, r0:r1][:, :, None, :] * ring[None, None, :, 0, None]
        + rows_V[touching, r0:r1][:, :, None, :] * ring[None, None, :, 1, None]
    )
    all_segs, owner = slice_grids(X)
    if owner.size == 0:
        return None
    # each touching primitive's cut: bounding box, S_i and hei_i (Eq. 10), pixel window
    k = len(touching)
    xy_all = all_segs[:, :, :2]
    cnt = np.bincount(owner, minlength=k)
    order = np.argsort(owner, kind="stable")
    xy_sorted = xy_all[order]
    cuts = np.nonzero(cnt)[0]  # grids with a cut
    first = (np.cumsum(cnt) - cnt)[cuts]
    pts_x = xy_sorted[..., 0].min(axis=1), xy_sorted[..., 0].max(axis=1)
    pts_y = xy_sorted[..., 1].min(axis=1), xy_sorted[..., 1].max(axis=1)
    xmin = np.minimum.reduceat(pts_x[0], first)
    xmax = np.maximum.reduceat(pts_x[1], first)
    ymin = np.minimum.reduceat(pts_y[0], first)
    ymax = np.maximum.reduceat(pts_y[1], first)
    prims = touching[cuts]
    area = (xmax - xmin) * (ymax - ymin)
    centroid = np.stack([(xmin + xmax) / 2, (ymin + ymax) / 2, np.zeros(len(cuts))], axis=1)
    height = _norm(brush.cc[prims, -1] - centroid)
    ix0 = np.maximum(np.floor(xmin * ppm - 0.5).astype(np.int64), 0)
    iy0 = np.maximum(np.floor(ymin * ppm - 0.5).astype(np.int64), 0)
    ix1 = np.minimum(np.ceil(xmax * ppm - 0.5).astype(np.int64) + 1, W)
    iy1 = np.minimum(np.ceil(ymax * ppm - 0.5).astype(np.int64) + 1, H)
    h = np.maximum(iy1 - iy0, 0)
    w = np.maximum(ix1 - ix0, 0)
    # chord error of the grid's polygon against the true sections
    sag = 1.0 - np.cos(np.pi / ring.shape[0])
    semi = np.max(np.hypot(_norm(rows_U[prims]), _norm(rows_V[prims])), axis=1)
    chord = sag * semi * ppm
    slot = np.full(k, -1)
    slot[cuts] = np.arange(len(cuts))
    seg_win = slot[owner[order]]
    hh = np.where(w > 0, h, 0)  # a window without columns has no pixels
    win = np.stack([iy0, ix0, hh, w], axis=1)
    return Cut(
        prims,
        win,
        np.stack([h, w], axis=1),
        xy_sorted,
        seg_win,
        chord,
        (rows_c, rows_U, rows_V, rows_T, Zmin, ink_rows),
        np.split(xy_sorted, np.cumsum(cnt[cuts])[:-1]),
        area,
        height,
    )


def fill_marks(cuts: list[Cut | None], ppm: float) -> list[list[Mark]]:
    """The inked pixels of many steps' cuts and their ink (Eq. 21-23), evaluated together:
    the rows of all steps are stacked and every cut is one more window. Each pixel's values
    do not depend on what else is evaluated with it, so any grouping gives the same marks,
    bit for bit."""
    real = [c for c in cuts if c is not None]
    if not real:
        return [[] for _ in cuts]
    if len(real) == 1:
        c = real[0]
        prims, win, xy, seg_win, chord, rows = c.prims, c.win, c.xy, c.seg_win, c.chord, c.rows
    else:
        offs = np.cumsum([0] + [c.rows[0].shape[0] for c in real[:-1]])
        prims = np.concatenate([c.prims + o for c, o in zip(real, offs, strict=True)])
        woffs = np.cumsum([0] + [len(c.prims) for c in real[:-1]])
        seg_win = np.concatenate([c.seg_win + o for c, o in zip(real, woffs, strict=True)])
        win = np.concatenate([c.win for c in real])
        xy = np.concatenate([c.xy for c in real])
        chord = np.concatenate([c.chord for c in real])
        rows = tuple(np.concatenate(parts) for parts in zip(*(c.rows for c in real), strict=True))
    lo, hi = _scanline_spans(xy, seg_win, ppm, win, SPAN_MARGIN_PX + chord, SPAN_NEAR_PX + chord)
    ink, edge = _marks_ink_batched(prims, win, lo, hi, ppm, rows)
    redo = np.nonzero(edge)[0]
    if redo.size:  # the solid reaches past a span: scan those cuts' whole bounding boxes
        wr = win[redo]
        full = np.zeros(int(wr[:, 2].sum()), dtype=np.int64), np.repeat(wr[:, 3], wr[:, 2])
        again, _ = _marks_ink_batched(prims[redo], wr, *full, ppm, rows)
        for field, field2 in zip(ink, again, strict=True):
            for jj, j in enumerate(redo.tolist()):
                field[j] = field2[jj]
    out, at = [], 0
    for c in cuts:
        if c is None:
            out.append([])
            continue
        marks = []
        for j, i in enumerate(c.prims.tolist()):
            pr, pc, wet, col, lateral = (a[at + j] for a in ink)
            marks.append(
                Mark(
                    i,
                    int(c.win[j, 0]),
                    int(c.win[j, 1]),
                    pr,
                    pc,
                    wet,
                    col,
                    lateral,
                    (int(c.shape[j, 0]), int(c.shape[j, 1])),
                    c.segments[j],
                    float(c.area[j]),
                    float(c.height[j]),
                )
            )
        out.append(marks)
        at += len(c.prims)
    return out


def compute_marks(brush, sec, ink_rows, ppm: float, paper_shape) -> list[Mark]:
    """The current drawing mark of every primitive that reaches the paper."""
    return fill_marks([cut_marks(brush, sec, ink_rows, ppm, paper_shape)], ppm)[0]


def _norm(v):
    return np.sqrt(np.sum(v * v, axis=-1))


def _marks_ink_batched(prims, win, lo, hi, ppm, rows):
    """``_marks_ink`` over bands of scanlines of at most about BATCH_PIXELS span pixels (one
    band unless the marks are many and large), so that memory stays bounded; a band may cut a
    window in two, whose pieces are joined again."""
    k = len(prims)
    h = win[:, 2]
    lens = hi - lo
    total = int(lens.sum())
    if total <= BATCH_PIXELS:
        return _marks_ink(prims, win, lo, hi, ppm, *rows)
    band = (np.cumsum(lens) - lens) // BATCH_PIXELS  # band of every stacked scanline
    scan_win = np.repeat(np.arange(k), h)
    start = np.cumsum(h) - h
    # pieces: maximal runs of scanlines of one window in one band
    brk = np.r_[True, (band[1:] != band[:-1]) | (scan_win[1:] != scan_win[:-1])]
    p0 = np.nonzero(brk)[0]
    p1 = np.r_[p0[1:], len(band)]
    pw = scan_win[p0]  # window of each piece
    out = [[[] for _ in range(k)] for _ in range(5)]
    edge = np.zeros(k, dtype=bool)
    for b in np.unique(band[p0]).tolist():
        sel = np.nonzero(band[p0] == b)[0]
        js = pw[sel]
        off = p0[sel] - start[js]  # first row of each piece in its window
        wp = win[js].copy()
        wp[:, 0] += off
        wp[:, 2] = p1[sel] - p0[sel]
        r = np.concatenate([np.arange(p0[s], p1[s]) for s in sel.tolist()])
        ink, e = _marks_ink(prims[js], wp, lo[r], hi[r], ppm, *rows)
        edge[js] |= e
        for t, j in enumerate(js.tolist()):
            out[0][j].append(ink[0][t] + off[t])  # rows back in the window's frame
            for f in range(1, 5):
                out[f][j].append(ink[f][t])
    return [[np.concatenate(parts) for parts in field] for field in out], edge


def _dot(a, b):
    return np.einsum("...k,...k->...", a, b)


def _no_ink(k):
    """``_marks_ink``'s answer for k windows without a pixel inside."""
    none_i, none_f = np.zeros(0, dtype=np.int64), np.zeros(0)
    wet, col = np.zeros(0, dtype=np.float32), np.zeros((0, 3), dtype=np.float32)
    fields = [[none_i] * k, [none_i] * k, [wet] * k, [col] * k, [none_f] * k]
    return fields, np.zeros(k, dtype=bool)


def _marks_ink(prims, win, lo, hi, ppm, c, U, V, T, zmin, ink):
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
    paper count.

    Returns, per primitive, lists of (rows, cols, wet, col, lateral) of its inside pixels, and
    whether an inside pixel of the primitive lies at the end of a span that the window could
    extend (the span may then have cut the solid short)."""
    k = len(prims)
    Ns = c.shape[1]
    iy0, ix0, h, win_w = (win[:, j] for j in range(4))
    lens = hi - lo
    S = len(lo)
    scan_win = np.repeat(np.arange(k), h)  # window of every scanline
    scan_row = np.arange(S) - np.repeat(np.cumsum(h) - h, h)
    scan_x0 = ix0[scan_win]
    scan_y = (iy0[scan_win] + scan_row + 0.5) / ppm
    scan_off = np.cumsum(lens) - lens  # first pixel of every scanline
    N = int(lens.sum())
    if N == 0:
        return _no_ink(k)
    # only the rows next to one that reaches the paper can bound a slab that counts
    reach = zmin[prims] <= 0.0
    near = np.nonzero(reach.any(axis=0))[0]
    if near.size == 0:
        return _no_ink(k)
    j0, j1 = max(int(near[0]) - 1, 0), min(int(near[-1]) + 2, Ns)
    Ns = j1 - j0
    reach = reach[:, j0:j1]
    cp, Up, Vp, Tp = (a[prims, j0:j1] for a in (c, U, V, T))
    cT = _dot(cp, Tp)  # (k, Ns)
    slab_ok = reach[:, :-1] | reach[:, 1:]  # (k, Ns - 1)
    # the sign change of every row on every scanline
    T0 = Tp[scan_win, :, 0]  # (S, Ns)
    bk = scan_y[:, None] * Tp[scan_win, :, 1] - cT[scan_win]
    sl, sh = lo[:, None], hi[:, None]
    x0 = scan_x0[:, None]
    rise = T0 > 0  # Hd >= 0 on a suffix of the scanline (a prefix when T0 < 0)
    with np.errstate(divide="ignore", invalid="ignore"):
        cstar = np.where(T0 != 0, (-bk / np.where(T0 != 0, T0, 1.0)) * ppm - x0 - 0.5, 0.0)
    cstar = np.clip(cstar, -1.0, float(np.max(hi, initial=0)) + 1.0)  # inf where T0 is tiny
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
    # crossing pixels of slab j: [A_j, B_j) xor [A_j+1, B_j+1) = [a0, a1) u [b0, b1)
    a0 = np.minimum(A[:, :-1], A[:, 1:])
    a1 = np.maximum(A[:, :-1], A[:, 1:])
    b0 = np.minimum(B[:, :-1], B[:, 1:])
    b1 = np.maximum(B[:, :-1], B[:, 1:])
    s0 = np.stack([a0, np.maximum(a1, b0)], axis=-1)  # (S, Ns - 1, 2)
    s1 = np.stack([np.minimum(a1, b0), b1], axis=-1)
    ok = slab_ok[scan_win][..., None]
    n = np.where(ok, np.maximum(s1 - s0, 0), 0).ravel()
    if not n.any():
        return _no_ink(k)
    # the crossing intervals, in order of scanline (so of window), slab and part; every pixel of
    # an interval is an entry, and a pixel is an entry of each slab it crosses (a fold: more)
    iv = np.nonzero(n)[0]
    n = n[iv]
    E = int(n.sum())
    iv_scan = iv // (2 * (Ns - 1))
    iv_slab = (iv // 2) % (Ns - 1)
    iv_win = scan_win[iv_scan]
    iv_y = scan_y[iv_scan]
    step = np.arange(E) - np.repeat(np.cumsum(n) - n, n)  # position in its interval
    cols = np.repeat(s0.ravel()[iv], n) + step  # window column of every entry
    scan_e = np.repeat(iv_scan, n)
    e_iv = np.repeat(np.arange(len(iv)), n)  # interval of every entry
    # a pixel in several slabs (where the axis folds or the rows' planes fan out) keeps only
    # its entries of the first and the last slab; in interval order a pixel's entries come by
    # increasing slab
    pid = scan_off[scan_e] + cols - lo[scan_e]
    visits = np.bincount(pid, minlength=N)
    pair = None
    if visits.max(initial=0) > 1:
        ent = np.arange(E)
        multi_px = np.nonzero(visits > 1)[0]
        fpos = np.full(N, E)
        lpos = np.full(N, -1)
        np.minimum.at(fpos, pid, ent)
        np.maximum.at(lpos, pid, ent)
        keep = (visits[pid] == 1) | (ent == fpos[pid]) | (ent == lpos[pid])
        sel = np.nonzero(keep)[0]
        rank = np.cumsum(keep) - 1  # entry -> position among the kept
        pair = rank[fpos[multi_px]], rank[lpos[multi_px]]
        cols, scan_e, e_iv = cols[sel], scan_e[sel], e_iv[sel]
        per_iv = np.bincount(e_iv, minlength=len(iv))
    else:
        per_iv = n
    x = (scan_x0[scan_e] + cols + 0.5) / ppm
    # Between rows j and j + 1 the section's centre, U and V are linear in lam, so every dot
    # product of the least-squares solve below is a quadratic in lam whose coefficients belong
    # to the slab, and on a scanline y is fixed too: one table column per interval, repeated
    # over its pixels into contiguous rows.
    dc, dU, dV = np.diff(cp, axis=1), np.diff(Up, axis=1), np.diff(Vp, axis=1)
    c0, U0, V0 = cp[:, :-1], Up[:, :-1], Vp[:, :-1]
    slab_tab = np.stack(
        [
            _dot(U0, U0),
            2 * _dot(U0, dU),
            _dot(dU, dU),  # |U|^2
            _dot(V0, V0),
            2 * _dot(V0, dV),
            _dot(dV, dV),  # |V|^2
            _dot(U0, V0),
            _dot(U0, dV) + _dot(dU, V0),
            _dot(dU, dV),  # U.V
            U0[..., 0],
            U0[..., 1],
            _dot(c0, U0),
            dU[..., 0],
            dU[..., 1],
            _dot(c0, dU) + _dot(dc, U0),
            _dot(dc, dU),  # (tau - V^).U
            V0[..., 0],
            V0[..., 1],
            _dot(c0, V0),
            dV[..., 0],
            dV[..., 1],
            _dot(c0, dV) + _dot(dc, V0),
            _dot(dc, dV),  # (tau - V^).V
        ]
    ).reshape(23, -1)
    slab = iv_win * (Ns - 1) + iv_slab  # every interval's slab in the tables
    S_iv = np.take(slab_tab, slab, axis=1)
    row0 = iv_scan * Ns + iv_slab
    tab = np.stack(
        [
            *S_iv[:9],
            S_iv[9],
            iv_y * S_iv[10] - S_iv[11],
            S_iv[12],
            iv_y * S_iv[13] - S_iv[14],
            S_iv[15],
            S_iv[16],
            iv_y * S_iv[17] - S_iv[18],
            S_iv[19],
            iv_y * S_iv[20] - S_iv[21],
            S_iv[22],
            np.take(T0, row0),
            np.take(bk, row0),
            np.take(T0, row0 + 1),
            np.take(bk, row0 + 1),  # the planes of rows j and j + 1 on the scanline
        ]
    )
    C = np.repeat(tab, per_iv, axis=1)
    h0 = x * C[19] + C[20]  # the rounded Hd of the crossing search
    h1 = x * C[21] + C[22]
    lam = np.clip(h0 / np.where(h0 != h1, h0 - h1, 1.0), 0.0, 1.0)
    # the pixel in the section plane at lam: tau - V^ = p U + q V (least squares, tolerant of the
    # flat tip line)
    uu = C[0] + lam * (C[1] + lam * C[2]) + 1e-12
    vv = C[3] + lam * (C[4] + lam * C[5]) + 1e-12
    uv = C[6] + lam * (C[7] + lam * C[8])
    du = x * C[9] + C[10] + lam * (x * C[11] + C[12] - lam * C[13])
    dv = x * C[14] + C[15] + lam * (x * C[16] + C[17] - lam * C[18])
    det = uu * vv - uv * uv
    p = (du * vv - dv * uv) / det
    q = (dv * uu - du * uv) / det
    f2 = p * p + q * q
    keep = np.ones(len(f2), dtype=bool)
    if pair is not None:  # of the first and the last slab, the more inside: union of sections
        fi, la = pair
        keep[np.where(f2[la] < f2[fi], fi, la)] = False
    inside = keep & (f2 <= 1.0)
    # an inked pixel at the end of a span that the window could extend (the span may have cut
    # the solid short) is the first or the last kept entry of its interval
    has = per_iv > 0
    first = (np.cumsum(per_iv) - per_iv)[has]
    last = first + per_iv[has] - 1
    sc, wh = iv_scan[has], iv_win[has]
    s_lo, s_hi = lo[sc], hi[sc]
    hit = inside[first] & (cols[first] == s_lo) & (s_lo > 0)
    hit |= inside[last] & (cols[last] == s_hi - 1) & (s_hi < win_w[wh])
    edge = np.bincount(wh[hit], minlength=k) > 0
    ok = np.nonzero(inside)[0]
    n_ok = np.bincount(e_iv[ok], minlength=len(iv))  # inked pixels of every interval
    # Ink (Eq. 21-23), in float32 as the paper keeps it. Per interval: V^ and its ink at row j
    # and their change to row j + 1 (Eq. 21 along the axis), and the pixel's offset from row
    # j's centre at the interval's first column, all small numbers (millimetres from the
    # section), repeated over the interval's inked pixels. The texture function (wr, cr, wv,
    # cv, Eq. 22) is usually one ink's everywhere: then it is used as scalars
    inkp = ink[prims, j0:j1]
    tex = inkp[..., 4:12]
    tex0 = tex[0, 0]
    same_tex = bool(np.all(np.abs(tex - tex0) <= 1e-12 * (1.0 + np.abs(tex0))))
    nf = 4 if same_tex else inkp.shape[-1]
    c0s = c0.reshape(-1, 3)[slab]
    per = np.concatenate(
        [
            ((scan_x0[iv_scan] + 0.5) / ppm - c0s[:, 0])[None],
            (iv_y - c0s[:, 1])[None],
            -c0s[:, 2][None],
            dc.reshape(-1, 3)[slab].T,
            inkp[:, :-1, :nf].reshape(-1, nf)[slab].T,
            np.diff(inkp[..., :nf], axis=1).reshape(-1, nf)[slab].T,
        ]
    ).astype(np.float32)
    D = np.repeat(per, n_ok, axis=1)
    lam = lam[ok].astype(np.float32)
    cols = cols[ok]
    lateral = np.clip(p[ok], -1.0, 1.0)
    rows = scan_row[scan_e[ok]]
    # tau - V^ (V^ = c0 + lam dc on the axis), then Eq. 22 and 23: V = V^ + (tau - V^) / f lies
    # on the surface and takes its ink from V^'s texture function, and Eq. 23 mixes V^'s and
    # V's by f, which folds into one factor on V^'s ink:
    # (1 - f) a + f a (1 + |V - V^| r + (V - V^).v) = a (1 + |tau - V^| r + (tau - V^).v)
    ox = cols.astype(np.float32) * np.float32(1.0 / ppm) + D[0] - lam * D[3]
    oy = D[1] - lam * D[4]
    oz = D[2] - lam * D[5]
    at = D[6 : 6 + nf] + lam * D[6 + nf :]  # Eq. 21: V^'s ink between the two rows around it
    dist = np.sqrt(ox * ox + oy * oy + oz * oz)
    o = (dist, ox, oy, oz)
    if same_tex:
        wr, cr, wvx, wvy, wvz, cvx, cvy, cvz = (np.float32(v) for v in tex0.tolist())
    else:
        wr, cr, wvx, wvy, wvz, cvx, cvy, cvz = at[4:12]
    w_fac = _factor(o, (wr, wvx, wvy, wvz))  # Eq. 22, 23
    c_fac = _factor(o, (cr, cvx, cvy, cvz))
    wet = at[0] * w_fac
    np.maximum(wet, 0.0, out=wet)
    col = np.empty((ok.size, 3), dtype=np.float32)
    for ch in range(3):
        np.multiply(at[1 + ch], c_fac, out=col[:, ch])
    np.clip(col, 0.0, 1.0, out=col)
    cut = np.cumsum(np.bincount(iv_win, weights=n_ok, minlength=k)).astype(np.int64)[:-1]
    return [np.split(a, cut) for a in (rows, cols, wet, col, lateral)], edge


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
