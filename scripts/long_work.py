# SPDX-License-Identifier: GPL-3.0-or-later
"""A long work end to end, on a Dask cluster and on this machine's processes (issue 27): the
千字文 (examples/qianziwen.txt, 1,000 characters, 4 of them outside hanzi-writer-data and
left out with ``--skip-missing``), signed and sealed, composed twice with ``sim compose``, once
with ``--scheduler local`` (a Dask LocalCluster) and once with ``--workers`` processes; the two
sheets, layouts and recordings are compared byte for byte; the wall time of each run and the
peak memory are printed.

    python scripts/long_work.py [--char-size 64] [--workers 2] [--out DIR] [--text-file F]

A run whose three files are already in ``--out`` (from an earlier call) is not made again, so
the two halves can be run at different times. Exit status 0 when the two are identical."""

from __future__ import annotations

import argparse
import os
import resource
import subprocess
import sys
import time
from pathlib import Path

HERE = Path(__file__).resolve().parents[1]
FILES = ("png", "json", "rec.json")  # the sheet, its layout (--layout-out), its recording


def compose(name: str, out: Path, args, extra: list[str]) -> float | None:
    """One ``sim compose`` of the text into ``out/<name>.*``: its wall seconds, or None when
    its files were already there."""
    paths = [out / f"{name}.{ext}" for ext in FILES]
    if all(p.exists() for p in paths):
        return None
    argv = [sys.executable, "-m", "sim", "compose", "--text-file", str(args.text_file)]
    argv += ["--skip-missing", "--char-size", str(args.char_size), "--workers", str(args.workers)]
    argv += ["--signature", args.signature, "--seal", args.seal, "-o", str(paths[0])]
    argv += ["--layout-out", str(paths[1]), "--save-recording", str(paths[2]), *extra]
    env = dict(os.environ, XDG_CACHE_HOME=str(out / "cache"))
    t0 = time.perf_counter()
    subprocess.run(argv, cwd=HERE, env=env, check=True)
    return time.perf_counter() - t0


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--text-file", type=Path, default=HERE / "examples" / "qianziwen.txt")
    ap.add_argument("--char-size", type=int, default=64, help="pixels a character")
    ap.add_argument("--workers", type=int, default=2)
    ap.add_argument("--signature", default="周兴嗣")
    ap.add_argument("--seal", default="千字文")
    ap.add_argument("--out", type=Path, default=Path("long-work"))
    args = ap.parse_args()
    args.out.mkdir(parents=True, exist_ok=True)
    for name, extra in (("dask", ["--scheduler", "local"]), ("local", [])):
        took = compose(name, args.out, args, extra)
        if took is None:
            print(f"{name}: made earlier, in {args.out}")
        else:
            print(f"{name}: {took:.0f} s wall")
    peak = resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss / 1024.0
    if peak:
        print(f"peak memory of the largest process run here: {peak:.0f} MB")
    same = True
    for ext in FILES:
        a, b = (args.out / f"{n}.{ext}" for n in ("dask", "local"))
        ok = a.read_bytes() == b.read_bytes()
        print(f"{ext:<8} {'same' if ok else 'DIFFER'} ({a.stat().st_size} bytes)")
        same &= ok
    print("Dask and local: identical" if same else "Dask and local: NOT identical")
    return 0 if same else 1


if __name__ == "__main__":
    sys.exit(main())
