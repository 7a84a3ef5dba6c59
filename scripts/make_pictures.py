# SPDX-License-Identifier: GPL-3.0-or-later
"""Render the effect gallery shown in README (docs/img/*.png) with the engine alone."""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))

from sim.core.recording import Dip, Recording  # noqa: E402
from sim.engine.simulation import Simulation  # noqa: E402
from sim.image.png import write_png  # noqa: E402
from sim.writing.strokes import stroke  # noqa: E402

OUT = ROOT / "docs" / "img"


def run(
    samples,
    paper="raw_xuan",
    brush="mixed",
    ink="sumi_black",
    dips=None,
    ppm=6.0,
    size=(110, 40),
    seed=0,
    quality=None,
):
    rec = Recording(
        np.asarray(samples),
        width_mm=size[0],
        height_mm=size[1],
        px_per_mm=ppm,
        seed=seed,
        brush={"preset": brush},
        paper_preset=paper,
        ink={"preset": ink},
        quality=quality or {},
        dips=dips or [],
    )
    sim = Simulation(rec).run()
    return sim


def effects():
    """One strip per effect: the stroke left to right across a 110 x 40 mm sheet."""
    L = 30.0
    rows = []
    # gray levels: the same stroke with a full, a half and a nearly dry brush
    for wet in (0.95, 0.5, 0.25):
        s = stroke([[10, 20], [100, 20]], press_mm=9, hair_length_mm=L)
        rows.append((f"gray_{int(wet * 100):02d}", run(s, dips=[Dip(0, 0.8, (0, 0, 0), wet)])))
    # colour
    s = stroke([[10, 20], [100, 20]], press_mm=9, hair_length_mm=L)
    rows.append(("vermilion", run(s, dips=[Dip(0, 0.8, (0.82, 0.16, 0.09), 0.85)])))
    # flying white: a fast, pressed stroke with little ink
    s = stroke([[10, 20], [100, 20]], press_mm=10, speed_mm_s=160, hair_length_mm=L)
    rows.append(("flying_white", run(s, ink="dry_ink", dips=[Dip(0, 0.5, (0, 0, 0), 0.3)])))
    # saturation: slow, very wet stroke on raw xuan vs smooth paper
    s = stroke([[10, 20], [100, 20]], press_mm=9, speed_mm_s=25, hair_length_mm=L)
    rows.append(("bleed_raw_xuan", run(s, paper="raw_xuan", dips=[Dip(0, 1.0, (0, 0, 0), 1.0)])))
    rows.append(("bleed_smooth", run(s, paper="smooth", dips=[Dip(0, 1.0, (0, 0, 0), 1.0)])))
    # splitting: heavy pressure with a soft goat brush vs light pressure
    s = stroke([[10, 20], [100, 20]], press_mm=16, speed_mm_s=90, hair_length_mm=34)
    rows.append(("split_heavy", run(s, brush="goat_soft", dips=[Dip(0, 0.9, (0, 0, 0), 0.7)])))
    s = stroke([[10, 20], [100, 20]], press_mm=5, speed_mm_s=60, hair_length_mm=34)
    rows.append(("split_light", run(s, brush="goat_soft", dips=[Dip(0, 0.9, (0, 0, 0), 0.7)])))
    return rows


def imitation(chars="永心法风", n=256):
    """docs/img/imitate.png: for each character, the font (left) and the brush's writing with
    the defaults (right), and below them the two laid over each other (red: ink outside the
    outline, cyan: outline the ink missed)."""
    from sim.writing.hanzi import find_char
    from sim.writing.outline import iou
    from sim.writing.writer import coverage_mask, font_mask, write_character

    tmpl = Recording(np.zeros((1, 6)))  # the default brush, paper and quality
    cols, response = [], None
    for ch in chars:
        c = find_char(ch)
        _, response, sim = write_character(c, n, tmpl, response=response)
        font, ink = font_mask(c, n), coverage_mask(sim)
        top = np.concatenate([np.repeat(1.0 - font[..., None] * 0.9, 3, axis=2), sim.image()], 1)
        over = np.ones((n, n, 3))
        over[ink & ~font] = (0.9, 0.2, 0.2)
        over[font & ~ink] = (0.2, 0.8, 0.9)
        over[font & ink] = (0.1, 0.1, 0.1)
        pad = np.ones((n, n, 3))
        cols.append(np.concatenate([top, np.concatenate([over, pad], 1)], 0))
        print(f"{ch}: IoU {iou(ink, font):.3f}")
    write_png(OUT / "imitate.png", np.concatenate(cols, axis=1))


def overlay(chars, n=512, passes=None, quality=None, out=None):
    """Each character as the defaults write it (or with a quality file), the font's outline
    laid over it in red (its boundary), one PNG per character and a contact sheet."""
    from sim.fitting.search import load_quality
    from sim.writing.hanzi import find_char
    from sim.writing.outline import iou
    from sim.writing.writer import coverage_mask, font_mask, write_character

    q = load_quality(quality) if quality else {}
    tmpl = Recording(np.zeros((1, 6)), quality=q)  # the default brush and paper
    out = Path(out or ROOT / "out" / "overlay")
    out.mkdir(parents=True, exist_ok=True)
    tiles, response = [], None
    kw = {} if passes is None else {"passes": passes}
    for ch in chars:
        c = find_char(ch)
        _, response, sim = write_character(c, n, tmpl, response=response, **kw)
        font, ink = font_mask(c, n), coverage_mask(sim)
        edge = font & ~(
            np.roll(font, 1, 0) & np.roll(font, -1, 0) & np.roll(font, 1, 1) & np.roll(font, -1, 1)
        )
        img = sim.image().copy()
        img[edge] = (0.9, 0.1, 0.1)
        write_png(out / f"{ord(ch):x}.png", img)
        tiles.append(img[::2, ::2])
        print(f"{ch}: IoU {iou(ink, font):.3f}", flush=True)
    rows = [
        np.concatenate(tiles[i : i + 4] + [np.ones_like(tiles[0])] * (4 - len(tiles[i : i + 4])), 1)
        for i in range(0, len(tiles), 4)
    ]
    write_png(out / "sheet.png", np.concatenate(rows, 0))


def main():
    OUT.mkdir(parents=True, exist_ok=True)
    if "--imitation" in sys.argv:
        imitation()
        return
    if "--overlay" in sys.argv:  # --overlay CHARS [quality.json]: the defaults with the outline
        i = sys.argv.index("--overlay")
        rest = sys.argv[i + 1 :]
        overlay(rest[0], quality=rest[1] if len(rest) > 1 else None)
        return
    rows = effects()
    imgs = []
    for name, sim in rows:
        img = sim.image()
        write_png(OUT / f"effect_{name}.png", img)
        imgs.append(img)
        print(f"{name}: primitives {sim.brush.m}, splits {sim.brush.splits}")
    write_png(OUT / "effects.png", np.concatenate(imgs, axis=0))


if __name__ == "__main__":
    main()
