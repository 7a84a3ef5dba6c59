# SPDX-License-Identifier: GPL-3.0-or-later
"""Live painting through the paint operator's event logic (no window to run it modally)."""

from __future__ import annotations

import numpy as np
import pytest

from sim.engine.simulation import Simulation  # noqa: E402
from tests.blender.helpers import (
    ext,
    keyframe_stroke,
    pixels,
    setup_scene,
)

bpy = pytest.importorskip("bpy")


def paint_operator():
    """The paint operator's own methods on a stand-in (a modal operator cannot run headless)."""
    cls = ext().operators.paint.HAIRY_BRUSH_OT_paint

    class Stroke:
        reports = []

        def report(self, kind, msg):
            self.reports.append((kind, msg))

    for name in ("start", "step", "show", "_finish"):
        setattr(Stroke, name, getattr(cls, name))
    return Stroke()


# ----------------------------------------------------------------------------- live painting
def test_live_stroke_is_kept_in_the_recording_and_replays_identically(hb):
    LiveEvent = ext().sim.engine.live.LiveEvent  # noqa: N806 - the installed copy's class

    st = setup_scene(bpy)
    sc = bpy.context.scene
    paint = ext().operators.paint
    sim, fresh = paint.start_simulation(sc, (60.0, 100.0))
    assert fresh
    live = ext().sim.engine.live.LiveBrush(sim, press_mm=5.0, step_deg=2.0, xy=(60.0, 100.0))
    events = [LiveEvent("LEFTMOUSE", "PRESS", (60.0, 100.0))]
    for i in range(60):
        events.append(LiveEvent("MOUSEMOVE", "NOTHING", (60.0 + i, 100.0)))
        events.append(LiveEvent("TIMER", "NOTHING"))
    events.append(LiveEvent("LEFTMOUSE", "RELEASE", (120.0, 100.0)))
    for ev in events:
        state = live.handle(ev)
    assert state == "FINISHED"
    paint.keep_stroke(sc, live)
    ext().blender.images.show_paper(st.paper_image, live.sim.paper, live.sim.index)
    rec = ext().blender.recordings.recording_from_scene(sc)
    first = 1 + live.land + 60 + live.lift  # the stroke lands and lifts
    assert len(rec.samples) == first
    replay = Simulation(rec).run().paper.rgb()
    np.testing.assert_array_equal(replay, live.sim.paper.rgb())
    assert (replay[..., 0] < 0.5).sum() > 100
    # a second stroke continues the stored recording; the frame cache adopts the live state
    sim2, fresh = paint.start_simulation(sc, (60.0, 60.0))
    assert not fresh and sim2.index == first
    live2 = ext().sim.engine.live.LiveBrush(sim2, press_mm=5.0, xy=(60.0, 60.0))
    live2.handle(LiveEvent("LEFTMOUSE", "PRESS", (60.0, 60.0)))
    for i in range(30):
        live2.handle(LiveEvent("MOUSEMOVE", "NOTHING", (60.0, 60.0 + i)))
        live2.handle(LiveEvent("TIMER", "NOTHING"))
    assert live2.handle(LiveEvent("RET", "PRESS")) == "FINISHED"
    paint.keep_stroke(sc, live2)
    assert ext().blender.playback.playback_for(sc).sim is live2.sim  # no re-simulation
    rec2 = ext().blender.recordings.recording_from_scene(sc)
    assert len(rec2.samples) == first + live2.land + 30 + live2.lift
    np.testing.assert_array_equal(Simulation(rec2).run().paper.rgb(), live2.sim.paper.rgb())


def test_paint_operator_refreshes_what_changed_moves_the_brush_and_cancels_exactly(hb):
    LiveEvent = ext().sim.engine.live.LiveEvent  # noqa: N806 - the installed copy's class
    paint = ext().operators.paint
    st = setup_scene(bpy, ppm=3.0)
    sc = bpy.context.scene
    assert bpy.ops.hairy_brush.build_primitives() == {"FINISHED"}
    prim = ext().blender.primitives.primitive_objects(sc)[0]
    sim, _ = paint.start_simulation(sc, (60.0, 100.0))
    op = paint_operator()
    op.start(
        bpy.context, st.paper_image, ext().sim.engine.live.LiveBrush(sim, 5.0, 2.0, (60.0, 100.0))
    )
    before = pixels(st.paper_image)
    assert ext().blender.runtime.get().painter is op._live  # the runtime knows the painting
    t0 = op._live._t0
    op.step(bpy.context, LiveEvent("LEFTMOUSE", "PRESS", (60.0, 100.0), time=t0))
    brush_z, prim_z = [], []
    for k in range(1, 41):
        t = t0 + k / 60
        op.step(bpy.context, LiveEvent("MOUSEMOVE", "NOTHING", (60.0 + k, 100.0), time=t))
        op._last_draw = 0.0  # refresh on every tick
        op.step(bpy.context, LiveEvent("TIMER", "NOTHING", time=t))
        brush_z.append(st.brush_object.matrix_world.translation.x)
        prim_z.append(np.array(prim.data.splines[0].points[0].co)[0])
    # 40 ticks at 60 Hz: 80 samples at 120 Hz, whatever the loop cost (after the landing)
    assert len(op._live.new_samples) == op._live.land + 80
    shown = pixels(st.paper_image)[..., :3]
    assert np.abs(shown - sim.paper.rgb()).max() <= 0.5 / 4095 + 1e-6  # refreshed = full
    assert (np.abs(shown - before[..., :3]).max(axis=2) > 0.1).sum() > 100
    assert brush_z[-1] > brush_z[0] + 0.03  # the empty follows the live pose (metres)
    assert len(set(np.round(prim_z, 6))) > 1  # and the primitive surfaces follow the brush
    assert op.step(bpy.context, LiveEvent("ESC", "PRESS", time=t0 + 0.7)) == {"CANCELLED"}
    np.testing.assert_array_equal(pixels(st.paper_image), before)
    assert st.recording is None and ext().blender.runtime.get().painter is None


def test_bake_asks_before_replacing_painted_strokes(hb):
    LiveEvent = ext().sim.engine.live.LiveEvent  # noqa: N806
    st = setup_scene(bpy)
    sc = bpy.context.scene
    paint = ext().operators.paint
    sim, _ = paint.start_simulation(sc, (60.0, 100.0))
    live = ext().sim.engine.live.LiveBrush(sim, press_mm=5.0, xy=(60.0, 100.0))
    live.handle(LiveEvent("LEFTMOUSE", "PRESS", (60.0, 100.0)))
    for i in range(30):
        live.handle(LiveEvent("MOUSEMOVE", "NOTHING", (60.0 + i, 100.0)))
        live.handle(LiveEvent("TIMER", "NOTHING"))
    assert live.handle(LiveEvent("RET", "PRESS")) == "FINISHED"
    paint.keep_stroke(sc, live)
    text = st.recording.as_string()
    keyframe_stroke(bpy, st)
    n = live.land + 30 + live.lift
    with pytest.raises(RuntimeError, match=f"{n} samples painted live"):
        bpy.ops.hairy_brush.bake_samples()
    assert st.recording.as_string() == text
    assert bpy.ops.hairy_brush.bake_samples(replace_painted=True) == {"FINISHED"}
    assert st.recording.as_string() != text
