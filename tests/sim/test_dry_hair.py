# SPDX-License-Identifier: GPL-3.0-or-later
"""A brush late on its load (a model change to Eq. 23 and 27, ``sim.brush.bristles``: O_DARK):
its marks break into dark lines of hair along the motion with white between (飞白), not a flat
pale sheet; a loaded brush covers its mark whole."""

from dataclasses import replace

import numpy as np

from sim.brush import bristles
from sim.brush.state import BUNDLES
from sim.core.params import QualityParams
from sim.paper.paper import Paper
from tests.sim.builders import band

DT = 1.0 / 60.0
Q = QualityParams(ab=0.5, ren=0.0, dry=0.0)
PPM = 8.0
ROWS = (38, 62)  # the stroke's rows: it runs along the columns, at row 50


def _stroke(wet: float) -> np.ndarray:
    """A stroke along the paper's columns, a mark a step offered ``wet`` liquid of ink 1, laid by
    the hair bundles (all loaded alike, no gaps) as the brush moves on; the paper's density."""
    paper = Paper(100, 100, PPM, capacity=1.0, dry_per_step=0.0)
    edge = np.linspace(-1.0, 1.0, BUNDLES + 1)[1:-1][None]
    for k in range(30):
        x = (30 + 2 * k) / PPM  # mm: the front of the mark
        trail = np.stack([np.arange(x - 11.75, x + 0.01, 0.25), np.full(48, 50.0 / PPM)], axis=1)
        st = bristles.BristleState(
            np.ones((1, BUNDLES)), np.zeros((1, BUNDLES)), edge, np.array([1.5]),
            trail[-48:], np.array([1.0, 0.0]), 100.0,
        )  # fmt: skip
        mk = band(*ROWS, 10 + 2 * k, 30 + 2 * k, wet, 1.0)
        # Eq. 23's f: 0 on the section's axis (the stroke's middle row), 1 at its outside
        mk = replace(mk, depth=np.abs(mk.rows + ROWS[0] + 0.5 - 50.0) / 12.0)
        marks = bristles.lay(bristles.across([mk], st, PPM), st, PPM)
        paper.deposit(marks, Q, DT, k + 1)
    return paper.ink[ROWS[0] + 2 : ROWS[1] - 2, 30:60, 0]  # the stroke's middle, past its start


def test_a_brush_late_on_its_load_lays_dark_lines_along_the_stroke_not_a_pale_sheet():
    d = _stroke(0.15)
    inked = d > 0.05
    assert np.median(d[inked]) > 0.7  # dark where it lays ink (it was about 0.47, flat)
    assert 0.2 < 1.0 - inked.mean() < 0.9  # white between the lines of hair
    # the white runs along the motion: a row (one place across the stroke) is bare or inked
    share = inked.mean(axis=1)
    assert np.minimum(share, 1.0 - share).mean() < 0.1


def test_a_loaded_brush_covers_its_mark_whole():
    d = _stroke(0.9)
    assert (d > 0.8).all()
