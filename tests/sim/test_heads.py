# SPDX-License-Identifier: GPL-3.0-or-later
"""Stroke heads (issue 26, point 2: the tip lands, the belly presses, no knobs at entries).
No Blender."""

import numpy as np

from sim.writing.hanzi import find_char
from sim.writing.planner import WRITING, _movements, plan
from sim.writing.zones import entry_zone
from tests.sim.builders import filled_stroke


def _written(pl, response, stroke, side):
    """The brush's base (x, y) per body sample of ``stroke`` of plan ``pl`` filled at the
    planned press with the sideways placement ``side(n)`` (n body samples), and the body."""
    samples, body = filled_stroke(pl, response, stroke, side=side)
    return samples[body, :2], body


def test_a_head_is_placed_sideways_as_the_stroke_past_it(response):
    # 水's 竖钩 and 六's 撇: practice leaves an entry's sideways placement alone (it does not
    # follow the head's band) and corrects the rest of the stroke; the head is written as far
    # to the side as the first sample past the entry (before, the head kept none: the belly
    # landed off the stroke to the side the hair lays its ink, a knob beyond the outline)
    for char, stroke in (("水", 0), ("六", 2)):
        pl = plan(find_char(char), 100.0, 0.5)
        a, b = pl.strokes[stroke]
        body = np.flatnonzero(pl.phase[a:b] == WRITING) + a
        zone = entry_zone(pl, body)
        first = _movements(np.arange(len(body)), body)[0]
        head = zone & (np.arange(len(body)) <= first[-1])
        past = int(np.argmin(zone))  # the first sample past the first movement's entry
        assert head.sum() >= 4 and past > 0

        def practised(n, head=head):  # practice's reading: none at the entry, 0.6 mm past it
            return np.where(head, 0.0, 0.6)

        plain, _ = _written(pl, response, stroke, np.zeros)
        moved, _ = _written(pl, response, stroke, practised)
        normal = np.stack([-pl.tangent[body, 1], pl.tangent[body, 0]], axis=1)
        shift = np.sum((moved - plain) * normal, axis=1)
        assert np.allclose(shift[head], 0.6, atol=1e-3)
        assert np.allclose(shift[past:], 0.6, atol=1e-3)


def _entry(pl, response, stroke, run_up):
    """The base's (x, y) over the entry of ``stroke`` of plan ``pl`` (the samples before its
    first body sample that come down onto it) and the stroke's start and way (unit)."""
    samples, body = filled_stroke(pl, response, stroke, run_up)
    run = _movements(body)[0]
    way = pl.target[run[-1]] - pl.target[run[0]]
    a = pl.strokes[stroke][0]
    return samples[a : body[0], :2], samples[body[0], :2], way / np.linalg.norm(way)


def test_a_stroke_that_sets_off_down_hides_its_tip(response):
    # 十's 竖 and 八's 撇 are entered against their way (藏锋): the entry comes down from
    # inside the stroke, so the landing tip trails into it, not out behind the head as a beak
    # (before, every head's entry came from behind); 十's 横 and 八's 捺 land moving on (露锋:
    # the font's 横 head is its point, and a 捺 sets off thin, ``_narrow_head``); imitating a
    # picture (run-up 0) lands on the start
    cases = (("十", 1, 1.0), ("八", 0, 1.0), ("八", 1, -1.0), ("十", 0, -1.0))
    for char, stroke, side in cases:
        pl = plan(find_char(char), 100.0, 0.5)
        entry, start, way = _entry(pl, response, stroke, 1.0)
        ahead = (entry - start) @ way
        assert len(ahead) >= 4 and np.all(side * ahead[:-1] > 0.1), (char, stroke, ahead)
        entry, start, _ = _entry(pl, response, stroke, 0.0)
        assert np.allclose(entry, start, atol=1e-3)


def test_landing_hair_lies_back_along_the_way_the_brush_moves():
    # the brush comes down moving along +x, its hair sprung back nearly straight after the last
    # stroke's flick (a hundredth of a millimetre to the side at the tip): the tip lands and
    # lies back along the way the base goes, as friction holds it (before, it lay the way its
    # hundredth of a bend pointed: a thread of hair out of the side of 朋's inner 横's head);
    # one primitive (the walk on floats) as two (the arrays' walk)
    from tests.sim.builders import long_stroke, simulation

    tips = []
    for m in (1, 2):
        brush = simulation(long_stroke()[:2], 64, 1.0, primitives=m).brush
        hair = brush.L
        brush.place(np.array([20.0, 20.0, hair + 0.3, 0.0, 0.0, 0.0]))
        brush.touching[:] = False
        brush.cc[..., 1] += 0.01 * brush.sarc / hair
        pose = np.array([20.5, 20.0, hair - 1.0, 0.0, 0.0, 0.0])
        brush.move(pose, np.array([60.0, 0.0, -120.0, 0.0, 0.0, 0.0]), 1.0 / 120.0)
        tip = brush.cc[:, -1]
        assert np.all(tip[:, 2] == 0.0)  # on the paper
        assert np.all(tip[:, 0] < pose[0] - 0.5)  # behind the base
        assert np.all(np.abs(tip[:, 1] - pose[1]) < 0.05)  # not off to the side
        tips.append(tip[0])
    assert tips[0].tobytes() == tips[1].tobytes()


def test_a_hidden_tip_head_turns_in_its_cap(response):
    # 十's 竖 and 八's 撇 (entered against their way, 藏锋): the base goes on up past the
    # median's start into the cap before it turns and presses down, and is back on the planned
    # path past the entry's ramp (before, it turned on the median's start and the tip trailed
    # into the stroke: the cap above it stayed bare, 村's 竖 about 8 px short at its top);
    # 十's 横 (tip showing) and a picture's imitation (run-up 0) start on the median
    for char, stroke, run_up, reach in (
        ("十", 1, 1.0, True),
        ("八", 0, 1.0, True),
        ("十", 0, 1.0, False),
        ("十", 1, 0.0, False),
    ):
        pl = plan(find_char(char), 100.0, 0.5)
        samples, body = filled_stroke(pl, response, stroke, run_up)
        way = pl.tangent[body[0]]
        back = (pl.target[body[0]] - samples[body[0], :2]) @ way
        if reach:
            assert 0.2 * pl.width[body[0]] < back < 0.5 * pl.width[body[0]], (char, stroke)
            assert np.all(np.diff((samples[body[:8], :2] - samples[body[0], :2]) @ way) > 0.0)
        else:
            assert abs(back) < 1e-4, (char, stroke, run_up)


def test_a_na_sets_off_thin_and_lands_on_its_tip():
    # a 捺's head is a point in the outline (its first widths a fifth of its widest): it lands
    # moving on (露锋, ``_narrow_head``); every other stroke of these characters (横, 竖, 撇)
    # has a round or pressed head and keeps its landing (before: every stroke heading down hid
    # its tip, and the 捺's head was a round knob beside the 撇 it sets off from: 人's head
    # 197 px of ink outside the font, 125 with the tip landing on the point)
    from sim.writing.planner import _narrow_head

    for char in "人八大天又入长水":
        pl = plan(find_char(char), 100.0, 0.5)
        narrow = []
        for a, b in pl.strokes:
            body = np.flatnonzero(pl.phase[a:b] == WRITING) + a
            narrow.append(_narrow_head(pl.width[_movements(body)[0]]))
        assert narrow == [k == len(pl.strokes) - 1 for k in range(len(pl.strokes))], char


def test_a_head_opening_from_a_point_is_not_lifted_to_a_neck_after_its_tip():
    # practice corrects each sample on its own: at a pointed head (長's long 横 imitated from a
    # copybook) it pressed the tip down (its band read narrow) and lifted just after it (the
    # tip's blob spread into the band there): a drop at the tip, a bare neck, then the stroke.
    # Where the planned width keeps widening the press keeps NECK of the deepest before it
    from sim.writing.zones import NECK, rising_heads

    want = np.r_[np.linspace(0.8, 6.7, 20), np.full(10, 6.7), np.linspace(6.7, 5.0, 10)]
    press = np.r_[
        [3.25, 3.3, 3.39, 3.16, 2.78, 2.26, 1.63, 0.92, 0.66, 0.66],
        np.linspace(1.0, 7.4, 10),
        np.full(10, 7.3),
        np.linspace(7.3, 5.5, 10),
    ]
    got = rising_heads(press, want, [np.arange(40)])
    head = got[:20]
    assert np.all(head >= NECK * np.maximum.accumulate(press[:20]) - 1e-12)
    assert head[8] == NECK * 3.39 > press[8]  # the neck pressed on, ...
    assert np.array_equal(head[:6], press[:6])  # ... the tip as practice left it
    assert np.array_equal(got[20:], press[20:])  # and the rest of the stroke
    flat = np.full(12, 5.0)  # a blunt head: its width does not open, its press is its own
    wavy = np.r_[4.0, 1.0, 4.5, 1.5, np.full(8, 4.0)]
    assert np.array_equal(rising_heads(wavy, flat, [np.arange(12)]), wavy)
