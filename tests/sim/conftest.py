# SPDX-License-Identifier: GPL-3.0-or-later
"""Fixtures of the engine's tests (no Blender)."""

import numpy as np
import pytest

from sim.brush.primitive import HairyBrush
from sim.core.params import BrushGeometry, QualityParams


@pytest.fixture
def brush():
    b = HairyBrush(BrushGeometry(), QualityParams(), np.random.Generator(np.random.PCG64(0)))
    b.place([50.0, 50.0, 40.0, 0.0, 0.0, 0.0])
    return b
