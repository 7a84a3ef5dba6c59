# SPDX-License-Identifier: GPL-3.0-or-later
"""Issue 16: the model's texture mechanisms and the writer's clean entries, asserted on
outcomes (not on timings)."""

import numpy as np
import pytest

from sim.core.recording import Dip, Recording
from sim.engine.simulation import Simulation
from sim.fitting.texture import texture_stats
from sim.paper.paper import paper_grain
from sim.writing.strokes import stroke


def test_paper_grain_is_fixed_and_spread():
    idx = np.arange(200_000)
    g = paper_grain(idx)
    assert np.array_equal(g, paper_grain(idx.copy()))  # the same pixel, the same grain
    assert 0.0 <= g.min() and g.max() < 1.0 and abs(g.mean() - 0.5) < 0.01
    assert abs(np.corrcoef(g[:-1], g[1:])[0, 1]) < 0.02  # neighbours independent


def _fibre_stroke(fibre: float, wetness: float = 0.9):
    """A straight pressed stroke of the stiff wolf brush on smooth paper with this fibre."""
    s = stroke([[10.0, 20.0], [70.0, 20.0]], press_mm=10.0, hair_length_mm=28.0)
    rec = Recording(
        s,
        width_mm=80.0,
        height_mm=40.0,
        px_per_mm=6.0,
        brush={"preset": "wolf_stiff"},
        paper_preset="smooth",
        paper_overrides={"fibre": fibre},
        dips=[Dip(0, 1.0, (0.0, 0.0, 0.0), wetness)],
    )
    return Simulation(rec).run()


@pytest.mark.slow
def test_the_grain_shows_in_a_dry_strokes_grey_more_than_in_a_loaded_ones_black():
    # the same stroke, seed and draws: the sheet's grain (paper_grain, scaled by the paper's
    # fibre) changes the offer a pixel takes; where the ink is thin it shows pixel to pixel,
    # where the hair is loaded the colour saturates and it hardly does
    rough = {}
    for wetness in (0.9, 0.35):
        for fibre in (0.0, 0.8):
            ink = _fibre_stroke(fibre, wetness).paper.ink[..., 0]
            mid = ink[1:-1, 1:-1]
            ring = (ink[:-2, 1:-1], ink[2:, 1:-1], ink[1:-1, :-2], ink[1:-1, 2:])
            core = (mid > 0.3) & np.logical_and.reduce([r > 0.3 for r in ring])
            rough[wetness, fibre] = float(np.abs(mid - 0.25 * sum(ring))[core].mean())
    added = {w: rough[w, 0.8] - rough[w, 0.0] for w in (0.9, 0.35)}
    assert added[0.35] > 0.005 and added[0.35] > 2 * added[0.9]


def test_qp2_stage_adds_the_texture_term():
    # Sec. 7.2's texture class: in the Qp2 stage the fit's target adds the distance of the
    # result's five statistics from real writing's; the shape stage is Eq. 28 alone
    from sim.fitting.samples import TrainingSample
    from sim.fitting.target import TEXTURE_WEIGHT, render, target_function
    from sim.fitting.texture import score

    s = stroke([[8, 12], [36, 18]], press_mm=9.0, speed_mm_s=70, hover_mm=4.0)
    rec = Recording(s, width_mm=44, height_mm=30, px_per_mm=3.0, brush={"preset": "wolf_stiff"})
    img = render(rec, {})
    samples = [TrainingSample(rec, img, kind="both")]
    assert target_function({}, samples, "qp1") == 0.0
    want = TEXTURE_WEIGHT * (1.0 - score(texture_stats(img)))
    assert want > 0.0
    assert target_function({}, samples, "qp2") == want


def test_the_papers_grain_is_the_recordings_seeds_sheet():
    from sim.paper.paper import paper_grain

    idx = np.arange(10_000)
    a, b = paper_grain(idx, 0), paper_grain(idx, 7)
    np.testing.assert_array_equal(a, paper_grain(idx, 0))  # the same sheet every time
    assert np.mean(a != b) > 0.99  # another seed, another sheet
    assert 0.45 < a.mean() < 0.55 and a.min() >= 0.0 and a.max() < 1.0


@pytest.mark.slow
def test_fit_keeps_a_parameter_inside_its_bound():
    # the truth (e = 0.3) and the seed (0.7) lie below the bound e in [0.75, 0.8]: the bounded
    # fit stays inside it, the unbounded one does not go there; a bad bound is one message
    import pytest

    from sim.core.params import QP2, ParameterError
    from sim.fitting.samples import TrainingSample
    from sim.fitting.search import FitSettings, fit
    from sim.fitting.target import render

    known = {"e": 0.3, **{k: 0.0 for k in QP2}}
    s = stroke([[8, 12], [36, 16]], press_mm=9.0, speed_mm_s=70, hover_mm=4.0)
    rec = Recording(s, width_mm=44, height_mm=30, px_per_mm=1.2, brush={"preset": "wolf_stiff"})
    samples = [TrainingSample(rec, render(rec, known), kind="shape")]
    seed = {"e": 0.7, **{k: 0.0 for k in QP2}}
    kw = dict(divisions=2, rounds=2, iterations=3, workers=1, stages=("qp1",), only=("e",))
    bounded = fit(samples, seed, FitSettings(**kw, bounds={"e": (0.75, 0.8)})).quality["e"]
    free = fit(samples, seed, FitSettings(**kw)).quality["e"]
    assert 0.75 <= bounded <= 0.8 and free < 0.75
    with pytest.raises(ParameterError, match="bounds"):
        FitSettings(bounds={"e": (0.9, 0.2)})
    with pytest.raises(ParameterError, match="bounds"):
        FitSettings(bounds={"xyz": (0.0, 1.0)})
    for bad in ({"e": (0.5, 0.5)}, {"e": 0.5}, {"e": (0.1, 0.2, 0.3)}, [("e", (0, 1))]):
        with pytest.raises(ParameterError, match="bounds"):
            FitSettings(bounds=bad)


def test_the_fitted_quality_preset_is_what_the_default_brush_and_paper_carry():
    # one fit, two homes for its numbers (a quality preset, and the default presets' own
    # values): they must not drift apart
    from sim.core.params import QualityParams, load_preset, quality_from_presets
    from sim.core.recording import DEFAULT_BRUSH, DEFAULT_PAPER

    fitted = load_preset("quality", "kaishu_fit").data["quality"]
    carried = QualityParams().with_values(
        quality_from_presets(
            load_preset("brush", DEFAULT_BRUSH), load_preset("paper", DEFAULT_PAPER)
        )
    )
    assert fitted == {k: getattr(carried, k) for k in fitted}
    assert set(fitted) == set(QualityParams.names()) and fitted["e"] < 1.0  # texture on
