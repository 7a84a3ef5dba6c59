# SPDX-License-Identifier: GPL-3.0-or-later
"""Picks the real pages the realism proxy (``scripts/judge_proxy.py``) is trained on (issue 26,
point 5), by a stated rule, so that the set can be rebuilt on any machine.

The source: ``data/kaishu`` of ``wayofnumbers/chinese-calligraphy-classifier-fastai`` (529
web-scraped pictures of regular script: copybook pages, photographs of works, rubbings,
thumbnails, photos of people writing). The images carry no licence: they stay in /tmp and are
never committed. Extract them with::

    G=<bare git dir of the repository>
    git --git-dir=$G ls-tree -r -z --name-only HEAD data/kaishu | while IFS= read -r -d '' p; do
        git --git-dir=$G show "HEAD:$p" > "/tmp/judge-real/all/$(basename "$p")"; done

The rule (every threshold is a module constant below; the image is kept if all hold):

1. it opens and its shorter side is at least ``MIN_SIDE`` px;
2. a plain ground: the paper (pixels brighter than the image's 60th percentile of grey) has a
   median chroma (max - min of R, G, B) under ``MAX_GROUND_CHROMA`` (white, cream or grey
   paper; red, yellow or blue grounds are out) and a median grey of at least
   ``MIN_GROUND_GREY`` (rubbings, white on black, dark photographs are out);
3. dark ink: the ink (``judge_proxy.ink_density`` > 0.5) is at least ``MIN_INK_CONTRAST``
   darker than the paper (faded prints and pencil are out);
4. enough ink, but not a page of solid ink: its share of the picture is within ``INK_SHARE``;
5. ink, not a scene: at most ``MAX_MID_SHARE`` of the inked region (D > 0.2) is mid-tone
   (0.2 < D < 0.8): photographs of people, desks and hands are full of mid-tones, written
   ink is mostly solid with a thin transition;
6. written strokes, not a printed grid or print: at most ``MAX_THIN_SHARE`` of the inked area
   (D > 0.25) lies in thin pieces (no point deeper than a fifth of the stroke width: dashed
   and dotted grid lines, printed captions, halftone; a brush's hairline tail is joined to
   its stroke and counts with it);
7. the stroke width (``judge_proxy.stroke_width``) is within ``STROKE_WIDTH`` px: wide enough
   to be judged at 10 px without enlarging more than the proxy allows, narrow enough to be
   writing rather than a few giant characters on a poster;
8. near-duplicates (the same page scraped twice) are kept once: a 16 x 16 thumbnail of the
   density closer than ``DUP_DISTANCE`` (mean absolute difference) to one already kept;
9. no one book decides the set: of a series (names that differ only in a trailing ``_NNN``,
   the source's 167 pages of one printed copybook) at most ``SERIES_MAX`` pages are kept,
   evenly spread through it.

    python scripts/judge_real_set.py /tmp/judge-real/all --out /tmp/judge-real/sel \\
        [--sheet /tmp/judge-real/sheet] [--json /tmp/judge-real/rule.json]

``--sheet`` writes two contact sheets (kept, rejected with the first rule each broke), to look at.
"""

from __future__ import annotations

import argparse
import json
import re
import shutil
import sys
from pathlib import Path

import numpy as np
from PIL import Image, ImageDraw
from scipy import ndimage as ndi

sys.path.insert(0, str(Path(__file__).resolve().parent))
import judge_proxy as jp  # noqa: E402

MIN_SIDE = 200  # px, shorter side
MAX_GROUND_CHROMA = 0.10  # median (max - min of RGB) over the paper
MIN_GROUND_GREY = 0.62  # median grey of the paper
MIN_INK_CONTRAST = 0.45  # paper grey - median ink grey
INK_SHARE = (0.02, 0.45)  # share of the picture in ink (D > 0.5)
MAX_MID_SHARE = 0.45  # share of the inked region (D > 0.2) at mid density
MAX_THIN_SHARE = 0.10  # share of the inked area (D > 0.25) in thin pieces (grids, print)
STROKE_WIDTH = (8.0, 60.0)  # px, native
DUP_DISTANCE = 0.03  # mean |difference| of 16 x 16 density thumbnails
THUMB = 16
SERIES_MAX = 8  # pages kept of one series at most


def _thin_share(d: np.ndarray, width: float) -> float:
    """Share of the inked area (D > 0.25) in pieces no point of which is deeper than a fifth
    of the stroke width."""
    m = d > 0.25
    lab, n = ndi.label(m)
    if not n:
        return 0.0
    depth = np.asarray(ndi.maximum(ndi.distance_transform_edt(m), lab, np.arange(1, n + 1)))
    area = np.bincount(lab.ravel(), minlength=n + 1)[1:]
    return float(area[depth < width / 5].sum() / max(area.sum(), 1))


def _measure(path: Path) -> dict:
    """The figures the rule looks at; ``reason`` is the first rule broken (None: kept)."""
    try:
        im = Image.open(path)
        im.load()
    except Exception:  # noqa: BLE001 - any unreadable file is simply left out
        return {"reason": "unreadable"}
    if min(im.size) < MIN_SIDE:
        return {"reason": "small", "side": min(im.size)}
    rgb = np.asarray(im.convert("RGB"), dtype=np.float64) / 255.0
    grey = rgb.max(axis=2)
    ground = grey >= np.percentile(grey, 60)
    chroma = float(np.median((rgb.max(axis=2) - rgb.min(axis=2))[ground]))
    ground_grey = float(np.median(grey[ground]))
    out = {"chroma": chroma, "ground": ground_grey}
    if chroma > MAX_GROUND_CHROMA:
        return out | {"reason": "coloured ground"}
    if ground_grey < MIN_GROUND_GREY or np.median(grey) < 0.45:
        return out | {"reason": "dark ground"}
    d = jp.ink_density(grey)
    if d is None:
        return out | {"reason": "no ink"}
    ink = d > 0.5
    out["contrast"] = float(ground_grey - np.median(grey[ink])) if ink.any() else 0.0
    out["ink_share"] = float(ink.mean())
    inked = d > 0.2
    out["mid_share"] = float(((d > 0.2) & (d < 0.8)).sum() / max(inked.sum(), 1))
    out["width"] = jp.stroke_width(ink)
    out["thumb"] = (
        np.asarray(
            Image.fromarray(np.uint8(255 * d)).resize((THUMB, THUMB), Image.BILINEAR), float
        ).ravel()
        / 255.0
    )
    if out["contrast"] < MIN_INK_CONTRAST:
        return out | {"reason": "faint ink"}
    if not INK_SHARE[0] <= out["ink_share"] <= INK_SHARE[1]:
        return out | {"reason": "ink share"}
    if out["mid_share"] > MAX_MID_SHARE:
        return out | {"reason": "mid-tones (scene)"}
    out["thin_share"] = _thin_share(d, out["width"])
    if out["thin_share"] > MAX_THIN_SHARE:
        return out | {"reason": "grid or print"}
    if not STROKE_WIDTH[0] <= out["width"] <= STROKE_WIDTH[1]:
        return out | {"reason": "stroke width"}
    return out | {"reason": None}


def select(paths: list[Path]) -> dict[str, dict]:
    """Every image's figures and verdict, in name order (rules 1-7, ``_measure``), then
    duplicates (rule 8) and series beyond SERIES_MAX (rule 9) rejected."""
    return cap_series(drop_duplicates({p.name: _measure(p) for p in sorted(paths)}))


def drop_duplicates(res: dict[str, dict]) -> dict[str, dict]:
    """Rule 8: an image kept so far whose thumbnail is within DUP_DISTANCE of an earlier kept
    one is rejected (in name order); the thumbnails are dropped."""
    kept = []
    for r in res.values():
        thumb = r.pop("thumb", None)
        if r["reason"] is not None:
            continue
        if any(np.abs(thumb - t).mean() < DUP_DISTANCE for t in kept):
            r["reason"] = "duplicate"
        else:
            kept.append(thumb)
    return res


def cap_series(res: dict[str, dict]) -> dict[str, dict]:
    """Rule 9: of the kept images of one series (the same name but for a trailing _NNN), at
    most SERIES_MAX, evenly spread in name order."""
    series: dict[str, list[str]] = {}
    for n, r in res.items():
        if r["reason"] is None:
            series.setdefault(re.sub(r"_\d+$", "", Path(n).stem), []).append(n)
    for names in series.values():
        if len(names) > SERIES_MAX:
            pick = set(np.linspace(0, len(names) - 1, SERIES_MAX).round().astype(int).tolist())
            for i, n in enumerate(names):
                if i not in pick:
                    res[n]["reason"] = "series cap"
    return res


def contact_sheet(paths: list[Path], labels: list[str], out: Path, cell: int = 160) -> None:
    """A grid of thumbnails with a label under each."""
    if not paths:
        return
    cols = 10
    rows = -(-len(paths) // cols)
    sheet = Image.new("RGB", (cols * cell, rows * (cell + 14)), "white")
    draw = ImageDraw.Draw(sheet)
    for i, (p, lab) in enumerate(zip(paths, labels, strict=True)):
        x, y = (i % cols) * cell, (i // cols) * (cell + 14)
        try:
            im = Image.open(p).convert("RGB")
            im.thumbnail((cell - 4, cell - 4))
            sheet.paste(im, (x + 2, y + 2))
        except Exception:  # noqa: BLE001
            pass
        draw.text((x + 2, y + cell), lab[:26], fill="red")
    sheet.save(out)


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("src", type=Path, help="folder of all the source images")
    ap.add_argument("--out", type=Path, required=True, help="folder the kept images go to")
    ap.add_argument("--sheet", type=Path, help="folder for the contact sheets")
    ap.add_argument("--json", type=Path, help="every image's figures and verdict")
    a = ap.parse_args(argv)
    paths = [p for p in a.src.iterdir() if p.suffix.lower() in jp.IMAGE_EXT]
    res = select(paths)
    a.out.mkdir(parents=True, exist_ok=True)
    for f in a.out.iterdir():
        f.unlink()
    keep = [n for n, r in res.items() if r["reason"] is None]
    for n in keep:
        shutil.copy2(a.src / n, a.out / n)
    counts: dict[str, int] = {}
    for r in res.values():
        counts[r["reason"] or "kept"] = counts.get(r["reason"] or "kept", 0) + 1
    print(f"{len(res)} images: " + ", ".join(f"{k} {v}" for k, v in sorted(counts.items())))
    if a.json:
        a.json.write_text(json.dumps(res, indent=1))
    if a.sheet:
        a.sheet.mkdir(parents=True, exist_ok=True)
        w = [f"w{res[n]['width']:.0f} m{res[n]['mid_share']:.2f}" for n in keep]
        contact_sheet([a.src / n for n in keep], w, a.sheet / "kept.png")
        rej = [n for n, r in res.items() if r["reason"] is not None]
        why = [res[n]["reason"] for n in rej]
        contact_sheet([a.src / n for n in rej], why, a.sheet / "rejected.png")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
