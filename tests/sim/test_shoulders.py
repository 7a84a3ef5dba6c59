# SPDX-License-Identifier: GPL-3.0-or-later
"""A 折's shoulder written as one pressed move (the 顿) (issue 26, point 2): the samples through
the corner, written with ``stiff_template`` at 128 px, one pass. No Blender."""

import numpy as np
import pytest

from sim.writing.hanzi import find_char
from sim.writing.outline import median_pieces
from sim.writing.planner import WRITING, plan
from sim.writing.writer import write_character
from tests.sim.builders import stiff_template


def _through_corner(response, char, k, corner=0):
    """Stroke ``k``'s samples from the last body sample of its movement ending at its
    ``corner``-th sharp corner to the first of the next movement (x, y, press), and the
    brush's step (mm a sample)."""
    tpl = stiff_template()
    ch = find_char(char)
    rec, _, _ = write_character(ch, 128, tpl, response=response, passes=1)
    step = response.speed_mm_s / tpl.sample_rate_hz
    pl = plan(ch, rec.width_mm, step)
    a, b = pl.strokes[k]
    body = np.flatnonzero(pl.phase[a:b] == WRITING) + a
    cut = np.flatnonzero(np.diff(body) > 1)[corner]
    span = np.arange(body[cut], body[cut + 1] + 1)
    s = rec.samples[span]
    return np.column_stack([s[:, :2], tpl.resolve()[1].hair_length_mm - s[:, 2]]), step


@pytest.mark.parametrize("char,k", [("口", 1), ("永", 1), ("日", 1)])
def test_a_zhe_shoulder_is_one_move_never_at_rest_pressed(response, char, k):
    # the 顿 (issue 26): from the horizontal's end the base goes on down to where the leg sets
    # off, lifting a little and pressing again as it goes; it never stands pressed on the spot
    # (before: lifted on the corner and entered the leg there, 8 samples at rest pressed, and
    # turned back across the shoulder between: a round knob)
    s, step = _through_corner(response, char, k)
    moved = np.linalg.norm(np.diff(s[:, :2], axis=0), axis=1)
    pressed = s[1:, 2] > 0.0
    assert pressed.all()
    assert moved[pressed].min() > 0.2 * step


@pytest.mark.parametrize("char", ["口", "永", "日"])
def test_a_zhe_leg_sets_off_from_down_right_of_the_corner(char):
    # the leg sets off where the 顿 pressed to: down and to the right of the median's corner
    # (the horizontal's end), not on it, so that no back-drag crosses the shoulder
    (head, _), (leg, leg_w) = median_pieces(find_char(char))[1][:2]
    off = leg[0] - head[-1]
    body = float(np.median(leg_w))
    assert off[0] > 0.1 * body and off[1] < 0.0


@pytest.mark.parametrize("char", ["口", "马", "月"])
def test_the_way_into_a_zhe_swells_only_on_the_corner(char):
    # the 横 into a 折 (issue 26.2) is planned its own width (SHOULDER_OVER of its body's) until
    # SHOULDER_SWELL shoulder widths before the corner and swells to the shoulder's from there:
    # a little more than a shoulder width before the corner it is no wider than halfway (main:
    # pressed to the shoulder's over both widths, its belly stood up out of the font there)
    from sim.writing.corners import SHOULDER_OVER, SHOULDER_SWELL
    from sim.writing.feet import _body_width

    (head, head_w), (leg, leg_w) = median_pieces(find_char(char))[1][:2]
    own = SHOULDER_OVER * _body_width(head_w)
    shoulder = max(SHOULDER_OVER * _body_width(leg_w), own)
    d = np.linalg.norm(head - head[-1], axis=1)
    half = (d > 1.2 * shoulder) & (d < 1.4 * shoulder)
    assert SHOULDER_SWELL >= 2.0 and half.any()
    assert head_w[half].max() <= 0.5 * (own + shoulder) + 1e-9


@pytest.mark.slow
def test_a_written_zhe_stands_no_knob_out_of_the_font():
    # 月's 横折 written with the default brush at 512 px (as scripts/shoulders_eval.py reads
    # it): the ink outside the font within 1.5 widths of the corner, a ball on the 横's top
    # before the corner on main (134 px), is under 110 px (83)
    from scripts.shoulders_eval import measure
    from sim.core.recording import DEFAULT_BRUSH

    rows = [r for r in measure(("月", DEFAULT_BRUSH, 512, None, None)) if r[2] == "zhe"]
    assert len(rows) == 1
    assert rows[0][4] < 110
