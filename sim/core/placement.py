# SPDX-License-Identifier: GPL-3.0-or-later
"""Where the paper and the brush are in a 3D scene, and when samples happen on its timeline:
the pure maths behind the Blender glue (no bpy), tested on its own.

Units: a 3D scene works in metres, the engine in millimetres. The engine's paper coordinates
put (0, 0) at the paper's lower-left corner, x to the right, y up, z above the paper; the paper
object's local coordinates are centred on the sheet, so engine x = 1000 * local x + width / 2.
A sample is the brush pose relative to the paper (Sec. 4, Fig. 6(a)): x, y, z in mm and the
deflections d (sideways), q (forward) and the rotation r in degrees.
"""

from __future__ import annotations

import math

import numpy as np

from .exact import det3, inv, matmul
from .frames import angles_from_matrix, rotation_matrix

MM = 1000.0  # millimetres a metre


class PlacementError(ValueError):
    """The scene's placement cannot be used (e.g. a paper scaled to nothing)."""


def engine_to_paper_local(width_mm: float, height_mm: float) -> np.ndarray:
    """4x4: engine mm (paper corner origin) -> the paper object's local metres (centred)."""
    m = np.eye(4)
    m[:3, :3] /= MM
    m[0, 3] = -width_mm / (2 * MM)
    m[1, 3] = -height_mm / (2 * MM)
    return m


def sample_from_matrices(brush_mw, paper_mw, width_mm: float, height_mm: float) -> np.ndarray:
    """One 6-DOF sample from the brush's and the paper's world matrices (4x4)."""
    paper_mw = np.asarray(paper_mw, dtype=float)
    if not np.isfinite(paper_mw).all() or abs(det3(paper_mw[:3, :3])) < 1e-18:
        raise PlacementError("The paper is scaled to nothing (or not a number): fix its scale")
    rel = matmul(inv(paper_mw), np.asarray(brush_mw, dtype=float))
    rot = rel[:3, :3]
    scale = np.linalg.norm(rot, axis=0)
    rot = rot / np.where(scale > 0, scale, 1.0)
    x = rel[0, 3] * MM + width_mm / 2
    y = rel[1, 3] * MM + height_mm / 2
    z = rel[2, 3] * MM
    d, q, r = angles_from_matrix(rot)
    return np.array([x, y, z, d, q, r])


def matrix_from_sample(paper_mw, sample, width_mm: float, height_mm: float) -> np.ndarray:
    """World matrix of the brush for a 6-DOF sample (the inverse of sample_from_matrices); the
    paper's scale does not scale the brush."""
    x, y, z, d, q, r = (float(v) for v in sample)
    rel = np.eye(4)
    rel[:3, :3] = rotation_matrix(d, q, r)
    rel[:3, 3] = (x - width_mm / 2) / MM, (y - height_mm / 2) / MM, z / MM
    pm = np.asarray(paper_mw, dtype=float).copy()
    pm[:3, :3] /= np.linalg.norm(pm[:3, :3], axis=0)
    return matmul(pm, rel)


def ray_to_paper(engine_to_world: np.ndarray, origin, direction):
    """Where a view ray meets the paper's plane, in engine mm (x, y); None if it misses."""
    inv_world = inv(engine_to_world)
    o = matmul(inv_world, np.r_[np.asarray(origin, dtype=float), 1.0])
    d = matmul(inv_world[:3, :3], np.asarray(direction, dtype=float))
    if abs(d[2]) < 1e-12:
        return None
    t = -o[2] / d[2]
    if t < 0:
        return None
    p = o[:3] + t * d
    return float(p[0]), float(p[1])


def primitive_points(nets, to_local: np.ndarray) -> np.ndarray:
    """Engine control nets (m, Nu, Nv, 4) homogeneous, mm -> surface point coordinates (m,
    Nv * Nu, 4): Cartesian xyz in the object's local space and the weight; u (along the axis)
    runs fastest, as in Blender's surface point order."""
    w = nets[..., 3:4]
    xyz = nets[..., :3] / w
    hom = matmul(np.concatenate([xyz, np.ones_like(w)], axis=-1), to_local.T)
    co = np.concatenate([hom[..., :3], w], axis=-1)  # (m, Nu, Nv, 4)
    m, nu, nv, _ = co.shape
    return np.ascontiguousarray(co.transpose(0, 2, 1, 3).reshape(m, nv * nu, 4))


# ------------------------------------------------------------------------------ time
def samples_at_frame(n: int, start: float, frames_per_sample: float, frame: float) -> int:
    """How many of ``n`` samples have been written by the end of ``frame`` (sample i lies at
    frame start + i * frames_per_sample)."""
    if frame < start:
        return 0
    return int(min(n, math.floor((frame - start) / frames_per_sample + 1e-9) + 1))


def first_sample_from_frame(n: int, start: float, frames_per_sample: float, frame: float) -> int:
    """Index of the first of ``n`` samples at or after ``frame``."""
    if frame <= start:
        return 0
    return int(min(n, math.ceil((frame - start) / frames_per_sample - 1e-9)))
