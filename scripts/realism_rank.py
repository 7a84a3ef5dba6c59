# SPDX-License-Identifier: GPL-3.0-or-later
"""The realism ranking benchmark (issue 26, point 5): the realism measure
(``sim.fitting.realism``, this version's) of

- the flat font: the character's stroke outlines filled (what a Kaiti font gives);
- the previous version's writing (``--against REV``, default da71a3a, the version before issue
  26's round of realism work), ``python -m sim write-set`` run in REV's files;
- this version's writing, the same command here;

for the characters the project holds out (tests/data/unseen) and, with ``--bundled``, the ones
it ships (data/hanzi). Both versions write with their command line's defaults at ``--size``
px, the same stroke data (this checkout's files), one process each. It prints each character's
three scores, then per set the mean and range of each and whether font < old < new holds for
the means and for how many characters, then one JSON line.

    python scripts/realism_rank.py [--against da71a3a] [--bundled] [--size 512] [--keep DIR]
"""

from __future__ import annotations

import argparse
import json
import shutil
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))

from scripts.revision import DEFAULT_AGAINST, versions  # noqa: E402
from sim.fitting.realism import realism  # noqa: E402
from sim.image.png import read_png  # noqa: E402
from sim.writing.outline import rasterise  # noqa: E402

SETS = {"unseen": ROOT / "tests" / "data" / "unseen", "bundled": ROOT / "data" / "hanzi"}


def flat_font(char: dict, n: int) -> np.ndarray:
    """The font's character, its outlines filled: black on white, 2x supersampled (a font
    renderer's anti-aliased edges)."""
    cover = rasterise(char, 2 * n).reshape(n, 2, n, 2).mean(axis=(1, 3))
    return np.repeat(1.0 - cover[..., None], 3, axis=2)


def written(version, folder: Path, chars: list[str], size: int, out: Path, workers: int):
    """The version's writing of each character (RGB in [0, 1]), with write-set's defaults."""
    out.mkdir(parents=True)
    t0 = time.perf_counter()
    version.sim(
        "write-set",
        *chars,
        "--data",
        folder,
        "--size",
        size,
        "--workers",
        workers,
        "-q",
        "--out-dir",
        out,
    )
    sys.stderr.write(
        f"{version.name}: {len(chars)} characters in {time.perf_counter() - t0:.0f} s\n"
    )
    return [read_png(out / f"{k:03d}.png")[..., :3] / 255.0 for k in range(len(chars))]


def _stats(v) -> dict:
    return {
        "mean": round(float(np.mean(v)), 4),
        "min": round(float(np.min(v)), 4),
        "max": round(float(np.max(v)), 4),
    }


def rank_set(name, folder, vs, size, tmp, workers) -> dict:
    """One set's table and summary; the scores by version."""
    chars = sorted(p.stem for p in folder.glob("*.json"))
    data = {c: json.loads((folder / f"{c}.json").read_text("utf-8")) for c in chars}
    scores = {"font": [realism(flat_font(data[c], size)).score for c in chars]}
    for v in vs[::-1]:  # the old version first: the ranking reads font, old, new
        imgs = written(v, folder, chars, size, tmp / f"{name}_{v.name.split()[0]}", workers)
        scores[v.name] = [realism(img).score for img in imgs]
    cols = list(scores)
    print(f"\n{name} ({folder.relative_to(ROOT)}, {len(chars)} characters, {size} px)")
    print(f"{'char':<6}" + "".join(f"{c:>18}" for c in cols))
    for k, c in enumerate(chars):
        print(f"{c:<6}" + "".join(f"{scores[col][k]:18.3f}" for col in cols))
    summary = {col: _stats(scores[col]) for col in cols}
    for label, key in (("mean", "mean"), ("lowest", "min"), ("highest", "max")):
        print(f"{label:<6}" + "".join(f"{summary[col][key]:18.3f}" for col in cols))
    means = [summary[col]["mean"] for col in cols]
    holds = bool(all(a < b for a, b in zip(means, means[1:], strict=False)))
    each = sum(
        all(scores[a][k] < scores[b][k] for a, b in zip(cols, cols[1:], strict=False))
        for k in range(len(chars))
    )
    order = " < ".join(cols)
    print(
        f"{order}: {'holds' if holds else 'does NOT hold'} for the means; "
        f"for {each} of {len(chars)} characters"
    )
    return {
        "chars": "".join(chars),
        "size": size,
        "scores": {col: [round(s, 4) for s in scores[col]] for col in cols},
        "summary": summary,
        "order_holds_for_means": holds,
        "order_holds_for_chars": each,
    }


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument(
        "--against", default=DEFAULT_AGAINST, help="the previous version ('none': this alone)"
    )
    ap.add_argument("--bundled", action="store_true", help="also the bundled data/hanzi")
    ap.add_argument("--size", type=int, default=512, help="pixels a character (the em box)")
    ap.add_argument("--workers", type=int, default=1, help="processes of write-set")
    ap.add_argument("--keep", default=None, help="keep the written PNGs in this folder")
    args = ap.parse_args(argv)
    against = None if args.against.lower() == "none" else args.against
    t0 = time.perf_counter()
    res = {"against": against}
    with tempfile.TemporaryDirectory(prefix="hairy-brush-realism-") as t:
        tmp = Path(t)
        with versions(tmp, against) as vs:
            for name in ["unseen"] + (["bundled"] if args.bundled else []):
                res[name] = rank_set(name, SETS[name], vs, args.size, tmp, args.workers)
            if args.keep:
                keep = Path(args.keep)
                keep.mkdir(parents=True, exist_ok=True)
                for d in tmp.glob("*_*"):
                    if d.is_dir() and not d.name.startswith("cache"):
                        shutil.copytree(d, keep / d.name, dirs_exist_ok=True)
    res["seconds"] = round(time.perf_counter() - t0, 1)
    print(f"\n{res['seconds']:.0f} s")
    print(json.dumps(res, ensure_ascii=False))
    return 0


if __name__ == "__main__":
    sys.exit(main())
