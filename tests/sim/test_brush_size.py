# SPDX-License-Identifier: GPL-3.0-or-later
"""The brush for the size of the writing (sim.writing.brush_size): a recording's 'brush.scale',
the scale the writer picks, the calibration of a scaled brush, and small writing written with
a small brush."""

import numpy as np
import pytest

from sim.cli.main import main
from sim.core.recording import Recording, RecordingError, from_dict, load
from sim.writing.brush_size import brush_for_size, brush_scale_for, sized_brush
from sim.writing.hanzi import find_char
from sim.writing.outline import iou, rasterise
from sim.writing.response import PACE_POWER, calibrate
from sim.writing.writer import auto_size_mm, coverage_mask, write_character


def _template(**brush) -> Recording:
    return Recording(np.zeros((1, 6)), brush={"preset": "wolf_kaishu", **brush})


def test_a_brush_scale_makes_the_preset_smaller_and_a_bad_one_is_named():
    plain = _template().resolve()[1]
    half = _template(scale=0.5).resolve()[1]
    assert half.hair_length_mm == pytest.approx(plain.hair_length_mm / 2)
    assert half.base_radius_mm == pytest.approx(plain.base_radius_mm / 2)
    assert half.belly_diameter_mm == pytest.approx(plain.belly_diameter_mm / 2)
    assert half.belly_loc == plain.belly_loc  # a share of the hair: the same
    # the recording's own geometry is set after the scale
    own = _template(scale=0.5, geometry={"hair_length_mm": 20.0}).resolve()[1]
    assert own.hair_length_mm == 20.0 and own.base_radius_mm == half.base_radius_mm
    d = _template(scale=0.5).to_dict()
    assert from_dict(d).brush["scale"] == 0.5  # kept through the file
    for bad, says in (
        ("big", "must be a number"),
        (float("nan"), "must be finite"),
        (0.1, "must lie in"),
    ):
        with pytest.raises(RecordingError, match=f"'brush.scale' {says}"):
            from_dict({**d, "brush": {"preset": "wolf_kaishu", "scale": bad}})
    with pytest.raises(RecordingError, match="'brush.scale' must lie in"):
        _template(scale=9.0).resolve()


def test_the_writer_takes_a_brush_in_proportion_to_the_size_unless_its_own_is_set():
    assert brush_scale_for(100.0, 100.0) == 1.0
    assert brush_scale_for(95.0, 100.0) == 1.0 and brush_scale_for(108.0, 100.0) == 1.0
    assert brush_scale_for(30.0, 100.0) == 0.3 and brush_scale_for(250.0, 100.0) == 2.5
    assert brush_scale_for(10.0, 100.0) == 0.25 and brush_scale_for(900.0, 100.0) == 4.0
    plain = _template()
    assert sized_brush(plain, 100.0, 104.0) is plain
    assert sized_brush(plain, 40.0, 100.0).brush == {"preset": "wolf_kaishu", "scale": 0.4}
    for own in (_template(scale=0.7), _template(geometry={"hair_length_mm": 20.0})):
        assert sized_brush(own, 40.0, 100.0) is own  # a brush whose size is set is kept


@pytest.mark.slow
def test_a_smaller_brush_is_measured_at_its_own_pace_and_leaves_narrower_bands():
    plain, half = _template(), _template(scale=0.5)
    r1, r2 = calibrate(plain, presses=4), calibrate(half, presses=4)
    assert r2.speed_mm_s == pytest.approx(r1.speed_mm_s * 0.5**PACE_POWER)  # a slower hand
    np.testing.assert_allclose(r2.press_mm, r1.press_mm / 2)
    # the same strokes at half the size: bands about half as wide (the paper does not scale)
    ratio = r2.width_mm[1:] / r1.width_mm[1:]
    assert np.all((ratio > 0.4) & (ratio < 0.65)), ratio
    same, response = brush_for_size(plain, r1, 100.0, 100.0)
    assert same is plain and response is r1


@pytest.mark.slow
def test_a_small_character_is_written_nearer_its_outline_with_a_small_brush(tmp_path):
    ch = find_char("口", "tests/data/unseen")
    plain = _template()
    response = calibrate(plain)
    size, n = 25.0, 128
    natural = auto_size_mm(ch, response)
    sized, r_sized = brush_for_size(plain, response, size, natural)
    assert sized.brush["scale"] == pytest.approx(max(size / natural, 0.25), abs=1e-3)
    font = rasterise(ch, n)
    got = {}
    for name, (tpl, resp) in {"kept": (plain, response), "sized": (sized, r_sized)}.items():
        _, _, sim = write_character(ch, n, tpl, size_mm=size, response=resp, passes=1)
        got[name] = iou(coverage_mask(sim), font)
    # the brush 4 times too large presses the box shut (measured 0.51 against 0.72)
    assert got["sized"] > got["kept"] + 0.1, got
    # the command line writes so by default and keeps the brush with --keep-brush
    for extra, scaled in (([], True), (["--keep-brush"], False)):
        rec = tmp_path / "rec.json"
        argv = ["write", "口", "--data", "tests/data/unseen", "--size", "64", "--passes", "1"]
        argv += ["--size-mm", "25", "-q", "-o", str(tmp_path / "k.png"), "--recording", str(rec)]
        assert main(argv + extra) == 0
        assert ("scale" in load(rec).brush) is scaled


def test_live_painting_presses_a_smaller_brush_as_much_less_deep():
    from sim.engine.live import LiveBrush
    from sim.engine.simulation import Simulation

    pressed = {}
    for scale in (None, 0.5):
        rec = _template() if scale is None else _template(scale=scale)
        rec.samples = np.array([[50.0, 50.0, 40.0, 0.0, 0.0, 0.0]])
        live = LiveBrush(Simulation(rec).run(), press_mm=4.0)
        pressed[scale] = live.press()
    assert pressed == {None: 4.0, 0.5: 2.0}  # the sidebar's Press is the preset brush's
