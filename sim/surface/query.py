# SPDX-License-Identifier: GPL-3.0-or-later
"""Questions to the mesh: where a ray first meets it, its point nearest a point (with the
triangles binned in a grid of cubes, so a query looks at the triangles near it), the smooth
normal at a point."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..core.exact import inv, matmul
from .mesh import Surface


# ------------------------------------------------------------------------------ queries
@dataclass(frozen=True)
class Hit:
    tri: int
    bary: np.ndarray  # (3,)
    point: np.ndarray  # (3,) mm
    distance: float  # along the ray (ray_hit) or to the point (closest_point)


def ray_hit(surface: Surface, origin, direction) -> Hit | None:
    """The first surface point on the ray origin + t direction, t >= 0 (Moller-Trumbore over
    all triangles at once); None when the ray misses."""
    o = np.asarray(origin, dtype=float)
    d = np.asarray(direction, dtype=float)
    c = surface.corners
    e1, e2 = c[:, 1] - c[:, 0], c[:, 2] - c[:, 0]
    p = np.cross(d, e2)
    det = np.einsum("ij,ij->i", e1, p)
    ok = np.abs(det) > 1e-12
    inv = np.where(ok, 1.0 / np.where(ok, det, 1.0), 0.0)
    s = o - c[:, 0]
    u = np.einsum("ij,ij->i", s, p) * inv
    qv = np.cross(s, e1)
    v = (matmul(qv, d)) * inv
    t = np.einsum("ij,ij->i", e2, qv) * inv
    eps = 1e-9
    hit = ok & (u >= -eps) & (v >= -eps) & (u + v <= 1 + eps) & (t >= 0)
    if not hit.any():
        return None
    i = int(np.flatnonzero(hit)[np.argmin(t[hit])])
    bary = np.array([1 - u[i] - v[i], u[i], v[i]])
    return Hit(i, bary, o + t[i] * d, float(t[i]))


def closest_point(surface: Surface, point, near: TriangleGrid | None = None) -> Hit:
    """The surface point nearest ``point`` (the triangles at once: the projection on its plane
    when inside, else the nearest point of its three edges). With ``near``, only the triangles
    in its cells around the point are looked at: in a cube twice as wide while none is there,
    then in the cube as wide as the nearest found is far (a point off the surface costs a
    few looks at the triangles near it, not every triangle)."""
    p = np.asarray(point, dtype=float)
    if near is not None:
        reach, span = near.reach, float(np.ptp(surface.verts, axis=0).max()) + 2 * near.reach
        while reach <= 2 * span:
            tris = near.query_box(p - reach, p + reach)
            if tris.size:
                hit = _closest_among(surface, p, tris)
                if hit.distance <= reach:  # every triangle that near was looked at: exact
                    return hit
                reach = max(hit.distance + 1e-6, 1.001 * reach)  # holds all nearer than it
            else:
                reach *= 2
    return _closest_among(surface, p, None)


def _closest_among(surface: Surface, p: np.ndarray, tris) -> Hit:
    c = surface.corners if tris is None else surface.corners[tris]
    n = surface.face_normals if tris is None else surface.face_normals[tris]
    cands, barys = [], []
    proj = p - np.einsum("ij,ij->i", p - c[:, 0], n)[:, None] * n
    b = _barycentric(c, proj)
    inside = (b >= -1e-12).all(axis=1)
    cands.append(np.where(inside[:, None], proj, np.inf))
    barys.append(b)
    for a, bb in ((0, 1), (1, 2), (2, 0)):
        e = c[:, bb] - c[:, a]
        t = np.clip(np.einsum("ij,j->i", e, p) - np.einsum("ij,ij->i", e, c[:, a]), 0, None)
        t = np.minimum(t / np.maximum(np.einsum("ij,ij->i", e, e), 1e-30), 1.0)
        cands.append(c[:, a] + t[:, None] * e)
        w = np.zeros((len(c), 3))
        w[:, a], w[:, bb] = 1 - t, t
        barys.append(w)
    pts = np.stack(cands)  # (4, T, 3)
    dist = np.linalg.norm(pts - p, axis=2)
    dist = np.where(np.isfinite(dist), dist, np.inf)
    k, i = np.unravel_index(int(np.argmin(dist)), dist.shape)
    tri = int(i) if tris is None else int(tris[i])
    return Hit(tri, np.asarray(barys[k][i]), pts[k, i], float(dist[k, i]))


MAX_BOX_CELLS = 512  # a box over more cubes (one huge triangle among small ones) is not binned


class BoxGrid:
    """Boxes binned in cubes of ``cell`` mm: the boxes that may meet a box, in time
    proportional to the boxes there, whatever the mesh's size."""

    def __init__(self, lo: np.ndarray, hi: np.ndarray, cell: float):
        self.cell = float(cell)
        a = np.floor(lo / self.cell).astype(np.int64)
        b = np.floor(hi / self.cell).astype(np.int64)
        self.lo = a.min(axis=0) if len(a) else np.zeros(3, np.int64)
        self.dims = (b.max(axis=0) - self.lo + 1) if len(a) else np.ones(3, np.int64)
        ext = b - a + 1
        n = np.prod(ext, axis=1)
        big = n > MAX_BOX_CELLS  # a box far larger than the cell: checked by its box instead
        self.big, self.big_lo, self.big_hi = np.flatnonzero(big), lo[big], hi[big]
        n = np.where(big, 0, n)
        box = np.repeat(np.arange(len(a)), n)
        k = np.arange(int(n.sum())) - np.repeat(np.cumsum(n) - n, n)
        e = ext[box]
        ijk = a[box] + np.stack([k // (e[:, 1] * e[:, 2]), k // e[:, 2] % e[:, 1], k % e[:, 2]], 1)
        keys = self._key(ijk)
        order = np.argsort(keys, kind="stable")
        self.keys, self.ids = keys[order], box[order]

    def _key(self, ijk):
        r = ijk - self.lo
        return (r[:, 0] * self.dims[1] + r[:, 1]) * self.dims[2] + r[:, 2]

    def query_box(self, lo, hi) -> np.ndarray:
        """The boxes (sorted, once each) binned in the cubes that meet the box [lo, hi], and
        the oversized ones that meet it."""
        meet = ((self.big_lo <= np.asarray(hi)) & (self.big_hi >= np.asarray(lo))).all(axis=1)
        return np.union1d(self._binned(lo, hi), self.big[meet])

    def _binned(self, lo, hi) -> np.ndarray:
        a = np.maximum(np.floor(np.asarray(lo) / self.cell).astype(np.int64), self.lo)
        b = np.floor(np.asarray(hi) / self.cell).astype(np.int64)
        b = np.minimum(b, self.lo + self.dims - 1)
        if (b < a).any():
            return np.zeros(0, dtype=np.int64)
        axes = [np.arange(a[k], b[k] + 1) for k in range(3)]
        keys = self._key(np.stack(np.meshgrid(*axes, indexing="ij"), axis=-1).reshape(-1, 3))
        s = np.searchsorted(self.keys, keys, "left")
        e = np.searchsorted(self.keys, keys, "right")
        n = e - s
        pos = np.repeat(s - (np.cumsum(n) - n), n) + np.arange(int(n.sum()))
        return np.unique(self.ids[pos])


class TriangleGrid(BoxGrid):
    """The triangles binned by their bounding boxes in cubes of ``cell`` mm: the triangles
    within ``reach`` of a point, whatever the mesh's size (live painting's nearest points)."""

    def __init__(self, surface: Surface, cell: float | None = None):
        c = surface.corners
        lo, hi = c.min(axis=1), c.max(axis=1)
        if cell is None:  # about a triangle's size, so each lies in a few cubes
            cell = float(np.clip(np.median((hi - lo).max(axis=1)), 1.0, 50.0))
        super().__init__(lo, hi, cell)
        self.reach = 2 * self.cell

    def query(self, point) -> np.ndarray:
        """The triangles whose boxes meet the cube of half side ``reach`` around the point."""
        return self.query_box(point - self.reach, point + self.reach)


def hit_at(surface: Surface, tri: int, point, distance: float) -> Hit:
    """A Hit from a triangle and a point on it (what another ray caster reports)."""
    p = np.asarray(point, dtype=float)
    return Hit(int(tri), _barycentric(surface.corners[[tri]], p[None])[0], p, float(distance))


def uv_hit(surface: Surface, uv) -> Hit | None:
    """The surface point whose texture coordinates are ``uv`` (the UV map read backwards: a
    layout made in the texture's space put on the mesh): in the triangle whose UV triangle
    holds ``uv`` (the one it lies deepest in, where islands overlap), at the same barycentric
    coordinates; None where no UV triangle covers it."""
    t = surface.uvs
    d1, d2, p = t[:, 1] - t[:, 0], t[:, 2] - t[:, 0], np.asarray(uv, dtype=float) - t[:, 0]
    den = d1[:, 0] * d2[:, 1] - d1[:, 1] * d2[:, 0]
    ok = np.abs(den) > 1e-20
    den = np.where(ok, den, 1.0)
    b1 = (p[:, 0] * d2[:, 1] - p[:, 1] * d2[:, 0]) / den
    b2 = (d1[:, 0] * p[:, 1] - d1[:, 1] * p[:, 0]) / den
    depth = np.where(ok, np.minimum(np.minimum(b1, b2), 1.0 - b1 - b2), -np.inf)
    i = int(np.argmax(depth))
    if depth[i] < -1e-9:
        return None
    bary = np.array([1.0 - b1[i] - b2[i], b1[i], b2[i]])
    return Hit(i, bary, matmul(bary, surface.corners[i]), 0.0)


def uv_axes(surface: Surface, tri: int) -> tuple[np.ndarray, np.ndarray]:
    """(dP/du, dP/dv): how a triangle's points move (mm) per unit of u and of v (the UV map's
    Jacobian inverted: the directions of the texture's x and y on the surface)."""
    t, c = surface.uvs[tri], surface.corners[tri]
    d = np.stack([t[1] - t[0], t[2] - t[0]], axis=1)  # (2, 2): UV edges as columns
    e = np.stack([c[1] - c[0], c[2] - c[0]], axis=1)  # (3, 2): the same edges in 3D
    j = matmul(e, inv(d))
    return j[:, 0], j[:, 1]


def _barycentric(c: np.ndarray, p: np.ndarray) -> np.ndarray:
    """(T, 3) barycentric coordinates of points p (T, 3) in the triangles c (T, 3, 3)."""
    v0, v1, v2 = c[:, 1] - c[:, 0], c[:, 2] - c[:, 0], p - c[:, 0]
    d00, d01, d11 = (np.einsum("ij,ij->i", a, b) for a, b in ((v0, v0), (v0, v1), (v1, v1)))
    d20, d21 = np.einsum("ij,ij->i", v2, v0), np.einsum("ij,ij->i", v2, v1)
    den = d00 * d11 - d01 * d01
    den = np.where(np.abs(den) > 1e-30, den, 1.0)
    v = (d11 * d20 - d01 * d21) / den
    w = (d00 * d21 - d01 * d20) / den
    return np.stack([1 - v - w, v, w], axis=1)


def normal_at(surface: Surface, hit: Hit) -> np.ndarray:
    """The smooth (vertex-interpolated) unit normal at a hit."""
    n = matmul(hit.bary, surface.corner_normals[hit.tri])
    ln = np.linalg.norm(n, axis=-1)
    return n / ln if ln > 1e-12 else surface.face_normals[hit.tri]
