# SPDX-License-Identifier: GPL-3.0-or-later
"""Texture statistics of written ink, compared with real brush writing (numpy only, so the fit
can use them inside Blender too).

A written character is cropped to its ink and scaled to SIDE x SIDE; D is the ink density (the
paper's colour flattened to 0, full black 1); the mask is D above Otsu's threshold. Five numbers
describe its texture:

- ink tone: coefficient of variation of D (3 x 3 median) inside the mask eroded by 3 px;
- flying white: (closing of the mask by a disk of radius 2) minus the mask, as a share of the
  closing: the small white gaps dry hair leaves inside strokes;
- partial ink: share of the closing's pixels with D < 0.6: ink laid thin;
- ragged edge: perimeter of the mask / perimeter of the mask smoothed (Gaussian, sigma 1) - 1;
- width variation: coefficient of variation of the stroke width (2 x the distance to the paper)
  along the skeleton.

REAL_WRITING holds these statistics measured on nine high-resolution scans of old and modern
brush calligraphy (the scans are not ours to ship; their statistics are facts). ``score`` is the
geometric mean over the five of (min + eps) / (max + eps) of a writing's statistic and the real
one: 1 is real writing's texture, a plain font scores 0.25-0.30.
"""

from __future__ import annotations

from dataclasses import asdict, dataclass

import numpy as np

from ..core.exact import matmul
from ..image.filters import (
    _bilinear,
    _dilate,
    _distance_to,
    _erode,
    _gaussian,
    _median3,
    otsu,
    perimeter,
    skeleton,
)

SIDE = 256  # pixels a side of the scaled crop


@dataclass(frozen=True)
class TextureStats:
    ink_tone: float
    flying_white: float
    partial_ink: float
    ragged_edge: float
    width_variation: float

    def as_dict(self) -> dict:
        return asdict(self)


REAL_WRITING = TextureStats(0.033, 0.012, 0.052, 0.060, 0.50)
EPS = TextureStats(0.005, 0.005, 0.01, 0.005, 0.05)  # keeps a ratio of small numbers sane


def score(stats: TextureStats, real: TextureStats = REAL_WRITING) -> float:
    """Geometric mean of (min + eps) / (max + eps) over the five statistics."""
    ratios = []
    for name in TextureStats.__dataclass_fields__:
        a, b, e = getattr(stats, name), getattr(real, name), getattr(EPS, name)
        ratios.append((min(a, b) + e) / (max(a, b) + e))
    return float(np.exp(np.mean(np.log(ratios))))


def density(rgb, paper_rgb=None) -> np.ndarray:
    """Ink density D in [0, 1] of an RGB image (H, W, 3) in [0, 1]: 0 where it shows the paper's
    colour (the brightest colour in the image when not given), 1 for black."""
    lum = matmul(np.asarray(rgb, dtype=np.float64), np.array([0.2126, 0.7152, 0.0722]))
    ref = (
        float(matmul(np.asarray(paper_rgb), [0.2126, 0.7152, 0.0722]))
        if paper_rgb is not None
        else None
    )
    ref = ref if ref is not None else float(np.percentile(lum, 99.5))
    return np.clip(1.0 - lum / max(ref, 1e-6), 0.0, 1.0)


def texture_stats(rgb, paper_rgb=None) -> TextureStats:
    """The five statistics of a written character's image (RGB in [0, 1])."""
    d = density(rgb, paper_rgb)
    d = _crop_scaled(d, d > otsu(d))
    mask = d > otsu(d)
    if mask.sum() < 16:
        raise ValueError("the image holds almost no ink")
    inner = _erode(mask, 3)
    med = _median3(d)[inner] if inner.any() else d[mask]
    tone = float(np.std(med) / max(np.mean(med), 1e-9))
    closed = _erode(_dilate(mask, 2), 2)
    n_closed = max(int(closed.sum()), 1)
    white = float((closed & ~mask).sum() / n_closed)
    partial = float((closed & (d < 0.6)).sum() / n_closed)
    smooth = _gaussian(mask.astype(np.float64), 1.0) > 0.5
    ragged = perimeter(mask) / max(perimeter(smooth), 1e-9) - 1.0
    skel = skeleton(mask)
    width = 2.0 * _distance_to(~mask, skel)
    wv = float(np.std(width) / max(np.mean(width), 1e-9)) if width.size else 0.0
    return TextureStats(tone, white, partial, float(ragged), wv)


def _crop_scaled(d, mask) -> np.ndarray:
    """The box around the ink (a square, centred), scaled to SIDE x SIDE by area averaging of a
    bilinear resample."""
    ys, xs = np.nonzero(mask)
    if ys.size == 0:
        raise ValueError("the image holds no ink")
    cy, cx = (ys.min() + ys.max()) / 2, (xs.min() + xs.max()) / 2
    half = max(ys.max() - ys.min(), xs.max() - xs.min()) / 2 + 2
    t = (np.arange(SIDE) + 0.5) / SIDE * 2 * half - half
    return _bilinear(d, cy + t[:, None], cx + t[None, :])
