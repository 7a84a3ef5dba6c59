# SPDX-License-Identifier: GPL-3.0-or-later
"""Measure imitating pictures: for each character (hanzi-writer JSON) its outlines are
rendered into a picture, the picture alone is imitated, and the table gives the strokes found
against the known ones, the share of stroke pairs in the known order and of strokes running the
known way, the IoU of the brush's ink with the picture's ink and the texture score - beside the
same writer given the true stroke data (``sim write``) - and the seconds taken; then one JSON
line.

    python scripts/picture_eval.py tests/data/unseen/*.json [--size 512] [--passes 3] [--read-only]
"""

from __future__ import annotations

import argparse
import json
import sys
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))

from sim.core.recording import Recording  # noqa: E402
from sim.fitting.texture import score, texture_stats  # noqa: E402
from sim.picture.imitate import imitate, order_agreement, read_picture  # noqa: E402
from sim.writing.hanzi import find_char  # noqa: E402
from sim.writing.outline import iou, rasterise  # noqa: E402
from sim.writing.writer import coverage_mask, write_character  # noqa: E402


def template(seed: int = 0) -> Recording:
    return Recording(
        np.zeros((1, 6)),
        seed=seed,
        brush={"preset": "wolf_stiff"},
        paper_preset="smooth",
        ink={"preset": "sumi_black"},
    )


def evaluate(path: str, n: int, read_only: bool, passes: int = 3) -> dict:
    char = find_char(path)
    font = rasterise(char, n)
    pic = np.where(font, 0.05, 0.95)
    im = read_picture(pic, n)
    row = {"char": Path(path).stem, "read_s": round(im.seconds, 2)}
    row.update(order_agreement(im.char, char, n))
    if read_only:
        return row
    t0 = time.perf_counter()
    _, resp, sim, _ = imitate(pic, template(), n, passes=passes)
    row["write_s"] = round(time.perf_counter() - t0, 1)
    row["iou"] = round(iou(coverage_mask(sim), im.ink.mask), 4)
    row["score"] = round(score(texture_stats(sim.image())), 3)
    _, _, true = write_character(char, n, template(), response=resp, passes=passes)
    row["iou_true_data"] = round(iou(coverage_mask(true), font), 4)
    row["score_true_data"] = round(score(texture_stats(true.image())), 3)
    return row


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("chars", nargs="+")
    ap.add_argument("--size", type=int, default=512)
    ap.add_argument("--read-only", action="store_true", help="strokes and order only")
    ap.add_argument("--passes", type=int, default=3, help="practice passes per stroke")
    args = ap.parse_args(argv)
    rows = []
    for path in args.chars:
        rows.append(evaluate(path, args.size, args.read_only, args.passes))
        print("  ".join(f"{k} {v}" for k, v in rows[-1].items()), flush=True)
    keys = [k for k, v in rows[0].items() if isinstance(v, (int, float)) and k != "char"]
    mean = {k: round(float(np.mean([r[k] for r in rows])), 4) for k in keys}
    mean["same_order"] = sum(r["same"] for r in rows)
    print("mean  " + "  ".join(f"{k} {v}" for k, v in mean.items()))
    out = {"size": args.size, "passes": args.passes, "mean": mean, "rows": rows}
    print(json.dumps(out, ensure_ascii=False))
    return 0


if __name__ == "__main__":
    sys.exit(main())
