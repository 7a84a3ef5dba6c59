# SPDX-License-Identifier: GPL-3.0-or-later
"""Practice passes (issue 28): a later pass is written again only from the last hold before the
first sample its correction changes, bit for bit as the pass written from the stroke's start; a
pass its correction does not change is not written at all; practice ends once a pass gains
little. No Blender."""

import numpy as np
import pytest

from sim.writing import practice
from sim.writing.hanzi import find_char
from sim.writing.writer import write_character
from tests.sim.builders import stiff_template

_template = stiff_template  # the stiff wolf brush on smooth paper (conftest: response)


def _write(ch, response, passes, exact_ends=False):
    rec, _, sim = write_character(
        ch, 96, _template(), response=response, passes=passes, exact_ends=exact_ends
    )
    paper = sim.paper  # the whole state of the sheet: not only the image, which may hide a step
    return rec.samples.copy(), sim.image8(), paper.ink, paper.wet, paper.last


def _spy_take_back(monkeypatch) -> list:
    """The sample every take-back goes back to, in order."""
    begun = []
    take_back = practice.Simulation.take_back

    def spy(sim, hold):
        begun.append(hold["index"])
        return take_back(sim, hold)

    monkeypatch.setattr(practice.Simulation, "take_back", spy)
    return begun


def _spy_passes(monkeypatch) -> list:
    """Every pass's end: the sheet's whole state (not only the image, which may hide a step)
    and the band's readings."""
    ends = []
    practise = practice._practise

    def spy(sim, start, rd, probes, band, holds):
        practise(sim, start, rd, probes, band, holds)
        p = sim.paper
        ends.append([x.copy() for x in (p.ink, p.wet, p.last, *band)])

    monkeypatch.setattr(practice, "_practise", spy)
    return ends


@pytest.mark.slow
@pytest.mark.parametrize("exact_ends", [False, True])
def test_a_pass_begun_at_a_hold_is_the_pass_written_from_the_start(
    response, monkeypatch, exact_ends
):
    # the corrections kept to the second half of each stroke: later passes begin mid-stroke
    correct = practice._correct

    def late(response, placed, *args):
        p, s = correct(response, placed, *args)
        half = len(p) // 2
        p[:half], s[:half] = placed[0][:half], placed[1][:half]
        return p, s

    monkeypatch.setattr(practice, "_correct", late)
    monkeypatch.setattr(practice, "SMALL_GAIN", -np.inf)  # every pass written
    ch = find_char("十")
    starts = [a for a, _ in _stroke_spans(ch, response)]
    begun = _spy_take_back(monkeypatch)
    passes = _spy_passes(monkeypatch)
    held = _write(ch, response, 3, exact_ends)
    held_passes, resumed = list(passes), [i for i in begun if i not in starts]
    monkeypatch.setattr(practice, "HOLD_EVERY", 10**9)  # every pass from the stroke's start
    begun.clear()
    passes.clear()
    whole = _write(ch, response, 3, exact_ends)
    assert resumed  # some passes did begin mid-stroke, at a hold
    assert set(begun) <= set(starts)  # and here every pass began at its stroke's start
    assert len(held_passes) == len(passes) == 3 * len(starts)
    for a, b in zip(held_passes + [held], passes + [whole], strict=True):
        for x, y in zip(a, b, strict=True):  # every pass's end, and the result
            assert x.tobytes() == y.tobytes()


def _stroke_spans(ch, response):
    from sim.writing.planner import plan
    from sim.writing.writer import auto_size_mm

    step_mm = response.speed_mm_s / _template().sample_rate_hz
    return plan(ch, auto_size_mm(ch, response), step_mm, None).strokes


@pytest.mark.slow
def test_a_pass_its_correction_does_not_change_is_not_written_again(response, monkeypatch):
    # no correction: every pass the first again, which is written once, as with one pass
    monkeypatch.setattr(practice, "_correct", lambda response, placed, *args: placed)
    monkeypatch.setattr(practice, "SMALL_GAIN", -np.inf)  # every pass written (or not)
    ch = find_char("十")
    begun = _spy_take_back(monkeypatch)
    once = _write(ch, response, 1)
    for a, b in zip(_write(ch, response, 4), once, strict=True):
        assert a.tobytes() == b.tobytes()
    assert begun == []  # nothing taken back: no pass written twice


@pytest.mark.slow
def test_practice_ends_when_a_pass_gains_little(response, monkeypatch):
    ch = find_char("十")
    passes = _spy_passes(monkeypatch)
    monkeypatch.setattr(practice, "SMALL_GAIN", -np.inf)  # never: every pass written
    _write(ch, response, 4)
    assert len(passes) == 4 * 2
    twice = _write(ch, response, 2)
    passes.clear()
    monkeypatch.setattr(practice, "SMALL_GAIN_FROM", 1)
    monkeypatch.setattr(practice, "SMALL_GAIN", 1.0)  # the second pass can never gain enough
    ended = _write(ch, response, 4)
    assert len(passes) == 2 * 2  # practice ended after the second pass of each stroke
    for a, b in zip(ended, twice, strict=True):  # as if two passes had been asked for
        assert a.tobytes() == b.tobytes()
    passes.clear()
    _write(ch, response, 4, exact_ends=True)  # imitating a picture: every pass written
    assert len(passes) == 4 * 2
