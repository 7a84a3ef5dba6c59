# SPDX-License-Identifier: GPL-3.0-or-later
"""Writing at sizes other than the brush's own (sim.writing.brush_size): held-out IoU with the
outlines at each character size, with the brush made smaller or larger for the size (the
default) and with the brush as it is (``--keep-brush``), side by side.

    python scripts/sizes_eval.py [--sizes 30 50 70 150] [--chars 亡凶出口左木王生禾]
                                 [--data tests/data/unseen] [--workers 2]

Each cell is ``python -m sim iou CHARS --data DATA --size-mm S [--keep-brush]`` (512 px, the
defaults), its mean IoU; the last row is the brush's own size (no --size-mm)."""

from __future__ import annotations

import argparse
import json
import subprocess
import sys
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent


def mean_iou(chars: str, data: str, size: float | None, keep: bool) -> float:
    cmd = [sys.executable, "-m", "sim", "iou", *chars, "--data", data]
    if size is not None:
        cmd += ["--size-mm", f"{size:g}"]
    if keep:
        cmd.append("--keep-brush")
    out = subprocess.run(cmd, cwd=ROOT, check=True, capture_output=True, text=True).stdout
    return float(json.loads(out.strip().splitlines()[-1])["mean_iou_brush"])


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--sizes", type=float, nargs="+", default=[30.0, 50.0, 70.0, 150.0])
    ap.add_argument("--chars", default="亡凶出口左木王生禾")
    ap.add_argument("--data", default="tests/data/unseen")
    ap.add_argument("--workers", type=int, default=2)
    a = ap.parse_args(argv)
    jobs = [(s, keep) for s in a.sizes for keep in (False, True)] + [(None, False)]
    with ThreadPoolExecutor(a.workers) as pool:
        got = list(pool.map(lambda j: mean_iou(a.chars, a.data, *j), jobs))
    res = dict(zip(jobs, got, strict=True))
    print(f"{'size (mm)':<12}{'brush for the size':>20}{'brush as it is':>16}")
    for s in a.sizes:
        print(f"{s:<12g}{res[s, False]:>20.4f}{res[s, True]:>16.4f}")
    print(f"{'its own':<12}{res[None, False]:>20.4f}{res[None, False]:>16.4f}")
    print(json.dumps({f"{s:g}": [res[s, False], res[s, True]] for s in a.sizes}))
    return 0


if __name__ == "__main__":
    sys.exit(main())
