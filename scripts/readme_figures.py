# SPDX-License-Identifier: GPL-3.0-or-later
"""README's pictures of issues 26 and 27, each made by the command line (``python -m sim``)
in a child process, so that they can be made again after any change to the writing:

- realism_before_after.png: 永 and 虎 written at 512 px by the previous version (``--against
  REV``, default da71a3a, before issue 26's realism work) and by this one (``sim write`` with
  the defaults); for each, the whole character (boxes where the crops are) and four crops at
  4x zoom, nearest-neighbour (every pixel a 4 x 4 block): a stretch of edge, a stroke's end
  written late in the character (where the brush is driest), a turn and a hook. The places are
  found in the stroke data (the longest straight stretch, the end of the last long stroke, the
  sharpest turn with most of the stroke after it, the sharpest turn near a stroke's end), not
  chosen by eye;
- imitate_real.png: real-style pictures (``scripts/picture_real.py``: a system Kaiti font,
  blurred, uneven light, paper texture, JPEG) beside ``sim imitate``'s writing of them, with the
  box-normalised IoU of the imitation's ink against the picture's true ink;
- work_vertical.png: ``sim compose`` of a four-line poem in columns, signed and sealed;
- work_horizontal.png: a shorter text in a row, signed and sealed.

PNGs are kept under MAX_BYTES (fewer colours, then smaller) with Pillow. ``--demo`` also runs
``scripts/demo.py`` (Blender, Cycles) and copies its 永 and scroll render to demo_yong.png and
demo_render.png.

    python scripts/readme_figures.py [--against da71a3a] [--out docs/img] [--only NAME,...]
        [--char-size 160] [--demo]
"""

from __future__ import annotations

import argparse
import io
import json
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))

from scripts.revision import DEFAULT_AGAINST, versions  # noqa: E402

MAX_BYTES = 600_000
LABEL_FONTS = (  # Latin and CJK labels: the first installed
    "/usr/share/fonts/truetype/wqy/wqy-microhei.ttc",
    "/usr/share/fonts/truetype/arphic/uming.ttc",
    "/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf",
)
PAPER_WHITE = (255, 255, 255)
# -------------------------------------------------------------------- realism_before_after
BA_CHARS = "永虎"
BA_SIZE = 512  # px the em box, as ``sim write`` writes by default
CROP = 64  # px of the 512 px character a crop shows (an eighth of the em box)
ZOOM = 4
FEATURES = ("edge", "dry end", "turn", "hook")
BOX_COLOURS = ((0, 110, 220), (230, 120, 0), (0, 160, 80), (200, 0, 160))
STEP = 4.0  # data units between resampled median points
CHORD = 60.0  # data units either side over which a median's heading is read
END_BACK = 40.0  # data units the dry end's crop is centred back from the median's end
HOOK_TAIL = 0.3  # a sharp turn with less than this share of its stroke after it is a hook
# ------------------------------------------------------------------------ imitate_real
IMITATE = (("国", "ukai", "scan"), ("飞", "gkai", "photo"))  # never tuned on (imitate_eval)
IMITATE_SIZE = 512
PANEL = 360  # px each picture is shown at
# ------------------------------------------------------------------------------ works
POEM = "床前明月光\n疑是地上霜\n举头望明月\n低头思故乡"
POEM_SIGN, POEM_SEAL = "李白静夜思", "太白"
ROW = "上善若水"
ROW_SIGN, ROW_SEAL = "老子句", "守拙"


# ------------------------------------------------------------------------------ helpers
def save_png(rgb: np.ndarray, path: Path) -> None:
    """RGB uint8 as an optimised PNG under MAX_BYTES: as it is, else with 256 (then 128)
    colours (median cut, no dither: flat paper stays flat), else smaller by steps of 0.85."""
    from PIL import Image

    img = Image.fromarray(np.ascontiguousarray(rgb, dtype=np.uint8), "RGB")
    tries = [(img, None), (img, 256), (img, 128)]
    data = b""
    while True:
        for im, colours in tries:
            if colours:
                im = im.quantize(colours, Image.Quantize.MEDIANCUT, dither=Image.Dither.NONE)
            buf = io.BytesIO()
            im.save(buf, "PNG", optimize=True)
            data = buf.getvalue()
            if len(data) <= MAX_BYTES:
                path.write_bytes(data)
                print(f"{path}: {im.width} x {im.height} px, {len(data) // 1000} KB", flush=True)
                return
        img = img.resize((int(img.width * 0.85), int(img.height * 0.85)), Image.Resampling.LANCZOS)
        tries = [(img, 256)]


def read_rgb(path: Path) -> np.ndarray:
    from PIL import Image

    return np.asarray(Image.open(path).convert("RGB"))


def label(text: str, width: int, height: int = 30, size: int = 18) -> np.ndarray:
    """A white strip with the text centred on it (in the first of LABEL_FONTS installed)."""
    from PIL import Image, ImageDraw, ImageFont

    img = Image.new("RGB", (width, height), PAPER_WHITE)
    d = ImageDraw.Draw(img)
    found = [f for f in LABEL_FONTS if Path(f).exists()]
    font = ImageFont.truetype(found[0], size) if found else None
    x0, y0, x1, y1 = d.textbbox((0, 0), text, font=font)
    d.text(((width - (x1 - x0)) / 2 - x0, (height - (y1 - y0)) / 2 - y0), text, fill=0, font=font)
    return np.asarray(img)


def vlabel(text: str, height: int, width: int = 30) -> np.ndarray:
    """A label turned to read upwards, for the left of a row."""
    return np.rot90(label(text, height, width)).copy()


def gap(h: int, w: int, grey: int = 255) -> np.ndarray:
    return np.full((h, w, 3), grey, np.uint8)


def resized(rgb: np.ndarray, w: int, h: int) -> np.ndarray:
    from PIL import Image

    return np.asarray(Image.fromarray(rgb).resize((w, h), Image.Resampling.LANCZOS))


# ---------------------------------------------------------------- where the crops are
def _resampled(median) -> tuple[np.ndarray, np.ndarray]:
    p = np.asarray(median, float)
    cum = np.concatenate([[0.0], np.cumsum(np.linalg.norm(np.diff(p, axis=0), axis=1))])
    s = np.linspace(0.0, cum[-1], max(int(cum[-1] / STEP), 1) + 1)
    return np.stack([np.interp(s, cum, p[:, 0]), np.interp(s, cum, p[:, 1])], 1), s


def _turns(pts) -> np.ndarray:
    """The heading's turn (rad) at each resampled point over chords of CHORD either side (0
    within a chord of the ends)."""
    w = max(int(round(CHORD / STEP)), 1)
    out = np.zeros(len(pts))
    if len(pts) > 2 * w:
        a, b = pts[w:-w] - pts[: -2 * w], pts[2 * w :] - pts[w:-w]
        out[w:-w] = np.abs(np.arctan2(a[:, 0] * b[:, 1] - a[:, 1] * b[:, 0], (a * b).sum(1)))
    return out


def feature_points(char: dict) -> dict:
    """Data-space points (x, y up, 1024 em) of the figure's four places, from the medians:
    edge - the middle of the longest stretch that turns less than 0.2 rad; dry end - the end of
    the last stroke at least half as long as the longest that does not end in a hook (written
    late: the driest brush), END_BACK short of it; turn - the sharpest turn with at least
    HOOK_TAIL of its stroke after it; hook - the sharpest turn with less (moved a third of the
    way to the stroke's end)."""
    meds = [_resampled(m) for m in char["medians"]]
    lengths = [s[-1] for _, s in meds]
    best_edge, turn, hook = (0.0, None), (0.3, None), (0.6, None)
    for pts, s in meds:
        t = _turns(pts)
        straight = t < 0.2
        run, start = 0, 0
        for i, ok in enumerate(np.append(straight, False)):  # the longest straight run
            if ok:
                run, start = (run + 1, start) if run else (1, i)
            elif run:
                if s[start + run - 1] - s[start] > best_edge[0]:
                    best_edge = (s[start + run - 1] - s[start], pts[start + run // 2])
                run = 0
        late = (s[-1] - s) < HOOK_TAIL * s[-1]
        i, j = int(np.argmax(np.where(late, 0.0, t))), int(np.argmax(np.where(late, t, 0.0)))
        if t[i] > turn[0]:
            turn = (t[i], pts[i])
        if t[j] > hook[0]:
            hook = (t[j], pts[j] + (pts[-1] - pts[j]) / 3)
    hooked = [bool((_turns(p)[(s[-1] - s) < HOOK_TAIL * s[-1]] > 0.6).any()) for p, s in meds]
    late = [k for k, n in enumerate(lengths) if n >= 0.5 * max(lengths) and not hooked[k]]
    end = None
    if late:  # a little back from the median's end, which runs on past the ink's tip
        pts, s = meds[late[-1]]
        end = pts[int(np.searchsorted(s, max(s[-1] - END_BACK, 0.0)))]
    return {"edge": best_edge[1], "dry end": end, "turn": turn[1], "hook": hook[1]}


def to_pixels(p, n: int) -> tuple[int, int]:
    """(row, column) in an n x n image of a data point (outline.py: y_img = (900 - y) n / 1024)."""
    return int(round((900.0 - p[1]) * n / 1024.0)), int(round(p[0] * n / 1024.0))


def crop(rgb: np.ndarray, centre) -> np.ndarray:
    """CROP x CROP pixels round centre (paper beyond the image), zoomed ZOOM x by repeating."""
    r, c = centre
    h = CROP // 2
    pad = np.pad(rgb, ((CROP, CROP), (CROP, CROP), (0, 0)), mode="edge")
    tile = pad[r - h + CROP : r + h + CROP, c - h + CROP : c + h + CROP]
    return np.repeat(np.repeat(tile, ZOOM, 0), ZOOM, 1)


def boxed(rgb: np.ndarray, places: dict) -> np.ndarray:
    """The whole character at half size, a box drawn where each crop is."""
    out = rgb.copy()
    h = CROP // 2
    for place, col in zip(places.values(), BOX_COLOURS, strict=True):
        if place is None:
            continue
        r, c = place
        r0, r1 = max(r - h, 0), min(r + h, out.shape[0] - 1)
        c0, c1 = max(c - h, 0), min(c + h, out.shape[1] - 1)
        for t in range(3):  # 3 px lines (1.5 px at half size)
            out[r0 + t, c0 : c1 + 1] = out[r1 - t, c0 : c1 + 1] = col
            out[r0 : r1 + 1, c0 + t] = out[r0 : r1 + 1, c1 - t] = col
    return resized(out, ZOOM * CROP, ZOOM * CROP)


def before_after(vs, out: Path, tmp: Path) -> None:
    from sim.writing.hanzi import find_char

    data = tmp / "ba_chars"
    data.mkdir()
    chars = {}
    for ch in BA_CHARS:  # one data file both versions read (the old one had no bundle)
        chars[ch] = find_char(ch)
        (data / f"{ch}.json").write_text(json.dumps(chars[ch], ensure_ascii=False), "utf-8")
    side = ZOOM * CROP
    head = [gap(30, 30), label("whole (half size)", side)]
    head += [x for f in FEATURES for x in (gap(30, 6), label(f"{f} (4x)", side))]
    rows = [np.concatenate(head, 1)]
    new, old = vs[0], vs[1]
    for ch in BA_CHARS:
        found = feature_points(chars[ch])
        places = {f: None if p is None else to_pixels(p, BA_SIZE) for f, p in found.items()}
        print(f"{ch}: crops at (row, column) {places}", flush=True)
        for v, name in ((old, "before"), (new, "after")):
            png = tmp / f"ba_{ord(ch):x}_{name}.png"
            v.sim("write", ch, "--data", data, "--size", BA_SIZE, "-q", "-o", png)
            rgb = read_rgb(png)
            row = [vlabel(f"{ch} {name}", side), boxed(rgb, places)]
            row += [
                x
                for f in FEATURES
                for x in (
                    gap(side, 6),
                    gap(side, side) if places[f] is None else crop(rgb, places[f]),
                )
            ]
            rows.append(np.concatenate(row, 1))
        rows.append(gap(10, rows[0].shape[1]))
    save_png(np.concatenate(rows[:-1], 0), out / "realism_before_after.png")


# ------------------------------------------------------------------------ imitate_real
def imitate_real(vs, out: Path, tmp: Path) -> None:
    from scripts.picture_real import KINDS, available_fonts, box_iou, has_glyph, real_style
    from sim.fitting.texture import density
    from sim.image.filters import otsu

    panels = []
    for ch, font, kind in IMITATE:
        if font not in available_fonts() or not has_glyph(ch, font):
            print(f"{ch}: the font {font} is not installed or lacks it (picture_real.py), left out")
            continue
        rgb, data, truth = real_style(ch, font, kind, seed=1)
        pic = tmp / f"real_{ord(ch):x}.{'png' if KINDS[kind]['jpeg'] is None else 'jpg'}"
        pic.write_bytes(data)
        got = tmp / f"imitated_{ord(ch):x}.png"
        t0 = time.perf_counter()
        vs[0].sim("imitate", pic, "-o", got, "--size", IMITATE_SIZE, "-q")
        dt = time.perf_counter() - t0
        ink_rgb = read_rgb(got) / 255.0
        d = density(ink_rgb)
        score = box_iou(d > max(0.5 * otsu(d), 0.1), truth)
        print(f"{ch} ({font}, {kind}): box IoU {score:.3f}, {dt:.0f} s", flush=True)
        pair = [resized((rgb * 255 + 0.5).astype(np.uint8), PANEL, PANEL), gap(PANEL, 8)]
        pair.append(resized(read_rgb(got), PANEL, PANEL))
        k = KINDS[kind]
        what = f"picture: {ch} in {font}, {kind} ({k['px']} px, JPEG {k['jpeg']})"
        caption = np.concatenate(
            [
                label(what, PANEL, size=14),
                gap(30, 8),
                label(f"imitated (box IoU {score:.2f})", PANEL, size=14),
            ],
            1,
        )
        panels.append(np.concatenate([np.concatenate(pair, 1), caption], 0))
        panels.append(gap(PANEL + 30, 24))
    save_png(np.concatenate(panels[:-1], 1), out / "imitate_real.png")


# ------------------------------------------------------------------------------ works
def work(vs, out: Path, tmp: Path, name: str, args: list, size: int) -> None:
    png = tmp / f"{name}.png"
    t0 = time.perf_counter()
    vs[0].sim("compose", *args, "--char-size", size, "-q", "-o", png)
    print(f"{name}: composed in {time.perf_counter() - t0:.0f} s", flush=True)
    save_png(read_rgb(png), out / f"{name}.png")


SIZE_TEXT = "床前明月光\n疑是地上霜"  # fitted to an A5 sheet: about 34 mm a character
SIZE_DPI = 200


def brush_for_size(vs, out: Path, tmp: Path) -> None:
    """A short poem fitted to an A5 sheet (about 34 mm a character, a third of the brush's own
    size) with the brush as it is (--keep-brush) and with a brush for the size: the second
    column of each, side by side."""
    cols = []
    for name, extra in (("the brush as it is", ["--keep-brush"]), ("a brush for the size", [])):
        png = tmp / f"size_{len(cols)}.png"
        vs[0].sim("compose", SIZE_TEXT, "--paper", "A5", "--dpi", SIZE_DPI, *extra, "-q", "-o", png)
        rgb = read_rgb(png)
        ink = np.flatnonzero((rgb.mean(axis=2) < 100).any(axis=0))
        mid = (ink[0] + ink[-1]) // 2  # the two columns' ink either side
        part = rgb[:, ink[0] - 20 : mid]
        top = np.flatnonzero((part.mean(axis=2) < 100).any(axis=1))
        part = part[max(top[0] - 20, 0) : top[-1] + 20]
        cols += [np.concatenate([label(name, part.shape[1]), part], 0), gap(part.shape[0] + 30, 24)]
    h = min(c.shape[0] for c in cols)
    save_png(np.concatenate([c[:h] for c in cols[:-1]], 1), out / "brush_for_size.png")


def demo(out: Path) -> None:
    """scripts/demo.py (Blender as a module): its 永 and the scroll it renders with Cycles."""
    t0 = time.perf_counter()
    subprocess.run([sys.executable, str(ROOT / "scripts" / "demo.py")], cwd=ROOT, check=True)
    print(f"demo: {time.perf_counter() - t0:.0f} s", flush=True)
    save_png(read_rgb(ROOT / "out" / "demo.png"), out / "demo_yong.png")
    save_png(read_rgb(ROOT / "out" / "demo_render.png"), out / "demo_render.png")


NAMES = ("before_after", "imitate_real", "work_vertical", "work_horizontal", "brush_for_size")


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--against", default=DEFAULT_AGAINST, help="the 'before' version (git)")
    ap.add_argument("--out", default=str(ROOT / "docs" / "img"), help="folder for the PNGs")
    ap.add_argument("--only", default=",".join(NAMES), help=f"some of {','.join(NAMES)}")
    ap.add_argument("--char-size", type=int, default=160, help="px a character of the works")
    ap.add_argument("--demo", action="store_true", help="also the demo (Blender, Cycles)")
    args = ap.parse_args(argv)
    only = [n.strip() for n in args.only.split(",") if n.strip()]
    unknown = sorted(set(only) - set(NAMES))
    if unknown:
        ap.error(f"--only: unknown {', '.join(unknown)} (choose from {', '.join(NAMES)})")
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    t0 = time.perf_counter()
    with tempfile.TemporaryDirectory(prefix="hairy-brush-figures-") as t:
        tmp = Path(t)
        against = args.against if "before_after" in only else None
        with versions(tmp, against) as vs:
            if "before_after" in only:
                before_after(vs, out, tmp)
            if "imitate_real" in only:
                imitate_real(vs, out, tmp)
            if "work_vertical" in only:
                poem = [POEM, "--signature", POEM_SIGN, "--seal", POEM_SEAL]
                work(vs, out, tmp, "work_vertical", poem, args.char_size)
            if "work_horizontal" in only:
                row = [ROW, "--layout", "horizontal", "--signature", ROW_SIGN]
                row += ["--seal", ROW_SEAL, "--seal-style", "zhuwen"]
                work(vs, out, tmp, "work_horizontal", row, args.char_size)
            if "brush_for_size" in only:
                brush_for_size(vs, out, tmp)
    if args.demo:
        demo(out)
    print(f"{time.perf_counter() - t0:.0f} s")
    return 0


if __name__ == "__main__":
    sys.exit(main())
