# SPDX-License-Identifier: GPL-3.0-or-later
"""Strokes that touch in the outline touch in the ink (issue 26, point 2): practice carries a
stroke's free end on until its ink joins a stroke already written that its outline runs into
(``practice._join_error``). No Blender."""

import numpy as np
import pytest

from scripts.picture_real import pieces  # pieces of ink, specks left out
from sim.core.recording import Recording
from sim.writing.hanzi import find_char
from sim.writing.response import calibrate
from sim.writing.writer import coverage_mask, font_mask, write_character

N = 256


@pytest.fixture(scope="module")
def template():
    return Recording(np.zeros((1, 6)), brush={"preset": "wolf_kaishu"}, paper_preset="sized_xuan")


@pytest.fixture(scope="module")
def kaishu_response(template):
    return calibrate(template)


@pytest.mark.parametrize("char", ["人", "日", "相"])
def test_strokes_that_touch_in_the_outline_touch_in_the_ink(template, kaishu_response, char):
    # 人's 捺 sets off from the 撇's side; 日's 横折 from the top of its left vertical; 相's 木
    # has its right dot set beside the vertical (the join is sideways, not along the dot's way
    # out): as many pieces in the ink as in the font (before the joins were practised, one
    # more at 512 px)
    ch = find_char(char)
    _rec, _resp, sim = write_character(ch, N, template, response=kaishu_response)
    assert pieces(coverage_mask(sim)) == pieces(font_mask(ch, N))
