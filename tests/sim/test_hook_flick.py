# SPDX-License-Identifier: GPL-3.0-or-later
"""A hook flicks out in one movement (issue 26, points 1-2): practice corrects a hook's sideways
placement as a whole, never zigzagging from sample to sample, and never presses it deeper again
as it flicks out; the base rests on the hook's foot as planned. (Before, the band read across
the short narrowing hook swung from side to side, the correction followed it sample by sample,
and every zig of the flick laid its own crisp hair lines: a cross-hatched broom.) No Blender."""

import numpy as np
import pytest

from sim.writing import writer
from sim.writing.hanzi import find_char
from sim.writing.planner import WRITING, _flicks, _is_hook, _movements
from sim.writing.practice import _one_flick
from sim.writing.writer import write_character
from tests.sim.builders import stiff_template


def _passes(response, monkeypatch, char):
    """Every pass's (plan, a, b, press, side) of ``char`` written with practice."""
    seen = []
    practise = writer._practise_stroke

    def spy(sim, a, b, passes, fill, own, ctx, *args):
        def watched(a_, b_, press, side, *more):
            seen.append((ctx[0], a_, b_, press.copy(), side.copy()))
            return fill(a_, b_, press, side, *more)

        return practise(sim, a, b, passes, watched, own, ctx, *args)

    monkeypatch.setattr(writer, "_practise_stroke", spy)
    write_character(find_char(char), 256, stiff_template(), response=response)
    return seen


def _hooks(pl, a, b):
    """The body samples (indices into the stroke's body) of each flicked hook of stroke a..b."""
    body = np.flatnonzero(pl.phase[a:b] == WRITING) + a
    runs, moves = _movements(np.arange(len(body)), body), _movements(body)
    flicked = _flicks(pl, moves, _is_hook(pl, moves))
    return [run for run, hook in zip(runs, flicked, strict=True) if hook]


@pytest.mark.slow
@pytest.mark.parametrize("char", ["心", "永"])
def test_practice_corrects_a_hook_as_one_movement(response, monkeypatch, char):
    # on main the corrected sideways placement of 心's 卧钩 and 永's 竖钩 went back and forth
    # along the hook (its steps changing sign), and the hook was pressed again past its root
    corrected = 0
    for pl, a, b, press, side in _passes(response, monkeypatch, char):
        for run in _hooks(pl, a, b):
            if not side.any():  # the first pass: as planned
                continue
            corrected += 1
            step = np.diff(side[run])
            assert np.all(step >= -1e-9) or np.all(step <= 1e-9)
            assert np.all(np.diff(press[run]) <= 1e-9)
    assert corrected


def test_a_hooks_placement_is_a_line_and_its_foot_rests_as_planned():
    # a noisy correction over a hook becomes the straight line nearest it, its press never
    # deeper than the foot's end nor deepening again; the foot's last width,
    # where the base rests, is eased to the planned placement (none)
    from sim.writing.planner import TURNING, Plan

    leg = np.stack([np.zeros(20), np.linspace(10.0, 0.5, 20)], axis=1)
    hook = np.stack([np.linspace(0.3, 3.0, 10), np.linspace(0.3, 1.5, 10)], axis=1)
    target = np.concatenate([leg, leg[-1:], hook])
    phase = np.r_[np.full(20, WRITING), TURNING, np.full(10, WRITING)]
    width = np.r_[np.full(21, 1.0), np.linspace(1.0, 0.2, 10)]  # the hook narrows to a point
    pl = Plan(target, width, np.zeros((31, 2)), phase, [], [(0, 31)], hooks=(21,))
    body = np.flatnonzero(phase == WRITING)
    rng = np.random.default_rng(0)
    side = 0.3 + rng.normal(0.0, 0.2, len(body))
    press = 2.0 + rng.normal(0.0, 0.2, len(body))
    first = np.full(len(body), 2.0)
    p, s = _one_flick(pl, body, (press, side), first)
    h = slice(20, 30)
    assert np.abs(np.diff(s[h], 2)).max() < 1e-9  # a line
    assert abs(s[h].mean() - side[h].mean()) < 1e-9  # the nearest: the same mean
    assert np.all(np.diff(p[h]) <= 0.0) and p[h].max() <= press[19]  # no deeper than the foot
    assert s[19] == 0.0 and np.allclose(s[:15], side[:15])  # the foot's rest, the leg as it was
    assert np.array_equal(p[:20], press[:20])
