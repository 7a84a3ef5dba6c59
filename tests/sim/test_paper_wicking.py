# SPDX-License-Identifier: GPL-3.0-or-later
"""Capillary wicking (a model addition, ``sim.paper.wick._wick``): the sheet draws liquid and
pigment a little way out of a stroke's edge along its fibres."""

import numpy as np
import pytest

from sim.core.params import load_preset, paper_from_preset
from sim.paper.paper import TILE, Paper
from sim.paper.texture import DRAW_MIN, sheet_draw
from sim.paper.wick import WICK_MAX_PASSES, WICK_RATE, _wick, wick_steps

SIZED_FIBRE = paper_from_preset(load_preset("paper", "sized_xuan")).fibre  # the default paper's


def _edge(draw, passes=3):
    """A wet, inked block (columns < 20) beside dry paper, wicked ``passes`` times."""
    w = np.zeros((40, 40), np.float32)
    ink = np.zeros((40, 40, 3), np.float32)
    w[:, :20] = 0.6
    ink[:, :20] = 0.95
    w0 = w.copy()
    _wick(w, ink, draw, passes)
    return w0, w, ink


def test_wicking_keeps_the_water_and_pulls_a_lighter_fringe_a_few_pixels_out():
    draw = sheet_draw(slice(0, 40), slice(0, 40), 10.0, 3, TILE, SIZED_FIBRE)
    w0, w, ink = _edge(draw, 3)
    assert abs(w.sum(dtype=np.float64) - w0.sum(dtype=np.float64)) < 1e-3  # the water kept
    assert w[:, 20:].sum() > 0.01
    fringe = ink[:, 20, 0]
    assert fringe.max() > 0.05  # the sheet drew ink out of the edge
    assert fringe.mean() < 0.95 * ink[:, 19, 0].mean()  # lighter than the stroke
    assert not ink[:, 24:, 0].any()  # no further than a pixel a pass
    assert ink[:, 21, 0].mean() < fringe.mean()  # fading outward


def test_wicking_follows_the_sheet_uneven_along_a_straight_edge():
    draw = sheet_draw(slice(0, 40), slice(0, 40), 10.0, 3, TILE, SIZED_FIBRE)
    assert draw.min() >= DRAW_MIN and draw.max() <= 1.0 and draw.std() > 0.05
    _, _, ink = _edge(draw, 3)
    assert ink[:, 20, 0].std() > 0.01  # a fibrous front, not a ruled line
    _, _, even = _edge(np.full((40, 40), 0.5, np.float32), 3)
    assert even[:, 20, 0].std() < 1e-6
    _, w, none = _edge(np.zeros((40, 40), np.float32), 3)
    assert not none[:, 20:].any() and not w[:, 20:].any()  # a sheet that draws nothing


def test_the_reach_in_mm_is_the_same_at_any_resolution():
    assert wick_steps(1000.0, 20.0) == (0, 0.0)  # smooth paper: none
    cap = WICK_MAX_PASSES * WICK_RATE
    checked = 0
    for capacity in (1.0, 0.55):
        for ppm in (1.0, 2.0, 2.7):  # reach in px, squared: (rate x passes) / ppm^2 the same
            n, rate = wick_steps(capacity, ppm)
            n2, rate2 = wick_steps(capacity, 2 * ppm)
            assert 1 <= n <= WICK_MAX_PASSES and 0 < rate <= WICK_RATE
            if n2 * rate2 < cap:  # below the most a step does
                assert n2 * rate2 == pytest.approx(4 * n * rate)
                checked += 1
    assert checked >= 3
    raw, sized = wick_steps(0.55, 2.0), wick_steps(1.0, 2.0)
    assert raw[0] * raw[1] > sized[0] * sized[1]  # a paper that holds less passes more on
    assert wick_steps(0.01, 50.0) == (WICK_MAX_PASSES, WICK_RATE)
    paper = Paper(32, 32, 10.0, capacity=0.55)
    assert (paper.wick_passes, paper.wick_rate) == wick_steps(0.55, 10.0)


def test_draw_is_the_same_in_any_window():
    a = sheet_draw(slice(0, 128), slice(0, 128), 8.0, 5, TILE, SIZED_FIBRE)
    b = sheet_draw(slice(40, 90), slice(70, 120), 8.0, 5, TILE, SIZED_FIBRE)
    np.testing.assert_array_equal(a[40:90, 70:120], b)
    assert not np.array_equal(
        a, sheet_draw(slice(0, 128), slice(0, 128), 8.0, 6, TILE, SIZED_FIBRE)
    )
    even = sheet_draw(slice(0, 64), slice(0, 64), 8.0, 5, TILE, fibre=0.0)  # no fibre: evenly
    assert np.all(even == even[0, 0])
    weak = sheet_draw(slice(0, 128), slice(0, 128), 8.0, 5, TILE, fibre=0.2)
    assert 0.0 < weak.std() < a.std()


def test_liquid_drawn_through_a_wet_grey_pool_leaves_its_grey_as_it_was():
    """Issue 26: ink drawn into ink still wet with the same ink merges with it. A pool of grey
    ink whose wetness runs down across it (the liquid moves one way, pass after pass, as at a
    mark's or a window's edge inside a stroke) keeps its grey: no pixel darkens (laid over it
    as a layer, the takers went darker pass after pass, thin dark lines inside the stroke)."""
    draw = sheet_draw(slice(0, 40), slice(0, 40), 10.0, 3, TILE, SIZED_FIBRE)
    w = np.tile(np.linspace(0.9, 0.3, 40, dtype=np.float32), (40, 1))
    ink = np.full((40, 40, 3), 0.5, np.float32)
    for _ in range(50):  # fifty steps of a paused brush
        _wick(w, ink, draw, 1)
    assert np.abs(ink - 0.5).max() < 1e-6


def test_a_fringe_the_liquid_keeps_coming_to_darkens_toward_the_stroke_not_past_it():
    draw = np.full((40, 40), 1.0, np.float32)
    w = np.zeros((40, 40), np.float32)
    ink = np.zeros((40, 40, 3), np.float32)
    fringe = []
    for _ in range(60):  # the stroke's edge kept wet (a paused brush), its grey ink 0.5
        w[:, :20], ink[:, :20] = 0.6, 0.5
        _wick(w, ink, draw, 1)
        fringe.append(float(ink[:, 20, 0].mean()))
    assert fringe[0] > 0.05 and fringe[-1] > fringe[0]  # darker as the liquid keeps coming
    assert fringe[-1] <= 0.5 + 1e-6  # never darker than the ink it came from
