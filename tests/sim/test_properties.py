# SPDX-License-Identifier: GPL-3.0-or-later
"""Invariants under random strokes and random quality parameters (hypothesis)."""

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from sim.brush.primitive import HairyBrush
from sim.core.params import BrushGeometry, QualityParams
from sim.core.recording import Dip, Recording
from sim.engine.simulation import Simulation
from sim.writing.strokes import stroke

unit = st.floats(0.0, 1.0)
quality = st.fixed_dictionaries({k: unit for k in QualityParams.names()})
SETTINGS = dict(max_examples=12, deadline=None, suppress_health_check=[HealthCheck.too_slow])


def random_recording(q, x1, y1, press, speed, wet, tilt, seed):
    s = stroke(
        [[15, 15], [x1, y1]],
        press_mm=press,
        speed_mm_s=speed,
        hair_length_mm=30,
        tilt=(tilt, -tilt / 2, tilt * 3),
    )
    return Recording(
        s,
        width_mm=60,
        height_mm=40,
        px_per_mm=3,
        seed=seed,
        quality=q,
        dips=[Dip(0, 0.8, (0.2, 0.1, 0.0), wet)],
    )


stroke_args = dict(
    q=quality,
    x1=st.floats(20, 50),
    y1=st.floats(5, 35),
    press=st.floats(0, 22),
    speed=st.floats(10, 250),
    wet=unit,
    tilt=st.floats(-30, 30),
    seed=st.integers(0, 2**32),
)


@pytest.mark.slow
@settings(**SETTINGS)
@given(**stroke_args)
def test_wetness_colour_in_range_and_hair_never_through_the_paper(
    q, x1, y1, press, speed, wet, tilt, seed
):
    sim = Simulation(random_recording(q, x1, y1, press, speed, wet, tilt, seed))
    area0 = None
    while not sim.done:
        sim.step()
        b = sim.brush
        if area0 is None:
            area0 = b.hair_area()
        assert np.all(b.cc[..., 2] >= 0.0)  # recovery and deformation never pass psi
        assert np.all((b.wet >= 0) & (b.wet <= 1.0 + 1e-9))
        assert np.all((b.col >= 0) & (b.col <= 1.0 + 1e-9))
        assert abs(b.hair_area() - area0) < 1e-6 * area0  # splits keep the hair (Eq. 19)
        assert np.all(np.isfinite(b.cc))
    p = sim.paper
    assert np.all(p.wet >= 0) and np.all(np.isfinite(p.wet))
    assert np.all((p.ink >= 0) & (p.ink <= 1.0))
    img = sim.image()
    assert np.all((img >= 0) & (img <= 1))


@settings(**SETTINGS)
@given(stress=st.floats(0, 20), tre=st.floats(0, 1), m0=st.integers(1, 3))
def test_split_conserves_hair_area(stress, tre, m0):
    b = HairyBrush(BrushGeometry(), QualityParams(tre=tre), np.random.default_rng(1))
    b.place([0, 0, 20, 0, 0, 0])
    if m0 > 1:  # 2 m0 primitives to begin with
        b.q = QualityParams(tre=1.0 / m0)
        b.split_under(2.0)
        b.q = QualityParams(tre=tre)
    area = b.hair_area()
    b.split_under(stress)
    assert abs(b.hair_area() - area) < 1e-9 * area
    assert b.m <= 32
    assert b.cc.shape == (b.m, b.n, 3)


@pytest.mark.slow
@settings(max_examples=5, deadline=None)
@given(**stroke_args)
def test_replay_is_deterministic(q, x1, y1, press, speed, wet, tilt, seed):
    rec = random_recording(q, x1, y1, press, speed, wet, tilt, seed)
    a = Simulation(rec).run().image()
    b = Simulation(rec).run().image()
    assert a.tobytes() == b.tobytes()
