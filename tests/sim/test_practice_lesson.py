# SPDX-License-Identifier: GPL-3.0-or-later
"""The practice's lesson (issue 28): what practice settled on for the strokes written so far
presses the next stroke's first pass, so it begins nearer its width. No Blender."""

import numpy as np

from sim.writing import practice, writer
from sim.writing.hanzi import find_char
from sim.writing.response import Response
from tests.sim.builders import stiff_template


def _linear_response() -> Response:
    press = np.linspace(1.0, 11.0, 11)
    return Response(press, press.copy(), np.zeros(11), 60.0)  # a band as wide as the press


def test_a_lesson_widens_the_steady_body_by_what_practice_settled_on():
    resp, lesson = _linear_response(), practice.Lesson()
    want = np.full(50, 5.0)
    steady = np.ones(50, dtype=bool)
    steady[:5] = False  # the entry keeps its width
    assert np.array_equal(lesson.widen(want, steady), want)  # nothing taught yet
    settled = np.where(np.arange(50) < 25, 5.0, 5.5)  # the back half pressed 10 % wider
    lesson.learn(resp, settled, want, steady)
    got = lesson.widen(want, steady)
    assert np.array_equal(got[:5], want[:5])
    assert np.allclose(got[5:20], 5.0)
    assert np.allclose(got[30:], 5.5)


def _first_pass_errors(monkeypatch, response, taught: bool) -> list[float]:
    """The mean width error (mm, band less plan) over the steady body of each stroke's first
    pass, 山 written with two passes at 96 px; without ``taught`` every first pass is pressed
    for the plan's width (as before the lesson)."""
    firsts, stroke = {}, [None]
    practise, correct = practice._practise_stroke, practice._correct

    def spy_stroke(sim, a, *rest):
        stroke[0] = a
        return practise(sim, a, *rest)

    def spy_correct(resp, placed, want, band, ceiling, zones):
        if stroke[0] not in firsts:  # the first correction reads the first pass
            got, _, valid = band
            use = valid & ~zones[0] & ~zones[1] & (got > 0)
            firsts[stroke[0]] = float(np.mean(got[use] - want[use]))
        return correct(resp, placed, want, band, ceiling, zones)

    monkeypatch.setattr(writer, "_practise_stroke", spy_stroke)
    monkeypatch.setattr(practice, "_correct", spy_correct)
    if not taught:
        monkeypatch.setattr(practice.Lesson, "widen", lambda self, want, steady: want)
    writer.write_character(find_char("山"), 96, stiff_template(), response=response, passes=2)
    monkeypatch.undo()
    return [firsts[a] for a in sorted(firsts)]


def test_a_later_stroke_begins_nearer_its_width(monkeypatch, response):
    # the stiff brush's first pass is too wide; the strokes after the first are pressed as
    # practice settled the first, and begin nearer their width
    plain = _first_pass_errors(monkeypatch, response, taught=False)
    taught = _first_pass_errors(monkeypatch, response, taught=True)
    assert len(plain) == len(taught) == 3
    assert taught[0] == plain[0]  # the first stroke: nothing taught yet
    assert all(e > 0.1 for e in plain[1:])
    assert sum(abs(e) for e in taught[1:]) < 0.7 * sum(abs(e) for e in plain[1:])
