# SPDX-License-Identifier: GPL-3.0-or-later
"""Writing on a 3D surface (issue 17; the paper's Sec. 9 "3D writing effects"): any UV-mapped
triangle mesh is the paper, as plain arrays (no bpy), and every geometric question is answered
here.

The design, in three parts:

1. **The local frame.** Each sample is taken where the brush's axis meets the surface (the
   closest surface point when the axis misses it): the point P, the smooth normal N there (the
   paper's z: the brush's height above the surface and its tilts are measured against it; faces
   meeting at less than SMOOTH_ANGLE_DEG are smoothed, sharper edges stay) and a tangent T
   (B = N x T). T is carried from sample to sample by the smallest rotation that keeps it
   tangent (parallel transport, ``transport``); the first sample's T is the brush's own x axis
   (baking) or the surface's x axis (painting) on the tangent plane, and the rotation r is kept
   continuous. The engine's sample is the brush's pose in that frame, so the
   brush model, which only knows a flat paper at z = 0, is unchanged: it writes on the tangent
   plane at P.
2. **The chart.** The brush's dynamics need one continuous plane to move on, so the surface is
   *developed* along the writing: the chart position c of a sample's point is the previous one
   plus the step P_i - P_(i-1) seen in the previous frame (``develop``). On a flat surface this
   is the plane itself, exactly; on a curved one it unrolls the surface along the path (as a
   sheet laid on a vase). The recording keeps the chart samples (its usual ``samples``) and, per
   sample, the frame (c, P, T, N) in ``surface.frames``; replay reads them, so it is bit for bit.
3. **Where the ink lands** (``SurfacePaper.splat``). The marks are rasterised on the chart's own
   pixel grid at the paper's px/mm, then splatted into the texels whose 3D points lie under
   them: every texel knows its 3D point (``TexelTiles``: each UV triangle rasterised in the
   texture, plus a pad of PAD_TEXELS around it for filtering, a tile at a time when the marks
   first reach it), the triangles' pieces binned in 3D find the texels near P, and each is
   projected on the tangent plane and takes the chart pixel it falls in.
   So the UV map's stretch is exact (a texel's ink is decided in the surface's own millimetres)
   and seams are free (a mark straddling a seam inks the texels of both islands, whatever their
   place in the texture). The work per sample is the texels near the mark, never the texture;
   nor is the texture's whole set of texel points ever built before writing.

What is approximate: a mark is the brush's cut by the tangent plane at P, projected along N onto
the surface (a decal): on a surface curving with radius R a mark of radius r is off by about
r^2 / (2R) in depth and (r/R)^2 in size (1% for a 5 mm mark on a 50 mm vase). Texels take the
chart pixel under their centre (nearest): where the UVs give fewer texels a millimetre than the
paper's px/mm, edges alias. The paper's physics (absorption, drying, the saturation spreading of
``sim.paper``) runs on the texture's grid: its spreading is measured in texels, so it is
anisotropic where the UVs stretch and stops at seams (ink does not bleed from one island into
the next).
"""

from __future__ import annotations

import copy
import math
import threading
from dataclasses import dataclass, field, replace

import numpy as np

from ..core.frames import angles_from_matrix, rotation_matrix

PAD_TEXELS = 1.5  # texels around each UV triangle that get its 3D points (filtering at seams)
FRAME_WIDTH = 11  # a frame: chart cx, cy; point P; tangent T; normal N (mm, unit vectors)
FRAME_DECIMALS = 5  # as a recording's samples (sim.recording.SAMPLE_DECIMALS)
CHART_SIDES = 11.0  # the chart's origin, in paper sides from its own 0 (samples reach 10)
CHART_SHAPE = (1 << 30, 1 << 30)  # the chart's pixel grid is unbounded for the marks
NORMAL_DOT_MIN = 0.0  # a texel whose normal faces away from the frame's is on another side
DEPTH_TOL_MM = 0.5  # plus half the mark's radius: how far off the tangent plane a texel may be
GROUP_TILE = 64  # texture tiles by which one sample's texels are grouped for the paper


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
    v = (qv @ d) * inv
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
    n = hit.bary @ surface.corner_normals[hit.tri]
    ln = np.linalg.norm(n)
    return n / ln if ln > 1e-12 else surface.face_normals[hit.tri]


# ------------------------------------------------------------------------------ frames
def transport(tangent, normal) -> np.ndarray:
    """The tangent carried onto the plane normal to ``normal`` by the smallest rotation (the
    part along the normal removed); the surface's x (else y) axis when it is lost."""
    n = np.asarray(normal, dtype=float)
    for t in (np.asarray(tangent, dtype=float), np.array([1.0, 0, 0]), np.array([0, 1.0, 0])):
        t = t - (t @ n) * n
        ln = np.linalg.norm(t)
        if ln > 0.3:
            return t / ln
    raise SurfaceError("a surface normal is not a number")  # pragma: no cover - unreachable


def quantise(a) -> np.ndarray:
    """Frames exactly as a saved recording holds them (see sim.recording.quantise)."""
    a = np.asarray(a, dtype=float)
    return np.array([round(float(v), FRAME_DECIMALS) for v in a.ravel()]).reshape(a.shape)


def frame_parts(frame):
    """(c (2,), P, T, B, N) of a frame row."""
    f = np.asarray(frame, dtype=float)
    n = f[8:11]
    t = f[5:8]
    return f[:2], f[2:5], t, np.cross(n, t), n


def new_frame(surface: Surface, hit: Hit, prev=None, origin_xy=(0.0, 0.0), first_t=None):
    """The frame at ``hit``: the tangent carried from the previous frame, the chart position
    developed from it. The first frame's tangent is ``first_t`` (the brush's own x axis when
    baking, so its rotation r starts at 0; the surface's x axis by default) on the tangent
    plane, and its chart position ``origin_xy`` + the point's coordinates along T and B (so a
    flat surface's chart is its own plane)."""
    n = normal_at(surface, hit)
    if prev is None:
        t = transport(np.array([1.0, 0.0, 0.0]) if first_t is None else first_t, n)
        c = np.asarray(origin_xy, dtype=float) + [hit.point @ t, hit.point @ np.cross(n, t)]
    else:
        c0, p0, t0, b0, _n0 = frame_parts(prev)
        step = hit.point - p0
        c = c0 + np.array([step @ t0, step @ b0])
        t = transport(t0, n)
    return quantise(np.r_[c, hit.point, t, n])


def local_sample(frame, base_mm, rot) -> np.ndarray:
    """The engine's 6-DOF sample of a brush (base point, rotation 3x3 in the surface's space)
    in the frame's local coordinates: x, y on the chart, z above the tangent plane."""
    c, p, t, b, n = frame_parts(frame)
    F = np.stack([t, b, n], axis=1)
    F = F / np.linalg.norm(F, axis=0)
    rel = F.T @ (np.asarray(base_mm, dtype=float) - p)
    d, q, r = angles_from_matrix(F.T @ np.asarray(rot, dtype=float))
    return np.array([c[0] + rel[0], c[1] + rel[1], rel[2], d, q, r])


def pose_from_sample(frame, sample) -> tuple[np.ndarray, np.ndarray]:
    """(base point, rotation) in the surface's space of a local sample (local_sample's
    inverse)."""
    c, p, t, b, n = frame_parts(frame)
    F = np.stack([t, b, n], axis=1)
    F = F / np.linalg.norm(F, axis=0)
    s = np.asarray(sample, dtype=float)
    base = p + F @ np.array([s[0] - c[0], s[1] - c[1], s[2]])
    return base, F @ rotation_matrix(*s[3:6])


def axis_hit(surface: Surface, base_mm, rot, cast=None, near=None) -> Hit:
    """Where the brush's axis (its -z, from the base) meets the surface; the closest surface
    point when it does not (through ``near``, a TriangleGrid, when given). ``cast(origin,
    direction)`` finds a ray's first hit (ray_hit, or the caller's faster one: Blender's BVH
    tree)."""
    cast = (lambda o, d: ray_hit(surface, o, d)) if cast is None else cast
    hit = cast(np.asarray(base_mm, dtype=float), -np.asarray(rot, dtype=float)[:, 2])
    return hit if hit is not None else closest_point(surface, base_mm, near)


def develop(
    surface: Surface, bases, rots, origin_xy, cast=None, near=None, progress=None
) -> tuple[np.ndarray, np.ndarray]:
    """Baked brush poses (N bases in mm, N rotations, in the surface's space) -> the engine's
    chart samples (N, 6) and their frames (N, FRAME_WIDTH); see new_frame for origin_xy and
    axis_hit for cast and near. The rotation r is kept continuous (no jump of 360 degrees).
    ``progress(fraction)`` is told how far it is."""
    frames = np.empty((len(bases), FRAME_WIDTH))
    samples = np.empty((len(bases), 6))
    prev = None
    for i, (base, rot) in enumerate(zip(bases, rots, strict=True)):
        if progress is not None and i % 64 == 0:
            progress(i / len(bases))
        hit = axis_hit(surface, base, rot, cast, near)
        prev = frames[i] = new_frame(surface, hit, prev, origin_xy, np.asarray(rot)[:, 0])
        samples[i] = local_sample(prev, base, rot)
        if i:
            r0 = samples[i - 1, 5]
            samples[i, 5] = r0 + (samples[i, 5] - r0 + 180.0) % 360.0 - 180.0
    return samples, frames


def follow(surface: Surface, prev, xy, near: TriangleGrid | None = None) -> np.ndarray:
    """The frame of a sample painted at chart position ``xy`` after the frame ``prev``: the
    surface point nearest the spot of prev's tangent plane at xy (live painting)."""
    c, p, t, b, _n = frame_parts(prev)
    guess = p + (xy[0] - c[0]) * t + (xy[1] - c[1]) * b
    return new_frame(surface, closest_point(surface, guess, near), prev)


LAY_STEP_MM = 2.0  # the longest step by which lay_on follows the surface (far below a radius)


def start_frame(surface: Surface, hit: Hit, xy, first_t) -> np.ndarray:
    """The frame at ``hit`` whose chart position is ``xy``, its tangent ``first_t`` (the
    brush's own x axis) on the tangent plane: where writing done on flat paper is laid."""
    n = normal_at(surface, hit)
    return quantise(np.r_[np.asarray(xy, dtype=float), hit.point, transport(first_t, n), n])


def lay_on(surface: Surface, start, samples, near=None, progress=None):
    """Writing done on flat paper (samples (N, 6) in mm, on the chart whose position ``start``
    has) laid on the surface: each sample's frame follows the previous one (``follow``, from
    ``start`` for the first) over the surface to its chart position, in steps of at most
    LAY_STEP_MM, so a jump in the air between strokes also goes round the surface. The
    samples stay as they are (their height and tilts are then against each frame's normal);
    returns their frames (N, FRAME_WIDTH)."""
    xy = np.asarray(samples, dtype=float)[:, :2]
    frames = np.empty((len(xy), FRAME_WIDTH))
    prev = np.asarray(start, dtype=float)
    for i, target in enumerate(xy):
        prev = frames[i] = step_to(surface, prev, target, near)
        if progress is not None and i % 64 == 0:
            progress(i / len(xy))
    return frames


def step_to(surface: Surface, prev, target, near=None) -> np.ndarray:
    """The frame at chart position ``target`` followed from the frame ``prev`` over the surface
    in steps of at most LAY_STEP_MM (lay_on's and live painting's)."""
    prev = np.asarray(prev, dtype=float)
    c, target = prev[:2], np.asarray(target, dtype=float)
    n = max(1, math.ceil(float(np.hypot(*(target - c))) / LAY_STEP_MM))
    for k in range(1, n + 1):
        prev = follow(surface, prev, c + (target - c) * (k / n), near)
    return prev


def chart_xy_over(surface: Surface, frame, point, near=None) -> tuple[float, float]:
    """The chart position of a surface point however far from the frame: walked towards it
    over the surface in steps of LAY_STEP_MM, each seen on the last step's tangent plane (on
    the far side of a cup, not the point's shadow on the first frame's plane)."""
    frame = np.asarray(frame, dtype=float)
    for _ in range(MAX_WALK_STEPS):
        xy = np.array(chart_xy(frame, point))
        d = float(np.hypot(*(xy - frame[:2])))
        if d <= LAY_STEP_MM:
            break
        frame = follow(surface, frame, frame[:2] + (xy - frame[:2]) * (LAY_STEP_MM / d), near)
    return float(xy[0]), float(xy[1])


MAX_WALK_STEPS = 2000  # chart_xy_over's steps (4 m of surface)


def chart_xy(frame, point) -> tuple[float, float]:
    """The chart position of a surface point near the frame (the mouse's, while painting)."""
    c, p, t, b, _n = frame_parts(frame)
    d = np.asarray(point, dtype=float) - p
    return float(c[0] + d @ t), float(c[1] + d @ b)


def frames_from_dict(d, n_samples: int) -> np.ndarray | None:
    """A recording's ``surface`` section (its frames), checked; None for flat paper."""
    if d is None:
        return None
    rows = d.get("frames") if isinstance(d, dict) else None
    if not isinstance(rows, list):
        raise SurfaceError("'surface.frames' must be a list of frames")
    if len(rows) != n_samples:
        raise SurfaceError(f"'surface.frames' has {len(rows)} frames for {n_samples} samples")
    try:
        a = np.asarray(rows, dtype=float)
    except (TypeError, ValueError):
        raise SurfaceError("'surface.frames' must hold lists of 11 numbers") from None
    if a.shape != (n_samples, FRAME_WIDTH) or not np.isfinite(a).all():
        raise SurfaceError("'surface.frames' must hold lists of 11 finite numbers")
    return a


# ------------------------------------------------------------------------------ texels
@dataclass(frozen=True)
class TexelPoints:
    """The 3D point (and face normal) of every texel a UV triangle (or its pad) covers."""

    index: np.ndarray  # (K,) flat texel index row * W + col, rows from the bottom (v = 0)
    xyz: np.ndarray  # (K, 3) mm
    normal: np.ndarray  # (K, 3)
    W: int
    H: int


def texel_points(surface: Surface, W: int, H: int) -> TexelPoints:
    """Every texel's 3D point in a W x H texture (see TexelTiles, which builds them only where
    the writing reaches)."""
    return TexelTiles(surface, W, H).all()


TEXEL_TILE = 16  # texels a side of the tiles in which texel points are built on first use
BUILD_CHUNK = 1 << 20  # candidate texels rasterised together at most (bounds the memory)


class TexelTiles:
    """The 3D point of every texel a UV triangle (or its pad of PAD_TEXELS) covers, built a
    TEXEL_TILE tile at a time when a splat first reaches it and kept: so no frame change or
    first stroke pays for the whole texture, only for the tiles its marks touch. A texel's
    point comes from the triangle it lies deepest in (its signed distance in texels to the
    nearest edge, the largest; the later triangle on a tie), whatever the order in which the
    tiles are built.

    Made at once, in time proportional to the triangles: each triangle's part in each tile it
    covers (a "piece": its texel rectangle there) and that piece's 3D box (the affine image of
    the rectangle holds every point the triangle gives its texels there), binned in a BoxGrid.
    A query's 3D box finds the pieces, hence the tiles, that may hold texels in it."""

    def __init__(self, surface: Surface, W: int, H: int):
        self.surface, self.W, self.H = surface, int(W), int(H)
        uvp = surface.uvs * np.array([W, H]) - 0.5  # texel centres at integers
        lo = np.maximum(np.floor(uvp.min(axis=1) - PAD_TEXELS).astype(np.int64) + 1, 0)
        hi = np.minimum(np.ceil(uvp.max(axis=1) + PAD_TEXELS).astype(np.int64), [W, H])
        self.coef = _edge_functions(uvp)
        # each edge function over its gradient's length: the signed distance (texels) to it
        with np.errstate(invalid="ignore"):
            norm = np.hypot(self.coef[:, :, 0], self.coef[:, :, 1])[:, :, None]
            self.dist = (self.coef / norm).astype(np.float32)
        tri = np.flatnonzero(np.isfinite(self.coef).all(axis=(1, 2)) & (hi > lo).all(axis=1))
        self.tiles_x = -(-self.W // TEXEL_TILE)
        n_tiles = self.tiles_x * -(-self.H // TEXEL_TILE)
        key, ptri, rect = self._pieces(tri, lo, hi)
        order = np.lexsort((ptri, key))  # by tile, then triangle
        self.key, self.tri, self.rect = key[order], ptri[order], rect[order]
        plo, phi = self._piece_boxes()
        self.box_lo, self.box_hi = plo, phi
        cell = float(np.clip(np.median((phi - plo).max(axis=1)), 1.0, 50.0)) if len(plo) else 1.0
        self.grid = BoxGrid(plo, phi, cell)
        self.owner = np.full(self.W * self.H, -1, np.int32)  # the triangle that gives its point
        self.xyz = np.zeros((self.W * self.H, 3), np.float32)  # pages touched when built only
        self.built = np.zeros(n_tiles, bool)
        self._lock = threading.Lock()

    def _pieces(self, tri, lo, hi):
        """(tile key, triangle, texel rectangle x0, x1, y0, y1) of each triangle in each tile
        its padded rectangle covers."""
        T = TEXEL_TILE
        t0, t1 = lo[tri] // T, (hi[tri] - 1) // T
        ext = t1 - t0 + 1
        n = ext[:, 0] * ext[:, 1]
        j = np.repeat(np.arange(len(tri)), n)
        k = np.arange(int(n.sum())) - np.repeat(np.cumsum(n) - n, n)
        tx, ty = t0[j, 0] + k % ext[j, 0], t0[j, 1] + k // ext[j, 0]
        ptri = tri[j]
        rect = np.stack(
            [
                np.maximum(lo[ptri, 0], tx * T),
                np.minimum(hi[ptri, 0], tx * T + T),
                np.maximum(lo[ptri, 1], ty * T),
                np.minimum(hi[ptri, 1], ty * T + T),
            ],
            axis=1,
        )
        return ty * self.tiles_x + tx, ptri, rect

    def _piece_boxes(self):
        """Each piece's 3D box: its texel rectangle's corners through the triangle's map."""
        corners = self.surface.corners[self.tri]
        pts = []
        for x, y in ((0, 2), (0, 3), (1, 2), (1, 3)):
            xs = self.rect[:, x] - (x == 1)  # the last texel of [x0, x1)
            ys = self.rect[:, y] - (y == 3)
            bary = _bary(self.coef[self.tri], xs.astype(float), ys.astype(float))
            pts.append(np.einsum("kj,kjd->kd", bary, corners))
        pts = np.stack(pts)
        return pts.min(axis=0) - 1e-3, pts.max(axis=0) + 1e-3  # float32 points: a margin

    def query_box(self, lo, hi) -> np.ndarray:
        """The texels (flat indices, by tile then row) whose points lie in the box [lo, hi],
        looked for in the tiles that may hold them; those tiles are built first if they are
        not yet."""
        lo, hi = np.asarray(lo, dtype=float), np.asarray(hi, dtype=float)
        p = self.grid.query_box(lo, hi)
        p = p[((self.box_lo[p] <= hi) & (self.box_hi[p] >= lo)).all(axis=1)]
        tiles = np.unique(self.key[p])
        with self._lock:  # a kept paper is shared by a worker (writing) and Blender's thread
            self.build(tiles[~self.built[tiles]])
        idx = self._tile_texels(tiles)
        idx = idx[self.owner[idx] >= 0]
        xyz = self.xyz[idx]
        return idx[((xyz >= lo) & (xyz <= hi)).all(axis=1)]

    def _tile_texels(self, tiles) -> np.ndarray:
        T = TEXEL_TILE
        r = np.arange(T)
        ys = (tiles // self.tiles_x)[:, None, None] * T + r[None, :, None]
        xs = (tiles % self.tiles_x)[:, None, None] * T + r[None, None, :]
        ys, xs = np.broadcast_arrays(ys, xs)
        inside = (ys < self.H) & (xs < self.W)
        return (ys * self.W + xs)[inside]

    def normal(self, idx) -> np.ndarray:
        return self.surface.face_normals[self.owner[idx]].astype(np.float32)

    def build(self, tiles):
        """Rasterise the triangles' pieces in these tiles (a chunk of tiles at a time)."""
        if len(tiles) == 0:
            return
        s = np.searchsorted(self.key, tiles, "left")
        e = np.searchsorted(self.key, tiles, "right")
        self.built[tiles[e == s]] = True  # no triangle there: no texel
        tiles, s, e = tiles[e > s], s[e > s], e[e > s]
        if len(tiles) == 0:
            return
        r = self.rect
        size = (r[:, 1] - r[:, 0]) * (r[:, 3] - r[:, 2])
        per_tile = np.add.reduceat(size, s)
        start = 0
        while start < len(tiles):
            cum = np.cumsum(per_tile[start:])
            stop = start + max(int(np.searchsorted(cum, BUILD_CHUNK)), 1)
            n = e[start:stop] - s[start:stop]
            pos = np.repeat(s[start:stop] - (np.cumsum(n) - n), n) + np.arange(int(n.sum()))
            self._rasterise(pos)
            self.built[tiles[start:stop]] = True
            start = stop

    def _rasterise(self, pieces):
        """Each texel of these pieces goes to its deepest triangle; its point is made."""
        r = self.rect[pieces]
        nx = r[:, 1] - r[:, 0]
        n = nx * (r[:, 3] - r[:, 2])
        j = np.repeat(np.arange(len(pieces)), n)
        k = np.arange(int(n.sum())) - np.repeat(np.cumsum(n) - n, n)
        x, y = r[j, 0] + k % nx[j], r[j, 2] + k // nx[j]
        tri = self.tri[pieces][j]
        c = self.dist[tri]  # float32: the pad's edge needs no more
        xf, yf = x.astype(np.float32), y.astype(np.float32)
        depth = c[:, 0, 0] * xf + c[:, 0, 1] * yf + c[:, 0, 2]
        for i in (1, 2):
            np.minimum(depth, c[:, i, 0] * xf + c[:, i, 1] * yf + c[:, i, 2], out=depth)
        keep = depth >= -PAD_TEXELS
        flat, depth, tri, x, y = (y * self.W + x)[keep], depth[keep], tri[keep], x[keep], y[keep]
        order = np.lexsort((tri, depth, flat))  # the last of each texel: deepest, then latest
        flat, tri, x, y = flat[order], tri[order], x[order], y[order]
        last = np.r_[flat[1:] != flat[:-1], True] if flat.size else np.zeros(0, bool)
        flat, tri, x, y = flat[last], tri[last], x[last], y[last]
        bary = _bary(self.coef[tri], x.astype(float), y.astype(float))
        self.xyz[flat] = np.einsum("kj,kjd->kd", bary, self.surface.corners[tri])
        self.owner[flat] = tri

    def all(self) -> TexelPoints:
        """Every texel's point (all tiles built): tests, pictures."""
        with self._lock:
            self.build(np.flatnonzero(~self.built))
        idx = np.flatnonzero(self.owner >= 0).astype(np.int32)
        return TexelPoints(idx, self.xyz[idx], self.normal(idx), self.W, self.H)


def _edge_functions(uvp) -> np.ndarray:
    """(T, 3, 3): for each triangle and corner i, (A, B, C) with A x + B y + C its barycentric
    coordinate at texel (x, y); NaN for a triangle of no area."""
    a, b, c = uvp[:, 0], uvp[:, 1], uvp[:, 2]
    den = (b[:, 0] - a[:, 0]) * (c[:, 1] - a[:, 1]) - (b[:, 1] - a[:, 1]) * (c[:, 0] - a[:, 0])
    with np.errstate(divide="ignore", invalid="ignore"):
        inv = np.where(np.abs(den) > 1e-14, 1.0 / den, np.nan)
    out = np.empty((len(uvp), 3, 3))
    for i, (p, q) in enumerate(((b, c), (c, a), (a, b))):  # corner i: the edge opposite it
        out[:, i, 0] = (p[:, 1] - q[:, 1]) * inv
        out[:, i, 1] = (q[:, 0] - p[:, 0]) * inv
        out[:, i, 2] = (p[:, 0] * q[:, 1] - q[:, 0] * p[:, 1]) * inv
    return out


def _bary(coef, x, y) -> np.ndarray:
    return coef[:, :, 0] * x[:, None] + coef[:, :, 1] * y[:, None] + coef[:, :, 2]


# ------------------------------------------------------------------------------ the paper
class SurfacePaper:
    """What the engine needs to write on a surface: the frames of the recording's samples,
    the chart's origin, and the splat of a sample's chart marks into the texture."""

    def __init__(self, surface: Surface, frames, W: int, H: int, ppm: float, side_mm: float):
        self.surface = surface
        self.ppm = float(ppm)
        self.tiles = TexelTiles(surface, W, H)  # texel points, built where the marks reach
        self.W, self.H, self.side_mm = W, H, float(side_mm)
        # the chart is offset so that its pixels are never negative (samples reach 10 sides)
        self.offset = math.ceil(CHART_SIDES * side_mm * self.ppm) / self.ppm
        self.near = TriangleGrid(surface)  # the frames of live samples
        self._set_frames(frames)

    @property
    def texels(self) -> TexelPoints:
        """Every texel's point (builds them all: for tests and pictures, not the splat)."""
        return self.tiles.all()

    def _set_frames(self, frames):
        self.frames = list(np.asarray(frames, dtype=float)) if frames is not None else []
        self.given = len(self.frames)  # the recording's; the rest follow live samples
        self._followed = {}  # frame index -> the chart position it was made for

    def with_frames(self, frames) -> SurfacePaper:
        """The same surface and texels (the costly part) for another recording's frames."""
        other = copy.copy(self)
        other._set_frames(frames)
        return other

    def frame(self, i: int, sample) -> np.ndarray:
        """Sample i's frame. A sample painted live (beyond the recording's frames) gets one that
        follows the previous frame to its chart position; a stroke taken back and painted again
        gets new ones."""
        xy = (float(sample[0]), float(sample[1]))
        if i >= self.given and i < len(self.frames) and self._followed.get(i) != xy:
            del self.frames[i:]
        while len(self.frames) <= i:
            if not self.frames:
                raise SurfaceError("a surface recording's first sample has no frame")
            k = len(self.frames)
            self.frames.append(step_to(self.surface, self.frames[-1], xy, self.near))
            self._followed[k] = xy
        return self.frames[i]

    def engine_sample(self, i: int, sample) -> np.ndarray:
        """Sample i on the offset chart the marks are rasterised in."""
        self.frame(i, sample)
        s = np.array(sample, dtype=float)
        s[:2] += self.offset
        return s

    def splat(self, marks, i: int) -> list[list]:
        """Sample i's chart marks as texture marks, in groups of texels far enough apart (a
        mark straddling a seam lands in two places of the texture) that the paper takes each
        group as its own window; [] when no texel is under the marks."""
        marks = [mk for mk in marks if mk.rows.size]
        if not marks:
            return []
        c, p, t, b, n = frame_parts(self.frames[i])
        c = c + self.offset
        ppm = self.ppm
        x0 = min(mk.ix0 for mk in marks) / ppm
        y0 = min(mk.iy0 for mk in marks) / ppm
        x1 = max(mk.ix0 + mk.shape[1] for mk in marks) / ppm
        y1 = max(mk.iy0 + mk.shape[0] for mk in marks) / ppm
        tol = DEPTH_TOL_MM + math.hypot(x1 - x0, y1 - y0) / 4
        # the box in 3D around the marks' rectangle on the tangent plane, tol off it
        corners = np.array(
            [
                p + (x - c[0]) * t + (y - c[1]) * b + h * n
                for x in (x0, x1)
                for y in (y0, y1)
                for h in (-tol, tol)
            ]
        )
        tiles = self.tiles
        cand = tiles.query_box(corners.min(axis=0), corners.max(axis=0))
        d = tiles.xyz[cand] - p
        ok = (np.abs(d @ n) <= tol) & (tiles.normal(cand) @ n > NORMAL_DOT_MIN)
        cand, d = cand[ok], d[ok]
        col = np.floor((c[0] + d @ t) * ppm).astype(np.int64)
        row = np.floor((c[1] + d @ b) * ppm).astype(np.int64)
        out = []
        for mk in marks:
            tm = self._texture_mark(mk, row, col, cand)
            if tm is not None:
                out.append(tm)
        return group_marks(out)

    def _texture_mark(self, mk, row, col, texel):
        """One chart mark as the texels that fall in its inked pixels (None: none do)."""
        h, w = mk.shape
        r, cc = row - mk.iy0, col - mk.ix0
        inwin = (r >= 0) & (r < h) & (cc >= 0) & (cc < w)
        if not inwin.any():
            return None
        lut = np.full(h * w, -1, dtype=np.int64)
        lut[mk.rows * w + mk.cols] = np.arange(mk.rows.size)
        k = lut[r[inwin] * w + cc[inwin]]
        hit = k >= 0
        if not hit.any():
            return None
        k = k[hit]
        tex = texel[inwin][hit].astype(np.int64)
        ty, tx = tex // self.W, tex % self.W
        iy0, ix0 = int(ty.min()), int(tx.min())
        return _replace_pixels(
            mk, iy0, ix0, ty - iy0, tx - ix0, k, (int(ty.max()) - iy0 + 1, int(tx.max()) - ix0 + 1)
        )


def _replace_pixels(mk, iy0, ix0, rows, cols, k, shape):
    """A copy of the mark at other pixels, each with the ink of the mark's pixel k."""
    return replace(
        mk,
        iy0=iy0,
        ix0=ix0,
        rows=rows,
        cols=cols,
        wet=mk.wet[k],
        col=mk.col[k],
        lateral=mk.lateral[k],
        depth=mk.depth[k],
        shape=shape,
    )


def group_marks(marks) -> list[list]:
    """Split texture marks into groups whose GROUP_TILE tiles do not touch (each mark cut at
    the gaps): the paper deposits each group in its own window, so a mark on both sides of a
    seam costs its texels, not the texture between them."""
    if not marks:
        return []
    keys = [_tile_keys(mk) for mk in marks]
    tiles = np.unique(np.concatenate(keys))
    if tiles.size == 1 or np.ptp(tiles // _KEY) <= 1 and np.ptp(tiles % _KEY) <= 1:
        return [marks]  # one tile or a block of touching ones: one window
    label = _tile_components([divmod(int(k), _KEY) for k in tiles])
    lab_of = np.array([label[divmod(int(k), _KEY)] for k in tiles])
    if np.unique(lab_of).size == 1:
        return [marks]
    groups: dict[int, list] = {}
    for mk, key in zip(marks, keys, strict=True):
        lab = lab_of[np.searchsorted(tiles, key)]
        for g in np.unique(lab).tolist():
            groups.setdefault(g, []).append(_subset(mk, lab == g))
    return [groups[g] for g in sorted(groups)]


_KEY = 1 << 20  # tile row * _KEY + tile column


def _tile_keys(mk) -> np.ndarray:
    return ((mk.rows + mk.iy0) // GROUP_TILE) * _KEY + (mk.cols + mk.ix0) // GROUP_TILE


def _tile_components(tiles: list) -> dict:
    """Connected components (8-neighbourhood, so groups are at least a tile apart)."""
    label, left = {}, set(tiles)
    comp = 0
    for t0 in tiles:
        if t0 in label:
            continue
        stack = [t0]
        label[t0] = comp
        left.discard(t0)
        while stack:
            y, x = stack.pop()
            for dy in (-1, 0, 1):
                for dx in (-1, 0, 1):
                    nb = (y + dy, x + dx)
                    if nb in left:
                        left.discard(nb)
                        label[nb] = comp
                        stack.append(nb)
        comp += 1
    return label


def _subset(mk, sel):
    rows, cols = mk.rows[sel] + mk.iy0, mk.cols[sel] + mk.ix0
    iy0, ix0 = int(rows.min()), int(cols.min())
    shape = (int(rows.max()) - iy0 + 1, int(cols.max()) - ix0 + 1)
    k = np.flatnonzero(sel)
    return _replace_pixels(mk, iy0, ix0, rows - iy0, cols - ix0, k, shape)
