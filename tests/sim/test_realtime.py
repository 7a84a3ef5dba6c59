# SPDX-License-Identifier: GPL-3.0-or-later
"""Real time where the artist feels it (no bpy): the live sample clock follows the wall clock
through a stalled UI loop, the engine catches up, a refresh of the shown image costs only the
tiles that changed and equals a full one, and seeks through delta snapshots equal simulating
straight to the sample."""

import numpy as np
import pytest

from sim.core.recording import Recording
from sim.engine.live import LiveBrush, LiveEvent
from sim.engine.simulation import Simulation
from sim.engine.timeline import Timeline
from sim.paper.display import PaperView, encode, linear_to_srgb
from sim.paper.paper import TILE
from sim.writing.strokes import stroke

RATE = 120.0


def fresh(xy=(20.0, 50.0), ppm=3.0):
    rec = Recording(np.array([[*xy, 40.0, 0.0, 0.0, 0.0]]), width_mm=100, height_mm=100)
    rec.px_per_mm = ppm
    return Simulation(rec).run()


def timed_drag(live, t0, speed_mm_s, seconds, hitch=None, ui_hz=60.0):
    """A drag along y = 50 from x = 20 at ``speed_mm_s``; the pointer reports at 240 Hz; the
    UI loop handles events at ``ui_hz``, and stalls over ``hitch`` = (start, length) seconds:
    events that happen in a stall are handled together at its end."""
    x = lambda t: 20.0 + speed_mm_s * t  # noqa: E731
    live.handle(LiveEvent("LEFTMOUSE", "PRESS", (x(0), 50.0), time=t0))
    moves = np.arange(1, int(seconds * 240) + 1) / 240
    ticks = np.arange(1, int(seconds * ui_hz) + 1) / ui_hz
    events = [(t, "MOUSEMOVE") for t in moves] + [(t, "TIMER") for t in ticks]
    events.sort(key=lambda e: e[0])
    for t, kind in events:
        handled = t
        if hitch is not None and hitch[0] <= t < hitch[0] + hitch[1]:
            if kind == "TIMER":
                continue  # Blender drops the timer ticks it missed
            handled = hitch[0] + hitch[1]
        xy = (x(t), 50.0) if kind == "MOUSEMOVE" else None
        live.handle(LiveEvent(kind, "NOTHING", xy, time=t0 + handled))
    return live.handle(LiveEvent("LEFTMOUSE", "RELEASE", (x(seconds), 50.0), time=t0 + seconds))


@pytest.mark.parametrize("hitch", [None, (0.4, 0.3)])
def test_samples_are_uniform_in_time_and_on_the_pointers_path(hitch):
    live = LiveBrush(fresh(), press_mm=5.0)
    assert timed_drag(live, 1000.0, 100.0, 1.2, hitch) == "FINISHED"
    s = live.new_samples[live.land : -live.lift]  # between the landing and the lift
    assert len(s) == 144  # 1.2 s at 120 Hz, whatever the UI loop did
    assert np.all(s[:, 1] == 50.0)
    assert s[0, 0] == pytest.approx(20.0 + 100.0 / RATE, abs=0.5)
    assert s[-1, 0] == pytest.approx(20.0 + 120.0, abs=0.5)
    steps = np.diff(s[:, 0])
    assert steps.min() >= 0.0
    # 100 mm/s at 120 Hz is 0.83 mm a sample; through the stall too (no 30 mm jump)
    assert steps.max() < 2.5 * 100.0 / RATE
    np.testing.assert_allclose(np.median(steps), 100.0 / RATE, rtol=0.05)


def test_the_engine_falls_behind_and_catches_up_on_release():
    live = LiveBrush(fresh(), press_mm=5.0)
    live.handle(LiveEvent("LEFTMOUSE", "PRESS", (20.0, 50.0), time=0.0))
    live.handle(LiveEvent("MOUSEMOVE", "NOTHING", (60.0, 50.0), time=0.5))
    live.handle(LiveEvent("TIMER", "NOTHING", time=0.5))
    due = live.land + 60  # the landing, then the clock's samples
    assert live.behind == due and live.sim.index == 1  # produced, not simulated yet
    assert live.advance(budget_s=0.0) == due - 8  # one batch at least
    live.handle(LiveEvent("LEFTMOUSE", "RELEASE", (60.0, 50.0), time=0.6))
    assert live.behind == 0 and len(live.sim.rec.samples) == 1 + live.land + 72 + live.lift
    replay = Simulation(live.sim.rec).run()
    np.testing.assert_array_equal(replay.paper.ink, live.sim.paper.ink)
    np.testing.assert_array_equal(replay.paper.wet, live.sim.paper.wet)


def test_cancel_gives_back_exactly_the_tiles_it_changed():
    sim = fresh()
    before = {k: v.copy() for k, v in sim.paper.snapshot().items() if isinstance(v, np.ndarray)}
    live = LiveBrush(sim, press_mm=6.0)
    timed_drag(live, 0.0, 80.0, 0.5)  # kept: a first stroke
    live = LiveBrush(sim, press_mm=6.0)
    mid = {k: v.copy() for k, v in sim.paper.snapshot().items() if isinstance(v, np.ndarray)}
    live.handle(LiveEvent("LEFTMOUSE", "PRESS", (30.0, 30.0), time=0.0))
    live.handle(LiveEvent("MOUSEMOVE", "NOTHING", (70.0, 35.0), time=0.4))
    live.handle(LiveEvent("TIMER", "NOTHING", time=0.4))
    live.advance()
    assert not np.array_equal(sim.paper.ink, mid["ink"])
    assert live.handle(LiveEvent("ESC", time=0.5)) == "CANCELLED"
    for k, v in mid.items():
        np.testing.assert_array_equal(sim.paper.snapshot()[k], v)
    assert not np.array_equal(mid["ink"], before["ink"])


# ------------------------------------------------------------------ the image the artist sees
def test_a_refresh_rewrites_only_changed_tiles_and_equals_a_full_one():
    sim = fresh(ppm=6.0)  # 600 x 600 px

    def whole():
        return encode(sim.paper.rgb(), linear=True)

    view = PaperView(linear=True)
    assert view.refresh(sim.paper) == 0  # a blank paper is filled, not converted
    np.testing.assert_array_equal(view.pixels[..., :3], whole())
    live = LiveBrush(sim, press_mm=6.0)
    live.handle(LiveEvent("LEFTMOUSE", "PRESS", (20.0, 50.0), time=0.0))
    for k in range(1, 13):
        live.handle(LiveEvent("MOUSEMOVE", "NOTHING", (20.0 + k, 50.0), time=k / RATE))
        live.handle(LiveEvent("TIMER", "NOTHING", time=k / RATE))
        live.advance()
        done = view.refresh(sim.paper)
        assert done < 600 * 600 / 4
        np.testing.assert_array_equal(view.pixels[..., :3], whole())
        again = PaperView(linear=True)  # a whole refresh of a written paper: the same
        again.refresh(sim.paper)
        np.testing.assert_array_equal(again.pixels, view.pixels)
    assert view.refresh(sim.paper) == 0  # nothing changed, nothing rewritten
    np.testing.assert_array_equal(view.pixels[..., 3], 1.0)


def test_float_images_get_linear_light_that_decodes_to_the_visible_colour():
    rgb = np.random.default_rng(1).random((50, 3)).astype(np.float32)
    np.testing.assert_array_equal(encode(rgb, linear=False), rgb)
    back = linear_to_srgb(encode(rgb, linear=True))
    assert np.abs(back - rgb).max() < 1.0 / 4095  # finer than an 8-bit image
    assert encode(np.float32([0.5]), True)[0] == pytest.approx(0.214, abs=1e-3)


# ------------------------------------------------------------------ scrubbing
def long_recording(ppm=4.0):
    pts = [[20, 60], [80, 60], [70, 40], [20, 40], [30, 20], [80, 20]]
    samples = stroke(pts, press_mm=8, speed_mm_s=90, hair_length_mm=30)
    return Recording(
        samples, width_mm=100, height_mm=80, px_per_mm=ppm, brush={"preset": "wolf_stiff"}
    )


@pytest.mark.slow
def test_seeks_in_any_order_equal_simulating_straight_there():
    rec = long_recording()
    n = len(rec.samples)
    tl = Timeline(Simulation(rec), every=8)
    rng = np.random.default_rng(3)
    targets = [n // 2, n // 2 - 1, n, 5, n - 3, n // 3 + 1] + list(rng.integers(0, n, 4))
    for target in targets:
        sim = tl.seek(int(target))
        want = Simulation(rec).run(int(target))
        assert sim.index == want.index
        for a in ("ink", "wet", "last"):
            np.testing.assert_array_equal(getattr(sim.paper, a), getattr(want.paper, a))
        assert sim.rng.bit_generator.state == want.rng.bit_generator.state
    # snapshots hold only changed tiles: far less than a whole paper each
    whole = sum(a.nbytes for a in (tl.sim.paper.ink, tl.sim.paper.wet, tl.sim.paper.last))
    assert len(tl.snaps) > 10
    assert tl.nbytes < whole * len(tl.snaps) / 4


def test_a_backward_seek_rewrites_only_tiles_that_changed_since():
    rec = long_recording(ppm=8.0)
    n = len(rec.samples)
    tl = Timeline(Simulation(rec), every=8)
    tl.seek(n // 2)
    v = tl.sim.paper.version
    tl.seek(n // 2 - 9)
    rewritten = len(tl.sim.paper.tiles_since(v))
    ntiles = tl.sim.paper.tile_ver.size
    assert 0 < rewritten < ntiles / 4, (rewritten, ntiles, TILE)


@pytest.mark.slow
def test_snapshots_thin_at_the_budget_and_seeks_stay_exact():
    rec = long_recording()
    n = len(rec.samples)
    budget = 6_000_000  # well under the 14.6 MB of a snapshot every 4 samples
    tl = Timeline(Simulation(rec), every=4, budget_bytes=budget)
    tl.seek(n)
    assert tl.stride > 1  # the budget filled: every other snapshot dropped, then half as often
    assert tl.nbytes < budget + 1_000_000  # the last one may pass it
    assert max(tl.snaps) > n - tl.every * tl.stride  # snapshots over the whole recording
    held = sum(sum(a.nbytes for a in c) for _i, cs in tl._history.values() for c in cs)
    assert held <= tl.nbytes  # the tiles' copies counted, the dropped ones freed
    for target in (n - 3, n // 2 + 3, 5, n - 40):
        sim = tl.seek(target)
        want = Simulation(rec).run(target)
        for a in ("ink", "wet", "last"):
            np.testing.assert_array_equal(getattr(sim.paper, a), getattr(want.paper, a))
        assert sim.rng.bit_generator.state == want.rng.bit_generator.state
    # a seek near the end steps on from the snapshot before it, not from the start
    tl.seek(5)
    steps = []
    real_run = tl.sim.run
    tl.sim.run = lambda until=None, progress=None: steps.append(until) or real_run(until)
    tl.seek(n - 1)
    assert len(steps) <= tl.stride + 1, steps


@pytest.mark.slow
def test_checkpoints_on_disk_let_a_fresh_process_seek_anywhere_exactly(tmp_path):
    from sim.engine.checkpoints import cache_key_of, load_checkpoints, save_checkpoints

    rec = long_recording()
    n = len(rec.samples)
    made = Timeline(Simulation(rec), every=32)
    made.seek(n)
    save_checkpoints(made, tmp_path / "cache", key="abc")
    assert cache_key_of(tmp_path / "cache") == "abc"
    assert cache_key_of(tmp_path / "nothing") is None
    files = sorted((tmp_path / "cache").glob("checkpoint_*.npz"))
    assert len(files) == len(made.snaps) > 3
    for target in (n - 5, 40, n // 2 + 7, 3):
        fresh = Timeline(Simulation(rec), every=32)  # as a render farm's worker starts
        load_checkpoints(fresh, tmp_path / "cache", "abc")
        sim = fresh.seek(target)
        want = Simulation(rec).run(target)
        for a in ("ink", "wet", "last"):
            np.testing.assert_array_equal(getattr(sim.paper, a), getattr(want.paper, a))
        assert sim.rng.bit_generator.state == want.rng.bit_generator.state
    # a fresh worker stepped at most one interval of samples from the nearest checkpoint
    fresh = Timeline(Simulation(rec), every=32)
    load_checkpoints(fresh, tmp_path / "cache", "abc")
    steps = []
    fresh.sim.timings = {}
    real_run = fresh.sim.run
    fresh.sim.run = lambda until=None, progress=None: steps.append(until) or real_run(until)
    fresh.seek(n - 5)
    assert len(steps) <= 2
