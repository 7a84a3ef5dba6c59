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


def slice_grid(X) -> np.ndarray:
    """Segments (M, 2, 3) where the periodic-in-t grid X (Ns, Nt, 3) crosses z = 0."""
    Z = X[..., 2]
    inside = Z <= 0.0
    Xn = np.roll(X, -1, axis=1)
    Zn = np.roll(Z, -1, axis=1)
    c00, c01 = inside[:-1], np.roll(inside, -1, axis=1)[:-1]
    c10, c11 = inside[1:], np.roll(inside, -1, axis=1)[1:]
    case = c00 * 1 + c01 * 2 + c11 * 4 + c10 * 8
    ii, jj = np.nonzero((case != 0) & (case != 15))
    if ii.size == 0:
        return np.zeros((0, 2, 3))
    cs = case[ii, jj]

    def crossing(pa, pb, za, zb):
        t = za / np.where(za != zb, za - zb, 1.0)
        return pa + t[:, None] * (pb - pa)

    # crossing points of the four edges of each cell (computed per edge, so shared edges agree)
    e0 = crossing(X[ii, jj], Xn[ii, jj], Z[ii, jj], Zn[ii, jj])
    e1 = crossing(Xn[ii, jj], Xn[ii + 1, jj], Zn[ii, jj], Zn[ii + 1, jj])
    e2 = crossing(X[ii + 1, jj], Xn[ii + 1, jj], Z[ii + 1, jj], Zn[ii + 1, jj])
    e3 = crossing(X[ii, jj], X[ii + 1, jj], Z[ii, jj], Z[ii + 1, jj])
    E = np.stack([e0, e1, e2, e3], axis=1)  # (C, 4, 3)
    segs = []
    for k in range(2):
        a, b = _SEG_A[cs, k], _SEG_B[cs, k]
        ok = a >= 0
        if ok.any():
            r = np.nonzero(ok)[0]
            segs.append(np.stack([E[r, a[ok]], E[r, b[ok]]], axis=1))
    return np.concatenate(segs, axis=0)


def compute_marks(brush, sec, ink_rows, ppm: float, paper_shape) -> list[Mark]:
    """The current drawing mark of every primitive that reaches the paper."""
    lay = brush.layout
    H, W = paper_shape
    Cx, Cy = lay.ring[:, 0], lay.ring[:, 1]
    rows_c, rows_U, rows_V, rows_T = sec.rows_c, sec.rows_U, sec.rows_V, sec.rows_T
    # z of the whole grid for all primitives at once
    Zmin = rows_c[..., 2] - np.hypot(rows_U[..., 2], rows_V[..., 2])  # lowest point of each row
    touching = np.nonzero(Zmin.min(axis=1) <= 0.0)[0]
    marks = []
    for i in touching:
        X = (
            rows_c[i][:, None, :]
            + rows_U[i][:, None, :] * Cx[None, :, None]
            + rows_V[i][:, None, :] * Cy[None, :, None]
        )
        segs = slice_grid(X)
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
        empty = Mark(
            i,
            iy0,
            ix0,
            np.zeros(0, int),
            np.zeros(0, int),
            np.zeros(0),
            np.zeros((0, 3)),
            np.zeros(0),
            (0, 0),
            xy,
            area,
            height,
        )
        if ix1 <= ix0 or iy1 <= iy0:
            marks.append(empty)
            continue
        h, w = iy1 - iy0, ix1 - ix0
        # the solid is the union of its sections: a pixel is inked when some section contains
        # it (robust where a sharply bent axis folds the surface over itself, which an even-odd
        # fill of cur_u would punch holes into)
        gy, gx = np.mgrid[0:h, 0:w]
        P = np.stack(
            [(ix0 + gx.ravel() + 0.5) / ppm, (iy0 + gy.ravel() + 0.5) / ppm, np.zeros(h * w)],
            axis=1,
        )
        inside, wet, col, lateral = _pixel_ink(P, i, rows_c, rows_U, rows_V, rows_T, Zmin, ink_rows)
        pr, pc = gy.ravel()[inside], gx.ravel()[inside]
        marks.append(Mark(i, iy0, ix0, pr, pc, wet, col, lateral, (h, w), xy, area, height))
    return marks


def _pixel_ink(P, i, rows_c, rows_U, rows_V, rows_T, Zmin, ink):
    """Which of the pixels P (N, 3) on psi lie inside primitive i's solid, and their ink
    (Eq. 21-23). A pixel lies in the section plane through it between two rows of the surface
    where its signed distance to the rows' planes changes sign; that distance is affine in the
    pixel's (x, y), so it is cheap for every row, and the full evaluation runs only on the (at
    most two) slabs where it changes sign: the first and the last, which covers a fold."""
    c, U, V, T = rows_c[i], rows_U[i], rows_V[i], rows_T[i]
    Ns = c.shape[0]
    reach = Zmin[i] <= 0.0
    slab_ok = reach[:-1] | reach[1:]  # slabs between rows that reach the paper
    x, y = P[:, 0], P[:, 1]
    cT = np.einsum("sk,sk->s", c, T)
    Hd = x[:, None] * T[None, :, 0] + y[:, None] * T[None, :, 1] - cT[None, :]  # (N, Ns)
    pos = Hd >= 0
    cross = (pos[:, :-1] != pos[:, 1:]) & slab_ok[None, :]
    any_cross = cross.any(axis=1)
    first = np.argmax(cross, axis=1)
    last = Ns - 2 - np.argmax(cross[:, ::-1], axis=1)
    cand = np.stack([first, last], axis=1)  # (N, 2)
    n_all = np.arange(len(P))
    k0, k1 = cand, cand + 1
    h0 = Hd[n_all[:, None], k0]
    h1 = Hd[n_all[:, None], k1]
    lam = np.clip(h0 / np.where(h0 != h1, h0 - h1, 1.0), 0.0, 1.0)
    L = lam[..., None]
    cc = c[k0] + L * (c[k1] - c[k0])
    Uu = U[k0] + L * (U[k1] - U[k0])
    Vv = V[k0] + L * (V[k1] - V[k0])
    d = P[:, None, :] - cc  # tau - V^
    # tau - V^ = p U + q V in the section plane (least squares, tolerant of the flat tip line)
    uu = np.einsum("nsk,nsk->ns", Uu, Uu) + 1e-12
    vv = np.einsum("nsk,nsk->ns", Vv, Vv) + 1e-12
    uv = np.einsum("nsk,nsk->ns", Uu, Vv)
    du = np.einsum("nsk,nsk->ns", d, Uu)
    dv = np.einsum("nsk,nsk->ns", d, Vv)
    det = uu * vv - uv * uv
    p = (du * vv - dv * uv) / det
    q = (dv * uu - du * uv) / det
    f2 = p * p + q * q
    best = np.argmin(f2, axis=1)  # the most inside of the candidate sections: union of sections
    f = np.sqrt(f2[n_all, best])
    inside = any_cross & (f <= 1.0)
    n_idx, best, f = n_all[inside], best[inside], f[inside]
    lam_b = lam[n_idx, best]
    offset = d[n_idx, best]
    lateral = np.clip(p[n_idx, best], -1.0, 1.0)
    ka = cand[n_idx, best]
    kb = ka + 1

    def at_axis(field):  # Eq. 21 along the axis, between the two rows around V^
        fa, fb = field[i][ka], field[i][kb]
        if fa.ndim == 1:
            return fa + lam_b * (fb - fa)
        return fa + lam_b[:, None] * (fb - fa)

    wet_a, col_a = at_axis(ink["wet"]), at_axis(ink["col"])
    wr, cr = at_axis(ink["wr"]), at_axis(ink["cr"])
    wv, cv = at_axis(ink["wv"]), at_axis(ink["cv"])
    # V = V^ + (tau - V^) / f  lies on the surface; Eq. 22 gives its ink from V^'s texture function
    ov = offset / np.maximum(f, 1e-9)[:, None]
    ov = np.where((f > 1e-9)[:, None], ov, 0.0)
    dist_v = np.sqrt(np.sum(ov * ov, axis=1))
    wet_v = wet_a * (1.0 + dist_v * wr + np.sum(ov * wv, axis=1))  # Eq. 22
    col_v = col_a * (1.0 + dist_v * cr + np.sum(ov * cv, axis=1))[:, None]
    wet = (1.0 - f) * wet_a + f * wet_v  # Eq. 23
    col = (1.0 - f)[:, None] * col_a + f[:, None] * col_v
    return inside, np.clip(wet, 0.0, None), np.clip(col, 0.0, 1.0), lateral
