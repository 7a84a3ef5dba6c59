# SPDX-License-Identifier: GPL-3.0-or-later
"""The example files show calligraphy (issue 29.10): examples/strokes.json renders the
character its note names, whole, as the font draws it."""

from __future__ import annotations

import pytest

from sim.core.recording import load
from sim.engine.simulation import Simulation
from sim.writing.hanzi import find_char
from sim.writing.outline import iou, rasterise
from sim.writing.writer import coverage_mask
from tests.paths import ROOT


@pytest.mark.slow
def test_the_example_recording_renders_the_character_it_names():
    rec = load(ROOT / "examples" / "strokes.json")
    assert rec.width_px == rec.height_px  # the em box, as sim write makes it
    assert "永" in rec.extra["note"]
    ink = coverage_mask(Simulation(rec).run())
    font = rasterise(find_char("永"), rec.width_px)
    assert ink.mean() > 0.1  # a character, not a few thin lines
    assert iou(ink, font) > 0.8
