# SPDX-License-Identifier: GPL-3.0-or-later
"""The non-default presets write the character too (issue 26): a brush dipped in little ink runs
dry along the stroke instead of pressing ever harder and flinging its hair out of the character;
a split soft brush keeps its clumps inside the stroke; the soft goat brush and the dry ink write
a character the outline recognises."""

import numpy as np
import pytest

from sim.brush import dynamics
from sim.brush.primitive import HairyBrush
from sim.core.params import BrushGeometry, QualityParams
from sim.core.recording import Dip, Recording
from sim.engine.simulation import Simulation
from sim.writing.hanzi import find_char
from sim.writing.response import calibrate
from sim.writing.strokes import stroke
from sim.writing.writer import coverage_mask, font_mask, write_character


def _brush(**quality) -> HairyBrush:
    b = HairyBrush(BrushGeometry(), QualityParams(**quality), np.random.default_rng(7))
    b.place([0, 0, 20, 0, 0, 0])
    return b


def test_a_drying_brush_is_no_more_stressed_than_dry_hair():
    """Eq. 10's n / sum(wet) is bounded: an empty brush is as stressed as one whose key points
    hold a third of a soaked one's liquid; a loaded brush is not touched by the bound."""

    def stress(wet):
        b = _brush()
        b.wet[:] = wet
        b.update_stress(np.array([20.0]), np.array([10.0]), 60.0, 1 / 30)
        return float(b.stress[0])

    assert stress(0.0) == pytest.approx(stress(1.0 / dynamics.WET_FACTOR_MAX))
    assert stress(0.0) < 3.5 * stress(0.9)  # bound 20: 22 times a loaded brush's
    assert stress(0.5) == pytest.approx(stress(0.9) * 0.9 / 0.5)  # Eq. 10 itself above it


def test_eq15_squeezes_less_of_the_last_ink():
    """Above W_SQUEEZE Eq. 15 takes its amount; below, in proportion to what the hair holds, so
    the last ink is spent a share at a time."""
    lost = []
    for w in (0.9, dynamics.W_SQUEEZE, 0.5 * dynamics.W_SQUEEZE):
        b = _brush()
        b.wet[:] = w
        b.cc[..., 2] = 0.0
        b.active[:] = b.n - 1
        b.touching[:] = True
        b.gamma[:] = 0.5
        b.contact[:] = 0.0
        b.sweep[:] = 0.0
        b.lose_wetness(1 / 30)
        lost.append(w - float(b.wet[0, -1]))
    assert lost[0] == pytest.approx(lost[1]) and lost[2] == pytest.approx(0.5 * lost[1])


def test_split_children_lie_side_by_side_across_the_stroke_inside_its_width():
    b = _brush(tre=0.1)
    b.travel = np.array([1.0, 0.0])  # writing to the right: the children part along y
    rest = b.cc.copy()
    assert b.split_under(0.45) == 3  # k = 4
    tip = b.cc[:, -1] - rest[0, -1]
    assert np.allclose(tip[:, 0], 0.0) and np.allclose(tip[:, 2], 0.0)  # only across the way
    g = BrushGeometry()
    inside = 0.5 * g.belly_diameter_mm * (1 - 1 / np.sqrt(4))  # a child of a/2 within a
    reach = min(inside, (0.45 - 0.1) * g.base_radius_mm)  # and the paper's (str - tre) r
    assert np.all(np.abs(tip[:, 1]) <= reach + 1e-9)
    assert np.all(np.diff(tip[:, 1]) > 0)  # side by side, in order
    assert np.ptp(tip[:, 1]) > reach  # spread over the width, not bunched


@pytest.mark.slow
def test_a_brush_with_little_ink_runs_dry_along_the_stroke_instead_of_stopping():
    """A half dip of ink at wetness 0.35, pressed deep: its streaks go on to the stroke's end
    (with Eq. 15's squeeze taking the same amount from the driest hair and the pressure rising
    as the brush dried, the ink stopped dead 30 mm into a 90 mm stroke), and none flies further
    from the stroke's path than the pressed belly reaches."""
    rec = Recording(
        np.asarray(stroke([[10, 20], [100, 20]], hair_length_mm=28.0, press_mm=11.8)),
        width_mm=110,
        height_mm=40,
        px_per_mm=5.0,
        brush={"preset": "wolf_kaishu"},
        paper_preset="sized_xuan",
        dips=[Dip(0, 0.5, (0.03, 0.03, 0.04), 0.35)],
    )
    sim = Simulation(rec).run()
    ys, xs = np.nonzero(sim.paper.ink.mean(axis=-1) > 0.05)
    assert xs.max() / 5.0 > 80.0
    assert np.abs(ys / 5.0 - 20.0).max() < BrushGeometry().belly_diameter_mm / 2 + 1.0


def _written(char: str, brush="wolf_kaishu", ink="sumi_black"):
    template = Recording(np.zeros((1, 6)), brush={"preset": brush}, ink={"preset": ink})
    ch = find_char(char)
    rec, _, sim = write_character(ch, 192, template, response=calibrate(template))
    got, want = coverage_mask(sim), font_mask(ch, 192)
    return rec.width_mm, np.count_nonzero(got & want) / np.count_nonzero(got | want)


@pytest.mark.slow
@pytest.mark.parametrize(
    ("brush", "ink", "least"), [("wolf_kaishu", "dry_ink", 0.65), ("goat_soft", "sumi_black", 0.83)]
)
def test_a_non_default_preset_writes_the_character(brush, ink, least):
    """水 (the issue's pictures show 永) with the dry ink and with the soft goat brush: the
    ink matches the outline (before: IoU 0.54 with the dry ink, the brush's flying white read
    as a band 2.4 mm wide, the character written 30 mm tall and pressed to the heel; 0.78 with
    the goat brush, split into a dozen clumps thrown about), and the character is written at
    most 30 % smaller than with the default presets (the size follows the brush's widest solid
    band; since the dry hair lays its ink in lines along the stroke with its outer hair bare
    first, the dry ink's band is 0.74 of the default's: 74 mm against 100; 0.76 before, when a
    dry mark's outer rim was a pale sheet; the old fault wrote it at 30 %)."""
    size, iou = _written("水", brush, ink)
    default_size, _ = _written("水")
    assert iou >= least
    assert size >= 0.7 * default_size
