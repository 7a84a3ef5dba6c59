# SPDX-License-Identifier: GPL-3.0-or-later
"""numpy filters of grey and binary images (no scipy, so they run in Blender): Otsu's
threshold, bilinear sampling, erosion and dilation by a disk, the 3 x 3 median, the Gaussian
blur, the perimeter (as scikit-image's), Zhang-Suen thinning and exact distances to the
background. The tests check each against scikit-image's and scipy's own."""

from __future__ import annotations

import numpy as np

from ..core import exact


def otsu(values) -> float:
    """Otsu's threshold of values in [0, 1] (256 bins)."""
    hist, edges = np.histogram(np.ravel(values), bins=256, range=(0.0, 1.0))
    centres = (edges[:-1] + edges[1:]) / 2
    w0 = np.cumsum(hist)
    w1 = w0[-1] - w0
    s0 = np.cumsum(hist * centres)
    m0 = s0 / np.maximum(w0, 1)
    m1 = (s0[-1] - s0) / np.maximum(w1, 1)
    between = w0 * w1 * (m0 - m1) ** 2
    return float(centres[int(np.argmax(between))])


def _bilinear(img, y, x) -> np.ndarray:
    h, w = img.shape
    y = np.broadcast_to(y, np.broadcast_shapes(y.shape, x.shape))
    x = np.broadcast_to(x, y.shape)
    y0 = np.clip(np.floor(y).astype(int), 0, h - 1)
    x0 = np.clip(np.floor(x).astype(int), 0, w - 1)
    y1, x1 = np.clip(y0 + 1, 0, h - 1), np.clip(x0 + 1, 0, w - 1)
    fy, fx = np.clip(y - y0, 0, 1), np.clip(x - x0, 0, 1)
    inside = (y >= 0) & (y <= h - 1) & (x >= 0) & (x <= w - 1)
    v = (img[y0, x0] * (1 - fy) + img[y1, x0] * fy) * (1 - fx) + (
        img[y0, x1] * (1 - fy) + img[y1, x1] * fy
    ) * fx
    return np.where(inside, v, 0.0)


def _disk(r: int):
    yy, xx = np.mgrid[-r : r + 1, -r : r + 1]
    return [
        (dy, dx)
        for dy, dx in zip(yy.ravel(), xx.ravel(), strict=True)
        if dy * dy + dx * dx <= r * r
    ]


def _shifted(a, dy: int, dx: int, fill):
    out = np.full_like(a, fill)
    h, w = a.shape
    out[max(dy, 0) : h + min(dy, 0), max(dx, 0) : w + min(dx, 0)] = a[
        max(-dy, 0) : h + min(-dy, 0), max(-dx, 0) : w + min(-dx, 0)
    ]
    return out


def _erode(mask, r: int):
    out = mask.copy()
    for dy, dx in _disk(r):
        out &= _shifted(mask, dy, dx, False)
    return out


def _dilate(mask, r: int):
    out = mask.copy()
    for dy, dx in _disk(r):
        out |= _shifted(mask, dy, dx, False)
    return out


def _median3(a):
    stack = np.stack([_shifted(a, dy, dx, 0.0) for dy in (-1, 0, 1) for dx in (-1, 0, 1)])
    return np.median(stack, axis=0)


def _gaussian(a, sigma: float):
    r = int(np.ceil(4 * sigma))
    k = exact.exp(-0.5 * (np.arange(-r, r + 1) / sigma) ** 2)
    k /= k.sum()
    pad = np.pad(a, r, mode="edge")
    rows = sum(k[i] * pad[:, i : i + a.shape[1]] for i in range(2 * r + 1))
    return sum(k[i] * rows[i : i + a.shape[0], :] for i in range(2 * r + 1))


def perimeter(mask) -> float:
    """Perimeter of a binary image, as scikit-image's ``measure.perimeter`` (4-connectivity):
    the boundary pixels, each weighted by how its boundary neighbours run (1 straight, sqrt 2
    diagonal, (1 + sqrt 2) / 2 at a corner)."""
    m = mask.astype(bool)
    inner = m.copy()
    for dy, dx in ((-1, 0), (1, 0), (0, -1), (0, 1)):
        inner &= _shifted(m, dy, dx, False)
    border = (m & ~inner).astype(np.int64)
    kernel = ((10, 2, 10), (2, 1, 2), (10, 2, 10))
    conv = sum(
        kernel[dy + 1][dx + 1] * _shifted(border, -dy, -dx, 0)
        for dy in (-1, 0, 1)
        for dx in (-1, 0, 1)
    )
    weights = np.zeros(50)
    weights[[5, 7, 15, 17, 25, 27]] = 1.0
    weights[[21, 33]] = np.sqrt(2)
    weights[[13, 23]] = (1 + np.sqrt(2)) / 2
    return float(weights[np.clip(conv, 0, 49)].sum())


def skeleton(mask) -> np.ndarray:
    """Zhang-Suen thinning of a binary image (each pass over all pixels at once)."""
    img = mask.astype(bool).copy()
    offsets = ((-1, 0), (-1, 1), (0, 1), (1, 1), (1, 0), (1, -1), (0, -1), (-1, -1))
    while True:
        changed = False
        for step in (0, 1):
            p = [_shifted(img, -dy, -dx, False) for dy, dx in offsets]  # P2..P9
            b = sum(q.astype(np.int8) for q in p)
            a = sum((~p[i] & p[(i + 1) % 8]).astype(np.int8) for i in range(8))
            if step == 0:
                c1, c2 = p[0] & p[2] & p[4], p[2] & p[4] & p[6]
            else:
                c1, c2 = p[0] & p[2] & p[6], p[0] & p[4] & p[6]
            kill = img & (b >= 2) & (b <= 6) & (a == 1) & ~c1 & ~c2
            if kill.any():
                img &= ~kill
                changed = True
        if not changed:
            return img


def _distance_to(background, where) -> np.ndarray:
    """Euclidean distance from each pixel in ``where`` to the nearest ``background`` pixel
    (exact, by brute force over the background's border pixels)."""
    ys, xs = np.nonzero(where)
    grown = _dilate(~background, 1) & background  # background pixels touching the ink
    by, bx = np.nonzero(grown)
    if ys.size == 0 or by.size == 0:
        return np.zeros(ys.size)
    out = np.empty(ys.size)
    for at in range(0, ys.size, 512):
        dy = ys[at : at + 512, None] - by[None, :]
        dx = xs[at : at + 512, None] - bx[None, :]
        out[at : at + 512] = np.sqrt((dy * dy + dx * dx).min(axis=1))
    return out
