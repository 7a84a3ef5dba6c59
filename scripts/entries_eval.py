# SPDX-License-Identifier: GPL-3.0-or-later
"""Stroke starts and dots against the font outline (issue 26, point 2: pressed entries, dots).

    python scripts/entries_eval.py write TAG CHARS [BRUSH] [NAME=VALUE ...]
    python scripts/entries_eval.py report TAG_BRUSH [TAG_BRUSH ...]

``write`` writes each character (512 px, the command line's defaults but the brush; NAME=VALUE
sets a constant of sim.writing.planner / writer / outline for an experiment) and keeps its ink
and image in /tmp/entries_eval/TAG_BRUSH.npz; ``report`` prints per character, for every
stroke start, the ink more than a pixel outside the outline and the bare outline pixels within
1.2 stroke widths (the first third's widest) of the median's start, and of that ink outside the
thin protrusions (hair threads, spikes: what an opening of THIN px takes off the ink outside)
in pixels and pieces; for every dot (a median shorter than 3.4 of its widest) the ink's length
along the dot's direction over the font's, and the ink pixels past the font dot's end.
Characters of data/hanzi are read from there, the rest from /tmp/chars/package
(hanzi-writer-data)."""

from __future__ import annotations

import argparse
import os
import sys
from pathlib import Path

import numpy as np
from scipy import ndimage as ndi

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))

from sim.cli.shared import _chars, _response, _template  # noqa: E402
from sim.writing.outline import (  # noqa: E402
    EM,
    distance_to_outline,
    fill,
    median_movements,
    resample,
    stroke_polygons,
    to_image,
)
from sim.writing.planner import RUN_UP, _landing, _narrow_head  # noqa: E402
from sim.writing.writer import coverage_mask, write_character  # noqa: E402

OUT = os.environ.get("ENTRIES_EVAL_OUT", "/tmp/entries_eval")
SHIPPED = "一中之书人十大天山心日月水永法风"
N = 512
DOT = 3.4  # median length over widest below which a stroke is read as a dot
THIN = 3  # px: ink outside the outline narrower than this is a thin protrusion (a thread)


def load(c: str) -> dict:
    return _chars([c], str(ROOT / "data/hanzi") if c in SHIPPED else "/tmp/chars/package")[0]


def write(tag: str, chars: str, brush: str) -> None:
    from sim.core.recording import DEFAULT_PAPER

    ns = argparse.Namespace(seed=0, brush=brush, paper=DEFAULT_PAPER, ink="sumi_black")
    ns.quality = None
    template = _template(ns)
    resp, out = _response(template), {}
    for c in chars:
        _, resp, sim = write_character(load(c), N, template, response=resp)
        out[c] = coverage_mask(sim)
        out[c + "_img"] = (np.clip(sim.image(), 0, 1) * 255).astype(np.uint8)
        print(c, flush=True)
    os.makedirs(OUT, exist_ok=True)
    np.savez_compressed(f"{OUT}/{tag}_{brush}.npz", **out)


def strokes(ch: dict) -> list[dict]:
    """Per stroke: its median (image px), length, widest, first third's widest, mask, and
    whether its head is entered with the tip hidden (``planner._landing`` of its first
    movement)."""
    out = []
    moves = median_movements(ch)
    for k, (med, polys) in enumerate(zip(ch["medians"], stroke_polygons(ch), strict=True)):
        med = np.asarray(med, float)
        pts, _ = resample(med, 4.0)
        r = np.maximum(distance_to_outline(pts, polys), 0.0)
        length = np.linalg.norm(np.diff(med, axis=0), axis=1).sum()
        dot = len(moves[k][0]) == 1 and length < DOT * 2 * r.max()  # (the planner's: lifts.is_dot)
        out.append(
            {
                "med": to_image(med, N),
                "length": length * N / EM,
                "w": 2 * r.max() * N / EM,
                "w0": 2 * r[: max(len(r) // 3, 1)].max() * N / EM,
                "mask": fill([to_image(p, N) for p in polys], N),
                "hidden": _landing(moves[k][0][0][0], RUN_UP, dot or _narrow_head(r)) < 0.0,
            }
        )
    return out


def measure(ch: dict, ink: np.ndarray):
    info = strokes(ch)
    font = np.any([s["mask"] for s in info], axis=0)
    near = ndi.binary_dilation(font, iterations=1)
    yy, xx = np.mgrid[0:N, 0:N] + 0.5
    outside = ink & ~near
    thin = outside & ~ndi.binary_opening(outside, np.ones((THIN, THIN), bool))
    starts, dots = [], []
    for k, s in enumerate(info):
        p0 = s["med"][0]
        zone = np.hypot(xx - p0[0], yy - p0[1]) < 1.2 * s["w0"]
        starts.append((int((ink & ~near & zone).sum()), int((s["mask"] & ~ink & zone).sum())))
        starts[-1] += (int((s["mask"] & zone).sum()),)
        threads = thin & zone
        starts[-1] += (int(threads.sum()), int(ndi.label(threads)[1]), s["hidden"])
        if s["length"] >= DOT * s["w"]:
            continue
        d = s["med"][-1] - p0
        d /= np.linalg.norm(d)
        others = np.any([o["mask"] for j, o in enumerate(info) if j != k] or [~font], axis=0)
        own = ndi.binary_dilation(s["mask"], iterations=max(int(0.5 * s["w"]), 2))
        mine = ink & own & ~ndi.binary_dilation(others, iterations=2)
        pf = (xx[s["mask"]] - p0[0]) * d[0] + (yy[s["mask"]] - p0[1]) * d[1]
        pi = (xx[mine] - p0[0]) * d[0] + (yy[mine] - p0[1]) * d[1]
        if len(pi):
            dots.append(
                ((pi.max() - pi.min()) / (pf.max() - pf.min()), int((pi > pf.max() + 1).sum()))
            )
    return starts, dots


def report(tags) -> None:
    for tag in tags:
        z = np.load(f"{OUT}/{tag}.npz")
        out = bare = area = thin = pieces = 0
        lengths, past = [], 0
        split = np.zeros((2, 5), int)  # per kind of head (tip showing, hidden): out .. pieces
        print(tag)
        for c in [k for k in z.files if not k.endswith("_img")]:
            starts, dots = measure(load(c), z[c])
            o, b, a, t, p = (sum(s[i] for s in starts) for i in range(5))
            out, bare, area = out + o, bare + b, area + a
            thin, pieces = thin + t, pieces + p
            lengths += [d[0] for d in dots]
            past += sum(d[1] for d in dots)
            for s in starts:
                split[int(s[5])] += s[:5]
            ds = " ".join(f"{d[0]:.2f}/{d[1]}" for d in dots)
            print(
                f"  {c} starts: out {o:5d} (thin {t:4d} in {p:2d}) bare {b:5d} of {a:6d}"
                f"  dots (length/font/past): {ds}"
            )
        dl = f"mean {np.mean(lengths):.3f} max {np.max(lengths):.3f}" if lengths else "-"
        print(
            f"  all starts: out {out} (thin {thin} in {pieces} pieces) bare {bare} of {area};"
            f" dots {len(lengths)}: {dl}, past {past}"
        )
        for kind, (o, b, a, t, p) in zip(("tip showing", "hidden tip"), split, strict=True):
            print(f"    {kind:11s} heads: out {o} (thin {t} in {p} pieces) bare {b} of {a}")


if __name__ == "__main__":
    if sys.argv[1] == "write":
        import sim.writing.outline as O
        import sim.writing.planner as P
        import sim.writing.writer as W

        for kv in sys.argv[5:]:
            name, value = kv.split("=")
            v = tuple(map(float, value.split(","))) if "," in value else float(value)
            for mod in (P, W, O):
                if hasattr(mod, name):
                    setattr(mod, name, v)
        write(sys.argv[2], sys.argv[3], sys.argv[4] if len(sys.argv) > 4 else "wolf_kaishu")
    else:
        report(sys.argv[2:])
