# SPDX-License-Identifier: GPL-3.0-or-later
"""The local frames and the chart (the design's parts 1 and 2, see the package): each
sample's frame (point, tangent carried by parallel transport, normal), the chart developed
along the writing, the brush's pose in a frame and back, writing done on flat paper laid on the
surface, and a recording's frames read back."""

from __future__ import annotations

import math

import numpy as np

from ..core.exact import matmul
from ..core.frames import angles_from_matrix, rotation_matrix
from ..core.recording import SAMPLE_DECIMALS
from ..core.recording import quantise as quantise_values
from .mesh import Surface, SurfaceError
from .query import Hit, TriangleGrid, closest_point, normal_at, ray_hit

FRAME_WIDTH = 11  # a frame: chart cx, cy; point P; tangent T; normal N (mm, unit vectors)
FRAME_DECIMALS = SAMPLE_DECIMALS  # frames are stored as a recording's samples are


# ------------------------------------------------------------------------------ frames
def transport(tangent, normal) -> np.ndarray:
    """The tangent carried onto the plane normal to ``normal`` by the smallest rotation (the
    part along the normal removed); the surface's x (else y) axis when it is lost."""
    n = np.asarray(normal, dtype=float)
    for t in (np.asarray(tangent, dtype=float), np.array([1.0, 0, 0]), np.array([0, 1.0, 0])):
        t = t - (matmul(t, n)) * n
        ln = np.linalg.norm(t, axis=-1)
        if ln > 0.3:
            return t / ln
    raise SurfaceError("a surface normal is not a number")  # pragma: no cover - unreachable


def quantise(a) -> np.ndarray:
    """Frames exactly as a saved recording holds them (sim.core.recording.quantise)."""
    return quantise_values(a, FRAME_DECIMALS)


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
        c = np.asarray(origin_xy, dtype=float) + [
            matmul(hit.point, t),
            matmul(hit.point, np.cross(n, t)),
        ]
    else:
        c0, p0, t0, b0, _n0 = frame_parts(prev)
        step = hit.point - p0
        c = c0 + np.array([matmul(step, t0), matmul(step, b0)])
        t = transport(t0, n)
    return quantise(np.r_[c, hit.point, t, n])


def local_sample(frame, base_mm, rot) -> np.ndarray:
    """The engine's 6-DOF sample of a brush (base point, rotation 3x3 in the surface's space)
    in the frame's local coordinates: x, y on the chart, z above the tangent plane."""
    c, p, t, b, n = frame_parts(frame)
    F = np.stack([t, b, n], axis=1)
    F = F / np.linalg.norm(F, axis=0)
    rel = matmul(F.T, (np.asarray(base_mm, dtype=float) - p))
    d, q, r = angles_from_matrix(matmul(F.T, np.asarray(rot, dtype=float)))
    return np.array([c[0] + rel[0], c[1] + rel[1], rel[2], d, q, r])


def pose_from_sample(frame, sample) -> tuple[np.ndarray, np.ndarray]:
    """(base point, rotation) in the surface's space of a local sample (local_sample's
    inverse)."""
    c, p, t, b, n = frame_parts(frame)
    F = np.stack([t, b, n], axis=1)
    F = F / np.linalg.norm(F, axis=0)
    s = np.asarray(sample, dtype=float)
    base = p + matmul(F, np.array([s[0] - c[0], s[1] - c[1], s[2]]))
    return base, matmul(F, rotation_matrix(*s[3:6]))


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
    return float(c[0] + matmul(d, t)), float(c[1] + matmul(d, b))


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
