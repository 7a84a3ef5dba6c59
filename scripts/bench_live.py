# SPDX-License-Identifier: GPL-3.0-or-later
"""What the artist waits for, measured through the extension's own code with real bpy (headless):
the live refresh while painting, the lag from release to the final image, scrubbing at 4K, and the
engine alone. Prints a table, then one JSON object as its last line.

    .venv/bin/python scripts/bench_live.py [--quick]

The extension is built and installed into a temporary Blender user folder, as a user would.
Painting is driven through the paint operator's own methods (``start``/``step``/``show``) with
events stamped by the wall clock as they are handled, in real time: the pointer moves at 100 mm/s
and reports at 120 Hz, timer events come as the operator asks for them."""

from __future__ import annotations

import argparse
import json
import os
import statistics
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))
sys.path.insert(0, str(ROOT / "scripts"))
os.environ["BLENDER_USER_RESOURCES"] = tempfile.mkdtemp(prefix="hairy-brush-bench-")

import bpy  # noqa: E402
import numpy as np  # noqa: E402
from build_extension import build  # noqa: E402

ADDON = "bl_ext.user_default.hairy_brush"
PAPER_MM = 200.0
SPEED_MM_S = 100.0
POINTER_HZ = 120.0


def install():
    out = Path(tempfile.mkdtemp(prefix="hairy-brush-dist-"))
    res = bpy.ops.extensions.package_install_files(
        filepath=str(build(out)), repo="user_default", enable_on_install=True
    )
    assert res == {"FINISHED"}, res
    return sys.modules[ADDON]


def scene(ext, size_px: int, brush="wolf_stiff"):
    bpy.ops.wm.read_homefile(use_empty=True)
    st = bpy.context.scene.hairy_brush
    st.paper_width_mm = st.paper_height_mm = PAPER_MM
    st.px_per_mm = size_px / PAPER_MM
    st.brush_preset = brush
    assert bpy.ops.hairy_brush.setup() == {"FINISHED"}
    return bpy.context.scene, st


def split(sim, primitives: int):
    """Split the brush into ``primitives`` up front, as ``python -m sim bench`` does."""
    b = sim.brush
    b.max_primitives = primitives
    b.dip(sim.ink, 0.8, (0, 0, 0), 0.9)
    b.split_under((primitives + 0.5) * b.q.tre)  # Eq. 18: k = floor(stress / tre)
    sim.dips = []


class Stroke:
    """The paint operator's methods on a stand-in (a modal operator cannot run headless); each
    refresh made while painting is timed (the image, the brush and its surfaces)."""

    refreshes: list

    def report(self, kind, msg):
        pass

    def show(self, context, final):
        drawn = self._last_draw
        t = time.perf_counter()
        self._show(context, final)
        if not final and self._last_draw != drawn:
            self.refreshes.append(time.perf_counter() - t)


def operator(ext):
    cls = ext.operators.paint.HAIRY_BRUSH_OT_paint
    for name in ("start", "step", "_finish"):
        setattr(Stroke, name, getattr(cls, name))
    Stroke._show = cls.show
    op = Stroke()
    op.refreshes = []
    return op


def paint(ext, size_px: int, primitives: int, seconds: float):
    """One stroke painted in real time; returns (refresh times, lag at release, samples)."""
    LiveEvent = ext.sim.engine.live.LiveEvent  # noqa: N806
    sc, st = scene(ext, size_px)
    paint_mod = ext.operators.paint
    x0, y = 40.0, PAPER_MM / 2
    sim, _ = paint_mod.start_simulation(sc, (x0, y))
    if primitives > 1:
        split(sim, primitives)
    op = operator(ext)
    op.start(bpy.context, st.paper_image, ext.sim.engine.live.LiveBrush(sim, 6.0, 2.0, (x0, y)))
    t0 = op._live._t0
    op.step(bpy.context, LiveEvent("LEFTMOUSE", "PRESS", (x0, y), time=time.perf_counter()))
    next_move = t0
    while True:
        now = time.perf_counter()
        if now - t0 >= seconds:
            break
        while next_move <= now:  # the pointer's reports since the last pass of the loop
            xy = (x0 + SPEED_MM_S * (next_move - t0), y)
            op.step(bpy.context, LiveEvent("MOUSEMOVE", "NOTHING", xy, time=now))
            next_move += 1.0 / POINTER_HZ
        op.step(bpy.context, LiveEvent("TIMER", "NOTHING", time=time.perf_counter()))
        time.sleep(max(0.0, 1.0 / POINTER_HZ - (time.perf_counter() - now)))
    xy = (x0 + SPEED_MM_S * seconds, y)
    t = time.perf_counter()
    state = op.step(bpy.context, LiveEvent("LEFTMOUSE", "RELEASE", xy, time=t))
    lag = time.perf_counter() - t
    assert state == {"FINISHED"}, state
    return op.refreshes, lag, len(op._live.new_samples), sim.brush.m


def scrub(ext, size_px: int, frames: int, seed: int = 0):
    """A recording of ``frames`` frames written over the sheet; played through once, then
    frame -1, frame +1 and random jumps, timed through the frame-change handler."""
    from importlib import import_module

    stroke = import_module(ADDON + ".sim.writing.strokes").stroke
    sc, st = scene(ext, size_px)
    rate, fps = 120.0, 24.0
    need = int(frames / fps * rate)
    rows, parts, k = 0, [], 0
    while rows < need:
        yy = 170.0 - 25.0 * (k % 6)
        pts = [[30.0, yy], [170.0, yy - 8.0]] if k % 2 == 0 else [[160.0, yy], [40.0, yy - 10.0]]
        s = stroke(pts, press_mm=8, speed_mm_s=60, hair_length_mm=30)
        parts.append(s)
        rows += len(s)
        k += 1
    samples = np.concatenate(parts)[:need]
    rec = ext.blender.recordings.new_recording(sc, samples)
    ext.blender.recordings.store_recording(st, rec)
    sc.frame_start, sc.frame_end = 1, frames
    st.sync_frames = True

    def at(f):
        t = time.perf_counter()
        sc.frame_set(f)
        return time.perf_counter() - t

    t = time.perf_counter()
    for f in range(1, frames + 1):
        sc.frame_set(f)
    first_pass = time.perf_counter() - t
    rng = np.random.default_rng(seed)
    back, fwd, jump = [], [], []
    for f in rng.integers(10, frames - 10, 8):
        at(int(f))
        back.append(at(int(f) - 1))
        fwd.append(at(int(f)))
        fwd.append(at(int(f) + 1))
    for f in rng.integers(1, frames + 1, 8):
        jump.append(at(int(f)))
    return back, fwd, jump, first_pass


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--quick", action="store_true", help="shorter strokes and scrubs")
    args = ap.parse_args(argv)
    ext = install()
    seconds = 1.0 if args.quick else 2.0
    frames = 60 if args.quick else 300
    res, rows = {}, []
    med = lambda v: statistics.median(v)  # noqa: E731
    for size, prims, label in ((1024, 1, "1024_1p"), (2048, 1, "2048_1p"), (4096, 16, "4096_16p")):
        refresh, lag, n, m = paint(ext, size, prims, seconds)
        res[f"refresh_ms_{size}"] = round(med(refresh) * 1e3, 2)
        res[f"lag_s_{label}"] = round(lag, 3)
        rows.append((f"paint {size} px, {m} primitive(s)", f"{n} samples in {seconds} s"))
        rows.append(("  refresh (median, ms)", f"{med(refresh) * 1e3:.1f} of {len(refresh)}"))
        rows.append(("  lag from release to final image (s)", f"{lag:.3f}"))
    back, fwd, jump, first = scrub(ext, 4096, frames)
    res["scrub_back_ms_4096"] = round(med(back) * 1e3, 1)
    res["scrub_fwd_ms_4096"] = round(med(fwd) * 1e3, 1)
    res["jump_s_4096"] = round(max(jump), 3)
    res["scrub_first_pass_s_4096"] = round(first, 1)
    rows.append((f"scrub 4096 px, {frames} frames", f"first play-through {first:.1f} s"))
    rows.append(("  frame -1 (median, worst ms)", f"{med(back) * 1e3:.0f}, {max(back) * 1e3:.0f}"))
    rows.append(("  frame +1 (median, worst ms)", f"{med(fwd) * 1e3:.0f}, {max(fwd) * 1e3:.0f}"))
    rows.append(("  random jump (median, worst s)", f"{med(jump):.3f}, {max(jump):.3f}"))
    from importlib import import_module

    bench = import_module(ADDON + ".sim.cli.bench")
    rate, _m = bench.samples_per_second(bench.long_stroke(), 4096, 4096 / PAPER_MM, 16, 3)
    res["samples_per_s_16p_4096"] = round(rate, 1)
    rows.append(("engine alone, 16 primitives, 4096 px (samples/s)", f"{rate:.0f}"))
    for a, b in rows:
        print(f"{a:<52} {b}")
    print(json.dumps(res))
    return 0


if __name__ == "__main__":
    sys.exit(main())
