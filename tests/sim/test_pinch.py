# SPDX-License-Identifier: GPL-3.0-or-later
"""A movement's width does not collapse in its middle (issue 26): a median that cuts across a
corner passes by its inner point, where the distance to the outline, read as the width, falls
to nothing; the brush lifted to its tip there and the ink broke in two (端's 山 imitated from a
picture: 7 pieces where the picture has 6). No Blender."""

import numpy as np

from sim.writing.planner import PINCH_FLOOR, WRITING, _movements, _unpinched, plan


def test_a_pinch_in_the_middle_is_raised_to_the_floor_an_end_that_narrows_is_not():
    pinched = np.array([4.0, 5.0, 5.0, 0.3, 0.2, 0.4, 6.0, 6.0, 5.0])
    got = _unpinched(pinched)
    assert np.all(got[3:6] == PINCH_FLOOR * 5.0)  # the lesser of the widest either side
    assert np.array_equal(got[[0, 1, 2, 6, 7, 8]], pinched[[0, 1, 2, 6, 7, 8]])
    pie = np.linspace(6.0, 0.2, 30)  # a 撇 narrowing to its point; a 捺 widening from its head
    assert np.array_equal(_unpinched(pie), pie)
    assert np.array_equal(_unpinched(pie[::-1]), pie[::-1])
    waist = np.array([5.0, 4.0, 3.0, 3.0, 4.0, 5.0])  # a 横's waist, thinner than its ends
    assert np.array_equal(_unpinched(waist), waist)


def test_a_bevelled_corner_is_written_on_the_belly_not_lifted_to_the_tip():
    # a picture's 竖折 (down, then right: turning the way a 竖弯 turns, read as one movement),
    # 60 wide, its median cutting the corner by a bevel through the corner's inner point
    outline = [(200, 700), (260, 700), (260, 260), (700, 260), (700, 200), (200, 200)]
    path = "M " + " L ".join(f"{x} {y}" for x, y in outline) + " Z"
    ch = {"strokes": [path], "medians": [[[230, 690], [230, 290], [290, 230], [690, 230]]]}
    pl = plan(ch, 60.0, 0.5, font=False)
    body = np.flatnonzero(pl.phase == WRITING)
    assert len(_movements(body)) == 1  # one movement round the bevel
    w = pl.width[body]
    legs = min(float(np.median(w[: len(w) // 4])), float(np.median(w[-len(w) // 4 :])))
    assert legs > 2.0  # mm: the legs read their width (60 of 1024 of 60 mm is 3.5 mm)
    assert w.min() >= PINCH_FLOOR * legs * 0.95  # before: 1.4 mm at the bevel, 0.4 of the legs
