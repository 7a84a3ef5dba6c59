# SPDX-License-Identifier: GPL-3.0-or-later
"""Resampling an image to another size (issue 29.4: prints at a chosen size and DPI): separable
filtering with the Mitchell-Netravali cubic (B = C = 1/3: sharp, with little ringing and no
visible grid), its support widened by the reduction when an image is made smaller, so that
every input pixel counts (no aliasing of the paper's grain). Edges repeat the border pixel.
Weights are computed once per axis: (output pixels, taps) indices and weights, each row summing
to 1, so flat paper stays exactly flat. numpy only."""

from __future__ import annotations

import math

import numpy as np

MITCHELL_B = MITCHELL_C = 1.0 / 3.0
SUPPORT = 2.0  # the cubic's half-width, in input pixels (at scale 1)


def mitchell(x) -> np.ndarray:
    """The Mitchell-Netravali cubic at x (input pixels from the output pixel's centre)."""
    b, c = MITCHELL_B, MITCHELL_C
    x = np.abs(np.asarray(x, dtype=np.float64))
    near = ((12 - 9 * b - 6 * c) * x**3 + (-18 + 12 * b + 6 * c) * x**2 + (6 - 2 * b)) / 6
    far = (
        (-b - 6 * c) * x**3 + (6 * b + 30 * c) * x**2 + (-12 * b - 48 * c) * x + (8 * b + 24 * c)
    ) / 6
    return np.where(x < 1, near, np.where(x < 2, far, 0.0))


def weights(n_in: int, n_out: int) -> tuple[np.ndarray, np.ndarray]:
    """(index (n_out, K) int64, weight (n_out, K) float32) of one axis: output pixel o is the sum
    over k of weight[o, k] x input[index[o, k]]; pixel centres line up at the image's edges."""
    scale = n_out / n_in
    stretch = max(1.0, 1.0 / scale)  # a reduction widens the filter over the input
    centre = (np.arange(n_out) + 0.5) / scale - 0.5
    taps = int(math.ceil(2 * SUPPORT * stretch)) + 1
    first = np.floor(centre - SUPPORT * stretch).astype(np.int64) + 1
    idx = first[:, None] + np.arange(taps)
    w = mitchell((idx - centre[:, None]) / stretch)
    w /= w.sum(axis=1, keepdims=True)
    return np.clip(idx, 0, n_in - 1), w.astype(np.float32)


def resample_rows(src, idx, w) -> np.ndarray:
    """Resample axis 0 of ``src`` (float32) with one axis's weights (rows of ``idx`` index
    src's axis 0)."""
    out = np.zeros((idx.shape[0],) + src.shape[1:], np.float32)
    shape = (-1,) + (1,) * (src.ndim - 1)
    for k in range(idx.shape[1]):
        out += w[:, k].reshape(shape) * src[idx[:, k]]
    return out


def resample(a, out_h: int, out_w: int) -> np.ndarray:
    """The image ``a`` (H, W[, C]) resampled to (out_h, out_w[, C]), float32."""
    a = np.asarray(a, dtype=np.float32)
    iy, wy = weights(a.shape[0], out_h)
    ix, wx = weights(a.shape[1], out_w)
    tall = resample_rows(a, iy, wy)
    return np.moveaxis(resample_rows(np.moveaxis(tall, 1, 0), ix, wx), 0, 1)
