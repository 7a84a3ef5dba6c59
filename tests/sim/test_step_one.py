# SPDX-License-Identifier: GPL-3.0-or-later
"""Issue 28: a brush of one primitive steps on Python floats (``sections``' axis, ``move``,
``update_stress``, ``lose_wetness``, ``adjust_ellipse``), and gives the same bits as the
arrays' step of many primitives: every state of a written stroke, stepped both ways - the one
primitive, and the same primitive twice (two rows step as one, on the arrays) - leaves the
same numbers."""

import numpy as np

from sim.brush.state import FIELDS, take_primitives
from tests.sim.builders import long_stroke, simulation

SECTIONS = ("centres", "U", "V", "T", "params", "rows_c", "rows_U", "rows_V", "rows_T")


def _twin(brush, snap):
    """A brush of the snapshot's one primitive twice (the arrays' step)."""
    twin = simulation(long_stroke()[:2], 64, 1.0).brush
    twin.restore(snap)
    take_primitives(twin, np.array([0, 0]))
    return twin


def _same(one, twin, label):
    for f in FIELDS:
        a, b = getattr(one, f.name), getattr(twin, f.name)
        assert b[0].tobytes() == b[1].tobytes(), (label, f.name)  # (two rows as one)
        assert a.dtype == b.dtype and a.tobytes() == b[:1].tobytes(), (label, f.name)
    for name in ("B", "R", "travel"):
        assert getattr(one, name).tobytes() == getattr(twin, name).tobytes(), (label, name)


STEPS = ("move", "update_stress", "lose_wetness", "adjust_ellipse")


def _step(brush, label, pose, vel, dt, area, height):
    if label == "move":
        brush.move(pose, vel, dt)
    elif label == "update_stress":
        brush.update_stress(np.repeat(area, brush.m), np.repeat(height, brush.m), 35.0, dt)
    elif label == "lose_wetness":
        brush.lose_wetness(dt)
    else:
        brush.adjust_ellipse(vel, dt)


def test_one_primitive_steps_as_the_arrays_step_it():
    sim = simulation(long_stroke()[:160], 256, 1.28)
    rng = np.random.default_rng(28)
    touched = moved_on_paper = 0
    while not sim.done:
        one = sim.brush
        snap = one.snapshot()
        twin = _twin(one, snap)
        a, b = one.sections(), twin.sections()
        for name in SECTIONS:
            x, y = getattr(a, name), getattr(b, name)
            assert x.tobytes() == y[:1].tobytes(), name
        i = sim.index
        args = (
            sim.rec.samples[i],  # the pose
            rng.normal(0.0, 40.0, 6) * (i % 5 != 0),  # the velocity (and at rest)
            sim.dt,
            np.array([rng.choice([0.0, 2.5, 9.0])]),  # S_i
            np.array([rng.uniform(0.0, 12.0)]),  # hei_i
        )
        for label in STEPS:
            one.restore(snap)
            twin = _twin(one, snap)
            _step(one, label, *args)
            _step(twin, label, *args)
            _same(one, twin, label)
        touched += bool(one.touching[0])
        moved_on_paper += int(np.count_nonzero(one.cc[0, :, 2] == 0.0) > 0)
        one.restore(snap)
        sim._advance()
        sim._drop_pending()
    assert touched > 50 and moved_on_paper > 50  # the stroke pressed the hair on the paper


def test_one_cut_as_the_arrays_cut_it():
    """Issue 28: one primitive's cut (``cut_marks``, its sizes and widths) on Python floats
    has the bits of the arrays' cut of the same primitive twice."""
    from sim.brush.mark import cut_marks

    sim = simulation(long_stroke()[:160], 256, 1.28)
    cuts = 0
    while not sim.done:
        one = sim.brush
        twin = _twin(one, one.snapshot())
        args = (None, sim.paper.ppm, sim.paper.shape)
        a, b = cut_marks(one, one.sections(), *args), cut_marks(twin, twin.sections(), *args)
        assert (a is None) == (b is None)
        if a is not None:
            cuts += 1
            for name in ("box", "area", "height", "centre", "extent"):
                x, y = getattr(a, name), getattr(b, name)
                assert x.dtype == y.dtype and x.tobytes() == y[:1].tobytes(), name
            assert a.prims.tolist() == [0] and a.near == b.near
            across = tuple(np.random.default_rng(cuts).normal(size=2).tolist())
            assert a.widths(1, across).tobytes() == b.widths(2, across)[:1].tobytes()
            for x, y in zip(a.sizes(1), b.sizes(2), strict=True):
                assert x.tobytes() == y[:1].tobytes()
        sim._advance()
        sim._drop_pending()
    assert cuts > 50
