# SPDX-License-Identifier: GPL-3.0-or-later
"""The current drawing mark (Sec. 6): each writing primitive's sweep surface SS(s, t) cut by the
paper plane psi (z = 0), and the ink information of every pixel inside the cut.

1. The surface is evaluated on its fixed (s, t) grid: every row is c(s) + U(s) Cx(t) + V(s) Cy(t)
   (see ``nurbs``). Marching squares on the grid's z values gives the intersection curve cur_u
   as a set of segments in the paper plane (one contour per closed curve).
2. Within the curve's bounding box, a pixel is inked when some section of the solid contains it
   (the solid is the union of its sections, also where a bent axis folds the surface).
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
# kept on each side of cur_u's extent on a scanline: a section between two grid rows reaches a
# little past the grid's contour where the surface grazes the paper (measured: up to 0.26 mm at
# 20 px/mm on the benchmark stroke), plus the grid's chords and a pixel and a half
SPAN_MARGIN_MM = 0.35
SPAN_MARGIN_PX = 1.5

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
    Z = X[..., 2]
    inside = Z <= 0.0
    Xn = np.roll(X, -1, axis=2)
    Zn = np.roll(Z, -1, axis=2)
    c00, c01 = inside[:, :-1], np.roll(inside, -1, axis=2)[:, :-1]
    c10, c11 = inside[:, 1:], np.roll(inside, -1, axis=2)[:, 1:]
    case = c00 * 1 + c01 * 2 + c11 * 4 + c10 * 8
    gg, ii, jj = np.nonzero((case != 0) & (case != 15))
    if ii.size == 0:
        return np.zeros((0, 2, 3)), np.zeros(0, dtype=np.intp)
    cs = case[gg, ii, jj]

    def crossing(pa, pb, za, zb):
        t = za / np.where(za != zb, za - zb, 1.0)
        return pa + t[:, None] * (pb - pa)

    # crossing points of the four edges of each cell (computed per edge, so shared edges agree)
    e0 = crossing(X[gg, ii, jj], Xn[gg, ii, jj], Z[gg, ii, jj], Zn[gg, ii, jj])
    e1 = crossing(Xn[gg, ii, jj], Xn[gg, ii + 1, jj], Zn[gg, ii, jj], Zn[gg, ii + 1, jj])
    e2 = crossing(X[gg, ii + 1, jj], Xn[gg, ii + 1, jj], Z[gg, ii + 1, jj], Zn[gg, ii + 1, jj])
    e3 = crossing(X[gg, ii, jj], X[gg, ii + 1, jj], Z[gg, ii, jj], Z[gg, ii + 1, jj])
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


def _scanline_spans(xy, ppm, ix0, iy0, h, w, margin_px):
    """Pixel columns [lo, hi) of every pixel row of the window that can lie inside the cut.

    The section's boundary is cur_u, so every inside point of a scanline has cur_u on both
    sides of it on that scanline: the pixels outside the x range of the segments that come
    near the scanline are outside (the margin covers the grid's chords against the true
    surface)."""
    m = margin_px / ppm
    ylo = xy[:, :, 1].min(axis=1) - m
    yhi = xy[:, :, 1].max(axis=1) + m
    xlo = xy[:, :, 0].min(axis=1) - m
    xhi = xy[:, :, 0].max(axis=1) + m
    yc = (iy0 + np.arange(h) + 0.5) / ppm
    near = (ylo[None, :] <= yc[:, None]) & (yc[:, None] <= yhi[None, :])  # (h, M)
    lo_mm = np.where(near, xlo[None, :], np.inf).min(axis=1)
    hi_mm = np.where(near, xhi[None, :], -np.inf).max(axis=1)
    seen = np.isfinite(lo_mm)
    lo_mm = np.where(seen, lo_mm, 0.0)
    hi_mm = np.where(seen, hi_mm, 0.0)
    lo = np.clip(np.floor(lo_mm * ppm - 0.5).astype(np.int64) + 1 - ix0, 0, w)
    hi = np.clip(np.floor(hi_mm * ppm - 0.5).astype(np.int64) + 1 - ix0, 0, w)
    hi = np.where(seen, hi, lo)
    return lo, np.maximum(hi, lo)


def _span_pixels(lo, hi):
    """Row and column indices of every pixel in the spans [lo_r, hi_r)."""
    lens = hi - lo
    total = int(lens.sum())
    rows = np.repeat(np.arange(len(lo)), lens)
    starts = np.cumsum(lens) - lens
    cols = np.arange(total) - np.repeat(starts - lo, lens)
    return rows, cols


def compute_marks(brush, sec, ink_rows, ppm: float, paper_shape) -> list[Mark]:
    """The current drawing mark of every primitive that reaches the paper."""
    lay = brush.layout
    H, W = paper_shape
    ring = lay.ring
    rows_c, rows_U, rows_V, rows_T = sec.rows_c, sec.rows_U, sec.rows_V, sec.rows_T
    # z of the whole grid for all primitives at once
    Zmin = rows_c[..., 2] - np.hypot(rows_U[..., 2], rows_V[..., 2])  # lowest point of each row
    touching = np.nonzero(Zmin.min(axis=1) <= 0.0)[0]
    if touching.size == 0:
        return []
    X = (
        rows_c[touching][:, :, None, :]
        + rows_U[touching][:, :, None, :] * ring[None, None, :, 0, None]
        + rows_V[touching][:, :, None, :] * ring[None, None, :, 1, None]
    )
    all_segs, owner = slice_grids(X)
    # chord error of the grid's polygon against the true sections, plus a pixel
    sag = 1.0 - np.cos(np.pi / ring.shape[0])
    marks = []
    for g, i in enumerate(touching):
        segs = all_segs[owner == g]
        if len(segs) == 0:
            continue
        xy = segs[:, :, :2]
        xmin, ymin = xy.reshape(-1, 2).min(axis=0)
        xmax, ymax = xy.reshape(-1, 2).max(axis=0)
        area = float((xmax - xmin) * (ymax - ymin))
        centroid = np.array([(xmin + xmax) / 2, (ymin + ymax) / 2, 0.0])
        height = float(np.linalg.norm(brush.cc[i, -1] - centroid))
        ix0 = max(int(np.floor(xmin * ppm - 0.5)), 0)
        iy0 = max(int(np.floor(ymin * ppm - 0.5)), 0)
        ix1 = min(int(np.ceil(xmax * ppm - 0.5)) + 1, W)
        iy1 = min(int(np.ceil(ymax * ppm - 0.5)) + 1, H)
        h, w = max(iy1 - iy0, 0), max(ix1 - ix0, 0)
        pr = pc = np.zeros(0, dtype=np.intp)
        if h and w:
            semi = float(np.max(np.hypot(_norm(rows_U[i]), _norm(rows_V[i]))))
            lo, hi = _scanline_spans(
                xy, ppm, ix0, iy0, h, w, SPAN_MARGIN_PX + (SPAN_MARGIN_MM + sag * semi) * ppm
            )
            pr, pc = _span_pixels(lo, hi)
        if pr.size == 0:
            marks.append(
                Mark(
                    i,
                    iy0,
                    ix0,
                    pr,
                    pc,
                    np.zeros(0),
                    np.zeros((0, 3)),
                    np.zeros(0),
                    (h, w),
                    xy,
                    area,
                    height,
                )
            )
            continue
        px = (ix0 + pc + 0.5) / ppm
        py = (iy0 + pr + 0.5) / ppm
        inside, wet, col, lateral = _pixel_ink(
            px, py, rows_c[i], rows_U[i], rows_V[i], rows_T[i], Zmin[i], ink_rows[i]
        )
        marks.append(
            Mark(i, iy0, ix0, pr[inside], pc[inside], wet, col, lateral, (h, w), xy, area, height)
        )
    return marks


def _norm(v):
    return np.sqrt(np.sum(v * v, axis=-1))


def _pixel_ink(px, py, c, U, V, T, zmin, ink):
    """Which of the pixels (px, py) on psi lie inside one primitive's solid, and their ink
    (Eq. 21-23). A pixel lies in the section plane through it between two rows of the surface
    where its signed distance to the rows' planes changes sign; that distance is affine in the
    pixel's (x, y), so it is cheap for every row, and the full evaluation runs only on the (at
    most two) slabs where it changes sign: the first and the last, which covers a fold. Only
    the rows around the slabs that reach the paper are looked at."""
    reach = zmin <= 0.0
    slab_ok = reach[:-1] | reach[1:]  # slabs between rows that reach the paper
    ks = np.nonzero(slab_ok)[0]
    k_lo, k_hi = int(ks[0]), int(ks[-1]) + 2  # rows k_lo .. k_hi - 1
    c, U, V, T = c[k_lo:k_hi], U[k_lo:k_hi], V[k_lo:k_hi], T[k_lo:k_hi]
    slab_ok = slab_ok[k_lo : k_hi - 1]
    ink = ink[k_lo:k_hi]
    Nr = c.shape[0]
    cT = np.einsum("sk,sk->s", c, T)
    Hd = px[:, None] * T[None, :, 0] + (py[:, None] * T[None, :, 1] - cT[None, :])  # (N, Nr)
    pos = Hd >= 0
    cross = (pos[:, :-1] != pos[:, 1:]) & slab_ok[None, :]
    hit = np.nonzero(cross.any(axis=1))[0]
    cross = cross[hit]
    Hd = Hd[hit]
    first = np.argmax(cross, axis=1)
    last = Nr - 2 - np.argmax(cross[:, ::-1], axis=1)
    pxh, pyh = px[hit], py[hit]
    # Between rows k and k + 1 the section's centre, U and V are linear in lam, so every dot
    # product of the least-squares solve below is a quadratic in lam whose coefficients belong
    # to the slab: one table row per slab, gathered once per pixel.
    dc, dU, dV = np.diff(c, axis=0), np.diff(U, axis=0), np.diff(V, axis=0)
    c0, U0, V0 = c[:-1], U[:-1], V[:-1]

    def dot(a, b):
        return np.einsum("sk,sk->s", a, b)

    coef = np.stack(
        [
            dot(U0, U0),
            2 * dot(U0, dU),
            dot(dU, dU),  # |U|^2
            dot(V0, V0),
            2 * dot(V0, dV),
            dot(dV, dV),  # |V|^2
            dot(U0, V0),
            dot(U0, dV) + dot(dU, V0),
            dot(dU, dV),  # U.V
            U0[:, 0],
            U0[:, 1],
            dot(c0, U0),
            dU[:, 0],
            dU[:, 1],
            dot(c0, dU) + dot(dc, U0),
            dot(dc, dU),  # (tau - V^).U
            V0[:, 0],
            V0[:, 1],
            dot(c0, V0),
            dV[:, 0],
            dV[:, 1],
            dot(c0, dV) + dot(dc, V0),
            dot(dc, dV),  # (tau - V^).V
        ],
        axis=1,
    )

    def section(sel, k):
        """Position (lam, p, f^2) of pixels ``sel`` in the section plane between rows k, k+1:
        tau - V^ = p U + q V (least squares, tolerant of the flat tip line)."""
        h0 = Hd[sel, k]
        h1 = Hd[sel, k + 1]
        lam = np.clip(h0 / np.where(h0 != h1, h0 - h1, 1.0), 0.0, 1.0)
        x, y = pxh[sel], pyh[sel]
        C = coef[k].T
        uu = C[0] + lam * (C[1] + lam * C[2]) + 1e-12
        vv = C[3] + lam * (C[4] + lam * C[5]) + 1e-12
        uv = C[6] + lam * (C[7] + lam * C[8])
        du = x * C[9] + y * C[10] - C[11] + lam * (x * C[12] + y * C[13] - C[14] - lam * C[15])
        dv = x * C[16] + y * C[17] - C[18] + lam * (x * C[19] + y * C[20] - C[21] - lam * C[22])
        det = uu * vv - uv * uv
        p = (du * vv - dv * uv) / det
        q = (dv * uu - du * uv) / det
        return lam, p, p * p + q * q

    lam, p, f2 = section(np.arange(len(hit)), first)
    ka = first.copy()
    fold = np.nonzero(last != first)[0]
    if fold.size:  # the most inside of the two candidate sections: union of sections
        lam2, p2, f22 = section(fold, last[fold])
        better = f22 < f2[fold]
        b = fold[better]
        lam[b], p[b], f2[b] = lam2[better], p2[better], f22[better]
        ka[b] = last[b]
    ok = np.nonzero(f2 <= 1.0)[0]
    inside = np.zeros(len(px), dtype=bool)
    inside[hit[ok]] = True
    f, lam, ka = np.sqrt(f2[ok]), lam[ok], ka[ok]
    lateral = np.clip(p[ok], -1.0, 1.0)
    L = lam[:, None]
    offset = np.stack([pxh[ok], pyh[ok], np.zeros(len(ok))], axis=1) - (c0[ka] + L * dc[ka])
    # Eq. 21 along the axis: V^'s ink between the two rows around it
    at = ink[ka] + L * (ink[ka + 1] - ink[ka])
    wet_a, col_a = at[:, 0], at[:, 1:4]
    wr, cr, wv, cv = at[:, 4], at[:, 5], at[:, 6:9], at[:, 9:12]
    # V = V^ + (tau - V^) / f  lies on the surface; Eq. 22 gives its ink from V^'s texture function
    ov = offset / np.maximum(f, 1e-9)[:, None]
    ov = np.where((f > 1e-9)[:, None], ov, 0.0)
    dist_v = _norm(ov)
    wet_v = wet_a * (1.0 + dist_v * wr + np.einsum("nk,nk->n", ov, wv))  # Eq. 22
    col_v = col_a * (1.0 + dist_v * cr + np.einsum("nk,nk->n", ov, cv))[:, None]
    wet = (1.0 - f) * wet_a + f * wet_v  # Eq. 23
    col = (1.0 - f)[:, None] * col_a + f[:, None] * col_v
    return inside, np.clip(wet, 0.0, None), np.clip(col, 0.0, 1.0), lateral
