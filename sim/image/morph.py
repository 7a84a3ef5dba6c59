# SPDX-License-Identifier: GPL-3.0-or-later
"""Image tools for imitating a picture, numpy only (they run inside Blender with its own
numpy): the exact Euclidean distance transform with the nearest feature pixel, connected
components, the paper's level under uneven lighting, and resampling. Zhang-Suen thinning,
Otsu's threshold and the Gaussian blur are in ``filters``. The tests check each against
scipy.ndimage / scikit-image."""

from __future__ import annotations

import numpy as np

NEIGHBOURS_8 = ((-1, -1), (-1, 0), (-1, 1), (0, -1), (0, 1), (1, -1), (1, 0), (1, 1))


def _column_nearest(features: np.ndarray) -> np.ndarray:
    """For every pixel, the row of the nearest feature pixel in its own column (-BIG: none)."""
    h, w = features.shape
    big = 1 << 30
    rows = np.arange(h)[:, None]
    above = np.maximum.accumulate(np.where(features, rows, -big), axis=0)
    below = np.minimum.accumulate(np.where(features, rows, big)[::-1], axis=0)[::-1]
    return np.where(rows - above <= below - rows, above, below)


def nearest_feature(features, limit: float | None = None):
    """Exact Euclidean distance transform with indices: for every pixel, the squared distance to
    the nearest True pixel of ``features`` and that pixel's (row, col). Separable: the nearest
    feature in each column first, then across the columns, trying column offsets in order of
    size until no pixel can get nearer (or beyond ``limit`` pixels, where the distance is inf).
    Returns (d2 float64, rows int, cols int); rows/cols are -1 where no feature is in reach."""
    f = np.asarray(features, dtype=bool)
    h, w = f.shape
    near_row = _column_nearest(f)
    g2 = (np.arange(h)[:, None] - near_row).astype(np.float64) ** 2
    g2[np.abs(near_row) >= 1 << 29] = np.inf
    best = g2.copy()
    brow = np.where(np.isfinite(g2), near_row, -1)
    bcol = np.where(np.isfinite(g2), np.arange(w)[None, :], -1)
    cap = np.inf if limit is None else float(limit) ** 2
    if not f.any():
        return best, brow, bcol
    for d in range(1, w):
        if d * d > cap or d * d > best.max():
            break
        for sign in (1, -1):
            lo, hi = (0, w - d) if sign == 1 else (d, w)  # columns that look at c + sign * d
            cand = g2[:, lo + sign * d : hi + sign * d] + d * d
            better = cand < best[:, lo:hi]
            if better.any():
                best[:, lo:hi] = np.where(better, cand, best[:, lo:hi])
                src = slice(lo + sign * d, hi + sign * d)
                brow[:, lo:hi] = np.where(better, near_row[:, src], brow[:, lo:hi])
                bcol[:, lo:hi] = np.where(better, np.arange(w)[None, src], bcol[:, lo:hi])
    if limit is not None:
        far = best > cap
        best[far], brow[far], bcol[far] = np.inf, -1, -1
    return best, brow, bcol


def edt(mask) -> np.ndarray:
    """Distance from every True pixel to the nearest False pixel (0 on False pixels), as
    scipy.ndimage.distance_transform_edt; the image's border is not background."""
    d2, _, _ = nearest_feature(~np.asarray(mask, dtype=bool))
    return np.sqrt(d2)


def _shift(a: np.ndarray, dy: int, dx: int, fill) -> np.ndarray:
    out = np.full_like(a, fill)
    h, w = a.shape
    out[max(dy, 0) : h + min(dy, 0), max(dx, 0) : w + min(dx, 0)] = a[
        max(-dy, 0) : h + min(-dy, 0), max(-dx, 0) : w + min(-dx, 0)
    ]
    return out


def _runs(m: np.ndarray):
    """The runs of True in each row: row, first column, column past the end (raster order)."""
    h, w = m.shape
    pad = np.zeros((h, w + 2), dtype=np.int8)
    pad[:, 1:-1] = m
    d = np.diff(pad, axis=1)
    rows, starts = np.nonzero(d == 1)
    _, ends = np.nonzero(d == -1)
    return rows, starts, ends


def _touching_runs(rows, starts, ends, h: int):
    """Pairs of runs in neighbouring rows that touch (8-connected)."""
    first = np.searchsorted(rows, np.arange(h + 1))
    ea, eb = [], []
    for r in range(1, h):
        a0, a1, b1 = first[r - 1], first[r], first[r + 1]
        if a0 == a1 or a1 == b1:
            continue
        lo = a0 + np.searchsorted(ends[a0:a1], starts[a1:b1], side="left")
        hi = a0 + np.searchsorted(starts[a0:a1], ends[a1:b1], side="right")
        k = np.maximum(hi - lo, 0)
        if k.any():
            b = np.repeat(np.arange(a1, b1), k)
            ea.append(np.repeat(lo, k) + np.arange(k.sum()) - np.repeat(np.cumsum(k) - k, k))
            eb.append(b)
    if not ea:
        return np.zeros(0, int), np.zeros(0, int)
    return np.concatenate(ea), np.concatenate(eb)


def label(mask) -> tuple[np.ndarray, int]:
    """8-connected components: labels 1..n in the raster order of each component's first
    pixel (0: background), as scipy.ndimage.label with a 3 x 3 structure. The rows' runs of
    pixels are joined where runs of neighbouring rows touch: each run takes the least run
    index it touches, then follows that run's own (pointer jumping), until nothing changes."""
    m = np.asarray(mask, dtype=bool)
    h, w = m.shape
    rows, starts, ends = _runs(m)
    ea, eb = _touching_runs(rows, starts, ends, h)
    lab = np.arange(len(rows))
    while True:
        old = lab.copy()
        np.minimum.at(lab, ea, lab[eb])
        np.minimum.at(lab, eb, lab[ea])
        while True:
            jumped = lab[lab]
            if np.array_equal(jumped, lab):
                break
            lab = jumped
        if np.array_equal(lab, old):
            break
    roots, ids = np.unique(lab, return_inverse=True)
    delta = np.zeros((h, w + 1), dtype=np.int64)
    np.add.at(delta, (rows, starts), ids + 1)
    np.add.at(delta, (rows, ends), -(ids + 1))
    return np.cumsum(delta, axis=1)[:, :w].astype(np.int32), int(len(roots))


def block_max(grid: np.ndarray, r: int = 1) -> np.ndarray:
    """Maximum over a (2r + 1)^2 window, edges repeated (scipy's maximum_filter, 'nearest')."""
    p = np.pad(grid, r, mode="edge")
    h, w = grid.shape
    out = np.full(grid.shape, -np.inf)
    for dy in range(2 * r + 1):
        for dx in range(2 * r + 1):
            np.maximum(out, p[dy : dy + h, dx : dx + w], out=out)
    return out


def resize(img: np.ndarray, h: int, w: int) -> np.ndarray:
    """Bilinear resampling of a 2-D image to (h, w), pixel centres aligned (as
    skimage.transform.resize without anti-aliasing); shrinking by more than two averages
    blocks of pixels first."""
    a = np.asarray(img, dtype=np.float64)
    while a.shape[0] >= 2 * h and a.shape[1] >= 2 * w and min(a.shape) >= 2:
        hh, ww = a.shape[0] // 2 * 2, a.shape[1] // 2 * 2
        a = a[:hh, :ww].reshape(hh // 2, 2, ww // 2, 2).mean(axis=(1, 3))
    y = np.clip((np.arange(h) + 0.5) * a.shape[0] / h - 0.5, 0, a.shape[0] - 1)
    x = np.clip((np.arange(w) + 0.5) * a.shape[1] / w - 0.5, 0, a.shape[1] - 1)
    y0 = np.floor(y).astype(int)
    x0 = np.floor(x).astype(int)
    y1, x1 = np.minimum(y0 + 1, a.shape[0] - 1), np.minimum(x0 + 1, a.shape[1] - 1)
    fy, fx = (y - y0)[:, None], (x - x0)[None, :]
    top = a[y0][:, x0] * (1 - fx) + a[y0][:, x1] * fx
    bot = a[y1][:, x0] * (1 - fx) + a[y1][:, x1] * fx
    return top * (1 - fy) + bot * fy


def paper_level(grey: np.ndarray, block: int, quantile: float = 0.8) -> np.ndarray:
    """The paper's brightness under uneven light and stains: a high quantile of every
    block x block tile (ink covers less than the rest of a tile), the brightest of each tile's
    3 x 3 neighbourhood (a tile full of ink takes its neighbours' paper), smoothed back up to
    the picture's size bilinearly."""
    h, w = grey.shape
    bh, bw = max(-(-h // block), 1), max(-(-w // block), 1)
    pad = np.pad(grey, ((0, bh * block - h), (0, bw * block - w)), mode="edge")
    tiles = pad.reshape(bh, block, bw, block).transpose(0, 2, 1, 3).reshape(bh, bw, -1)
    level = block_max(np.quantile(tiles, quantile, axis=2), 1)
    return np.maximum(resize(level, h, w), 1e-3)
