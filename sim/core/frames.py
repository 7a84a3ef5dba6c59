# SPDX-License-Identifier: GPL-3.0-or-later
"""The brush's orientation (Sec. 4, Fig. 6(a)) and the small vector helpers the engine shares.

R = Rx(q) Ry(d) Rz(r): r turns the brush about its handle, d deflects it sideways (about the
paper's y axis), q forward (about the x axis). The helpers skip numpy's Python wrappers on the
hot paths and give the same sums and products as np.linalg.norm, np.cross and np.dot, and the
same numbers as np.clip, np.diff and np.stack (the brush's step calls them on arrays of a few
numbers, where the wrappers cost more than the arithmetic: issue 28)."""

from __future__ import annotations

import math

import numpy as np

from .exact import _NUMPY_2, arcsin, arctan2, clip, matmul, sin_cos  # noqa: F401 (handed on)

_add = np.add.reduce  # np.sum without its Python wrapper (the same sums)


def diff(a, axis: int = -1):
    """np.diff(a, axis=axis) for an array a (the same subtraction)."""
    hi = [slice(None)] * a.ndim
    lo = [slice(None)] * a.ndim
    hi[axis], lo[axis] = slice(1, None), slice(None, -1)
    return a[tuple(hi)] - a[tuple(lo)]


def stack1(arrays):
    """np.stack(arrays, axis=1) for arrays of one shape (the same copy)."""
    return np.concatenate([a[:, None] for a in arrays], axis=1)


def rotation_matrix(d_deg: float, q_deg: float, r_deg: float) -> np.ndarray:
    """R = Rx(q) Ry(d) Rz(r), angles in degrees (Sec. 4, Fig. 6(a))."""
    # the three angles' sines and cosines on Python floats, the same bits on any machine (and
    # the products in a fixed order, not through BLAS; issue 28.2)
    (sy, cy), (sx, cx), (sz, cz) = (sin_cos(math.radians(a)) for a in (d_deg, q_deg, r_deg))
    rx = np.array([[1.0, 0.0, 0.0], [0.0, cx, -sx], [0.0, sx, cx]])
    ry = np.array([[cy, 0.0, sy], [0.0, 1.0, 0.0], [-sy, 0.0, cy]])
    rz = np.array([[cz, -sz, 0.0], [sz, cz, 0.0], [0.0, 0.0, 1.0]])
    return matmul(matmul(rx, ry), rz)


def angles_from_matrix(R) -> tuple[float, float, float]:
    """(d, q, r) in degrees with rotation_matrix(d, q, r) == R, for |d| < 90 (inverse of the
    above; Blender's Euler mode 'ZYX' with (x, y, z) = (q, d, r) is the same matrix)."""
    R = np.asarray(R, dtype=float)
    d = arcsin(float(np.clip(R[0, 2], -1.0, 1.0)))
    q = arctan2(float(-R[1, 2]), float(R[2, 2]))
    r = arctan2(float(-R[0, 1]), float(R[0, 0]))
    return tuple(float(v) for v in np.degrees([d, q, r]))


def norm(v, axis=-1, keepdims=False):
    """Euclidean length along ``axis``."""
    return np.sqrt(_add(v * v, axis=axis, keepdims=keepdims))


def dot(a, b):
    """Dot products of (..., k) vectors."""
    return np.einsum("...k,...k->...", a, b)


_NEXT = np.array([1, 2, 0])  # each component's next and next but one, cyclically (cross)
_AFTER_NEXT = np.array([2, 0, 1])


def cross(a, b):
    """np.cross of (..., 3) vectors without its Python wrapper (the same products): a_j b_k -
    a_k b_j for every component i and its cyclic successors j, k, all three at once."""
    return a[..., _NEXT] * b[..., _AFTER_NEXT] - a[..., _AFTER_NEXT] * b[..., _NEXT]


def unit(v, fallback=None):
    """v / |v| along the last axis; where |v| is about 0, ``fallback`` when given."""
    n = norm(v, keepdims=True)
    out = v / np.maximum(n, 1e-12)
    if fallback is not None:
        out = np.where(n > 1e-9, out, fallback)
    return out


def per_pixel(col, a) -> np.ndarray:
    """col * a[:, None] of colours ``col`` (n, 3) and a number a pixel ``a`` (n,): the same
    products, made as one run of 3 n numbers (a broadcast over the colours goes three numbers
    at a time; issue 28)."""
    col = np.ascontiguousarray(col)
    return (col.reshape(-1) * a.repeat(3)).reshape(col.shape)
