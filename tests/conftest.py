# SPDX-License-Identifier: GPL-3.0-or-later
import sys
from pathlib import Path

import numpy as np
import pytest

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))

from sim.brush import HairyBrush  # noqa: E402
from sim.params import BrushGeometry, QualityParams  # noqa: E402


@pytest.fixture
def brush():
    b = HairyBrush(BrushGeometry(), QualityParams(), np.random.Generator(np.random.PCG64(0)))
    b.place([50.0, 50.0, 40.0, 0.0, 0.0, 0.0])
    return b
