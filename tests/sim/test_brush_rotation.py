# SPDX-License-Identifier: GPL-3.0-or-later
"""Issue 28: a brush held at one tilt turns by one rotation matrix, built once, step after step
(``dynamics._rotation``), and that matrix is the one ``rotation_matrix`` builds, bit for bit,
a negative zero angle included."""

import numpy as np
import pytest

from sim.core.frames import rotation_matrix
from tests.sim.builders import long_stroke, simulation


def test_a_held_tilt_builds_its_rotation_once():
    sim = simulation(long_stroke()[:40], 256, 1.0)
    sim.run(10)
    held = sim.brush.R
    sim.run(20)
    assert sim.brush.R is held  # main built a new matrix every step
    with pytest.raises(ValueError):
        held[0, 0] = 2.0  # shared between steps: read-only


@pytest.mark.parametrize("angles", [(0.0, 0.0, 0.0), (-0.0, 0.0, -0.0), (12.5, -30.0, 7.0)])
def test_the_kept_rotation_is_rotation_matrix(angles):
    sim = simulation(long_stroke()[:4], 256, 1.0)
    pose = np.r_[100.0, 100.0, 40.0, angles]
    sim.brush.move(pose, np.zeros(6), sim.dt)
    expect = rotation_matrix(*angles)
    assert sim.brush.R.tobytes() == expect.tobytes()
