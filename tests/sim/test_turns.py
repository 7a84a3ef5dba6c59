# SPDX-License-Identifier: GPL-3.0-or-later
"""The brush at pressed turns (issue 26): a pressed brush turning leaves a footprint about as
wide as its stroke, without lobes. Hand-made recordings (the default brush, pulled and turned
at set presses), replayed by the engine, measured against their own straight legs. No Blender."""

import numpy as np
import pytest

from sim.brush.dynamics import REF_RATE, move
from sim.brush.primitive import HairyBrush
from sim.core.params import BrushGeometry, QualityParams
from sim.core.recording import Recording
from sim.engine.simulation import Simulation

HAIR = 28.0  # the default brush's hair (wolf_kaishu), mm
RATE = 120.0  # samples a second
PPM = 6.0  # pixels a millimetre
SIDE = 70.0  # the paper, mm
SPEED = 60.0  # mm/s


def _samples(way, hover=3.0, land=12):
    """Samples through waypoints (x, y, press) at SPEED, the brush coming down onto the first
    and lifting off the last on the spot; press = how far the base is below touching height."""
    way = np.asarray(way, dtype=float)
    legs = []
    for p0, p1 in zip(way[:-1], way[1:], strict=True):
        n = max(2, int(np.ceil(np.linalg.norm(p1[:2] - p0[:2]) * RATE / SPEED)))
        legs.append(p0 + np.linspace(0.0, 1.0, n, endpoint=False)[:, None] * (p1 - p0))
    p = np.concatenate([*legs, way[-1:]])
    down = np.c_[np.repeat(p[:1, :2], land, 0), np.linspace(-hover, p[0, 2], land)]
    up = np.c_[np.repeat(p[-1:, :2], land, 0), np.linspace(p[-1, 2], -hover, land)]
    p = np.concatenate([down, p, up])
    out = np.zeros((len(p), 6))
    out[:, :2], out[:, 2] = p[:, :2], HAIR - p[:, 2]
    return out


def _air(a, b, seconds):
    """The brush carried through the air from sample a to sample b."""
    n = int(seconds * RATE)
    out = np.zeros((n, 6))
    out[:, :2] = a[:2] + np.linspace(0.0, 1.0, n)[:, None] * (b[:2] - a[:2])
    out[:, 2] = HAIR + 3.0
    return out


def _ink_points(samples) -> np.ndarray:
    """The inked pixels' centres (mm) of the recording's writing with the default brush."""
    rec = Recording(samples, width_mm=SIDE, height_mm=SIDE, px_per_mm=PPM, sample_rate_hz=RATE)
    grey = Simulation(rec).run().image8().mean(axis=2)
    rows, cols = np.nonzero(grey < 0.5 * np.median(grey))
    return np.c_[(cols + 0.5) / PPM, (grey.shape[0] - rows - 0.5) / PPM]


def _from_leg(p, a, b):
    """Distances of points p from the segment a-b, and where along it each is nearest (0-1)."""
    d = b - a
    t = np.clip((p - a) @ d / (d @ d), 0.0, 1.0)
    return np.linalg.norm(p - (a + t[:, None] * d), axis=1), t


def _turn_over_straight(ink, way, corner: int, leg: int) -> float:
    """How far the ink reaches from the path near waypoint ``corner`` (within two of the
    straight's half widths), over the half width of leg ``leg`` (waypoints leg, leg + 1) in its
    middle, where it runs straight at its press."""
    way = np.asarray(way, dtype=float)[:, :2]
    legs = [_from_leg(ink, a, b) for a, b in zip(way[:-1], way[1:], strict=True)]
    near_path = np.min([d for d, _ in legs], axis=0)
    d, t = legs[leg]
    half = np.percentile(d[(t > 0.3) & (t < 0.7) & (d <= near_path)], 99.5)
    at_turn = np.linalg.norm(ink - way[corner], axis=1) < 2.0 * half
    return float(np.percentile(near_path[at_turn], 99.5) / half)


def test_hanging_hair_coming_down_on_the_paper_falls_back_along_the_drag():
    # hair straightened in the air keeps a bend of 1e-8 mm the way it last lay (here sideways,
    # +y); pressed onto the paper while moving in +x it falls back along the drag (-x), not
    # the way of that bend (before: every key point that came down lay in +y, across the way)
    b = HairyBrush(BrushGeometry(), QualityParams(), np.random.Generator(np.random.PCG64(0)))
    b.place([30.0, 30.0, b.L + 0.2, 0.0, 0.0, 0.0])
    b.cc[0, 1:, 1] += 1e-8 * b.sarc[0, 1:] / b.L
    move(b, [30.5, 30.0, b.L - 4.0, 0.0, 0.0, 0.0], [60.0, 0.0, -500.0, 0, 0, 0], 1 / REF_RATE)
    down = b.cc[0, 1:][b.cc[0, 1:, 2] <= 0.0]
    assert len(down) >= 2
    off = down[:, :2] - b.B[:2]
    assert np.all(off[:, 0] < -0.5)  # behind the base
    assert np.all(np.abs(off[:, 1]) < 0.2 * np.abs(off[:, 0]))


@pytest.mark.slow
def test_a_shoulder_pressed_after_a_stroke_written_upwards_has_no_lobe():
    # 家's 横钩 shoulder: a light 横 turning 45 degrees down into a leg pressed 10 mm, written
    # 0.4 s after a stroke that went up (its hair lay down, behind it). The belly pressed at the
    # shoulder fell the way that stroke's hair had lain, across the new leg: a lobe reaching
    # 1.69 times the leg's half width from the path (1.03 now)
    first = _samples([(30.0, 12.0, 8.0), (30.0, 32.0, 8.0)])
    c, d = np.array([40.0, 55.0]), np.array([1.0, -1.0]) / np.sqrt(2.0)
    way = [(12.0, 55.0, 2.0), (*c, 2.5), (*(c + 4 * d), 10.0), (*(c + 16 * d), 10.0)]
    way.append((*(c + 24 * d), 10.0))
    second = _samples(way)
    ink = _ink_points(np.concatenate([first, _air(first[-1], second[0], 0.4), second]))
    ink = ink[ink[:, 1] > 36.0]  # the second stroke's (the first ends below y = 35)
    assert _turn_over_straight(ink, way, corner=2, leg=3) < 1.15


@pytest.mark.slow
def test_a_pressed_reversal_is_as_wide_as_its_stroke():
    # a 竖钩 at one press: pulled down 30 mm, then up-left 12 mm at the same press. The foot
    # is the belly turning on the spot: the ink reaches no further from the path there than
    # the straight's half width (measured 0.97-1.07 at presses of 5-11 mm and 30-120 mm/s)
    for press in (6.0, 10.0):
        way = [(35.0, 60.0, press), (35.0, 30.0, press), (26.5, 38.5, press)]
        ink = _ink_points(_samples(way))
        assert _turn_over_straight(ink, way, corner=1, leg=0) < 1.12
