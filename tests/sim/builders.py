# SPDX-License-Identifier: GPL-3.0-or-later
"""Builders of the engine states the tests look at, through the engine's public API only (but
``filled_stroke``: the planner's own ``_fill`` of one stroke, which the tests of heads and dots
look at sample by sample)."""

from __future__ import annotations

import numpy as np

from sim.brush.mark import Mark
from sim.cli.bench import long_stroke, workload
from sim.core.recording import Recording, from_dict
from sim.engine.simulation import Simulation
from sim.writing.hanzi import character_recording
from tests.paths import ROOT  # noqa: E402

__all__ = [
    "band",
    "character",
    "filled_stroke",
    "long_stroke",
    "simulation",
    "stepped",
    "stiff_template",
]


def simulation(samples, size_px: int, ppm: float, primitives: int = 1) -> Simulation:
    """The benchmark's workload: a wolf brush dipped once on sized xuan, split into
    ``primitives`` writing primitives before the first sample."""
    return workload(samples, size_px, ppm, primitives)


def character(ppm: float, char: str = "永") -> Recording:
    """The demo recording of a written character (its stroke data in data/hanzi), at ppm."""
    d = character_recording(ROOT / "data" / "hanzi" / f"{char}.json").to_dict()
    d["paper"]["px_per_mm"] = ppm
    return from_dict(d)


def stepped(sim: Simulation, every: int):
    """Step ``sim`` to its end, yielding it after every ``every``-th sample."""
    while not sim.done:
        sim.step()
        if sim.index % every == 0:
            yield sim


def band(row0: int, row1: int, col0: int, col1: int, wet: float, dark: float) -> Mark:
    """A mark filling rows row0:row1, columns col0:col1 of the paper, each pixel offered
    ``wet`` liquid of ink density ``dark`` (the paper's tests lay strokes with it)."""
    rr, cc = np.mgrid[0 : row1 - row0, 0 : col1 - col0]
    n = rr.size
    return Mark(
        primitive=0,
        iy0=row0,
        ix0=col0,
        rows=rr.ravel(),
        cols=cc.ravel(),
        wet=np.full(n, wet),
        col=np.full((n, 3), dark),
        lateral=np.zeros(n),
        depth=np.zeros(n),
        shape=(row1 - row0, col1 - col0),
        segments=np.zeros((0, 2, 2)),
        area_bbox=1.0,
        height=1.0,
    )


def stiff_template(**kw) -> Recording:
    """A recording of the stiff wolf brush on smooth paper, no samples (the writer's and the
    gestures' tests: the brush's own shape, no bleeding)."""
    return Recording(np.zeros((1, 6)), brush={"preset": "wolf_stiff"}, paper_preset="smooth", **kw)


def filled_stroke(pl, response, stroke: int, run_up=None, side=np.zeros):
    """The samples of plan ``pl`` with ``stroke`` filled in by the planner (``_fill``, the
    stiff brush's hair, presses from ``response``, the entries' ``run_up``, the planner's
    ``RUN_UP`` if None, the sideways placement ``side(n)`` of its n body samples) and that
    stroke's body samples."""
    from sim.core.params import HOVER_MM
    from sim.writing.planner import RUN_UP, WRITING, _fill

    hair = stiff_template().resolve()[1].hair_length_mm
    a, b = pl.strokes[stroke]
    body = np.flatnonzero(pl.phase[a:b] == WRITING) + a
    samples = np.zeros((len(pl.target), 6))
    samples[:, :2], samples[:, 2] = pl.target, hair + HOVER_MM
    press = response.press_for(pl.width[body])
    brush = (hair + HOVER_MM, hair, 0.5, 1.0)
    run_up = RUN_UP if run_up is None else run_up
    _fill(samples, pl, response, (a, b), press, side(len(body)), brush, run_up=run_up)
    return samples, body
