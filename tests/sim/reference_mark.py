# SPDX-License-Identifier: GPL-3.0-or-later
"""A plain implementation of the current drawing mark (every bounding-box pixel against every
row of the surface): the reference the fast ``sim.mark`` must agree with."""

import numpy as np

from sim.brush.mark import Mark, section_cover, slice_grid
from sim.brush.state import ink_field


def reference_marks(brush, sec, ink_rows, ppm: float, paper_shape) -> list[Mark]:
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
        where = dict(primitive=i, iy0=iy0, ix0=ix0, segments=xy, area_bbox=area, height=height)
        empty = Mark(
            **where,
            rows=np.zeros(0, int),
            cols=np.zeros(0, int),
            wet=np.zeros(0),
            col=np.zeros((0, 3)),
            lateral=np.zeros(0),
            depth=np.zeros(0),
            shape=(0, 0),
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
        inside, wet, col, lateral, depth = _pixel_ink(
            P, i, rows_c, rows_U, rows_V, rows_T, Zmin, ink_rows, ppm
        )
        pr, pc = gy.ravel()[inside], gx.ravel()[inside]
        px = dict(rows=pr, cols=pc, wet=wet, col=col, lateral=lateral, depth=depth)
        marks.append(Mark(**where, **px, shape=(h, w)))
    return marks


def _pixel_ink(P, i, rows_c, rows_U, rows_V, rows_T, Zmin, ink, ppm):
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
    ka = cand[n_idx, best]
    kb = ka + 1
    lateral = np.clip(p[n_idx, best], -1.0, 1.0)

    def at_axis(field):  # Eq. 21 along the axis, between the two rows around V^
        fa, fb = field[ka], field[kb]
        if fa.ndim == 1:
            return fa + lam_b * (fb - fa)
        return fa + lam_b[:, None] * (fb - fa)

    wet_a, col_a = at_axis(ink_field(ink[i], "wet")), at_axis(ink_field(ink[i], "col"))
    wr, cr = at_axis(ink_field(ink[i], "wr")), at_axis(ink_field(ink[i], "cr"))
    wv, cv = at_axis(ink_field(ink[i], "wv")), at_axis(ink_field(ink[i], "cv"))
    # V = V^ + (tau - V^) / f  lies on the surface; Eq. 22 gives its ink from V^'s texture function
    ov = offset / np.maximum(f, 1e-9)[:, None]
    ov = np.where((f > 1e-9)[:, None], ov, 0.0)
    dist_v = np.sqrt(np.sum(ov * ov, axis=1))
    wet_v = wet_a * (1.0 + dist_v * wr + np.sum(ov * wv, axis=1))  # Eq. 22
    col_v = col_a * (1.0 + dist_v * cr + np.sum(ov * cv, axis=1))[:, None]
    wet = (1.0 - f) * wet_a + f * wet_v  # Eq. 23
    col = (1.0 - f)[:, None] * col_a + f[:, None] * col_v
    # the share of the pixel the section covers (model addition, sim.brush.mark.section_cover)
    cover = section_cover(Uu[n_idx, best], Vv[n_idx, best], p[n_idx, best], q[n_idx, best], ppm)
    return inside, np.clip(wet, 0.0, None), np.clip(col, 0.0, 1.0) * cover[:, None], lateral, f
