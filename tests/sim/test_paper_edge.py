# SPDX-License-Identifier: GPL-3.0-or-later
"""The hair's edge on an unevenly sized sheet (a model addition, ``sim.paper.edge``): where a
mark's hair only grazes the paper, the sheet takes its ink or holds it off by its own pattern,
so a stroke's edge is finely ragged, never ruled, and no speck stands free of it."""

import numpy as np
import pytest
from scipy import ndimage as ndi

from sim.paper import laying
from sim.paper.edge import EDGE_TILE, bitten, sizing, sizing_at
from tests.sim.builders import long_stroke, simulation


def test_the_sizing_is_the_sheets_own_the_same_from_its_tiles_and_smooth_at_a_pixel():
    rng = np.random.default_rng(1)
    rows = rng.integers(0, 5 * EDGE_TILE, 4000)
    cols = rng.integers(0, 5 * EDGE_TILE, 4000)
    direct = sizing(rows, cols, 4.0, 7)
    np.testing.assert_array_equal(sizing_at(rows, cols, 4.0, 7), direct)  # bit for bit
    assert direct.min() >= 0.0 and direct.max() <= 1.0 and direct.std() > 0.1
    assert not np.array_equal(sizing(rows, cols, 4.0, 8), direct)  # another sheet
    grid = sizing(*np.mgrid[0:200, 0:200], 4.0, 7)
    step = np.abs(np.diff(grid, axis=1)).mean()
    assert step < 0.7 * grid.std()  # a pattern, not a stipple (pixel to pixel: 1.13 sd)


def _disc(radius=20.0):
    """A round mark's pixels (rows, cols about the centre) and Eq. 23's f (0 in the middle)."""
    r, c = np.mgrid[-30:31, -30:31]
    inside = np.hypot(r, c) <= radius
    return r[inside] + 100, c[inside] + 100, np.hypot(r, c)[inside] / radius


def test_the_sheet_bites_only_a_marks_outer_band_and_keeps_its_middle():
    rows, cols, f = _disc()
    sizes = np.array([f.size])
    assert bitten(sizes, f, rows, cols, 4.0, 3, 0.0) is None  # no fibre: the mark as it is
    keep, band, share = bitten(sizes, f, rows, cols, 4.0, 3, 0.3)
    lost = np.setdiff1d(np.arange(f.size), keep)
    assert lost.size > 0 and f[lost].min() > 0.7  # only from the outer 0.3 of the radius
    assert np.argmin(f) in keep
    assert f[band].min() > 0.7 and share.max() < 1.0  # the edge's pixels: a share of colour
    assert ((share > 0.0) & (share < 1.0)).sum() > 10  # a smooth edge, not a staircase
    # two marks in a row: each one bitten against its own middle and edge
    keep2, _, _ = bitten(
        np.array([f.size, f.size]),
        np.r_[f, f],
        np.r_[rows, rows + 80],
        np.r_[cols, cols],
        4.0,
        3,
        0.3,
    )
    assert np.array_equal(keep2[: keep.size], keep)


def _stroke_ink(monkeypatch, bite: float | None):
    """A straight pressed stroke across the sheet; its ink (rows x columns, top row first)."""
    if bite is not None:
        monkeypatch.setattr(laying, "EDGE_BITE", bite)
    sim = simulation(long_stroke()[:150], 800, 4.0)
    sim.run()
    return 1.0 - sim.image()[::-1].min(axis=2)


def _top_edge_wobble(ink) -> tuple[float, int]:
    """How far the stroke's top edge strays from its smoothed course (px, sd) along its
    middle, and the ink's pieces."""
    mask = ink > 0.5
    cols = np.arange(300, 520)  # 75-130 mm: the stroke's steady middle
    top = np.array([np.flatnonzero(mask[:, c]).min() for c in cols], dtype=float)
    smooth = ndi.uniform_filter1d(top, 21, mode="nearest")
    return float(np.std(top - smooth)), ndi.label(mask)[1]


@pytest.mark.slow
def test_a_strokes_edge_on_sized_xuan_is_ragged_and_no_speck_stands_free(monkeypatch):
    ragged, pieces = _top_edge_wobble(_stroke_ink(monkeypatch, None))
    ruled, pieces_ruled = _top_edge_wobble(_stroke_ink(monkeypatch, 0.0))
    assert ragged > 1.2 * ruled  # the edge strays further from its course: the sheet bit it
    assert pieces == pieces_ruled == 1
