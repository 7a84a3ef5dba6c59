# SPDX-License-Identifier: GPL-3.0-or-later
"""Fixtures of the engine's tests (no Blender)."""

import numpy as np
import pytest

from sim.brush.primitive import HairyBrush
from sim.core.params import BrushGeometry, QualityParams
from sim.writing.hanzi import find_char
from sim.writing.response import calibrate
from sim.writing.writer import coverage_mask, write_character
from tests.sim.builders import stiff_template


@pytest.fixture
def brush():
    b = HairyBrush(BrushGeometry(), QualityParams(), np.random.Generator(np.random.PCG64(0)))
    b.place([50.0, 50.0, 40.0, 0.0, 0.0, 0.0])
    return b


@pytest.fixture(scope="session")
def response():
    """The calibrated response of ``stiff_template``'s brush (a module that writes with
    another brush defines its own ``response``)."""
    return calibrate(stiff_template())


@pytest.fixture(scope="session")
def stiff_ink(response):
    """``stiff_ink(char, n=256)``: the ink (coverage, top row first) of a character written
    with ``stiff_template`` at n px with one pass, written once a session."""
    made = {}

    def ink(char: str, n: int = 256) -> np.ndarray:
        if (char, n) not in made:
            ch = find_char(char)
            _, _, sim = write_character(ch, n, stiff_template(), response=response, passes=1)
            made[char, n] = coverage_mask(sim)
        return made[char, n]

    return ink
