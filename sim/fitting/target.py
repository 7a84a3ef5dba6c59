# SPDX-License-Identifier: GPL-3.0-or-later
"""The target function, Eq. 28: the mean per-pixel |dr| + |dg| + |db| between each training
sample's image and the brush's result, plus in the Qp2 stage a texture term against real
writing's statistics. The samples of a worker process are set once (``_init_worker``)."""

from __future__ import annotations

import numpy as np

from ..core.recording import Recording, from_dict
from ..engine.simulation import Simulation
from .samples import TrainingSample

_SAMPLES: list[TrainingSample] = []


def _init_worker(samples):
    global _SAMPLES
    _SAMPLES = samples


def _for_stage(samples, stage: str | None):
    """The samples of a stage's class (all of them when that class is empty)."""
    if stage is None:
        return samples
    want = "shape" if stage == "qp1" else "texture"
    own = [s for s in samples if s.kind in (want, "both")]
    return own or samples


def render(rec: Recording, quality: dict) -> np.ndarray:
    """The brush's result C^i for a recording with the given quality values."""
    d = rec.to_dict()
    d["quality"] = {**d.get("quality", {}), **quality}
    return Simulation(from_dict(d)).run().image()


TEXTURE_WEIGHT = 0.05  # the texture term's weight against Eq. 28 (per pixel) in the Qp2 stage


def target_function(quality: dict, samples=None, stage: str | None = None) -> float:
    """Eq. 28 divided by the number of pixels: mean per-pixel |dr| + |dg| + |db|. In the Qp2
    stage (texture samples) a texture term is added: TEXTURE_WEIGHT times (1 - the texture
    score, sim.fitting.texture.score) of each result against REAL_WRITING, the five statistics of
    real brush writing. Sec. 7.2 fits Qp2 to scanned texture samples with Eq. 28; no licensed
    scans can ship with the project, so comparing the statistics measured on such scans is the
    honest form of that class of training (an image target S^i still adds its Eq. 28)."""
    from .texture import score, texture_stats

    samples = _for_stage(_SAMPLES if samples is None else samples, stage)
    total, pixels, tex = 0.0, 0, []
    for s in samples:
        c = render(s.recording, quality)
        total += float(np.abs(s.target - c).sum(dtype=np.float64))
        pixels += s.target.shape[0] * s.target.shape[1]
        if stage == "qp2":
            try:
                tex.append(1.0 - score(texture_stats(c)))
            except ValueError:  # no ink at all: as far from real writing as it gets
                tex.append(1.0)
    eq28 = total / max(pixels, 1)
    return eq28 + TEXTURE_WEIGHT * float(np.mean(tex)) if tex else eq28
