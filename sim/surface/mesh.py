# SPDX-License-Identifier: GPL-3.0-or-later
"""The mesh that is the paper: a UV-mapped triangle mesh as plain arrays (no bpy),
checked (faces, a UV map inside the image, manifold), with its smooth corner normals and the
texture size that gives its texels the paper's size."""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np


class SurfaceError(ValueError):
    """The mesh cannot be paper, or a recording's surface frames are malformed."""


@dataclass(frozen=True)
class Surface:
    """A triangle mesh in millimetres with one UV per triangle corner."""

    verts: np.ndarray  # (V, 3) mm
    tris: np.ndarray  # (T, 3) vertex indices
    uvs: np.ndarray  # (T, 3, 2) texture coordinates, 0..1
    face_normals: np.ndarray = field(repr=False)  # (T, 3)
    corner_normals: np.ndarray = field(repr=False)  # (T, 3, 3) smooth, unit (corner_normals)
    area_mm2: float = 0.0
    uv_area: float = 0.0  # of the unit texture square the UV triangles cover

    @property
    def corners(self) -> np.ndarray:
        """(T, 3, 3) the triangles' corner positions, mm."""
        return self.verts[self.tris]


def surface_from_arrays(verts_mm, tris, uvs, name: str = "The mesh") -> Surface:
    """A checked Surface; SurfaceError says in one sentence what keeps ``name`` from being
    paper (no triangles, no UV map, UVs of no area, an edge of more than two faces)."""
    verts = np.asarray(verts_mm, dtype=float).reshape(-1, 3)
    tris = np.asarray(tris, dtype=np.int64).reshape(-1, 3)
    if tris.shape[0] == 0:
        raise SurfaceError(f"{name} has no faces to write on")
    if uvs is None:
        raise SurfaceError(f"{name} has no UV map: add one (UV > Unwrap) to write on it")
    uvs = np.asarray(uvs, dtype=float).reshape(-1, 3, 2)
    if not (np.isfinite(verts).all() and np.isfinite(uvs).all()):
        raise SurfaceError(f"{name} has coordinates that are not numbers")
    if uvs.min() < -UV_SLACK or uvs.max() > 1 + UV_SLACK:
        raise SurfaceError(
            f"{name}'s UV map reaches outside the image (0..1, e.g. tiled or UDIM): pack its "
            "islands into it (UV > Pack Islands) to write on it"
        )
    _check_manifold(tris, name)
    c = verts[tris]
    cross = np.cross(c[:, 1] - c[:, 0], c[:, 2] - c[:, 0])
    area = np.linalg.norm(cross, axis=1) / 2
    d1, d2 = uvs[:, 1] - uvs[:, 0], uvs[:, 2] - uvs[:, 0]
    uv_area = float(np.abs(d1[:, 0] * d2[:, 1] - d1[:, 1] * d2[:, 0]).sum() / 2)
    if area.sum() <= 1e-9:
        raise SurfaceError(f"{name} has no area")
    if uv_area <= 1e-9:
        raise SurfaceError(f"{name}'s UV map has no area: unwrap it (UV > Unwrap)")
    fn = cross / np.where(area > 0, 2 * area, 1.0)[:, None]
    cn = corner_normals(tris, cross, fn)
    return Surface(verts, tris, uvs, fn, cn, float(area.sum()), uv_area)


UV_SLACK = 1e-4  # how far (UV units) a UV may lie outside 0..1: rounding, not a tile

SMOOTH_ANGLE_DEG = 60.0  # faces meeting at a sharper angle keep their edge sharp


def corner_normals(tris, cross, fn) -> np.ndarray:
    """(T, 3, 3) each triangle corner's smooth normal: the area-weighted mean of the normals
    of the faces around its vertex that meet this face at less than SMOOTH_ANGLE_DEG (so a
    cylinder's side is round and its rim stays a rim). A vertex whose faces all lie within
    half that angle of their mean has every pair near: its sum is taken once for all its
    corners (a fan of many faces costs no more than its faces); only the other vertices'
    corners compare their faces pairwise."""
    v = tris.ravel()  # corner c = 3 t + k
    nv = int(v.max()) + 1
    face_of = np.arange(v.size) // 3
    total = np.stack([np.bincount(v, cross[face_of, d], minlength=nv) for d in range(3)], 1)
    tl = np.linalg.norm(total, axis=1)
    mean = total / np.maximum(tl, 1e-300)[:, None]
    has_area = np.einsum("ij,ij->i", fn, fn)[face_of] > 0.5
    half = math.cos(math.radians(SMOOTH_ANGLE_DEG / 2 - 0.1))  # a margin for rounding
    off = has_area & (np.einsum("ij,ij->i", fn[face_of], mean[v]) <= half)
    rough = (np.bincount(v, off, minlength=nv) > 0) | (tl <= 1e-30)
    out = np.where(has_area[:, None], total[v], 0.0)
    pairwise = np.flatnonzero(has_area & rough[v])
    for part in np.array_split(pairwise, max(1, -(-_pair_count(v, pairwise) // 4_000_000))):
        out[part] = _pairwise_normals(v, cross, fn, part)
    ln = np.linalg.norm(out, axis=1)
    face = fn[face_of]  # a corner of a face of no area: the face's normal
    out = np.where(ln[:, None] > 1e-30, out / np.maximum(ln, 1e-30)[:, None], face)
    return out.reshape(-1, 3, 3)


def _pair_count(v, corners) -> int:
    return int(np.bincount(v)[v[corners]].sum())


def _pairwise_normals(v, cross, fn, corners) -> np.ndarray:
    """(len(corners), 3) the sums of the face areas around each corner's vertex that meet
    the corner's face at less than SMOOTH_ANGLE_DEG (corner_normals' general case)."""
    order = np.argsort(v, kind="stable")
    counts = np.bincount(v)
    starts = np.cumsum(counts) - counts
    n = counts[v[corners]]  # faces around each corner's vertex
    row = np.repeat(np.arange(len(corners)), n)
    k = np.arange(int(n.sum())) - np.repeat(np.cumsum(n) - n, n)
    other = order[np.repeat(starts[v[corners]], n) + k] // 3
    own = corners[row] // 3
    near = np.einsum("ij,ij->i", fn[own], fn[other]) > math.cos(math.radians(SMOOTH_ANGLE_DEG))
    w = cross[other] * near[:, None]
    return np.stack([np.bincount(row, w[:, d], minlength=len(corners)) for d in range(3)], 1)


def _check_manifold(tris: np.ndarray, name: str):
    """SurfaceError when an edge belongs to more than two triangles (the surface has no single
    side there, so no local frame)."""
    e = np.sort(np.concatenate([tris[:, [0, 1]], tris[:, [1, 2]], tris[:, [2, 0]]]), axis=1)
    _keys, counts = np.unique(e, axis=0, return_counts=True)
    bad = int((counts > 2).sum())
    if bad:
        raise SurfaceError(
            f"{name} is not manifold: {bad} edge(s) belong to more than two faces, so it has "
            "no single side to write on: clean it up (Mesh > Clean Up) or pick another mesh"
        )


def texture_side_mm(surface: Surface) -> float:
    """The side (mm) of a square texture whose texels have, on average over the surface, the
    paper's size: the surface's area over the part of the texture its UVs cover."""
    return math.sqrt(surface.area_mm2 / surface.uv_area)
