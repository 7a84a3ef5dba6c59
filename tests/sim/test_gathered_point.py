# SPDX-License-Identifier: GPL-3.0-or-later
"""A gathered hook's or 撇's point leaves as one, not as parallel lines of hair (issue 26, point
2). A model addition of ``sim.brush.bristles`` beyond Eq. 27 (``_hair_lines``): as the contact
narrows below GATHER of the belly the lines of hair converge with it (every hair runs to the
tip) and the gathered hair, held together by its ink, closes its bare lines. Main: the lines
were HAIR_MM wide whatever the contact, a narrow point laid as many bare lines as a wide belly
and broke into them. No Blender."""

from dataclasses import replace

import numpy as np

from sim.brush import bristles
from sim.brush.state import BUNDLES
from tests.sim.builders import band

PPM = 40.0  # px per mm: a point 0.3 mm wide is 12 px across
BELLY = 1.5  # mm: the belly's a / 2


def _across(radius: float, wet: float) -> np.ndarray:
    """Which rows across a contact of half width ``radius`` (mm) a brush offering ``wet``
    leaves bare (a band the contact swept along a straight trail: a row is bare or not)."""
    rows = int(round(2 * radius * PPM))
    edge = np.linspace(-1.0, 1.0, BUNDLES + 1)[1:-1][None]
    centre = 50.0 / PPM + radius  # mm: the trail runs along the band's middle
    trail = np.stack([np.arange(48) * bristles.TRAIL_MM, np.full(48, centre)], axis=1)
    st = bristles.BristleState(
        np.ones((1, BUNDLES)), np.zeros((1, BUNDLES)), edge, np.array([radius]),
        trail, np.array([1.0, 0.0]), 50.0, np.array([BELLY]),
    )  # fmt: skip
    mk = band(50, 50 + rows, 0, 20, wet, 1.0)
    # Eq. 23's f: 0 on the section's axis (the band's middle row), 1 at its outside
    mk = replace(mk, depth=np.abs(mk.rows + 0.5 - 0.5 * rows) / (0.5 * rows))
    (laid,) = bristles.lay(bristles.across([mk], st, PPM), st, PPM)
    return laid.skip.reshape(mk.shape).mean(axis=1)


def test_a_gathered_point_holds_the_lines_of_the_belly_not_one_or_two():
    for wet in (0.05, 0.1):
        wide, point = _across(BELLY, wet), _across(0.1 * BELLY, wet)
        runs = [int(np.count_nonzero(np.diff(a > 0.5))) + 1 for a in (wide, point)]
        # the same hair lies across the point as across the belly, its lines converged: the
        # point (a tenth of the belly) holds more than half the belly's runs of bare and
        # inked lines (main: HAIR_MM wide lines, one or two across the point)
        assert runs[0] >= 4
        assert runs[1] > 0.5 * runs[0]


def test_the_lines_converge_with_the_contact():
    # the same lines of hair lie across a contact however narrow: the lines per mm grow as
    # the contact gathers below GATHER of the belly, and not above it
    lines = [float(bristles._hair_lines(g)[0]) for g in (1.0, bristles.GATHER, 0.1)]
    assert lines[0] == lines[1] == np.float32(1.0 / bristles.HAIR_MM)
    assert lines[2] > 4.0 * lines[1]
