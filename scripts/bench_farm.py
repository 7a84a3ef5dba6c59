# SPDX-License-Identifier: GPL-3.0-or-later
"""A render farm's worker, measured (real bpy, headless): a 12,000-sample recording (100 s at
120 Hz) on a 1024 px paper is saved; a fresh process opens the .blend and is asked for one frame
late in the shot, with and without the farm cache (hairy_brush.bake_cache). Prints a table,
then one JSON line.

    .venv/bin/python scripts/bench_farm.py [--samples N]"""

from __future__ import annotations

import argparse
import json
import subprocess
import sys
import tempfile
import textwrap
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT / "scripts"))
import bench_live  # noqa: E402 - sets Blender's user folder before bpy is imported
import numpy as np  # noqa: E402
from bench_live import ADDON, install, scene  # noqa: E402

bpy = bench_live.bpy

WORKER = textwrap.dedent(
    """
    import time
    t0 = time.perf_counter()
    import bpy
    import addon_utils
    addon_utils.enable({addon!r}, default_set=True)
    bpy.ops.wm.open_mainfile(filepath={path!r})
    t1 = time.perf_counter()
    bpy.context.scene.frame_set({frame})
    print("FRAME_S", time.perf_counter() - t1, "OPEN_S", t1 - t0)
    """
)


def worker_seconds(path: Path, frame: int) -> tuple[float, float]:
    script = WORKER.format(addon=ADDON, path=str(path), frame=frame)
    out = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True)
    line = next(ln for ln in out.stdout.splitlines() if ln.startswith("FRAME_S"))
    _, frame_s, _, open_s = line.split()
    return float(frame_s), float(open_s)


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--samples", type=int, default=12_000)
    args = ap.parse_args(argv)
    ext = install()
    sc, st = scene(ext, 1024)
    stroke = sys.modules[ADDON + ".sim.writing.strokes"].stroke
    parts, k = [], 0
    while sum(len(p) for p in parts) < args.samples:
        y = 180.0 - 14.0 * (k % 12)
        parts.append(stroke([[25.0, y], [175.0, y - 6.0]], press_mm=6, speed_mm_s=25))
        k += 1
    samples = np.concatenate(parts)[: args.samples]
    ext.blender.recordings.store_recording(st, ext.blender.recordings.new_recording(sc, samples))
    sc.frame_start, sc.frame_end = 1, int(args.samples / 120 * 24)
    folder = Path(tempfile.mkdtemp(prefix="hairy-brush-farm-"))
    path = folder / "shot.blend"
    bpy.ops.wm.save_as_mainfile(filepath=str(path))
    frame = sc.frame_end - 7
    without, open_s = worker_seconds(path, frame)
    t = time.perf_counter()
    assert bpy.ops.hairy_brush.bake_cache() == {"FINISHED"}
    bake_s = time.perf_counter() - t
    with_cache = [worker_seconds(path, int(f))[0] for f in (frame, frame // 2 + 3, 41)]
    size = sum(f.stat().st_size for f in folder.rglob("checkpoint_*.npz"))
    res = {
        "samples": args.samples,
        "frame_s_without_cache": round(without, 2),
        "frame_s_with_cache_worst": round(max(with_cache), 2),
        "open_s": round(open_s, 2),
        "bake_cache_s": round(bake_s, 1),
        "cache_mb": round(size / 2**20, 1),
    }
    rows = [
        (f"fresh worker, frame {frame} of {args.samples} samples at 1024 px, no cache", without),
        ("the same and two other frames, with the farm cache (worst)", max(with_cache)),
        ("start Blender and open the .blend (not counted above)", open_s),
        ("bake the farm cache", bake_s),
    ]
    for a, b in rows:
        print(f"{a:<66} {b:6.2f} s")
    print(f"{'cache on disk':<66} {size / 2**20:6.1f} MB")
    print(json.dumps(res))
    return 0


if __name__ == "__main__":
    sys.exit(main())
