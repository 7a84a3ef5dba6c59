# SPDX-License-Identifier: GPL-3.0-or-later
"""Lines of dry hair only where the hair lies (issue 26, point 2), model additions of
``sim.brush.bristles`` beyond Eq. 27:

- a gathered hook's or 撇's point leaves as one, not as parallel lines of hair (``_closed``):
  as the contact narrows below GATHER of the belly the gathered hair, held together by the
  ink between its hairs, closes its bare lines, however dry;
- no line of hair lies past the bundles' span (``_hairs``'s ``past``): a running-dry pixel
  farther from the path than the span is bare (the grey fringe off a 折's pressed shoulder).

Main: the gathered point's lines were as bare as the belly's, and the outermost bundle's
lines ran on past the hair. No Blender."""

from dataclasses import replace

import numpy as np

from sim.brush import bristles
from sim.brush.state import BUNDLES
from tests.sim.builders import band

PPM = 40.0  # px per mm: a point 0.3 mm wide is 12 px across
BELLY = 1.5  # mm: the belly's a / 2


def _across(radius: float, wet: float, rows: int | None = None) -> np.ndarray:
    """Per row across a band ``rows`` px wide (the contact's width, 2 ``radius`` mm, if None)
    centred on a straight trail, the share of its pixels a brush offering ``wet`` leaves
    bare, the hair spanning ``radius`` mm either side of the trail."""
    rows = int(round(2 * radius * PPM)) if rows is None else rows
    edge = np.linspace(-1.0, 1.0, BUNDLES + 1)[1:-1][None]
    centre = 50.0 / PPM + 0.5 * rows / PPM  # mm: the trail runs along the band's middle
    trail = np.stack([np.arange(48) * bristles.TRAIL_MM, np.full(48, centre)], axis=1)
    st = bristles.BristleState(
        np.ones((1, BUNDLES)), np.zeros((1, BUNDLES)), edge, np.array([radius]),
        trail, np.array([1.0, 0.0]), 50.0, np.array([BELLY]),
    )  # fmt: skip
    mk = band(50, 50 + rows, 0, 20, wet, 1.0)
    # Eq. 23's f: 0 on the section's axis (the band's middle row), 1 at its outside
    mk = replace(mk, depth=np.minimum(np.abs(mk.rows + 0.5 - 0.5 * rows) / (0.5 * rows), 1.0))
    (laid,) = bristles.lay(bristles.across([mk], st, PPM), st, PPM)
    return laid.skip.reshape(mk.shape).mean(axis=1)


def test_a_gathered_point_closes_its_bare_lines_however_dry():
    for wet in (0.05, 0.1):
        wide, point = _across(BELLY, wet).mean(), _across(0.1 * BELLY, wet).mean()
        # a dry belly lays lines with white between; the same hair gathered to a tenth of
        # the belly lies pressed together and leaves (nearly) one point (main: as bare as
        # the belly, its point broke into lines)
        assert wide > 0.2
        assert point < 0.25 * wide


def test_no_line_of_hair_lies_past_its_span():
    radius, rows = 0.5, 80  # the hair spans 40 px across a mark 80 px wide
    inner = slice(22, 58)  # rows well inside the span
    outer = np.r_[0:18, 62:80]  # rows past it
    dry, loaded = _across(radius, 0.1, rows), _across(radius, 0.9, rows)
    # past the span a running-dry brush lays no line (main: the outermost bundle's lines ran
    # on there, a grey fringe); inside it, lines with white between; a loaded brush inks all
    assert dry[outer].min() == 1.0
    assert 0.0 < dry[inner].mean() < 1.0
    assert loaded.max() == 0.0
