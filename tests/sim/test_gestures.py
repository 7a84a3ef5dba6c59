# SPDX-License-Identifier: GPL-3.0-or-later
"""Kaishu gestures planned from the stroke data (issue 26, point 2): a 横折's chamfered
shoulder is a corner written by lifting slightly and pressing again, a round bend (转) stays
one movement, a hook sets off from its pressed foot and leaves in a point. No Blender."""

import numpy as np
import pytest

from sim.core.recording import Recording
from sim.writing.hanzi import find_char
from sim.writing.outline import (
    EM,
    TOP,
    corners,
    fill,
    median_pieces,
    resample,
    stroke_polygons,
    to_image,
)
from sim.writing.response import calibrate
from sim.writing.writer import coverage_mask, write_character

# a 横折 whose median cuts across its shoulder, as most of the font's do (口, 日, 永, 墨's 罒):
# along the horizontal, a short diagonal, then down
ZHE = [[100, 600], [500, 600], [530, 570], [530, 150]]
# a 竖弯 (down, a short bend, then on to the right): the same shape turning the other way
WAN = [[200, 700], [200, 300], [230, 270], [630, 270]]


def _template(**kw):
    return Recording(np.zeros((1, 6)), brush={"preset": "wolf_stiff"}, paper_preset="smooth", **kw)


@pytest.fixture(scope="module")
def response():
    return calibrate(_template())


def test_a_chamfered_shoulder_is_a_corner_but_a_round_bend_is_not():
    pts, _ = resample(ZHE, 4.0)
    found = corners(pts, 4.0)
    assert len(found) == 1
    assert np.linalg.norm(pts[found[0]] - [515.0, 585.0]) < 25.0  # on the chamfer
    assert corners(pts, 4.0, chamfered=False) == []  # read over one window: no corner
    bend, _ = resample(WAN, 4.0)
    assert corners(bend, 4.0) == []  # counter-clockwise: a 竖弯's round turn (转)
    arc = np.stack(
        [400 * np.cos(np.linspace(0, 1.6, 60)), 400 * np.sin(np.linspace(0, 1.6, 60))], 1
    )
    arc, _ = resample(arc[::-1], 4.0)
    assert corners(arc, 4.0) == []  # a gentle curve, clockwise
    # the font's: 永's 横折钩 is three movements (horizontal, leg, hook); 口's and 墨's 横折 two
    assert len(median_pieces(find_char("永"))[1]) == 3


def test_a_hook_sets_off_from_the_foot_and_narrows_to_its_point():
    # 永's 竖钩: the hook sets off from the middle of the foot (HOOK_FROM_FOOT of the way from
    # the median's corner at (478, 24) down to where the leg ended in the foot), planned as
    # wide as the vertical there, and its width falls to the tip
    from sim.writing.outline import HOOK_FROM_FOOT

    (_, _), (leg, leg_w), (hook, hook_w) = median_pieces(find_char("永"))[1]
    corner = np.array([478.0, 24.0])
    want = corner + HOOK_FROM_FOOT * (leg[-1] - corner)
    assert np.linalg.norm(hook[0] - want) < 12.0  # (the band's centre, off the path a little)
    assert hook[0][1] < corner[1] - 10.0  # in the foot, below the corner
    assert hook_w[0] > 0.9 * float(np.median(leg_w))  # as wide as the vertical
    assert hook_w[-1] < 0.3 * hook_w[0]


def test_a_zhe_turning_back_into_a_long_leg_is_no_hook():
    # 也's 横折钩: its 折 turns back by more than a right angle into a leg about two widths
    # long, but the leg goes on into the hook: it starts on the corner, not from a foot
    pieces = median_pieces(find_char("也"))[0]
    assert len(pieces) >= 2
    (first, _), (leg, _) = pieces[0], pieces[1]
    assert np.linalg.norm(leg[0] - first[-1]) > 10.0


def _own(ch, k, n):
    return fill([to_image(p, n) for p in stroke_polygons(ch)[k]], n)


def _img(p, n):
    return np.array([p[0] * n / EM, (TOP - p[1]) * n / EM])


@pytest.mark.slow
def test_a_written_hook_fills_its_triangle_out_to_a_point(response):
    # 永's hook: the ink covers the outline's triangle from the foot to the point (from the
    # corner above the foot it covered only a band along the triangle's upper edge, over a
    # round bulb), and near its end it is much narrower than the vertical
    ch = find_char("永")
    n = 256
    _, _, sim = write_character(ch, n, _template(), response=response, passes=1)
    ink = coverage_mask(sim)
    own = _own(ch, 1, n)
    leg_left = _img([490.0, 0.0], n)[0] - 0.5 * 60 * n / EM  # the vertical's left edge
    rows = slice(int(_img([0, 110], n)[1]), int(_img([0, -40], n)[1]))
    tri = own[rows].copy()
    tri[:, int(leg_left) :] = False  # the hook's triangle, left of the vertical
    covered = np.count_nonzero(tri & ink[rows]) / np.count_nonzero(tri)
    assert covered > 0.7
    # across the hook near its tip (the last fifth, on the median from the corner to the tip)
    med = np.array(ch["medians"][1], dtype=float)
    tip, corner = _img(med[-1], n), _img(med[-2], n)
    d = (tip - corner) / np.linalg.norm(tip - corner)
    nrm = np.array([-d[1], d[0]])
    near = corner + 0.85 * (tip - corner)
    off = np.arange(-15, 16)
    xy = np.round(near[None] + off[:, None] * nrm[None]).astype(int)
    across = int(np.count_nonzero(ink[xy[:, 1], xy[:, 0]]))
    mid = _img([505.0, 300.0], n).astype(int)
    leg = int(np.count_nonzero(ink[mid[1], mid[0] - 20 : mid[0] + 20]))
    assert leg > 8 and across < 0.45 * leg


@pytest.mark.slow
def test_a_written_zhe_keeps_its_shoulder_without_a_knob(response):
    # 墨's 罒: the 横折's shoulder is filled out to the outline's outer corner (as one
    # sweeping movement the pressed belly rounded it off inside: a round knob that missed 8 %
    # of it), and the ink bulges out of the outline there hardly more than along the straight
    # of the same stroke (the brush's band is a little wider than the font's at one pass)
    from scipy.ndimage import distance_transform_edt

    ch = find_char("墨")
    n = 256
    _, _, sim = write_character(ch, n, _template(), response=response, passes=1)
    ink = coverage_mask(sim)
    every = np.zeros_like(ink)
    for k in range(len(ch["strokes"])):
        every |= _own(ch, k, n)
    outside = distance_transform_edt(~every)

    def window(x, y):
        c = _img([x, y], n).astype(int)
        return slice(c[1] - 10, c[1] + 10), slice(c[0] - 10, c[0] + 10)

    shoulder, straight = window(745.0, 770.0), window(550.0, 800.0)
    missed = np.count_nonzero(every[shoulder] & ~ink[shoulder])
    assert missed < 0.05 * np.count_nonzero(every[shoulder])
    bulge = outside[shoulder][ink[shoulder]].max()
    assert bulge < outside[straight][ink[straight]].max() + 2.0
