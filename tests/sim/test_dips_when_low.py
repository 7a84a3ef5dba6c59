# SPDX-License-Identifier: GPL-3.0-or-later
"""The writer dips as a calligrapher does (issue 26): before the first stroke and again only
when the brush runs low, so the ink runs from dark after a dip to grey before the next."""

import numpy as np
import pytest

from sim.brush.ink import brush_load, full_load
from sim.brush.primitive import HairyBrush
from sim.core.recording import Recording
from sim.engine.simulation import Simulation
from sim.writing.hanzi import find_char
from sim.writing.outline import EM, TOP
from sim.writing.planner import plan
from sim.writing.practice import _stroke_masks
from sim.writing.response import calibrate
from sim.writing.writer import (
    DIP_EVERY_STROKE,
    LOW_INK,
    RUN_DRY,
    dips_when_low,
    ink_needed,
    stroke_areas,
    write_character,
)


def test_dips_when_the_brush_runs_low():
    assert not dips_when_low(1.0, 1.0) and not dips_when_low(LOW_INK + 0.01, 1.0)
    assert dips_when_low(LOW_INK - 0.01, 1.0) and dips_when_low(0.25, 0.5)


def test_dips_before_a_stroke_the_brush_would_end_dry():
    # begun above LOW_INK, a stroke that would take the load below RUN_DRY gets a dip first
    load = LOW_INK + 0.05
    assert not dips_when_low(load, 1.0, need=load - RUN_DRY - 0.01)
    assert dips_when_low(load, 1.0, need=load - RUN_DRY + 0.01)


def test_the_ink_a_stroke_needs_is_foreseen_from_the_strokes_before_it():
    # 0.2 of the load went on 500 mm^2 since the dip: a 250 mm^2 stroke will take 0.1
    assert ink_needed((1.0, 500.0), 0.8, 250.0) == pytest.approx(0.1)
    assert ink_needed((1.0, 0.0), 1.0, 250.0) == 0.0  # nothing written yet: nothing to go by
    assert ink_needed((1.0, 100.0), 0.9, 700.0) == 0.0  # a dot is no guide to a long stroke
    ch = find_char("永")
    pl = plan(ch, 60.0, 0.5)
    areas = stroke_areas(pl, 0.5)
    assert len(areas) == len(ch["medians"]) and min(areas) > 0.0
    assert np.argmax(areas) != np.argmin(areas)  # 永's long 横折钩 against its dot


def test_a_spent_load_is_less_than_a_full_one():
    rec = Recording(np.zeros((1, 6)))
    q, geometry, _, ink = rec.resolve()
    b = HairyBrush(geometry, q, np.random.Generator(np.random.PCG64(1)))
    assert brush_load(b) == 0.0  # a new brush is dry until dipped
    b.dip(ink)
    full = full_load(rec)
    assert full > 0.5 and brush_load(b) == pytest.approx(full)
    b.wet[:] *= 0.5
    assert brush_load(b) == pytest.approx(0.5 * full)


def _density(sim, window):
    """Mean ink density of a stroke's own outline."""
    ink = sim.paper.ink[window.rows, window.cols].mean(axis=-1)
    return float(ink[window.inside].mean())


def _inked_median(sim, window):
    """Median ink density of the inked pixels (0.4 or more) of a stroke's own outline."""
    ink = sim.paper.ink[window.rows, window.cols].mean(axis=-1)[window.inside]
    return float(np.median(ink[ink >= 0.4]))


def _last_half(ch, k, window, n):
    """The part of stroke k's outline (``window``) nearer its median's end than its start."""
    med = np.asarray(ch["medians"][k], dtype=float)
    ends = np.stack([med[:, 0] * n / EM, (med[:, 1] - (TOP - EM)) * n / EM], axis=1)[[0, -1]]
    rows, cols = np.nonzero(window.inside)
    p = np.stack([cols + window.cols.start + 0.5, rows + window.rows.start + 0.5], axis=1)
    d0, d1 = (np.linalg.norm(p - e, axis=1) for e in ends)
    inside = np.zeros_like(window.inside)
    inside[rows[d1 < d0], cols[d1 < d0]] = True
    return type(window)(window.rows, window.cols, inside)


@pytest.mark.slow
def test_a_character_is_written_on_few_dips_and_greys_before_the_next():
    template = Recording(np.zeros((1, 6)))
    response = calibrate(template)
    ch = find_char("永")
    rec, _, sim = write_character(ch, 160, template, response=response, passes=1)
    n = len(ch["medians"])
    assert 1 < len(rec.dips) < n  # not a dip before every stroke, but not one for 永
    every, _, _ = write_character(
        ch, 160, template, response=response, passes=1, dip_every_mm=DIP_EVERY_STROKE
    )
    assert len(every.dips) == n
    # the stroke written just before the second dip is lighter, over the half of it written
    # last, than the first stroke and than the stroke written after the dip (the whole
    # stroke: since issue 26's 折, pressed through 永's 横折 shoulder, its first half is dark)
    masks = _stroke_masks(ch, sim.paper.H, sim.paper.W)
    pl = plan(ch, rec.width_mm, response.speed_mm_s / rec.sample_rate_hz)
    starts = [a for a, _ in pl.strokes]
    second = starts.index(rec.dips[1].before_sample)
    spent = _density(sim, _last_half(ch, second - 1, masks[second - 1], sim.paper.H))
    # the dips decided as the writing went are the recording's: it replays to the same ink
    assert np.array_equal(Simulation(rec).run().paper.ink, sim.paper.ink)
    assert spent < 0.97 * _density(sim, masks[0]) and spent < 0.97 * _density(sim, masks[second])


@pytest.mark.slow
def test_the_brush_written_alone_decides_the_same_recording():
    """With ``paper`` False (one pass) the writer runs the brush alone (a composed work's cells
    are simulated again on the sheet): the same samples, dips and brush, bit for bit, and a
    blank paper, as the brush never reads the paper."""
    template = Recording(np.zeros((1, 6)))
    response = calibrate(template)
    ch = find_char("永")
    rec, _, sim = write_character(ch, 120, template, response=response, passes=1)
    alone, _, bare = write_character(ch, 120, template, response=response, passes=1, paper=False)
    assert len(rec.dips) > 1 and alone.dips == rec.dips
    assert alone.samples.tobytes() == rec.samples.tobytes()
    want, got = sim.brush.snapshot(), bare.brush.snapshot()
    assert want.keys() == got.keys()
    for key, value in want.items():
        assert np.array_equal(np.asarray(got[key]), np.asarray(value)), key
    assert sim.paper.ink.any() and not bare.paper.ink.any()


@pytest.mark.slow
def test_a_stroke_is_begun_on_two_thirds_of_a_load_and_written_grey():
    """As a calligrapher writes on until the brush runs low (issue 26, point 1): 永's 横撇,
    begun with about two thirds of a full load left after the 点 and the long 横折钩, is written
    on the first dip's ink (main dipped before it), and the half of it written last is clearly
    lighter than the first stroke, written just after the dip: lighter on the whole and in the
    ink it lays (a hair running dry lays its ink on fewer lines, each as dark as half a load's,
    ``bristles._hairs``: the spent half's mean density 0.86 of the first stroke's, 0.82 when it
    laid a paler ink everywhere; the median of its inked pixels 0.78 against 0.89)."""
    template = Recording(np.zeros((1, 6)))
    response = calibrate(template)
    ch = find_char("永")
    rec, _, sim = write_character(ch, 160, template, response=response, passes=1)
    pl = plan(ch, rec.width_mm, response.speed_mm_s / rec.sample_rate_hz)
    dipped = {[a for a, _ in pl.strokes].index(d.before_sample) for d in rec.dips}
    assert 0 in dipped and 2 not in dipped
    masks = _stroke_masks(ch, sim.paper.H, sim.paper.W)
    half = _last_half(ch, 2, masks[2], sim.paper.H)
    assert _density(sim, half) < 0.9 * _density(sim, masks[0])
    assert _inked_median(sim, half) < 0.92 * _inked_median(sim, masks[0])


def test_a_soak_dips_the_whole_hair_as_wet_as_the_dip_was():
    from sim.core.recording import Dip
    from sim.writing.writer import SOAK_DEPTH, soaked

    dip = Dip(7, 0.5, (0.1, 0.1, 0.1), 0.5)
    soak = soaked(dip)
    assert soak.depth == SOAK_DEPTH == 1.0 and soak.wetness == 0.5  # a dry ink stays dry
    assert (soak.before_sample, soak.color) == (7, dip.color) and dip.depth == 0.5


@pytest.mark.slow
def test_a_stroke_that_runs_dry_on_a_fresh_dip_is_written_again_on_a_soak(monkeypatch):
    """As a calligrapher loads the brush fully for a stroke one dip does not carry (issue 26:
    飞's imitated hook, a dry broom on a solid picture): a stroke begun on a fresh dip that ends
    below RUN_DRY of a full load is taken back and written again on a soak. 永 runs dry nowhere.
    With RUN_DRY raised every stroke 'runs dry' (and is dipped for) and each dip becomes a
    soak: the character lays more ink than when the soak is no deeper than the dip, and both
    recordings replay to their ink, bit for bit."""
    import sim.writing.writer as writer

    template = Recording(np.zeros((1, 6)))
    response = calibrate(template)
    ch = find_char("永")
    rec, _, _ = write_character(ch, 120, template, response=response, passes=1)
    assert all(d.depth == 0.7 for d in rec.dips)  # ordinary dips
    monkeypatch.setattr(writer, "RUN_DRY", 0.99)
    monkeypatch.setattr(writer, "SOAK_DEPTH", 0.7)  # taken back, written again the same
    same, _, plain = write_character(ch, 120, template, response=response, passes=1)
    monkeypatch.setattr(writer, "SOAK_DEPTH", 1.0)
    soak, _, wet = write_character(ch, 120, template, response=response, passes=1)
    assert len(same.dips) > len(rec.dips) and len(soak.dips) <= len(same.dips)  # carries further
    assert all(d.depth == 0.7 for d in same.dips)
    assert any(d.depth == 1.0 for d in soak.dips)
    assert all(d.depth in (0.7, 1.0) for d in soak.dips)
    assert float(wet.paper.ink.sum()) > float(plain.paper.ink.sum())  # the soaks laid more ink
    for r, s in ((same, plain), (soak, wet)):
        assert np.array_equal(Simulation(r).run().paper.ink, s.paper.ink)
