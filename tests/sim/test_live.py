# SPDX-License-Identifier: GPL-3.0-or-later
"""Live painting logic (Fig. 6(b)), driven by the event sequences Blender sends (no bpy)."""

import numpy as np
import pytest

from sim.core.frames import rotation_matrix
from sim.core.params import HOVER_MM
from sim.core.recording import Recording
from sim.engine.live import LiveBrush, LiveEvent
from sim.engine.simulation import Simulation


def fresh(xy=(50.0, 50.0)):
    rec = Recording(np.array([[*xy, 40.0, 0.0, 0.0, 0.0]]), width_mm=100, height_mm=100)
    rec.px_per_mm = 3.0
    return Simulation(rec).run()


def drag(live, start, end, n):
    events = [LiveEvent("LEFTMOUSE", "PRESS", start)]
    for k in range(n):
        t = k / (n - 1)
        xy = (start[0] + t * (end[0] - start[0]), start[1] + t * (end[1] - start[1]))
        events += [LiveEvent("MOUSEMOVE", "NOTHING", xy), LiveEvent("TIMER", "NOTHING")]
    return events


def test_keys_tilt_and_twist_with_the_papers_multipliers():
    live = LiveBrush(fresh(), step_deg=2.0)
    live.handle(LiveEvent("W"))  # d + 2
    live.handle(LiveEvent("E"))  # q - 2
    live.handle(LiveEvent("V", shift=True))  # r + 8
    assert list(live.angles) == [2.0, -2.0, 8.0]
    live.handle(LiveEvent("LEFTMOUSE", "PRESS", (50.0, 50.0)))
    live.handle(LiveEvent("Q"))  # left button held: d - 4
    live.handle(LiveEvent("R", "RELEASE"))  # releases do nothing
    assert list(live.angles) == [-2.0, -2.0, 8.0]
    pose = live.pose()
    assert pose[3] == -2.0 and pose[4] == -2.0 and pose[5] == 8.0


def test_wheel_sets_the_press_and_the_button_puts_the_brush_down():
    live = LiveBrush(fresh(), press_mm=4.0)
    L = live.L
    assert live.pose()[2] == pytest.approx(L + HOVER_MM)  # hovering
    live.handle(LiveEvent("WHEELDOWNMOUSE"))
    live.handle(LiveEvent("WHEELDOWNMOUSE"))
    live.handle(LiveEvent("WHEELUPMOUSE"))
    live.handle(LiveEvent("LEFTMOUSE", "PRESS", (10.0, 20.0)))
    assert live.pose()[:3] == pytest.approx([10.0, 20.0, L - 4.5])


def test_tablet_pressure_and_tilt_drive_z_d_q():
    live = LiveBrush(fresh(), press_mm=8.0)
    live.handle(LiveEvent("LEFTMOUSE", "PRESS", (30.0, 30.0), 0.25, (0.5, -0.25), True))
    pose = live.pose()
    assert tuple(pose[3:5]) == pytest.approx((30.0, -15.0))
    # the tip under the pointer, pressed Press x pressure into the paper
    tip = pose[:3] - live.L * rotation_matrix(*pose[3:])[:, 2]
    assert tip == pytest.approx([30.0, 30.0, -2.0])


def test_a_stroke_writes_and_release_keeps_it():
    live = LiveBrush(fresh(), press_mm=6.0)
    before = live.sim.paper.rgb().copy()
    state = "RUNNING"
    for ev in drag(live, (20.0, 50.0), (80.0, 50.0), 60):
        state = live.handle(ev)
    assert state == "RUNNING"
    assert live.handle(LiveEvent("LEFTMOUSE", "RELEASE", (80.0, 50.0))) == "FINISHED"
    n = live.land + 60 + live.lift  # it lands, writes, and lifts in place
    assert len(live.sim.rec.samples) == 1 + n and len(live.new_samples) == n
    hover = live.L + HOVER_MM
    assert np.all(live.new_samples[: live.land, :3] == [20.0, 50.0, hover])
    assert np.all(live.new_samples[-live.lift :, :3] == [80.0, 50.0, hover])
    inked = np.abs(live.sim.paper.rgb() - before).max(axis=2) > 0.1
    assert inked.sum() > 300
    # the kept recording replays to the same image
    np.testing.assert_array_equal(Simulation(live.sim.rec).run().paper.rgb(), live.sim.paper.rgb())


def test_hovering_leaves_no_ink():
    live = LiveBrush(fresh())
    before = live.sim.paper.rgb().copy()
    for k in range(30):
        live.handle(LiveEvent("MOUSEMOVE", "NOTHING", (20.0 + k, 50.0)))
        live.handle(LiveEvent("TIMER", "NOTHING"))
    np.testing.assert_array_equal(live.sim.paper.rgb(), before)


@pytest.mark.parametrize("key", ["ESC", "RIGHTMOUSE"])
def test_cancel_restores_the_simulation_exactly(key):
    sim = fresh()
    live = LiveBrush(sim, press_mm=6.0)
    live.handle(LiveEvent("LEFTMOUSE", "PRESS", (20.0, 50.0)))
    live.dip(1.0, (0.8, 0.1, 0.1), 0.9)
    base = sim.snapshot()
    for ev in drag(live, (20.0, 50.0), (70.0, 40.0), 40)[1:]:
        live.handle(ev)
    live.advance()
    assert np.abs(sim.paper.rgb() - Simulation(sim.rec).run(1).paper.rgb()).max() > 0.1
    assert live.handle(LiveEvent(key, "PRESS")) == "CANCELLED"
    assert len(sim.rec.samples) == 1 and sim.index == 1 and len(sim.rec.dips) == 0
    for k, v in base["paper"].items():
        if isinstance(v, np.ndarray):
            np.testing.assert_array_equal(sim.paper.snapshot()[k], v)
    # and it goes on from there as if nothing had happened
    assert live.handle(LiveEvent("TIMER")) == "CANCELLED"


def test_a_dip_while_painting_is_recorded():
    live = LiveBrush(fresh(), press_mm=6.0)
    for ev in drag(live, (20.0, 50.0), (40.0, 50.0), 10):
        live.handle(ev)
    live.dip(0.5, (0.1, 0.2, 0.9), 0.8)
    for ev in drag(live, (40.0, 50.0), (80.0, 50.0), 20)[1:]:
        live.handle(ev)
    live.handle(LiveEvent("RET"))
    dips = live.sim.rec.dips
    assert [d.before_sample for d in dips] == [0, live.land + 11]
    assert dips[1].color == (0.1, 0.2, 0.9)
