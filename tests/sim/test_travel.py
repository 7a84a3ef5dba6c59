# SPDX-License-Identifier: GPL-3.0-or-later
"""The brush's direction of travel (``HairyBrush.travel``, issue 26 point 1): it turns only with
motion longer than a hair's width (``bristles.HAIR_MM``). A fast creep back of a hundredth of a
millimetre while the base rests on the toe flipped it backwards (main), and the dry hair lines
of the toe were laid across the flick's. No Blender."""

import numpy as np
import pytest

from sim.brush import dynamics
from sim.brush.bristles import HAIR_MM
from sim.brush.primitive import HairyBrush  # noqa: I001 (after the engine: the package's order)
from sim.brush.state import take_primitives
from sim.core.params import BrushGeometry, QualityParams

DT = 1.0 / 200.0


def _moved(b: HairyBrush, path, z: float):
    """``move`` the base through ``path`` (x, y in mm), one step of DT each."""
    for (x0, y0), (x1, y1) in zip(path[:-1], path[1:], strict=True):
        vel = np.array([(x1 - x0) / DT, (y1 - y0) / DT, 0.0, 0.0, 0.0, 0.0])
        dynamics.move(b, np.array([x1, y1, z, 0.0, 0.0, 0.0]), vel, DT)


def _brush(m: int) -> tuple[HairyBrush, float]:
    b = HairyBrush(BrushGeometry(), QualityParams(), np.random.default_rng(2))
    z = 0.8 * b.L  # the toe pressed on the paper
    b.B = np.array([0.0, 0.0, z])
    b.cc = b._rest_world(b.sarc, b.B, b.R)
    take_primitives(b, np.zeros(m, dtype=int))
    return b, z


@pytest.mark.parametrize("m", [1, 3])  # one primitive on floats, several on arrays
def test_a_creep_back_shorter_than_a_hair_keeps_the_travel(m):
    b, z = _brush(m)
    right = [(0.1 * k, 0.0) for k in range(30)]
    _moved(b, right, z)
    assert b.travel.tolist() == [1.0, 0.0]
    x = right[-1][0]
    _moved(b, [(x, 0.0), (x - 0.01, 0.0)], z)  # 2 mm/s: fast enough to count as motion
    assert b.travel.tolist() == [1.0, 0.0]


@pytest.mark.parametrize("m", [1, 3])
def test_motion_longer_than_hairs_turns_the_travel(m):
    b, z = _brush(m)
    _moved(b, [(0.1 * k, 0.0) for k in range(30)], z)
    _moved(b, [(2.9, -0.1 * k) for k in range(2)], z)  # a right angle turns it at once
    assert b.travel.tolist() == [0.0, -1.0]
    back = [(2.9 - 0.1 * k, -0.1) for k in range(int(3 * HAIR_MM / 0.1) + 2)]
    _moved(b, back, z)  # back the other way, past the leash: travel follows
    assert b.travel.tolist() == [-1.0, 0.0]
