# SPDX-License-Identifier: GPL-3.0-or-later
"""Real-style pictures of writing for measuring ``sim imitate`` on pictures that are not the
simulator's own output, and the measures (issue 26, point 4). Nothing here ships with the
extension; fonts are read from the system (Debian: fonts-arphic-ukai, fonts-arphic-uming,
fonts-arphic-gkai00mp, fonts-arphic-bkai00mp, fonts-cwtex-kai, fonts-wqy-microhei) and never
committed.

- ``font_grey``: a character rendered by Pillow's ImageFont (4x supersampled, anti-aliased),
  black on white, the character ``px`` pixels tall in a square with a margin.
- ``degrade``: what a photograph or a scan does to it - ink that is not black, a tinted paper
  with fibres and grain, uneven light, the optics' blur, a smaller size, sensor noise, JPEG.
- ``box_iou``: the box-normalised IoU: both inks cropped to their bounding boxes (specks left
  out of the box), each scaled to a common BOX x BOX square (area-averaged, covered above
  half), then IoU. It forgives the imitation its place and size on the sheet, not its shape.
- ``holes``, ``pieces``: the closed counters (口 in 宫) and separate pieces of ink (a free dot)
  of a mask, ignoring pin-holes and specks below a share of the ink's box.
- ``width_error``: along the picture's skeleton, the stroke's width there (twice the distance
  to the paper) against the imitation's at the same place of the box (the widest inscribed
  disc near it), both in the picture's pixels; the median relative error and the median ratio.

    python scripts/picture_real.py 宫 /tmp/picture/gong.jpg --font ukai --kind scan
"""

from __future__ import annotations

import argparse
import io
import sys
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))

from sim.image import morph as M  # noqa: E402
from sim.image.filters import _gaussian, skeleton  # noqa: E402
from sim.picture.correct import box_shape, ink_box, shape_agreement  # noqa: E402

FONTS = {
    "ukai": "/usr/share/fonts/truetype/arphic/ukai.ttc",  # AR PL UKai: Kaiti
    "gkai": "/usr/share/fonts/truetype/arphic-gkai00mp/gkai00mp.ttf",  # AR PL KaitiM GB
    "bkai": "/usr/share/fonts/truetype/arphic-bkai00mp/bkai00mp.ttf",  # AR PL KaitiM Big5
    "cwkai": "/usr/share/fonts/truetype/cwtex/cwkai.ttf",  # cwTeX Kai
    "uming": "/usr/share/fonts/truetype/arphic/uming.ttc",  # AR PL UMing: Mingti
    "wqy": "/usr/share/fonts/truetype/wqy/wqy-microhei.ttc",  # WenQuanYi Micro Hei: sans
}
BOX = 256  # the common square of the box-normalised IoU
MIN_HOLE = 5e-4  # of the ink's box area: a smaller hole is a pin-hole
MIN_PIECE = 5e-4  # of the ink's box area: a smaller piece is a speck
MARGIN = 0.25  # of the character's size, paper round it on every side


def available_fonts() -> list[str]:
    return [k for k, p in FONTS.items() if Path(p).exists()]


def has_glyph(ch: str, font: str) -> bool:
    """Whether the font draws the character (not nothing, nor its "missing" box)."""
    got = font_grey(ch, font, 48)
    return bool((got < 0.5).any()) and not np.array_equal(got, font_grey("\U000f0000", font, 48))


def font_grey(ch: str, font: str, px: int, supersample: int = 4) -> np.ndarray:
    """The character in the font, ``px`` pixels for the em, on a square with MARGIN round it:
    (S, S) grey in [0, 1], black ink on white, anti-aliased."""
    from PIL import Image, ImageDraw, ImageFont

    k = supersample
    em = px * k
    side = int(round(px * (1 + 2 * MARGIN))) * k
    f = ImageFont.truetype(FONTS[font], em)
    img = Image.new("L", (side, side), 255)
    d = ImageDraw.Draw(img)
    x0, y0, x1, y1 = d.textbbox((0, 0), ch, font=f)
    d.text(((side - (x1 - x0)) / 2 - x0, (side - (y1 - y0)) / 2 - y0), ch, font=f, fill=0)
    small = img.resize((side // k, side // k), Image.Resampling.BOX)
    return np.asarray(small, dtype=np.float64) / 255.0


KINDS = {  # character size (px), blur (px), ink darkness, paper, light, noise, JPEG quality
    "clean": dict(px=400, blur=0.0, ink=0.95, paper=False, light=0.0, noise=0.0, jpeg=None),
    "blurred": dict(px=300, blur=2.0, ink=0.9, paper=False, light=0.0, noise=0.01, jpeg=90),
    "small": dict(px=150, blur=0.8, ink=0.85, paper=False, light=0.0, noise=0.02, jpeg=50),
    "uneven": dict(px=360, blur=1.0, ink=0.8, paper=False, light=0.45, noise=0.02, jpeg=80),
    "scan": dict(px=300, blur=1.2, ink=0.82, paper=True, light=0.25, noise=0.03, jpeg=75),
    "photo": dict(px=600, blur=2.5, ink=0.75, paper=True, light=0.5, noise=0.04, jpeg=70),
}
TINT = np.array([0.95, 0.88, 0.74])  # old xuan paper


def degrade(grey: np.ndarray, kind: str, seed: int = 0) -> tuple[np.ndarray, bytes]:
    """The clean rendering ``grey`` as a photograph or a scan of kind ``kind`` (KINDS): RGB in
    [0, 1] and the file's bytes (JPEG, or PNG when the kind has no JPEG quality)."""
    from PIL import Image

    k = KINDS[kind]
    rng = np.random.default_rng(seed)
    n = grey.shape[0]
    dark = 1.0 - grey
    if k["blur"]:
        dark = _gaussian(dark, k["blur"])
    # ink: not black, a little uneven (the ink's tone varies along the writing)
    tone = k["ink"] * (1.0 - 0.15 * np.clip(_gaussian(rng.standard_normal((n, n)), n / 40), -1, 1))
    yy, xx = np.mgrid[0:n, 0:n] / n
    ang = rng.uniform(0, 2 * np.pi)
    ramp = 0.5 + 0.5 * (np.cos(ang) * (xx - 0.5) + np.sin(ang) * (yy - 0.5)) * 2
    light = 1.0 - k["light"] * np.clip(ramp, 0, 1) ** 1.5  # a shadow falling across
    light *= 1.0 - 0.3 * k["light"] * ((xx - 0.5) ** 2 + (yy - 0.5) ** 2)  # vignette
    paper = np.ones((n, n, 3))
    if k["paper"]:
        paper = paper * TINT
        grain = _gaussian(rng.standard_normal((n, n)), 0.7)
        paper *= 1.0 + 0.04 * (grain / max(float(np.abs(grain).max()), 1e-9))[..., None]
        for _ in range(max(n // 6, 10)):  # fibres: short dark and light curved threads
            p = rng.uniform(0, n, 2)
            a = rng.uniform(0, np.pi)
            L = rng.uniform(0.03, 0.12) * n
            t = np.linspace(0, 1, int(L) + 2)
            bend = rng.normal(0, 0.3)
            xs = p[0] + L * t * np.cos(a + bend * t)
            ys = p[1] + L * t * np.sin(a + bend * t)
            ok = (xs >= 0) & (xs < n) & (ys >= 0) & (ys < n)
            paper[ys[ok].astype(int), xs[ok].astype(int)] *= rng.choice([0.88, 1.04])
    img = paper * light[..., None] * (1.0 - np.clip(dark * tone, 0, 1))[..., None]
    img += rng.normal(0, k["noise"], img.shape) if k["noise"] else 0.0
    img = np.clip(img, 0, 1)
    im = Image.fromarray((img * 255 + 0.5).astype(np.uint8), "RGB")
    buf = io.BytesIO()
    if k["jpeg"] is None:
        im.save(buf, "PNG")
    else:
        im.save(buf, "JPEG", quality=k["jpeg"])
    data = buf.getvalue()
    return np.asarray(Image.open(io.BytesIO(data)).convert("RGB")) / 255.0, data


def real_style(ch: str, font: str, kind: str, seed: int = 0):
    """A real-style picture of ``ch`` (``degrade``'s RGB and file bytes) and its true ink (the
    clean rendering covered above half, at the picture's size)."""
    grey = font_grey(ch, font, KINDS[kind]["px"])
    rgb, data = degrade(grey, kind, seed)
    return rgb, data, grey < 0.5


# ------------------------------------------------------------------------------- measures
_box = ink_box  # the ink's box, specks left out (one home: sim.picture.correct)


def box_normalised(mask: np.ndarray, side: int = BOX) -> np.ndarray:
    """The ink cropped to its bounding box and scaled to side x side (``correct.box_shape``)."""
    return box_shape(mask, side)


def box_iou(a: np.ndarray, b: np.ndarray, side: int = BOX) -> float:
    """The box-normalised IoU of two inks (module docstring; ``correct.shape_agreement``)."""
    return shape_agreement(a, b, side)


def holes(mask: np.ndarray) -> int:
    """Closed counters: regions of paper enclosed by the ink, of MIN_HOLE of its box or more."""
    box = np.pad(_box(np.asarray(mask, bool)), 1)
    lab, k = M.label(~box)
    if k == 0:
        return 0
    area = np.bincount(lab.ravel(), minlength=k + 1)
    outer = np.unique(np.concatenate([lab[0], lab[-1], lab[:, 0], lab[:, -1]]))
    big = area >= MIN_HOLE * box.size
    big[0] = False
    big[outer] = False
    return int(np.count_nonzero(big))


def pieces(mask: np.ndarray) -> int:
    """Separate pieces of ink of MIN_PIECE of its box or more."""
    box = _box(np.asarray(mask, bool))
    lab, k = M.label(box)
    area = np.bincount(lab.ravel(), minlength=k + 1)[1:]
    return int(np.count_nonzero(area >= MIN_PIECE * box.size))


def _widest(d: np.ndarray, y: int, x: int, r: int) -> float:
    return float(d[max(y - r, 0) : y + r + 1, max(x - r, 0) : x + r + 1].max(initial=0.0))


def width_error(picture: np.ndarray, imitation: np.ndarray) -> tuple[float, float]:
    """Along the picture's skeleton (away from its ends and junctions' blots: every skeleton
    pixel), the width there against the imitation's at the same place of the ink's box, in the
    picture's pixels (the imitation's box scaled to the picture's): the median of |w_i - w_p| /
    w_p and the median of w_i / w_p."""
    p = np.pad(_box(np.asarray(picture, bool)), 1)  # the paper round the box for the distances
    q = np.pad(_box(np.asarray(imitation, bool)), 1)
    dp = M.edt(p)
    dq = M.edt(q)
    sk = skeleton(_gaussian(p.astype(np.float64), 1.0) > 0.5) & p
    ys, xs = np.nonzero(sk)
    if ys.size == 0:
        return 1.0, 0.0
    wp = 2.0 * dp[ys, xs]
    sy, sx = q.shape[0] / p.shape[0], q.shape[1] / p.shape[1]
    scale = 0.5 * (1 / sy + 1 / sx)  # imitation pixels to the picture's
    # the widest inscribed disc within half the picture's width of the place, in both (the
    # same window in both: the imitation's ink is not exactly where the picture's is)
    r = np.maximum((0.5 * wp).astype(int), 1)
    qy, qx = (ys * sy).astype(int), (xs * sx).astype(int)
    wi = np.empty(len(ys))
    for j in range(len(ys)):
        wp[j] = 2.0 * _widest(dp, ys[j], xs[j], r[j])
        wi[j] = 2.0 * _widest(dq, qy[j], qx[j], max(int(r[j] * min(sy, sx)), 1)) * scale
    ok = wp >= 2.0
    rel = np.abs(wi[ok] - wp[ok]) / wp[ok]
    return float(np.median(rel)), float(np.median(wi[ok] / wp[ok]))


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("char")
    ap.add_argument("output", help=".jpg or .png (by the kind)")
    ap.add_argument("--font", default="ukai", choices=sorted(FONTS))
    ap.add_argument("--kind", default="scan", choices=sorted(KINDS))
    ap.add_argument("--seed", type=int, default=0)
    args = ap.parse_args(argv)
    _, data, _ = real_style(args.char, args.font, args.kind, args.seed)
    Path(args.output).write_bytes(data)
    return 0


if __name__ == "__main__":
    sys.exit(main())
