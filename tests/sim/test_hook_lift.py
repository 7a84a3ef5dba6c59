# SPDX-License-Identifier: GPL-3.0-or-later
"""A hook's root lifted off the lobe it spills past the outline (issue 26, point 2): as the belly
swings from the leg's way onto the flick's, the hair splayed in the heel swept out past the
triangle's lower edge in a round lobe below the hook's root (同, 永, 月). Practice reads the ink
past the character's outline round the hook, counts it to the sample whose base is nearest,
and lifts the brush there a little on the next pass, where the band across the hook is read in
the leg's ink and its own width correction never sees it. No Blender."""

import numpy as np
import pytest

from sim.core.recording import Recording
from sim.writing import hook_lift
from sim.writing.hanzi import find_char
from sim.writing.hook_lift import LIFT_MAX, _hook_runs, _Hooks, _lifted, _root_unread
from sim.writing.outline import rasterise, to_image
from sim.writing.planner import TURNING, WRITING, Plan
from sim.writing.response import Response
from sim.writing.writer import coverage_mask, write_character
from tests.sim.builders import stiff_template


def _leg_and_hook():
    """A plan of one stroke: a leg down and a hook flicked up to a point, its body samples."""
    leg = np.stack([np.zeros(20), np.linspace(10.0, 0.5, 20)], axis=1)
    hook = np.stack([np.linspace(0.3, 3.0, 10), np.linspace(0.3, 1.5, 10)], axis=1)
    target = np.concatenate([leg, leg[-1:], hook])
    phase = np.r_[np.full(20, WRITING), TURNING, np.full(10, WRITING)]
    width = np.r_[np.full(21, 1.0), np.linspace(1.0, 0.2, 10)]
    pl = Plan(target, width, np.zeros((31, 2)), phase, [], [(0, 31)], hooks=(21,))
    return pl, np.flatnonzero(phase == WRITING)


def test_the_root_unread_is_the_hooks_up_to_its_first_own_reading():
    pl, body = _leg_and_hook()
    valid = np.ones(len(body), dtype=bool)
    valid[5:8] = False  # the leg read in another stroke's ink: not a hook's root
    valid[20:23] = False  # the hook's root, read in the leg's ink
    valid[26] = False  # further on the hook: read again, not its root
    unread = _root_unread(_Hooks(_hook_runs(pl, body), None, None, None, None), valid)
    assert np.flatnonzero(unread).tolist() == [20, 21, 22]


def test_the_lift_grows_with_the_spill_where_unread_and_is_bounded():
    response = Response(
        press_mm=np.linspace(0.0, 4.0, 9), width_mm=np.linspace(0.5, 4.5, 9),
        lag_mm=np.zeros(9), speed_mm_s=50.0,
    )  # fmt: skip
    n = 30
    press = np.full(n, 2.0)
    spill = np.zeros(n)
    spill[10:15] = 0.4  # mm wider than the outline
    unread = np.zeros(n, dtype=bool)
    unread[8:17] = True
    once = _lifted(response, np.zeros(n), spill, press, unread)
    assert once[12] > 0.0 and np.all(once[:5] == 0.0) and np.all(once[20:] == 0.0)
    assert once[12] == pytest.approx(hook_lift.LIFT_GAIN * 0.4, rel=0.01)  # slope 1 mm/mm
    twice = _lifted(response, once, spill, press, unread)
    assert twice[12] > once[12]  # the lobe still there: lifted further
    many = once
    for _ in range(20):
        many = _lifted(response, many, spill, press, unread)
    assert many.max() == pytest.approx(LIFT_MAX * 2.0)  # never more than its share of the press
    assert np.all(_lifted(response, once, spill, press, ~unread)[10:15] == once[10:15])


@pytest.mark.slow
@pytest.mark.parametrize(("char", "stroke"), [("永", 1), ("月", 1), ("风", 1)])
def test_practice_lifts_a_hooks_lobe_in(monkeypatch, char, stroke):
    # on main (no lift) the ink outside the font round these hooks at 256 px was 45, 29 and 161
    # px; lifted, 39, 26 and 148
    n = 256
    c = find_char(char)
    font = rasterise(c, n)
    foot_tip = to_image(c["medians"][stroke][-2:], n)
    lo = np.maximum(foot_tip.min(axis=0) - 0.08 * n, 0).astype(int)
    hi = (foot_tip.max(axis=0) + 0.08 * n).astype(int)
    template: Recording = stiff_template()
    outside = []
    for gain in (0.0, hook_lift.LIFT_GAIN):
        monkeypatch.setattr(hook_lift, "LIFT_GAIN", gain)
        _, _, sim = write_character(c, n, template)
        out = coverage_mask(sim) & ~font
        outside.append(int(out[lo[1] : hi[1], lo[0] : hi[0]].sum()))
    assert outside[1] < outside[0]
