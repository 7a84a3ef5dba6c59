# SPDX-License-Identifier: GPL-3.0-or-later
"""A work written from text (issue 27), the engine's side, without the command line: the
restarting dip that makes each cell depend on nothing before it, the layout, the variation,
the seal and the grid, composing and rendering cells side by side bit for bit, appending text
and writing one cell again."""

from dataclasses import replace

import numpy as np
import pytest

from sim.core.recording import Dip, Recording, from_dict, loads
from sim.engine.simulation import Simulation
from sim.writing.strokes import stroke


# ------------------------------------------------------------------- the restarting dip
def _two_strokes(press_first: float):
    a = stroke([[15, 20], [45, 20]], press_mm=press_first, hair_length_mm=30)
    b = stroke([[70, 20], [100, 25]], press_mm=8.0, hair_length_mm=30)
    samples = np.concatenate([a, b])
    dips = [Dip(0, 0.7, (0, 0, 0), 0.9, restart=0), Dip(len(a), 0.7, (0, 0, 0), 0.6, restart=1)]
    rec = Recording(samples, width_mm=120, height_mm=40, px_per_mm=4.0, seed=3, dips=dips)
    return rec, len(a)


def test_a_restarting_dip_makes_what_follows_independent_of_what_came_before():
    (r1, n1), (r2, _) = _two_strokes(6.0), _two_strokes(12.0)
    p1, p2 = Simulation(r1).run().paper, Simulation(r2).run().paper
    right = slice(int(60 * 4), None)  # columns of the second stroke
    assert not np.array_equal(p1.ink[:, : 60 * 4], p2.ink[:, : 60 * 4])  # the first differs
    assert p1.ink[:, right].max() > 0.3
    assert np.array_equal(p1.ink[:, right], p2.ink[:, right])  # the second does not, bit for bit
    # the second alone, from its restarting dip, on the whole paper: the same ink
    alone = replace(r1, samples=r1.samples[n1:], dips=[replace(r1.dips[1], before_sample=0)])
    assert np.array_equal(Simulation(alone).run().paper.ink[:, right], p1.ink[:, right])


def test_a_restarting_dip_is_kept_by_the_recording_and_old_ones_are_unchanged():
    rec, _ = _two_strokes(8.0)
    d = rec.to_dict()
    assert d["dips"][1]["restart"] == 1
    back = from_dict(d)
    assert [dp.restart for dp in back.dips] == [0, 1]
    plain = Dip(5, 0.5)
    assert "restart" not in plain.to_dict() and plain.restart is None
    d["dips"][1]["restart"] = -1
    with pytest.raises(ValueError, match="restart"):
        loads(__import__("json").dumps(d))
