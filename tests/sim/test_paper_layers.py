# SPDX-License-Identifier: GPL-3.0-or-later
"""A second layer (a model change to Eq. 26, ``sim.paper.paper.LAYER_S``): ink laid over ink
that has set adds its pigment (a crossing shows darker); over wet ink, or within the pass that
laid it, the darker of the two stays."""

import numpy as np

from sim.brush.mark import Mark
from sim.core.params import QualityParams
from sim.paper.paper import LAYER_S, Paper
from tests.sim.builders import band

DT = 1.0 / 60.0
Q = QualityParams(ab=0.5, ren=0.0, dry=0.0)
DRY = 0.05  # wetness lost a step: a band's pixels dry in ten steps or so


def _band(row0: int, row1: int, col0: int, col1: int, wet=0.9, dark=0.45) -> Mark:
    return band(row0, row1, col0, col1, wet, dark)


def _sheet(dry: float = DRY) -> Paper:
    return Paper(100, 100, 8.0, capacity=1.0, dry_per_step=dry)


def _cross(paper: Paper, second_at: int) -> None:
    """A pale horizontal band at step 1, the brush off, a vertical one across it later."""
    paper.deposit([_band(40, 52, 10, 90)], Q, DT, 1)
    paper.deposit([], Q, DT, 2)
    paper.deposit([_band(10, 90, 44, 56)], Q, DT, second_at)


def test_a_stroke_crossing_a_set_one_lays_a_second_layer():
    later = int(np.ceil(LAYER_S / DT)) + 10
    paper = _sheet()
    _cross(paper, later)
    one = paper.ink[46, 20, 0]  # the first band alone
    two = paper.ink[20, 50, 0]  # the second band alone
    both = paper.ink[46, 50, 0]
    assert 0.2 < one < 0.9 and 0.2 < two < 0.9  # pale ink: a second layer shows
    assert both > max(one, two) + 0.1  # darker where they cross
    np.testing.assert_allclose(both, 1.0 - (1.0 - one) * (1.0 - two), atol=0.02)


def test_over_wet_ink_or_soon_after_the_darker_stays():
    wet = _sheet(dry=0.0)  # the first band never dries
    _cross(wet, int(np.ceil(LAYER_S / DT)) + 10)
    assert wet.ink[46, 50, 0] <= max(wet.ink[46, 20, 0], wet.ink[20, 50, 0]) + 1e-6
    soon = _sheet()  # set, but the brush is back at once
    _cross(soon, 3)
    assert soon.ink[46, 50, 0] <= max(soon.ink[46, 20, 0], soon.ink[20, 50, 0]) + 1e-6


def test_the_hair_passing_over_a_pixel_step_after_step_does_not_blacken_it():
    once, many = _sheet(), _sheet()
    once.deposit([_band(40, 52, 10, 90)], Q, DT, 1)
    for k in range(60):  # a second and more under the hair, drying as it goes
        many.deposit([_band(40, 52, 10, 90)], Q, DT, k + 1)
    # (the wick's fringe adds a little from step to step; a layer a step would blacken it)
    assert np.abs(many.ink[42:50, 20:80] - once.ink[42:50, 20:80]).max() < 0.01
