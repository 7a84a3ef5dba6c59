# SPDX-License-Identifier: GPL-3.0-or-later
"""Strokes that touch in the outline touch in the ink (issue 26, point 2): practice carries a
stroke's free end on until its ink joins a stroke already written that its outline runs into
(``practice._join_error``). No Blender."""

import numpy as np
import pytest

from scripts.picture_real import pieces  # pieces of ink, specks left out
from sim.core.recording import Recording
from sim.writing.hanzi import find_char
from sim.writing.outline import (
    _tips_and_join,
    distance_to_outline,
    median_movements,
    stroke_polygons,
)
from sim.writing.response import calibrate
from sim.writing.writer import coverage_mask, font_mask, write_character

N = 256


@pytest.fixture(scope="module")
def template():
    return Recording(np.zeros((1, 6)), brush={"preset": "wolf_kaishu"}, paper_preset="sized_xuan")


@pytest.fixture(scope="module")
def kaishu_response(template):
    return calibrate(template)


@pytest.mark.parametrize("char", ["人", "日", "相", "北", "好"])
def test_strokes_that_touch_in_the_outline_touch_in_the_ink(template, kaishu_response, char):
    # 人's 捺 sets off from the 撇's side; 日's 横折 from the top of its left vertical; 相's 木
    # has its right dot set beside the vertical (the join is sideways, not along the dot's way
    # out): as many pieces in the ink as in the font (before the joins were practised, one
    # more at 512 px); 北's 撇 and 好's 横撇 end in a point on the stroke they run into, which
    # is written after them (the path goes on into it: ``outline._join_point``)
    ch = find_char(char)
    _rec, _resp, sim = write_character(ch, N, template, response=kaishu_response)
    assert pieces(coverage_mask(sim)) == pieces(font_mask(ch, N))


@pytest.mark.parametrize("char", ["来", "以"])
def test_a_thin_head_is_carried_as_far_as_its_join(template, kaishu_response, char):
    # 来's 捺 sets off from the 竖 beside the 横 with a thin entry whose ink begins short of where
    # it is placed: carried on at most END_MAX (0.6) of its width it stayed 2 px short of the 竖
    # (4 pieces, not 3); so did one of 以's (4, not 3): a joining end goes on as far as its fan
    # sees the join (``practice.JOIN_MAX``)
    ch = find_char(char)
    _rec, _resp, sim = write_character(ch, N, template, response=kaishu_response)
    assert pieces(coverage_mask(sim)) == pieces(font_mask(ch, N))


@pytest.mark.parametrize("size", [320, 512])
def test_a_join_into_a_later_stroke_holds_over_sizes(template, kaishu_response, size):
    # a join is no luck of the size: 好's 横撇 runs into its 竖钩 (written after it) with its
    # belly down (``outline.JOIN_WIDTH``), not a dry broom short of it; with JOIN_WIDTH 0.45 it
    # broke off at 320 and 512 px (3 pieces, not 2)
    ch = find_char("好")
    _rec, _resp, sim = write_character(ch, size, template, response=kaishu_response)
    assert pieces(coverage_mask(sim)) == pieces(font_mask(ch, size))


@pytest.mark.parametrize(("char", "stroke", "into"), [("好", 3, 4), ("北", 3, 4)])
def test_an_end_that_joins_a_stroke_goes_on_into_it(char, stroke, into):
    # the median of 好's 横撇 (北's right 撇) stops short of the 竖钩 (竖弯钩) its outline runs
    # into: the path's end lies inside that stroke, and its last widths do not let go to nothing
    ch = find_char(char)
    polys = stroke_polygons(ch)
    others = polys[:stroke] + polys[stroke + 1 :]
    tipped, joins = _tips_and_join(ch["medians"][stroke], polys[stroke], others)
    assert joins
    assert distance_to_outline(np.asarray(ch["medians"][stroke][-1:], float), polys[into])[0] < 0
    assert distance_to_outline(tipped[-1:], polys[into])[0] > 0
    pieces_ = median_movements(ch)[stroke][0]
    _, width = pieces_[-1]
    assert width[-1] >= 0.4 * np.median(width)


def test_an_end_that_joins_nothing_is_left_as_it_was():
    ch = find_char("一")
    polys = stroke_polygons(ch)
    tipped, joins = _tips_and_join(ch["medians"][0], polys[0], [])
    assert not joins
    assert len(tipped) == len(ch["medians"][0]) + 2
