# SPDX-License-Identifier: GPL-3.0-or-later
"""Writing done on flat paper laid on the surface (Write Character, Imitate Picture; issue
29.7; model addition beyond the paper): the chart map (``ChartMap``), the surface developed
around the point under the brush, the same for every sample, and the straightest walks over
the mesh (``walk``) it is made of.

``ChartMap``: the chart position c0 + r (cos a, sin a) goes to the point reached by walking r
over the surface from the start's point in the direction a of its tangent plane (the
exponential map at the start: geodesic polar coordinates), the tangent carried along the way.
Rays are walked LAY_STEP_MM at a time, at most LAY_STEP_MM apart where the writing reaches and
only as far as it reaches in their direction; a chart position between rays and steps takes the
blend of the four around it, put on the surface (its nearest point) with its normal there and
the tangent carried onto it. On a developable surface (a cylinder, a vase's side, a folded
sheet) this unrolls the surface exactly; on a sphere a character keeps its lengths from its
centre (its width across them grows by (r/R)^2 / 6: 2% at r = R / 3).

Following the writing sample after sample instead (``chart.step_to``, which live painting
does) develops the surface along the path the brush took: on a curved surface two paths to the
same chart position end at different places and turns (by the curvature they enclose), so
strokes laid in one order landed shifted and turned against strokes laid in another - 3.6 mm
and 14 degrees for a 24 mm character on a 30 mm sphere - and a walk by nearest points stopped
at a sharp crease (over a ridge the nearest point of a point beyond it is the ridge).

``walk``: a straight line within a triangle; at its edge the direction (and the carried
tangent) turns about the edge onto the next triangle (the two unfolded into one plane), so a
walk goes over any crease as a sheet folded over it would."""

from __future__ import annotations

import math

import numpy as np

from ..core.exact import matmul
from .chart import FRAME_WIDTH, LAY_STEP_MM, quantise, transport
from .mesh import Surface
from .query import closest_point, hit_at, normal_at

MAX_CROSSINGS = 100_000  # triangles one walk may cross (a bound, never reached in practice)


def edge_neighbours(tris) -> np.ndarray:
    """(T, 3): the triangle across edge k (corner k to corner k + 1) of each triangle, -1 at
    the mesh's boundary (the mesh is manifold: at most two triangles an edge)."""
    tris = np.asarray(tris)
    t = len(tris)
    a = tris.ravel()
    b = np.roll(tris, -1, axis=1).ravel()
    key = np.minimum(a, b) * (int(tris.max()) + 1) + np.maximum(a, b)
    order = np.argsort(key, kind="stable")
    k = key[order]
    same = np.flatnonzero(k[1:] == k[:-1])
    out = np.full(3 * t, -1, np.int64)
    e1, e2 = order[same], order[same + 1]
    out[e1], out[e2] = e2 // 3, e1 // 3
    return out.reshape(t, 3)


def _rotate(v, axis, angle: float) -> np.ndarray:
    """v turned by ``angle`` about the unit ``axis`` (Rodrigues)."""
    c, s = math.cos(angle), math.sin(angle)
    return v * c + np.cross(axis, v) * s + axis * (matmul(axis, v)) * (1 - c)


def walk(surface: Surface, nbr, tri: int, p, d, t, length: float):
    """Walk ``length`` mm over the mesh from point p on triangle ``tri`` in direction d (in
    its plane), carrying the tangent t; returns (tri, p, d, t) where it ends (at the mesh's
    boundary when it gets there first)."""
    p, d, t = (np.asarray(v, dtype=float) for v in (p, d, t))
    left = float(length)
    came = -1
    for _ in range(MAX_CROSSINGS):
        c = surface.verts[surface.tris[tri]]
        out = None
        for k in range(3):  # where the line leaves the triangle: the nearest edge ahead
            if nbr[tri, k] == came and came >= 0:
                continue
            a, e = c[k], c[(k + 1) % 3] - c[k]
            m = np.cross(surface.face_normals[tri], e)  # the edge's inward normal in-plane
            den = matmul(d, m)
            if den >= -1e-15:
                continue  # running along or away from this edge
            s = (matmul((a - p), m)) / den
            if s >= -1e-12 and (out is None or s < out[0]):
                out = (max(s, 0.0), k)
        if out is None or out[0] >= left:
            return tri, p + d * left, d, t
        s, k = out
        p = p + d * s
        left -= s
        nxt = int(nbr[tri, k])
        if nxt < 0:
            return tri, p, d, t  # the mesh's boundary
        n0, n1 = surface.face_normals[tri], surface.face_normals[nxt]
        e = c[(k + 1) % 3] - c[k]
        e = e / max(np.linalg.norm(e, axis=-1), 1e-300)
        if (
            matmul(n1, n1) > 0.5 and matmul(n0, n0) > 0.5
        ):  # unfold onto the next face about the edge
            angle = math.atan2(matmul(np.cross(n0, n1), e), matmul(n0, n1))
            d, t = _rotate(d, e, angle), _rotate(t, e, angle)
        came, tri = tri, nxt
    return tri, p, d, t  # pragma: no cover - MAX_CROSSINGS


def lay_on(surface: Surface, start, samples, near=None, progress=None):
    """Writing done on flat paper (samples (N, 6) in mm, on the chart whose position ``start``
    has) laid on the surface: each sample's frame is the chart map's at its chart position
    (``ChartMap``): the same place and turn for a chart position whatever the samples before
    it. The samples stay as they are (their height and tilts are then against each frame's
    normal); returns their frames (N, FRAME_WIDTH)."""
    xy = np.asarray(samples, dtype=float)[:, :2]
    chart = ChartMap(surface, start, xy, near, progress)
    frames = np.empty((len(xy), FRAME_WIDTH))
    for i, target in enumerate(xy):
        if progress is not None and i % 64 == 0:
            progress(0.5 + 0.5 * i / len(xy))
        frames[i] = chart.frame(target)
    return frames


class ChartMap:
    """The surface developed around a start frame (see the module): ``frame(xy)``."""

    def __init__(self, surface: Surface, start, xy, near=None, progress=None):
        self.surface, self.near = surface, near
        self.start = np.asarray(start, dtype=float)
        rel = np.asarray(xy, dtype=float).reshape(-1, 2) - self.start[:2]
        r = np.hypot(rel[:, 0], rel[:, 1])
        reach = float(r.max()) if r.size else 0.0
        self.step = LAY_STEP_MM
        self.rays = max(16, math.ceil(2 * math.pi * reach / self.step))
        sector = 2 * math.pi / self.rays
        k = np.floor((np.arctan2(rel[:, 1], rel[:, 0]) % (2 * math.pi)) / sector).astype(int)
        need = np.zeros(self.rays)  # how far each ray goes: its two sectors' farthest
        np.maximum.at(need, k % self.rays, r)
        np.maximum.at(need, (k + 1) % self.rays, r)
        self.nbr = edge_neighbours(surface.tris)
        self.start_tri = closest_point(surface, self.start[2:5], near).tri
        self.nodes = []
        for j in range(self.rays):
            if progress is not None and j % 16 == 0:
                progress(0.5 * j / self.rays)
            self.nodes.append(self._ray(j * sector, need[j]))

    def _ray(self, angle: float, length: float) -> np.ndarray:
        """(J, 11): every ``step`` along the ray (and one step beyond), the chart position the
        node stands for, its point, and its tangent and binormal on the smooth normal's plane
        (the chart's x and y there)."""
        c0, p, t0, n0 = self.start[:2], self.start[2:5], self.start[5:8], self.start[8:11]
        tri = self.start_tri
        fn = self.surface.face_normals[tri]
        way = np.array([math.cos(angle), math.sin(angle)])
        d = way[0] * t0 + way[1] * np.cross(n0, t0)
        d, t = d - (matmul(d, fn)) * fn, t0 - (matmul(t0, fn)) * fn  # onto the face's plane
        d, t = d / np.linalg.norm(d, axis=-1), t / np.linalg.norm(t, axis=-1)
        nodes = [np.r_[c0, p, t0, np.cross(n0, t0)]]
        for j in range(1, math.ceil(length / self.step) + 2):
            tri, p, d, t = walk(self.surface, self.nbr, tri, p, d, t, self.step)
            n = normal_at(self.surface, hit_at(self.surface, tri, p, 0.0))
            tn = transport(t, n)
            nodes.append(np.r_[c0 + way * (j * self.step), p, tn, np.cross(n, tn)])
        return np.array(nodes)

    def frame(self, xy) -> np.ndarray:
        """The frame at chart position ``xy``: (c, P, T, N) with c = xy. Each of the four nodes
        around it places xy on its own tangent plane (the chart's axes there), and the four
        are blended (so a plane's chart map is the plane itself, exactly)."""
        xy = np.asarray(xy, dtype=float)
        rel = xy - self.start[:2]
        sector = (math.atan2(rel[1], rel[0]) % (2 * math.pi)) / (2 * math.pi / self.rays)
        ka = int(sector) % self.rays
        fa = sector - int(sector)
        j = float(np.hypot(*rel)) / self.step
        j0, fj = int(j), j - int(j)
        point, tangent = np.zeros(3), np.zeros(3)
        for k, wk in ((ka, 1 - fa), ((ka + 1) % self.rays, fa)):
            ray = self.nodes[k]
            for node, w in (
                (ray[min(j0, len(ray) - 1)], 1 - fj),
                (ray[min(j0 + 1, len(ray) - 1)], fj),
            ):
                off = xy - node[:2]
                point += wk * w * (node[2:5] + off[0] * node[5:8] + off[1] * node[8:11])
                tangent += wk * w * node[5:8]
        hit = closest_point(self.surface, point, self.near)
        hit = hit_at(self.surface, hit.tri, hit.point, 0.0)
        n = normal_at(self.surface, hit)
        return quantise(np.r_[xy, hit.point, transport(tangent, n), n])
