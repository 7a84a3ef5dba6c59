# SPDX-License-Identifier: GPL-3.0-or-later
"""Builders of the engine states the tests look at, through the engine's public API only."""

from __future__ import annotations

from sim.cli.bench import long_stroke, workload
from sim.core.recording import Recording, from_dict
from sim.engine.simulation import Simulation
from sim.writing.hanzi import character_recording
from tests.paths import ROOT  # noqa: E402

__all__ = ["character", "long_stroke", "simulation", "stepped"]


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
