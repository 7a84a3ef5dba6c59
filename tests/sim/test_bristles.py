# SPDX-License-Identifier: GPL-3.0-or-later
"""The hair bundles of a writing primitive (sim.brush.bristles, issue 26): Eq. 27's draw made per
bundle, the dry brush's streaks along the stroke, the ink spent by what the paper takes (Eq. 15),
the pool where the brush lingers, and a replay that is exact with the bundles' state."""

from dataclasses import replace

import numpy as np
import pytest

from sim.brush import bristles
from sim.brush.primitive import HairyBrush  # noqa: I001 (after the engine: the package's order)
from sim.core.params import BrushGeometry, QualityParams
from sim.core.recording import Dip, Recording
from sim.engine.simulation import Simulation
from sim.fitting.realism import realism
from sim.writing.strokes import stroke


def simulate(samples, wet=0.9, paper="sized_xuan", seed=0, size=(120, 60), ppm=6.0, depth=0.8):
    rec = Recording(
        np.asarray(samples),
        width_mm=size[0],
        height_mm=size[1],
        px_per_mm=ppm,
        seed=seed,
        brush={"preset": "wolf_kaishu"},
        paper_preset=paper,
        dips=[Dip(0, depth, (0.0, 0.0, 0.0), wet)],
    )
    return Simulation(rec).run()


def density(sim):
    """Ink density, top row first."""
    return sim.paper.ink[::-1, :, 0]


def test_a_loaded_bundle_goes_dry_with_eq27s_probability_alone():
    """With the hair loaded (no dryness) a bundle parts when its draw is below
    min(ren ab gamma, 1): over many bundles, that share of them."""
    b = HairyBrush(BrushGeometry(), QualityParams(ren=0.8, ab=0.5), np.random.default_rng(3))
    b._free_state(400)
    b.wet[:] = 0.9
    b.cc[..., 2] = 0.0  # every key point on the paper
    b.touching[:] = True
    b.gamma[:] = 1.0  # Eq. 27: P{Cr = 0} = min(0.8 * 0.5 * 1, 1) = 0.4
    b.step_bundles(0.0, bristles.RAMP_S)  # one full ramp: a dry bundle's gap is open
    parted = b.gap > 0.5
    assert parted.mean() == pytest.approx(0.4, abs=0.03)
    assert np.array_equal(parted, b.hair_u < 0.4)
    b.gamma[:] = 0.0
    b.step_bundles(0.0, bristles.RAMP_S)  # no pressure: every gap closes again
    assert not (b.gap > 0).any()


def test_a_drier_faster_brush_parts_more_bundles():
    b = HairyBrush(BrushGeometry(), QualityParams(), np.random.default_rng(4))
    b._free_state(300)
    b.cc[..., 2] = 0.0
    b.touching[:] = True
    parted = {}
    for wet, speed in ((0.9, 50.0), (0.4, 50.0), (0.4, 150.0)):
        b.wet[:], b.moist[:], b.gap[:] = wet, 0.0, 0.0
        b.step_bundles(speed, bristles.RAMP_S)
        parted[wet, speed] = (b.gap > 0.5).mean()
    assert parted[0.9, 50.0] < 0.02
    assert parted[0.9, 50.0] + 0.1 < parted[0.4, 50.0] < parted[0.4, 150.0] - 0.1


def _straight(speed, press=9.0, y=30.0):
    return stroke([[10, y], [110, y]], press_mm=press, speed_mm_s=speed, hair_length_mm=28.0)


@pytest.mark.slow
def test_a_dry_fast_stroke_leaves_streaks_along_it_a_loaded_one_does_not():
    loaded = realism(simulate(_straight(60), wet=0.9).image())
    dry = realism(simulate(_straight(150), wet=0.3).image())
    # light gaps inside the ink that run along the stroke, not speckle across it
    assert dry.streaks > 0.05 and dry.streaks > 3 * max(loaded.streaks, 0.0)
    assert dry.noise < dry.streaks and dry.specks < 1.0
    # the streaks are gaps the hair leaves, not the paper's: a pixel in one is the paper's
    d = density(simulate(_straight(150), wet=0.3))
    band = d[int(60 * 6.0) - int(30 * 6.0) - 6 : int(60 * 6.0) - int(30 * 6.0) + 6, 200:500]
    assert (band < 0.05).mean() > 0.05


@pytest.mark.slow
def test_the_streaks_follow_a_curved_stroke():
    """Bundles are placed across the path the hair is drawn along (the trail), so on an arc
    the dry streaks bend with it: their structure runs along the stroke there too."""
    t = np.linspace(0.0, np.pi, 40)
    arc = np.stack([60 + 40 * np.cos(t), 15 + 40 * np.sin(t)], axis=1)
    dry = realism(simulate(stroke(arc, press_mm=9.0, speed_mm_s=140), wet=0.3).image())
    assert dry.streaks > 0.05 and dry.streaks > dry.noise


@pytest.mark.slow
def test_the_ink_runs_out_along_a_long_stroke():
    """After a dip the stroke is dark; the paper takes ink from the hair as it goes (Eq. 15
    with what the paper takes), so the last part is paler and more broken."""
    pts = [[10, 50], [110, 50], [110, 38], [10, 38], [10, 26], [110, 26], [110, 14], [10, 14]]
    sim = simulate(stroke(pts, press_mm=9.0, speed_mm_s=70, hair_length_mm=28.0), wet=0.9)
    d = density(sim)
    # the ink laid over each 100 mm leg (its band's mean density): less and less
    laid = [
        float(d[int((60 - y) * 6.0) - 8 : int((60 - y) * 6.0) + 8, 120:560].mean())
        for y in (50, 38, 26, 14)
    ]
    assert laid[0] > laid[1] > laid[2] >= laid[3] and laid[0] > 2 * laid[2]
    assert sim.brush.wet.mean() < 0.3


@pytest.mark.slow
def test_the_ink_pools_where_the_brush_pauses():
    """The same stroke with and without a pause of 0.4 s halfway: where the hair lingers it
    offers more liquid (bristles.POOL), so the ink there is darker."""
    go = _straight(60, press=9.0)
    i = len(go) // 2
    paused = np.concatenate([go[:i], np.repeat(go[i : i + 1], 48, axis=0), go[i:]])
    x = int(go[i, 0] * 6.0)
    dark = {}
    for name, s in (("go", go), ("paused", paused)):
        d = density(simulate(s, wet=0.5))
        spot = d[:, x - 4 : x + 5]
        dark[name] = float(spot[spot > 0.05].mean())
    assert dark["paused"] > dark["go"] + 0.02


@pytest.mark.slow
def test_a_replay_from_a_snapshot_is_exact_with_the_bundles():
    """The bundles' state (draws, gaps, the trail) is in the snapshots: restoring one and
    running on gives the straight run's paper bit for bit."""
    s = _straight(120, press=9.0)
    rec = Recording(
        s,
        width_mm=120,
        height_mm=60,
        px_per_mm=4.0,
        brush={"preset": "wolf_kaishu"},
        dips=[Dip(0, 0.8, (0.0, 0.0, 0.0), 0.35)],
    )
    straight = Simulation(rec).run()
    sim = Simulation(rec)
    sim.run(len(s) // 2)
    snap = sim.snapshot()
    assert np.isfinite(snap["brush"]["trail"]).any() and (snap["brush"]["gap"] > 0).any()
    sim.run()
    sim.restore(snap)
    sim.run()
    assert sim.paper.ink.tobytes() == straight.paper.ink.tobytes()
    assert sim.paper.ink.tobytes() != Simulation(replace(rec, seed=1)).run().paper.ink.tobytes()
