# SPDX-License-Identifier: GPL-3.0-or-later
"""Synthetic 6-DOF trajectories: a calligrapher's stroke as touch-down, press, travel, lift.
Used by the demo, the tests and the benchmark."""

from __future__ import annotations

import numpy as np

from ..core.params import HOVER_MM


def stroke(
    points,
    rate_hz: float = 120.0,
    speed_mm_s: float = 60.0,
    press_mm=8.0,
    hair_length_mm: float = 30.0,
    hover_mm: float = HOVER_MM,
    tilt=(0.0, 0.0, 0.0),
    lift_fraction: float = 0.25,
    entry_samples: int = 10,
    end_samples: int = 10,
):
    """Samples (N, 6) along a polyline ``points`` (K, 2) in mm.

    press_mm: how deep the brush base goes below touching height (a number, or a callable of the
    fraction along the stroke). The brush comes down from hover_mm above touching, presses, travels
    at speed_mm_s, and over the last lift_fraction of the path rises again so that the stroke ends
    on the tip."""
    pts = np.asarray(points, dtype=float)
    seg = np.linalg.norm(np.diff(pts, axis=0), axis=1)
    total = float(seg.sum())
    n = max(int(np.ceil(total / speed_mm_s * rate_hz)), 2)
    cum = np.concatenate([[0.0], np.cumsum(seg)])
    s = np.linspace(0.0, total, n)
    x = np.interp(s, cum, pts[:, 0])
    y = np.interp(s, cum, pts[:, 1])
    frac = s / max(total, 1e-9)
    press = press_mm(frac) if callable(press_mm) else np.full(n, float(press_mm))
    lift = np.clip((frac - (1 - lift_fraction)) / max(lift_fraction, 1e-9), 0, 1)
    z = hair_length_mm - press * (1 - lift) + lift * 1.0
    top = hair_length_mm + hover_mm
    out = []
    for k in range(entry_samples):  # come down onto the paper
        f = (k + 1) / entry_samples
        out.append([x[0], y[0], top + (z[0] - top) * f])
    out += [[x[k], y[k], z[k]] for k in range(n)]
    for k in range(end_samples):  # rise off the paper
        f = (k + 1) / end_samples
        out.append([x[-1], y[-1], z[-1] + (top - z[-1]) * f])
    out = np.asarray(out)
    ang = np.tile(np.asarray(tilt, dtype=float), (len(out), 1))
    return np.concatenate([out, ang], axis=1)


def travel(a, b, n: int, z: float):
    t = np.linspace(0, 1, n)[:, None]
    xy = np.asarray(a, float) * (1 - t) + np.asarray(b, float) * t
    return np.concatenate([xy, np.full((n, 1), z), np.zeros((n, 3))], axis=1)
