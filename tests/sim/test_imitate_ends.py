# SPDX-License-Identifier: GPL-3.0-or-later
"""Where an imitation's strokes begin and end (issue 26, point 4): a picture shows where each
stroke's ink begins and ends, so the imitation lands the brush on a stroke's start (no run-up,
whose tip lays a hairline before it) and practises how far each free end's ink reaches
(``write_character(exact_ends=True)``). No Blender."""

import numpy as np
import pytest

from sim.core.recording import Recording
from sim.writing.outline import rasterise
from sim.writing.planner import END_SPAN, ENTERING, WRITING, _ends_moved, _fill, plan
from sim.writing.response import calibrate
from sim.writing.writer import coverage_mask, write_character

# a bar with squared ends, its median well inside them (as a picture's median is)
BAR = {
    "strokes": ["M 200 480 L 800 500 L 800 420 L 200 420 Z"],
    "medians": [[[230, 455], [770, 462]]],
}


def _template():
    return Recording(np.zeros((1, 6)))  # the command line's defaults, as sim imitate uses


@pytest.fixture(scope="module")
def response():
    return calibrate(_template())


def test_a_moved_end_moves_the_path_only_near_that_end():
    path = np.stack([np.linspace(0.0, 20.0, 41), np.zeros(41)], axis=1)
    tangent = np.tile([1.0, 0.0], (41, 1))
    width = np.full(41, 1.0)
    moved = _ends_moved(path, tangent, width, np.array([1.0, -0.5]))
    assert np.allclose(moved[0], [-1.0, 0.0]) and np.allclose(moved[-1], [19.5, 0.0])
    far = (path[:, 0] > END_SPAN) & (path[:, 0] < 20.0 - END_SPAN)
    assert far.any() and np.allclose(moved[far], path[far])  # the body stays
    assert np.all(np.diff(moved[:, 0]) > 0)  # still runs one way
    assert np.allclose(moved[:, 1], 0.0)  # along the way out, not sideways
    assert _ends_moved(path, tangent, width, np.zeros(2)) is path


def test_the_imitation_lands_on_the_start_and_the_writer_runs_on_to_it(response):
    from sim.core.params import HOVER_MM

    pl = plan(BAR, 100.0, 0.5)
    a, b = pl.strokes[0]
    body = np.flatnonzero(pl.phase[a:b] == WRITING) + a
    entry = np.flatnonzero(pl.phase[a:b] == ENTERING) + a
    hair = _template().resolve()[1].hair_length_mm
    brush = (hair + HOVER_MM, hair, 0.5, 1.0)
    press = response.press_for(pl.width[body])
    landed = []
    for run_up in (1.0, 0.0):
        samples = np.zeros((len(pl.target), 6))
        samples[:, :2], samples[:, 2] = pl.target, hair + HOVER_MM
        _fill(samples, pl, response, (a, b), press, np.zeros(len(body)), brush, None, run_up)
        landed.append(samples[entry, :2] - samples[body[0], :2])
    run_on, on_the_start = landed
    # the writer comes down moving along the bar (from behind its start), the imitation
    # straight down onto it
    t0 = pl.tangent[body[0]]
    behind = run_on @ t0
    assert behind[0] < -1.0 and np.all(np.diff(behind) > 0)
    assert np.allclose(run_on, behind[:, None] * t0[None, :], atol=1e-3)
    assert np.abs(on_the_start).max() < 0.01


@pytest.mark.slow
def test_practising_the_reach_brings_a_bars_ends_to_its_outline(response):
    # written as the writer writes it the bar runs on past its outline at both ends (the
    # run-up's tip and the round footprint of the lift: 6 px); with exact_ends it ends where its
    # outline does, within 3 px at 256 px, and its area agrees as well (2 or 3 px by the last
    # bits of the arithmetic: 2 under this machine's own BLAS kernels before sim/core/exact.py,
    # 3 under older ones and since; the same on every machine now)
    truth = rasterise(BAR, 256)
    xs = np.flatnonzero(truth.any(axis=0))
    off, iou = {}, {}
    for exact in (False, True):
        _, _, sim = write_character(BAR, 256, _template(), response=response, exact_ends=exact)
        ink = coverage_mask(sim)
        xw = np.flatnonzero(ink.any(axis=0))
        off[exact] = (xs[0] - xw[0], xw[-1] - xs[-1])  # px run on past the left and right
        iou[exact] = np.count_nonzero(ink & truth) / np.count_nonzero(ink | truth)
    assert max(off[False]) >= 4
    assert max(abs(v) for v in off[True]) <= 3
    assert iou[True] >= iou[False] - 0.01
