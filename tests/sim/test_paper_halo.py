# SPDX-License-Identifier: GPL-3.0-or-later
"""The water halo (a model addition, ``sim.paper.paper.Paper._halo``): as the brush leaves the
paper, the liquid a stroke left creeps on into the sheet with the finest pigment - a faint tint
round the ink, laid once a stroke."""

import numpy as np

from sim.brush.mark import Mark
from sim.core.params import QualityParams
from sim.paper import lift as lift_module
from sim.paper import paper as paper_module
from sim.paper.paper import HALO_MAX_PX, HALO_PIGMENT, Paper, WetStroke, halo_px
from tests.sim.builders import band

DT = 1.0 / 60.0
Q = QualityParams(ab=0.5, ren=0.0, dry=0.0)


def _band(row0: int, row1: int, col0: int, col1: int, wet=0.8, dark=0.9) -> Mark:
    return band(row0, row1, col0, col1, wet, dark)


def _stroke(paper: Paper, steps: int = 6, lift: bool = True) -> None:
    """A band written down the sheet over ``steps`` samples, then (``lift``) the brush off."""
    for k in range(steps):
        paper.deposit([_band(20 + 6 * k, 32 + 6 * k, 40, 60)], Q, DT, k + 1)
    if lift:
        paper.deposit([], Q, DT, steps + 1)


def _sheet(**kw) -> Paper:
    return Paper(100, 100, 8.0, capacity=1.0, fibre=0.5, **kw)


def test_the_halo_is_laid_as_the_brush_leaves_a_faint_tint_fading_out():
    before, after = _sheet(), _sheet()
    _stroke(before, lift=False)
    assert before.stroke is not None and before.stroke.start == 1
    _stroke(after)
    assert after.stroke is None
    r = after.halo_px
    assert 0 < r <= HALO_MAX_PX
    core, was = after.ink[30:50, 45:55, 0], before.ink[30:50, 45:55, 0]
    # the stroke not darker: its wet film levelled (LEVEL_MM), its pigment the same
    pigment, had = -np.log1p(-core.astype(float)), -np.log1p(-was.astype(float))
    assert abs(pigment.mean() - had.mean()) < 0.01 * had.mean()
    near = after.ink[30:50, 60 + r // 2, 0]  # half a box out of its edge
    far = after.ink[30:50, 60 + 2 * r - 1, 0]
    assert not before.ink[30:50, 60 + r // 2, 0].any()  # nothing there before the lift
    assert 0.0 < near.mean() <= HALO_PIGMENT * 0.9 + 1e-6  # a faint tint, never dark
    assert far.mean() < near.mean()  # fading outward
    reach = int(np.nonzero(after.wet.any(axis=0))[0].max()) + 2 * r  # the wet edge, the bell
    assert not after.ink[:, reach + 1 :].any()  # no further than its bell reaches
    assert np.array_equal(after.wet, before.wet)  # only pigment: the water is where it was


def test_the_halo_takes_the_wetness_the_stroke_left_not_older_strokes():
    paper = _sheet()
    _stroke(paper)
    once = paper.ink.copy()
    paper.deposit([], Q, DT, 8)  # still lifted: nothing more
    np.testing.assert_array_equal(paper.ink, once)
    paper.deposit([_band(80, 84, 5, 9, wet=0.05)], Q, DT, 9)  # a faint touch far away
    paper.deposit([], Q, DT, 10)
    # the first stroke's pixels gave no second halo: near it nothing changed
    np.testing.assert_array_equal(paper.ink[:70, 30:80], once[:70, 30:80])


def test_smooth_paper_and_a_halo_of_no_reach_lay_nothing():
    assert halo_px(1000.0, 8.0) == 0
    smooth = Paper(100, 100, 8.0, capacity=1000.0)
    _stroke(smooth)
    assert not smooth.ink[:, 62:].any()
    off = _sheet()
    off.halo_px = 0  # as on a mesh's texels (Simulation)
    _stroke(off)
    assert off.stroke is None and not off.ink[:, 64:].any()


def test_a_hold_and_a_snapshot_take_the_stroke_back_with_the_ink():
    paper = _sheet()
    for k in range(3):
        paper.deposit([_band(20 + 6 * k, 32 + 6 * k, 40, 60)], Q, DT, k + 1)
    snap = paper.snapshot()
    hold = paper.hold()
    for k in range(3, 6):
        paper.deposit([_band(20 + 6 * k, 32 + 6 * k, 40, 60)], Q, DT, k + 1)
    paper.deposit([], Q, DT, 7)
    want = paper.ink.copy()
    paper.give_back(hold)
    assert isinstance(paper.stroke, WetStroke) and paper.stroke.start == 1
    for k in range(3, 6):
        paper.deposit([_band(20 + 6 * k, 32 + 6 * k, 40, 60)], Q, DT, k + 1)
    paper.deposit([], Q, DT, 7)
    np.testing.assert_array_equal(paper.ink, want)
    paper.restore(snap)
    assert paper.stroke == snap["stroke"]


def test_the_halo_changes_only_the_tiles_it_darkens():
    paper = Paper(512, 512, 8.0, capacity=1.0, fibre=0.5)
    _stroke(paper, lift=False)
    v = paper.version
    paper.deposit([], Q, DT, 7)
    changed = {tuple(t) for t in paper.tiles_since(v).tolist()}
    assert changed and changed <= {(0, 0), (1, 0), (0, 1), (1, 1)}


def test_the_halo_made_in_bands_of_rows_is_the_halo_made_at_once(monkeypatch):
    whole, banded = _sheet(), _sheet()
    _stroke(whole)
    monkeypatch.setattr(paper_module, "HALO_ROWS", 7)  # bands far thinner than the bell
    _stroke(banded)
    np.testing.assert_allclose(banded.ink, whole.ink, atol=2e-6)
    assert (banded.ink > 0).sum() == (whole.ink > 0).sum()


def test_a_wet_stroke_levels_into_solid_ink_a_dry_one_keeps_its_texture():
    """The wet film levels as the brush leaves (LEVEL_MM): the grain's mottle inside a loaded
    stroke evens out with its pigment kept; a stroke that left little liquid keeps it."""
    for wet, levels in ((0.8, True), (0.12, False)):
        before, after = _sheet(), _sheet()
        _stroke(before, lift=False)
        _stroke(after)
        for paper in (before, after):  # the same band again, with this much liquid
            for k in range(6):
                paper.deposit([_band(86, 98, 10 + 6 * k, 22 + 6 * k, wet=wet)], Q, DT, 20 + k)
        after.deposit([], Q, DT, 26)
        core, was = after.ink[88:96, 15:40, 0], before.ink[88:96, 15:40, 0]
        assert was.std() > 0.0  # the grain mottled it
        if levels:
            assert core.std() < 0.5 * was.std()
            pigment, had = -np.log1p(-core.astype(float)), -np.log1p(-was.astype(float))
            assert abs(pigment.mean() - had.mean()) < 0.01 * had.mean()
        else:
            np.testing.assert_array_equal(core, was)


def _fast(paper: Paper, first: int = 1, lift: bool = True) -> None:
    """A loaded band written fast to the right (30 px a step), then the brush off."""
    for k in range(6):
        paper.deposit([_band(40, 52, 10 + 30 * k, 22 + 30 * k)], Q, DT, first + k)
    if lift:
        paper.deposit([], Q, DT, first + 6)


def test_a_fast_loaded_exit_throws_droplets_on_along_its_way(monkeypatch):
    """SPATTER_EXIT: droplets laid as the brush leaves, ahead of the exit, off the stroke."""
    monkeypatch.setattr(lift_module, "SPATTER_LAND", 0.0)
    monkeypatch.setattr(lift_module, "SPATTER_EXIT", 50.0)  # so many that the cap throws
    still, thrown = Paper(300, 100, 8.0, capacity=1.0, fibre=0.5), None
    _fast(still, lift=False)
    thrown = Paper(300, 100, 8.0, capacity=1.0, fibre=0.5)
    _fast(thrown)
    new = (thrown.ink[..., 0] > 0.3) & (still.ink[..., 0] == 0.0)  # darker than a halo
    assert not new[:, :172].any()  # none behind the last mark's far edge (column 172) ...
    fy, fx = np.nonzero(new)
    assert fx.size and fx.max() > 172 + 4  # ... but ahead of it, ...
    assert 30 <= fy.min() and fy.max() <= 62  # ... along the way it went, not sideways
    assert thrown.ink[..., 0].max() <= 1.0
    again = Paper(300, 100, 8.0, capacity=1.0, fibre=0.5)  # the same stroke: the same drops
    _fast(again)
    np.testing.assert_array_equal(again.ink, thrown.ink)
    later = Paper(300, 100, 8.0, capacity=1.0, fibre=0.5)  # later in the recording: the same
    _fast(later, first=41)
    np.testing.assert_array_equal(later.ink, thrown.ink)


def test_a_slow_exit_throws_nothing_and_counts_follow_poisson():
    slow = _sheet()
    _stroke(slow)  # 6 px a step at 60 steps a second, 8 px a mm: 45 mm/s, dry-ish exit
    assert lift_module._poisson(0.0, 0.99) == 0
    assert lift_module._poisson(1.0, 0.0) == 0 and lift_module._poisson(1.0, 0.5) == 1
    draws = np.linspace(0.0005, 0.9995, 1000)
    mean = np.mean([lift_module._poisson(0.3, u) for u in draws])
    assert abs(mean - 0.3) < 0.02


def test_a_droplet_on_or_touching_the_ink_runs_into_it():
    """SPATTER_MERGE: a droplet that would lie on the stroke or touch its edge (a bead stuck to
    a head or a point) is not laid; one clear of it is."""
    paper = _sheet()
    _stroke(paper)  # the band: rows 20-62, columns 40-60
    colour = np.array([0.9, 0.9, 0.9], dtype=np.float32)
    shape, merge = (3.0, 1.0), lift_module.SPATTER_MERGE * 0.9
    way = np.array([0.0, 1.0])
    for centre in ((40.0, 62.5), (40.0, 50.0), (40.0, 37.0)):  # touching, on, touching
        before = paper.ink.copy()
        lift_module._drop(paper, centre, way, shape, (colour, merge))
        np.testing.assert_array_equal(paper.ink, before)
    lift_module._drop(paper, (40.0, 70.0), way, shape, (colour, merge))  # 7 px clear of it
    assert paper.ink[40, 70, 0] > 0.8


def test_no_droplet_is_laid_against_the_stroke_it_came_from(monkeypatch):
    """However many droplets a landing shakes off, none is stuck to the stroke: every piece of
    ink darker than the halo beyond the stroke's own lies clear of it."""
    from scipy import ndimage as ndi

    monkeypatch.setattr(lift_module, "SPATTER_LAND", 50.0)
    monkeypatch.setattr(lift_module, "SPATTER_DRIP", 0.0)  # every landing drips
    monkeypatch.setattr(lift_module, "SPATTER_EXIT", 50.0)
    still, thrown = Paper(300, 100, 8.0, capacity=1.0, fibre=0.5), None
    _fast(still, lift=False)
    thrown = Paper(300, 100, 8.0, capacity=1.0, fibre=0.5)
    _fast(thrown)
    dark = thrown.ink[..., 0] > 0.3
    stroke = still.ink[..., 0] > 0.3
    pieces, n = ndi.label(dark)
    own = set(np.unique(pieces[stroke])) - {0}
    assert n > len(own)  # droplets were laid ...
    grown = ndi.binary_dilation(stroke)
    assert not (dark & grown & ~stroke).any()  # ... none of them on or against the stroke


def _landing_drops(monkeypatch, wet: float) -> int:
    """Dark pieces off a slow stroke (no exit droplets) landed with liquid ``wet``."""
    from scipy import ndimage as ndi

    monkeypatch.setattr(lift_module, "SPATTER_LAND", 50.0)  # so many that the cap throws
    paper = _sheet()
    for k in range(6):
        paper.deposit([band(20 + 6 * k, 32 + 6 * k, 40, 60, wet, 0.9)], Q, DT, k + 1)
    paper.deposit([], Q, DT, 7)
    _, n = ndi.label(paper.ink[..., 0] > 0.3)
    return n - 1  # the stroke itself is one piece


def test_only_an_overloaded_landing_drips(monkeypatch):
    """SPATTER_DRIP: a brush that lands with less liquid than a dip's first strokes offer drops
    nothing round its head, however often it may; one that lands overloaded does."""
    assert _landing_drops(monkeypatch, lift_module.SPATTER_DRIP - 0.1) == 0
    assert _landing_drops(monkeypatch, lift_module.SPATTER_DRIP + 0.2) > 0


def _tube(monkeypatch, wide_mm: float, wet: float) -> np.ndarray:
    """The ink across a band 6 mm wide written with ``wet`` liquid, darker toward its middle
    (the belly laid most there: a section's longest chord passes there), once the brush has
    left: the mean of its columns, row by row."""
    monkeypatch.setattr(lift_module, "LEVEL_WIDE_MM", wide_mm)
    paper = Paper(140, 110, 8.0, capacity=1.0, fibre=0.5)
    step = 1
    for inset, dark in ((0, 0.5), (6, 0.6), (12, 0.7), (18, 0.8)):
        for k in range(6):
            band = _band(30 + inset, 78 - inset, 10 + 6 * k, 22 + 6 * k, wet=wet, dark=dark)
            paper.deposit([band], Q, DT, step)
            step += 1
    paper.deposit([], Q, DT, step)
    return paper.ink[30:78, 20:36, 0].mean(axis=1)


def test_a_full_film_levels_across_the_stroke_a_thin_one_keeps_its_shading(monkeypatch):
    """LEVEL_WIDE_MM: a loaded stroke's film spreads from its middle, where the belly laid
    most, to its edges: it is evenly dark across; with little liquid the film is taken at once
    and the middle stays darker."""

    def middle_over_edges(ink):  # inside the edges' anti-aliasing
        return ink[20:28].mean() - np.r_[ink[3:8], ink[-8:-3]].mean()

    tube = _tube(monkeypatch, lift_module.LEVEL_MM, 0.8)  # levelled within half a mm only
    flat = _tube(monkeypatch, 2.5, 0.8)
    assert middle_over_edges(tube) > 0.1  # the middle darker ...
    assert middle_over_edges(flat) < 0.3 * middle_over_edges(tube)  # ... evened out
    # its pigment kept but for what the edges take from the darker middle (the move is
    # normalised by the film round each pixel: 4 % more here, the edges 0.5 against 0.8)
    pigment = -np.log1p(-tube.astype(float)).sum()
    assert abs(-np.log1p(-flat.astype(float)).sum() - pigment) < 0.05 * pigment
    dry_tube, dry = _tube(monkeypatch, lift_module.LEVEL_MM, 0.35), _tube(monkeypatch, 2.5, 0.35)
    assert middle_over_edges(dry) > 0.8 * middle_over_edges(dry_tube)
