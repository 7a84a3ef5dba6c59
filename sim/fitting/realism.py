# SPDX-License-Identifier: GPL-3.0-or-later
"""A realism measure built on the structure of brush writing (issue 26), numpy only.

A brush writes with bundles of hair that move along the stroke. Its marks therefore carry
structure that a filled outline or a filtered image does not: light streaks inside the ink and
fibres at its edge run along the stroke (dry hair, "flying white"); the edge frays into fibres,
not into specks of dust; and the tone of the ink changes at the scale of a stroke (dark after a
dip, grey before the next, darker where the brush paused), not from pixel to pixel.

The ink's density D is read at two scales: as it is, and blurred at a fraction of the stroke's
half width (SMOOTH). Blurring keeps the variation of D across an isolated edge (its total
variation, the sum of |grad D|) and removes that of fine texture. The fine texture's variation
is split by direction against the local stroke direction s (the structure tensor of the ink
blurred at stroke scale; n is the normal, and every pixel is weighted by how clearly it lies in
one stroke, the tensor's coherence):

- ``streaks``: the fine variation *across* the stroke less that *along* it (|d_n D| - |d_s D|,
  fine minus blurred), per unit of the blurred ink's own variation (about the outline's
  length times the ink's contrast): streaks and fibres running along the stroke. A filled
  outline has none; isotropic noise and stipple add as much along as across: none either.
- ``noise``: the fine variation *along* the stroke (|d_s D|, fine minus blurred), on the same
  scale: stipple, grain, specks and streaks across the stroke. A penalty.
- ``specks``: small components of ink (under (SPECK x the half width)^2) detached from the
  body, per 100 px of outline. A penalty.
- ``tone``: the coefficient of variation of D blurred at stroke scale inside the strokes (the
  blur normalised by the ink's own mask, so the paper outside does not pale the edges): how the
  ink's grey changes along the strokes and between them. Pixel noise leaves it unchanged.
- ``deep_share`` (a diagnostic): of the light pixels inside the ink closed over thin gaps, the
  share more than two pixels inside it (notches where strokes join lie at the outline; streaks
  inside the stroke do not).

The score: (streak score + tone score) / 2, each rising from 0 and saturating at a reference
value, times 1 / (1 + noise / NOISE_REF) and 1 / (1 + specks / SPECK_REF). A filled outline
scores 0. The image is cropped to its ink and scaled so that its longer side is SIDE pixels: a
character reads the same at any resolution. It is a measure of structure, not a discriminator
trained on scans: the reference values are orders of magnitude, named here once.
"""

from __future__ import annotations

from dataclasses import asdict, dataclass

import numpy as np

from ..image.filters import (
    _bilinear,
    _dilate,
    _disk,
    _erode,
    _gaussian,
    _shifted,
    otsu,
    perimeter,
)
from ..image.morph import label
from .texture import density

SIDE = 512  # pixels along the longer side of the scaled crop
FINE = 2  # px: gaps, fibres and specks thinner than about twice this are texture, not shape
CLOSE = 0.25  # for deep_share: gaps narrower than twice this many half widths are inside
AA_SIGMA = 0.8  # px: both the ink and its smooth shape are read through this blur
STREAK_REF = 0.15  # oriented fine variation (share of the outline's) where its score is 1/2
TONE_REF = 0.06  # coefficient of variation of the stroke-scale tone where its score is 1/2
TONE_MAX = 0.45  # past this the tone score falls (blotches, not the tone of ink)
SPECK = 0.5  # a component smaller than (SPECK x half width)^2 is a speck (a dot is larger)
NOISE_REF = 0.25  # fine variation along the stroke that halves the score
SPECK_REF = 1.0  # specks per 100 px of outline that halve the score


@dataclass(frozen=True)
class Realism:
    streaks: float  # fine variation across less along the stroke, share of the outline's
    noise: float  # fine variation along the stroke, share of the outline's
    specks: float  # small detached components per 100 px of outline
    tone: float  # coefficient of variation of the stroke-scale density inside the strokes
    deep_share: float  # share of the light pixels inside the ink deeper than 2 px (diagnostic)
    half_width: float  # the stroke's half width, px of the scaled crop
    streak_score: float
    tone_score: float
    score: float

    def as_dict(self) -> dict:
        return {k: round(float(v), 4) for k, v in asdict(self).items()}


def realism(rgb, paper_rgb=None) -> Realism:
    """The measure of an RGB image (H, W, 3) in [0, 1] holding one written character."""
    d = _scaled(density(rgb, paper_rgb))
    level = _ink_level(d)
    ink = d > level
    if ink.sum() < 64:
        raise ValueError("the image holds almost no ink")
    smooth = _smooth_shape(d)
    shape = smooth > level
    w = _half_width(_closed(shape, max(2, round(CLOSE * _half_width(shape)))))
    labels, n = label(ink)
    sizes = np.bincount(labels.ravel(), minlength=n + 1)
    sizes[0] = 0
    body = _closed(ink, max(2, round(CLOSE * w)))  # gaps narrower than a stroke bridged
    edge_len = max(perimeter(body), 1.0)
    tone_map = _tone_map(d, shape, w)
    sdir, coherence = _stroke_direction(d, w)
    streaks, noise = _fine_variation(d, smooth, sdir, coherence)
    specks = int(np.count_nonzero((sizes > 0) & (sizes < max(4.0, (SPECK * w) ** 2))))
    specks = specks * 100.0 / edge_len
    tone = _tone(tone_map, shape, w)
    light = body & (d < 0.5 * float(np.median(d[ink])))
    deep_share = float((light & _erode(body, 2)).sum() / max(light.sum(), 1))
    streak_score = max(streaks, 0.0) / (max(streaks, 0.0) + STREAK_REF)
    tone_score = tone / (tone + TONE_REF) * (1.0 if tone <= TONE_MAX else TONE_MAX / tone)
    damp = 1.0 / ((1.0 + noise / NOISE_REF) * (1.0 + specks / SPECK_REF))
    return Realism(
        streaks=streaks,
        noise=noise,
        specks=specks,
        tone=tone,
        deep_share=deep_share,
        half_width=w,
        streak_score=streak_score,
        tone_score=tone_score,
        score=0.5 * (streak_score + tone_score) * damp,
    )


def _scaled(d) -> np.ndarray:
    """The box around the ink, with a margin, scaled so that its longer side is SIDE pixels
    (area-averaged when it shrinks: a bilinear sample of a 2x finer grid, averaged)."""
    mask = d > _ink_level(d)
    ys, xs = np.nonzero(mask)
    if ys.size == 0:
        raise ValueError("the image holds no ink")
    span = max(ys.max() - ys.min(), xs.max() - xs.min()) + 1
    margin = 0.06 * span
    y0, x0 = ys.min() - margin, xs.min() - margin
    h = (ys.max() - ys.min() + 1) + 2 * margin
    w = (xs.max() - xs.min() + 1) + 2 * margin
    scale = SIDE / max(h, w)  # output pixels per input pixel
    oh, ow = int(round(h * scale)), int(round(w * scale))
    sub = 2 if scale < 1 else 1
    ty = y0 - 0.5 + (np.arange(oh * sub) + 0.5) / (scale * sub)
    tx = x0 - 0.5 + (np.arange(ow * sub) + 0.5) / (scale * sub)
    out = _bilinear(d, ty[:, None], tx[None, :])
    if sub > 1:
        out = out.reshape(oh, sub, ow, sub).mean(axis=(1, 3))
    return out


def _ink_level(d) -> float:
    """The density above which a pixel is ink: half Otsu's threshold (Otsu's alone can fall
    between grey and black ink, and grey ink is ink), and no less than 0.1 (the paper's own
    unevenness)."""
    return max(0.5 * otsu(d), 0.1)


def _half_width(shape) -> float:
    """Half the typical stroke width: area / (perimeter / 2) of the strokes' smooth shape."""
    return float(np.clip(shape.sum() / max(perimeter(shape) / 2.0, 1.0), 2.0, 60.0))


def _grad(a):
    gy = np.zeros_like(a)
    gx = np.zeros_like(a)
    gy[1:-1] = 0.5 * (a[2:] - a[:-2])
    gx[:, 1:-1] = 0.5 * (a[:, 2:] - a[:, :-2])
    return gy, gx


def _stroke_direction(d, w: float):
    """The local stroke direction (unit (sy, sx) per pixel) and its coherence in [0, 1]: the
    least-varying direction of the structure tensor of the ink blurred at stroke scale."""
    gy, gx = _grad(_gaussian(d, max(1.0, 0.5 * w)))
    s = max(1.0, w)
    jyy, jxx, jxy = (_gaussian(v, s) for v in (gy * gy, gx * gx, gx * gy))
    # the normal (the largest eigenvector) at angle theta from x; the stroke runs across it
    theta = 0.5 * np.arctan2(2 * jxy, jxx - jyy)
    tr = jxx + jyy
    coherence = np.sqrt((jxx - jyy) ** 2 + 4 * jxy**2) / np.maximum(tr, 1e-12)
    return (np.cos(theta), -np.sin(theta)), np.where(tr > 1e-12, coherence, 0.0)


def _fine_variation(d, smooth, sdir, coherence):
    """(streaks, noise) of the module doc: the variation of the ink less that of its smooth
    shape, across and along the stroke, per unit of the smooth shape's variation."""
    sy, sx = sdir
    ny, nx = sx, -sy
    c = coherence

    def directional(a):
        gy, gx = _grad(_gaussian(a, AA_SIGMA))
        return float((c * np.abs(gy * sy + gx * sx)).sum()), float(
            (c * np.abs(gy * ny + gx * nx)).sum()
        )

    ink_s, ink_n = directional(d)
    smooth_s, smooth_n = directional(smooth)
    outline = smooth_s + smooth_n
    if outline <= 1e-9:
        return 0.0, 0.0
    along = (ink_s - smooth_s) / outline
    across = (ink_n - smooth_n) / outline
    return across - along, max(along, 0.0)


def _closed(mask, r: int):
    pad = r + 2
    return _erode(_dilate(np.pad(mask, pad), r), r)[pad:-pad, pad:-pad] | mask


def _grey(a, r: int, pick, fill: float):
    """Grey-level dilation (pick np.maximum) or erosion (np.minimum) by a disk of radius r."""
    out = a.copy()
    for dy, dx in _disk(r):
        pick(out, _shifted(a, dy, dx, fill), out=out)
    return out


def _smooth_shape(d):
    """The ink without fibres, specks and thin gaps: its density closed, then opened, by a
    disk of radius FINE (grey-level: straight and gently curved edges keep their grey)."""
    closed = _grey(_grey(d, FINE, np.maximum, 0.0), FINE, np.minimum, 1.0)
    return _grey(_grey(closed, FINE, np.minimum, 1.0), FINE, np.maximum, 0.0)


def _tone_map(d, shape, w: float):
    """The density blurred at stroke scale inside the shape (normalised by the shape less its
    rim of FINE px, so that neither the paper outside nor the grey of the edge pales it)."""
    e = _erode(shape, FINE).astype(np.float64)
    s = max(1.0, w)
    return _gaussian(d * e, s) / np.maximum(_gaussian(e, s), 1e-9)


def _tone(tone_map, shape, w: float) -> float:
    """Coefficient of variation of the stroke-scale tone over the stroke interiors."""
    inner = _erode(shape, int(max(2, round(0.5 * w))))
    if inner.sum() < 16:
        inner = shape
    v = tone_map[inner]
    return float(np.std(v) / max(np.mean(v), 1e-9))
