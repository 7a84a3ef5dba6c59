# SPDX-License-Identifier: GPL-3.0-or-later
"""The recording as pen strokes (issue 29.4: Grease Pencil, for artists who edit strokes
there): one stroke for each run of samples in which the brush touches the paper, a point per
sample where the brush's axis meets the paper, its pressure from the press depth.

A sample's brush hangs along R (0, 0, -1) from its base (R = Rx(q) Ry(d) Rz(r), Sec. 4); the
axis meets the paper (z = 0) s = z / -(R_zz) from the base, and the brush presses L - s into it
(L: the hair length) - the press depth the writer and the painter set. A point's pressure is its
press over the recording's deepest (1 at the deepest point, so the strokes keep the writing's
full range), its radius that pressure times half the brush's belly diameter (roughly the band a
full press leaves). On a surface paper the points go from the chart onto each sample's tangent
plane (its frame), in the surface's space. This is a drawing aid, not the ink: the simulated
paper is the artwork."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..core.frames import rotation_matrix
from ..core.recording import Recording
from ..surface.chart import frame_parts

MIN_POINTS = 2  # a touch shorter than this makes no stroke


@dataclass(frozen=True)
class PenStroke:
    points: np.ndarray  # (N, 3) mm: the paper's (x, y, 0), or on a surface its space's points
    pressure: np.ndarray  # (N,) in (0, 1]
    radius_mm: np.ndarray  # (N,)
    samples: np.ndarray  # (N,) the recording's sample index of each point (its time)


def contact(samples, hair_mm: float) -> tuple[np.ndarray, np.ndarray]:
    """((N, 2) where each sample's axis meets the paper, (N,) its press depth in mm; <= 0 where
    it does not touch)."""
    s = np.asarray(samples, dtype=float)
    xy = s[:, :2].copy()
    press = np.full(len(s), -1.0)
    for i, row in enumerate(s):
        axis = -rotation_matrix(*row[3:6])[:, 2]  # R (0, 0, -1), no sum to round
        if axis[2] >= -1e-6:  # the brush lies flat or points up: no contact along its axis
            continue
        reach = row[2] / -axis[2]
        xy[i] = row[:2] + reach * axis[:2]
        press[i] = hair_mm - reach
    return xy, press


def pen_strokes(rec: Recording, frames=None) -> list[PenStroke]:
    """The recording's touches as pen strokes; ``frames`` (N, 11): a surface recording's
    frames (sim.surface), which put the points in the surface's space."""
    _q, geom, _paper, _ink = rec.resolve()
    xy, press = contact(rec.samples, geom.hair_length_mm)
    touching = press > 0
    deepest = float(press.max()) if touching.any() else 1.0
    if frames is not None:
        pts = np.array([_on_surface(f, p) for f, p in zip(frames, xy, strict=True)])
    else:
        pts = np.c_[xy, np.zeros(len(xy))]
    out = []
    edges = np.flatnonzero(np.diff(np.r_[0, touching.astype(np.int8), 0]))
    for a, b in zip(edges[::2], edges[1::2], strict=True):
        if b - a < MIN_POINTS:
            continue
        pressure = np.clip(press[a:b] / deepest, 1e-3, 1.0)
        out.append(
            PenStroke(
                points=pts[a:b],
                pressure=pressure,
                radius_mm=pressure * geom.belly_diameter_mm / 2,
                samples=np.arange(a, b),
            )
        )
    return out


def _on_surface(frame, xy) -> np.ndarray:
    """A chart point on the frame's tangent plane, in the surface's space (mm)."""
    c, p, t, b, _n = frame_parts(frame)
    return p + (xy[0] - c[0]) * t + (xy[1] - c[1]) * b
