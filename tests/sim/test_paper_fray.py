# SPDX-License-Identifier: GPL-3.0-or-later
"""The outer hair on the sheet's relief (issue 26, ``sim.paper.texture.outer_touch``): where the
sheet dips, the lightly pressing outer hair of a cluster misses it, so a stroke's edge has
small bays and facets; a loaded brush bridges more of them than a dry one; a smooth sheet and
the pressed middle of the cut are untouched. No Blender."""

from dataclasses import replace

import numpy as np

from sim.paper.paper import Paper
from sim.paper.texture import FRAY, outer_touch, sheet_hollow
from tests.sim.builders import band


def _edge_band(paper: Paper, offer: float) -> tuple[np.ndarray, np.ndarray]:
    """A mark 120 px wide whose Eq. 23 f runs from 0.6 (its middle row) to 1 (its top and
    bottom rows), as a pressed cluster's cut; the touch of each of its pixels, as a grid."""
    mk = band(10, 51, 10, 130, 1.0, 0.9)
    f = 0.6 + 0.4 * np.abs(mk.rows - 20) / 20.0
    mk = replace(mk, depth=f)
    full = (mk.rows + mk.iy0) * paper.W + (mk.cols + mk.ix0)
    touch = outer_touch(paper, full, [mk], np.full(full.size, offer, np.float32))
    return touch.reshape(41, 120), f.reshape(41, 120)


def test_a_smooth_sheet_and_the_pressed_middle_are_touched_everywhere():
    smooth = Paper(140, 60, 5.0, grain_seed=2, fibre=0.0)
    touch, _ = _edge_band(smooth, 0.2)
    assert touch.dtype == np.float32 and np.all(touch == 1.0)
    xuan = Paper(140, 60, 5.0, grain_seed=2, fibre=0.62)
    touch, f = _edge_band(xuan, 0.2)
    assert np.all(touch[f <= 1.0 - FRAY * 0.62] == 1.0)  # only the outer margin can miss
    missed = touch < 1.0
    assert missed.any() and np.all((touch >= 0.0) & (touch <= 1.0))


def test_the_outer_hair_misses_the_hollows_more_when_dry_and_nearer_the_edge():
    paper = Paper(140, 60, 5.0, grain_seed=2, fibre=0.62)
    dry, f = _edge_band(paper, 0.05)  # a brush run dry: little liquid offered
    loaded, _ = _edge_band(paper, 2.0)  # just dipped
    assert np.all(dry <= loaded) and (1.0 - dry).sum() > 2.0 * (1.0 - loaded).sum()
    # the outermost rows miss more than those a little inside them, and those more than the
    # rows further in (only the sheet's deepest hollows reach them)
    outer = (1.0 - dry)[f >= 0.97].mean()
    inner = (1.0 - dry)[(f >= 0.85) & (f < 0.9)].mean()
    deeper = (1.0 - dry)[(f >= 0.7) & (f < 0.75)].mean()
    assert outer > inner > deeper > 0.0 and outer > 0.2
    # where it misses follows the sheet's hollows: the rows' misses lie where the sheet dips
    hollow = sheet_hollow(np.arange(10, 51)[:, None], np.arange(10, 130)[None, :], 5.0, 2)
    edge = f >= 0.95
    assert hollow[edge & (dry < 0.5)].mean() > 2.0 * hollow[edge & (dry == 1.0)].mean()


def test_the_touch_is_the_sheets_at_every_step_in_any_order():
    paper = Paper(140, 60, 5.0, grain_seed=2, fibre=0.62)
    whole, _ = _edge_band(paper, 0.3)
    # the same pixels asked for in another order and as a part: the same values
    mk = replace(band(10, 51, 10, 130, 1.0, 0.9))
    mk = replace(mk, depth=0.6 + 0.4 * np.abs(mk.rows - 20) / 20.0)
    full = (mk.rows + mk.iy0) * paper.W + (mk.cols + mk.ix0)
    order = np.random.default_rng(0).permutation(full.size)[:1500]
    part = replace(mk, depth=mk.depth[order])
    again = outer_touch(paper, full[order], [part], np.full(order.size, 0.3, np.float32))
    assert np.array_equal(again, whole.ravel()[order])
    other = Paper(140, 60, 5.0, grain_seed=3, fibre=0.62)  # another sheet, other hollows
    assert not np.array_equal(_edge_band(other, 0.3)[0], whole)


def test_a_dry_stroke_on_xuan_has_bays_at_its_edge_and_a_solid_middle(monkeypatch):
    """A band laid on sized xuan: its outermost rows (f near 1) lose some pixels to the
    sheet's hollows, the middle none; with the outer hair's misses turned off the same band
    is solid."""
    import sim.paper.texture as texture

    def lay(fray: float) -> np.ndarray:
        monkeypatch.setattr(texture, "FRAY", fray)
        paper = Paper(140, 60, 5.0, grain_seed=2, fibre=0.62)
        paper.wick_passes = 0  # the hair's touch alone
        mk = band(10, 51, 10, 130, 0.3, 0.9)
        mk = replace(mk, depth=0.6 + 0.4 * np.abs(mk.rows - 20) / 20.0)
        q = type("Q", (), {"ab": 0.5})()
        paper.deposit([mk], q, 1 / 120, 1)
        return paper.ink[10:51, 10:130, 0]

    smooth, xuan = lay(0.0), lay(FRAY)
    assert smooth.min() > 0.5
    assert xuan[18:23].min() == smooth[18:23].min()  # the pressed middle: as laid
    edge_rows = np.r_[0:2, 39:41]
    bays = xuan[edge_rows] < 0.5 * smooth[edge_rows]
    assert 0.02 < bays.mean() < 0.8  # some of the edge, not all of it
