# SPDX-License-Identifier: GPL-3.0-or-later
"""Check that this checkout makes exactly the results of another (issue 28: a speed-up changes
nothing): the same commands run in both, each with a fresh cache of its own, and every image
compared byte for byte (the PNG files, and their pixels), and the engine's whole state after
the benchmark's workloads (the paper's buffers and the brush) compared by hash.

    python scripts/same_results.py /path/to/other/checkout [--quick] [--keep DIR]

``--keep DIR`` keeps the other checkout's results in DIR and uses them again on the next run
(for a checkout that does not change, such as the branch point).

Exit status 0 when everything is identical, 1 when anything differs."""

from __future__ import annotations

import argparse
import hashlib
import json
import os
import subprocess
import sys
import tempfile
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parents[1]

# what a user makes: the example recording, two characters (their practice and calibration run
# the engine hundreds of times), and a written character's recording replayed at about 2000 px
COMMANDS = [
    ("strokes.png", ["render", "examples/strokes.json", "-q", "-o", "{out}/strokes.png"]),
    (
        "yong.png",
        ["write", "永", "--data", "data/hanzi", "-q", "-o", "{out}/yong.png"]
        + ["--recording", "{out}/yong.json"],
    ),
    ("mo.png", ["write", "墨", "--data", "data/hanzi", "-q", "-o", "{out}/mo.png"]),
    (
        "yong_2000.png",
        ["render", "{out}/yong.json", "--px-per-mm", "20", "-q", "-o", "{out}/yong_2000.png"],
    ),
]

# the engine's state after the benchmark's workloads (bench.workload: 1 primitive at 2048 px,
# 16 at 4096 px for the first STEPS_16P samples, 8 at 1024 px)
STATE = """
import hashlib, sys
import numpy as np
from sim.cli import bench
s = bench.long_stroke()
cases = [("1p@2048", (s, 2048, 2048 / bench.PAPER_MM, 1), None),
         ("16p@4096", (s, 4096, 4096 / bench.PAPER_MM, 16), int(sys.argv[1])),
         ("8p@1024", (s, 1024, 5.0, 8), None)]
for name, args, until in cases:
    sim = bench.workload(*args).run(until)
    h = hashlib.sha256()
    for a in (sim.paper.ink, sim.paper.wet, sim.paper.last):
        h.update(np.ascontiguousarray(a).tobytes())
    snap = sim.brush.snapshot()
    for k in sorted(snap):
        v = snap[k]
        h.update(k.encode())
        h.update(v.tobytes() if isinstance(v, np.ndarray) else repr(v).encode())
    print(name, h.hexdigest())
"""


def run(root: Path, out: Path, quick: bool) -> dict:
    """Every command's output in ``out`` made by the checkout ``root``; returns the states."""
    env = dict(os.environ, XDG_CACHE_HOME=str(out / "cache"), PYTHONDONTWRITEBYTECODE="1")
    env.pop("HAIRY_BRUSH_CACHE", None)
    for _, argv in COMMANDS if not quick else COMMANDS[:2]:
        args = [a.format(out=out) for a in argv]
        subprocess.run([sys.executable, "-m", "sim", *args], cwd=root, env=env, check=True)
    steps = "120" if quick else "521"
    r = subprocess.run(
        [sys.executable, "-c", STATE, steps],
        cwd=root,
        env=dict(env, PYTHONPATH=str(root)),
        capture_output=True,
        text=True,
        check=True,
    )
    return dict(line.split() for line in r.stdout.strip().splitlines())


def pixels(path: Path) -> np.ndarray:
    from PIL import Image

    with Image.open(path) as im:
        return np.asarray(im)


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("other", type=Path, help="the checkout to compare with (e.g. main's)")
    ap.add_argument("--quick", action="store_true", help="the first two images, fewer states")
    ap.add_argument("--keep", type=Path, help="keep the other's results here, and reuse them")
    args = ap.parse_args()
    same = True
    with tempfile.TemporaryDirectory(prefix="same-results-") as tmp:
        outs = {"other": args.keep or Path(tmp) / "other", "this": Path(tmp) / "this"}
        states = {}
        for name, root in (("other", args.other.resolve()), ("this", HERE)):
            kept = outs[name] / ("states-quick.json" if args.quick else "states.json")
            if name == "other" and args.keep and kept.exists():
                states[name] = json.loads(kept.read_text())
                continue
            outs[name].mkdir(parents=True, exist_ok=True)
            states[name] = run(root, outs[name], args.quick)
            if name == "other" and args.keep:
                kept.write_text(json.dumps(states[name]))
        for image, _ in COMMANDS if not args.quick else COMMANDS[:2]:
            a, b = outs["other"] / image, outs["this"] / image
            byte_same = a.read_bytes() == b.read_bytes()
            pa, pb = pixels(a), pixels(b)
            px_same = pa.shape == pb.shape and np.array_equal(pa, pb)
            digest = hashlib.sha256(b.read_bytes()).hexdigest()[:16]
            print(f"{image:<14} bytes {'same' if byte_same else 'DIFFER'}, pixels "
                  f"{'same' if px_same else 'DIFFER'} ({pb.shape}, sha256 {digest})")  # fmt: skip
            same &= byte_same and px_same
        for case, digest in states["other"].items():
            ok = states["this"].get(case) == digest
            print(f"engine state {case:<9} {'same' if ok else 'DIFFERS'} (sha256 {digest[:16]})")
            same &= ok
    print("identical" if same else "NOT identical")
    return 0 if same else 1


if __name__ == "__main__":
    sys.exit(main())
