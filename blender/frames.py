# SPDX-License-Identifier: GPL-3.0-or-later
"""The scene's timeline and a recording's samples: which samples a frame shows."""

from __future__ import annotations

from ..sim.core import placement
from ..sim.core.recording import Recording


def timeline(rec: Recording, scene) -> tuple[float, float]:
    """(frame_start, frames per sample) of a recording in this scene's timeline."""
    b = rec.extra.get("blender", {}) if isinstance(rec.extra, dict) else {}
    fps = scene.render.fps / scene.render.fps_base
    start = float(b.get("frame_start", scene.frame_start))
    return start, fps / rec.sample_rate_hz


def samples_at_frame(rec: Recording, scene, frame: float) -> int:
    """How many samples have been written by the end of ``frame``."""
    return placement.samples_at_frame(len(rec.samples), *timeline(rec, scene), frame)


def first_sample_from_frame(rec: Recording, scene, frame: float) -> int:
    """Index of the first sample at or after ``frame``."""
    return placement.first_sample_from_frame(len(rec.samples), *timeline(rec, scene), frame)
