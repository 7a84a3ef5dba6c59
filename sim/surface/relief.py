# SPDX-License-Identifier: GPL-3.0-or-later
"""How a mesh carries the writing as a relief (issue 29.7; Sec. 9's "3D writing effects"; this
planning is a model addition): how finely it must be cut where the ink is, or whether the relief
goes into its material instead.

A Displace modifier moves vertices only, by the density at each vertex's UV: where the mesh's
edges are longer than the ink's texels, the relief is sampled at its vertices - a coarse mesh
shows nothing of a stroke between two vertices, a few subdivisions show it in blocks and stairs
(streaks, bands). So the faces under the ink (and one ring around them, so that the border
between cut and uncut faces lies on bare paper and opens no crack) are cut ``levels`` times in
two (each level halves every edge) until their longest edge spans at most TARGET_EDGE_TEXELS of
the density image: every texel of ink gets a vertex. When that would make more than
MAX_RELIEF_VERTICES vertices, the relief goes into the material instead (a bump map of the same
density: it shows in renders and Material Preview at any mesh density, the mesh does not move).

Inputs are the mesh's faces as Blender keeps them (each face's loops: their vertex and UV), so
the planning needs no Blender."""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

TARGET_EDGE_TEXELS = 1.5  # the longest edge of a cut face, in texels of the density image
MAX_LEVELS = 10  # cuts in two (a face into 4^10 = a million)
MAX_RELIEF_VERTICES = 3_000_000  # more than this and the relief goes into the material
INK_LEVEL = 1e-3  # a texel with more ink than this is ink


@dataclass(frozen=True)
class ReliefPlan:
    method: str  # "GEOMETRY" (cut where the ink is, then displace) or "MATERIAL" (bump map)
    levels: int  # cuts in two of the faces under the ink (0: the mesh as it is)
    faces: np.ndarray  # (F,) bool: the faces that are cut
    vertices: int  # the cut mesh's vertices, about
    edge_texels: float  # the longest edge under the ink before cutting, in the ink's texels

    def message(self, name: str) -> str:
        """What the operator says about this mesh."""
        if self.method == "MATERIAL":
            return (
                f"'{name}' would need about {self.vertices / 1e6:.1f} million vertices to carry "
                f"the relief: it is in the material instead (a bump map: renders and Material "
                "Preview show it, the mesh does not move)"
            )
        if self.levels == 0:
            return f"'{name}' is fine enough for the relief as it is"
        return (
            f"'{name}': {int(self.faces.sum())} faces under the ink cut {self.levels} times in "
            f"two (an edge spans {self.edge_texels:.0f} -> "
            f"{self.edge_texels / 2**self.levels:.1f} of the ink's texels), about "
            f"{self.vertices:,} vertices"
        )


def inked_faces(face_start, face_total, loop_uv, ink) -> np.ndarray:
    """(F,) bool: faces whose UV bounding box holds ink. ``ink`` (H, W) bool, rows from v = 0
    (Blender's image order); UVs outside 0..1 wrap as the image repeats."""
    h, w = ink.shape
    sat = np.zeros((h + 1, w + 1), np.int64)  # summed-area table: ink in any box at once
    sat[1:, 1:] = np.cumsum(np.cumsum(ink, axis=0), axis=1)
    uv = np.asarray(loop_uv, dtype=float)
    lo = np.minimum.reduceat(uv, face_start, axis=0)
    hi = np.maximum.reduceat(uv, face_start, axis=0)
    wide = (hi - lo >= 1.0).any(axis=1)  # a face that spans the whole image
    lo, hi = lo % 1.0, lo % 1.0 + np.minimum(hi - lo, 1.0)
    x0 = np.clip(np.floor(lo[:, 0] * w).astype(int) - 1, 0, w)
    y0 = np.clip(np.floor(lo[:, 1] * h).astype(int) - 1, 0, h)
    x1 = np.clip(np.ceil(hi[:, 0] * w).astype(int) + 1, 0, w)
    y1 = np.clip(np.ceil(hi[:, 1] * h).astype(int) + 1, 0, h)
    count = sat[y1, x1] - sat[y0, x1] - sat[y1, x0] + sat[y0, x0]
    # a box that wraps past 1 (the seam's far side) also looks at the image's start
    past = hi > 1.0
    x1b = np.clip(np.ceil((hi[:, 0] - 1.0) * w).astype(int) + 1, 0, w)
    y1b = np.clip(np.ceil((hi[:, 1] - 1.0) * h).astype(int) + 1, 0, h)
    count += np.where(past[:, 0], sat[y1, x1b] - sat[y0, x1b], 0)
    count += np.where(past[:, 1], sat[y1b, x1] - sat[y1b, x0], 0)
    return (count > 0) | (wide & ink.any())


def grow(faces, face_start, face_total, loop_vert, n_verts: int) -> np.ndarray:
    """The faces and every face that shares a vertex with one of them."""
    vert = np.zeros(n_verts, bool)
    owner = np.repeat(faces, face_total)
    vert[np.asarray(loop_vert)[owner]] = True
    return np.maximum.reduceat(vert[loop_vert], face_start) > 0


def longest_edges(face_start, face_total, loop_uv) -> np.ndarray:
    """(F,) the longest UV edge of each face (UV units), its loops taken round."""
    uv = np.asarray(loop_uv, dtype=float)
    nxt = np.arange(len(uv)) + 1
    last = face_start + face_total - 1
    nxt[last] = face_start  # each face's last loop closes on its first
    d = np.hypot(*(uv[nxt] - uv).T)
    return np.maximum.reduceat(d, face_start)


def plan_relief(
    face_start,
    face_total,
    loop_vert,
    loop_uv,
    n_verts: int,
    ink,
    levels: int | None = None,
    budget: int | None = None,
) -> ReliefPlan:
    """The plan for one mesh (its faces as Blender keeps them; ``ink`` the density image's inked
        texels, (H, W) bool from v = 0). ``levels``:
        the user's own number of cuts (None: as many as the ink's texels need); ``budget``: the
    most vertices the relief may take in the mesh (None: MAX_RELIEF_VERTICES)."""
    face_start = np.asarray(face_start, dtype=np.int64)
    face_total = np.asarray(face_total, dtype=np.int64)
    size = max(ink.shape)
    under = inked_faces(face_start, face_total, loop_uv, ink)
    faces = grow(under, face_start, face_total, loop_vert, n_verts)
    edge = longest_edges(face_start, face_total, loop_uv) * size  # texels
    worst = float(edge[faces].max()) if faces.any() else 0.0
    if levels is None:
        need = worst / TARGET_EDGE_TEXELS
        levels = min(MAX_LEVELS, max(0, math.ceil(math.log2(need)))) if need > 1 else 0
    # a face of k corners cut n times in two: about k 4^n / 4 + ... vertices; 4^n a corner
    added = int((face_total[faces] * (4**levels - 1) // 4 + face_total[faces]).sum())
    vertices = int(n_verts + (added if levels else 0))
    budget = MAX_RELIEF_VERTICES if budget is None else budget
    method = "GEOMETRY" if vertices <= budget else "MATERIAL"
    return ReliefPlan(method, int(levels), faces, vertices, worst)
