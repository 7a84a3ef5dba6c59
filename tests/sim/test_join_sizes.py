# SPDX-License-Identifier: GPL-3.0-or-later
"""A join is no luck of the size (issue 26, point 2): 好's 横撇 runs into its 竖钩 (written
after it) with its belly down (``outline.JOIN_WIDTH``), not a dry broom short of it, at sizes
where it once broke off. No Blender."""

import numpy as np
import pytest

from scripts.picture_real import pieces  # pieces of ink, specks left out
from sim.core.recording import Recording
from sim.writing.hanzi import find_char
from sim.writing.response import calibrate
from sim.writing.writer import coverage_mask, font_mask, write_character


@pytest.fixture(scope="module")
def template():
    return Recording(np.zeros((1, 6)), brush={"preset": "wolf_kaishu"}, paper_preset="sized_xuan")


@pytest.fixture(scope="module")
def kaishu_response(template):
    return calibrate(template)


@pytest.mark.parametrize("size", [320, 512])
def test_a_join_into_a_later_stroke_holds_over_sizes(template, kaishu_response, size):
    # with JOIN_WIDTH 0.45 the 横撇's end broke off at 320 and 512 px (3 pieces, not 2)
    ch = find_char("好")
    _rec, _resp, sim = write_character(ch, size, template, response=kaishu_response)
    assert pieces(coverage_mask(sim)) == pieces(font_mask(ch, size))
